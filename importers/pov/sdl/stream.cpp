// The token stream: frames for the scene file, includes and macro calls; identifiers resolved as
// they are read; located errors with the include chain.
#include <algorithm>
#include <fstream>
#include <sstream>

#include "core/util/error.h"
#include "importers/pov/sdl/parser.h"
#include "importers/pov/sdl/path_rules.h"

namespace fb::pov {

std::string SourceLocation::text() const {
  return file + ":" + std::to_string(line) + ":" + std::to_string(column);
}

namespace sdl {

Nesting::Nesting(Parser& parser) : parser_(parser) {
  // deep enough for any real scene, shallow enough for the default 8 MB stack
  if (++parser_.nesting > 400) {
    --parser_.nesting;
    parser_.fail("nesting deeper than 400 levels");
  }
  // A quarter of that stack: 400 levels take less in a Release build, but AddressSanitizer's
  // frames are larger (tests/fuzz/fuzz_pov.cpp overflowed at fewer than 400).
  constexpr uintptr_t kStackBytes = 2 << 20;
  const auto here = reinterpret_cast<uintptr_t>(__builtin_frame_address(0));
  if (parser_.stack_start - here > kStackBytes) {
    --parser_.nesting;
    parser_.fail("nesting deeper than 2 MiB of stack allow (" + std::to_string(parser_.nesting) +
                 " levels)");
  }
  EvaluationCounts& counts = parser_.counts();
  counts.nesting = std::max(counts.nesting, static_cast<uint32_t>(parser_.nesting));
}

Parser::Parser(const EvaluateOptions& options) : options_(options) {
  scene_folder_ = options.scene_file.parent_path();
  if (scene_folder_.empty()) scene_folder_ = ".";
  scopes_.emplace_back();  // global identifiers
  for (const auto& [name, value] : options.declarations)
    scopes_.front()[name] = Value::number(value);
  std::string name = options.scene_file.filename().string();
  std::ifstream probe(options.scene_file);
  if (!probe) throw_input(options.scene_file.string(), "", "cannot open the scene file");
  Frame frame;
  frame.file = load(options.scene_file, name);
  frame.folder = scene_folder_;
  scopes_.emplace_back();  // the scene file's #local identifiers
  frame.scope = 1;
  frames_.push_back(std::move(frame));
}

std::shared_ptr<TokenFile> Parser::load(const std::filesystem::path& path,
                                        const std::string& display) {
  std::string key = path.lexically_normal().string();
  if (auto it = file_cache_.find(key); it != file_cache_.end()) return it->second;
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("cannot read " + display);
  std::ostringstream text;
  text << in.rdbuf();
  std::string source = text.str();
  if (source.compare(0, 3, "\xEF\xBB\xBF") == 0) source.erase(0, 3);  // UTF-8 byte order mark
  auto file = tokenize(display, source);
  file_cache_[key] = file;
  return file;
}

std::optional<std::filesystem::path> Parser::resolve_include(
    const std::string& name, std::filesystem::path* folder, bool scene_folder_only,
    const std::vector<std::filesystem::path>& link_targets) const {
  namespace fs = std::filesystem;
  fs::path relative(name);
  if (name.empty() || relative.is_absolute() || relative.has_root_name()) return std::nullopt;
  std::vector<fs::path> folders{scene_folder_};
  // POV-Ray looks next to the including file first; that folder is inside an allowed one
  if (!frames_.empty() && frames_.back().folder != scene_folder_) {
    folders.insert(folders.begin(), frames_.back().folder);
  }
  if (!scene_folder_only) {
    folders.insert(folders.end(), options_.library_paths.begin(), options_.library_paths.end());
  }
  std::vector<fs::path> roots{scene_folder_};
  roots.insert(roots.end(), options_.library_paths.begin(), options_.library_paths.end());
  for (const fs::path& dir : folders) {
    fs::path candidate = (dir / relative).lexically_normal();
    const bool inside = std::any_of(roots.begin(), roots.end(), [&](const fs::path& root) {
      return lexically_inside(candidate, root);
    });
    if (!inside) continue;  // escapes every allowed folder
    std::error_code ec;
    for (const fs::path& attempt : {candidate, fs::path(candidate.string() + ".inc")}) {
      if (!fs::is_regular_file(attempt, ec)) continue;
      // A symbolic link is followed only to a file inside an allowed folder (or a link target).
      const auto really_in = [&](const fs::path& root) { return really_inside(attempt, root); };
      const bool real_inside = std::any_of(roots.begin(), roots.end(), really_in) ||
                               std::any_of(link_targets.begin(), link_targets.end(), really_in);
      if (!real_inside) continue;
      if (folder) *folder = attempt.parent_path();
      return attempt;
    }
  }
  return std::nullopt;
}

std::string Parser::chain() const {
  std::vector<const std::string*> links;  // innermost first
  for (size_t i = frames_.size(); i-- > 1;) {
    if (!frames_[i].from.empty()) links.push_back(&frames_[i].from);
  }
  // A runaway recursion would repeat one link hundreds of times: the innermost few, how many are
  // left out, and the outermost, which names the place in the scene that started it.
  constexpr size_t kInnermost = 3;
  std::string text;
  for (size_t i = 0; i < links.size(); ++i) {
    text += i == 0 ? " (" : ", ";
    if (i == kInnermost && links.size() > kInnermost + 2) {
      text += "... " + std::to_string(links.size() - kInnermost - 1) + " more, ";
      i = links.size() - 1;
    }
    text += *links[i];
  }
  return text.empty() ? text : text + ")";
}

void Parser::fail(const std::string& what) const {
  fail_at(here(), what);
}

void Parser::fail_at(const SourceLocation& where, const std::string& what) const {
  throw_input(where.text(), "", what + chain());
}

void Parser::warn(const std::string& what) {
  warn_at(here(), what);
}

void Parser::warn_at(const SourceLocation& where, const std::string& what) {
  scene_.warnings.push_back(where.text() + ": " + what);
}

void Parser::unsupported(const std::string& feature, const SourceLocation& where) {
  scene_.unsupported.push_back({feature, where, std::nullopt});
}

SourceLocation Parser::location_of(const Tok& tok) const {
  SourceLocation where;
  if (tok.file) where.file = *tok.file;
  where.line = tok.token.line;
  where.column = tok.token.column;
  return where;
}

const Token& Parser::raw() const {
  const Frame& frame = frames_.back();
  return frame.file->tokens[frame.pos];
}

Token Parser::raw_next() {
  Frame& frame = frames_.back();
  const Token& token = frame.file->tokens[frame.pos];
  if (token.kind != TokenKind::kEnd) ++frame.pos;
  last_ = {&frame.file->name, token.line, token.column};
  count_token();
  return token;
}

void Parser::count_token() {
  if (++scene_.counts.tokens > options_.limits.tokens) {
    fail("more than " + std::to_string(options_.limits.tokens) + " tokens read (limit)");
  }
}

Value* Parser::lookup(const std::string& name) {
  // innermost scope first: the running macro or include file, then outwards to the globals
  for (size_t i = scopes_.size(); i-- > 0;) {
    auto it = scopes_[i].find(name);
    if (it != scopes_[i].end()) return &it->second;
  }
  return nullptr;
}

Tok Parser::resolve(const Token& token) {
  Tok tok;
  tok.token = token;
  tok.file = &frames_.back().file->name;
  if (token.kind == TokenKind::kWord) {
    if (Value* value = lookup(token.text)) {
      tok.identifier = true;
      tok.value = *value;
    }
  }
  return tok;
}

// End of an include file: back to the includer. The scene file's end stays.
bool Parser::pop_finished_frame() {
  Frame& frame = frames_.back();
  // a directive's expression never reads on into the includer
  if (frames_.size() == 1 || frame.macro || frames_.size() == directive_frames_) return false;
  if (conds_.size() > frame.cond_base) fail("an #if, #while or #switch is missing its #end");
  scopes_.resize(frame.scope);
  frames_.pop_back();
  --include_depth_;
  return true;
}

bool Parser::transparent_directive(const Token& token) const {
  // #else/#elseif/#end that close an #if or a macro only skip or return, so peek() may run them:
  // an expression at the end of a macro body or an #if branch then continues with the caller's
  // tokens. A loop's #end re-evaluates its condition and must wait for pending assignments.
  const std::string& d = token.text;
  if (d == "else" || d == "elseif") return true;
  if (d != "end") return false;
  const Frame& frame = frames_.back();
  if (conds_.size() == frame.cond_base) return frame.macro;
  CondKind kind = conds_.back().kind;
  return kind == CondKind::kIf || kind == CondKind::kSwitch;
}

Tok Parser::next() {
  if (pushback_) {
    Tok tok = std::move(*pushback_);
    pushback_.reset();
    last_ = {tok.file, tok.token.line, tok.token.column};
    return tok;
  }
  for (;;) {
    Frame& frame = frames_.back();
    const Token& token = frame.file->tokens[frame.pos];
    if (token.kind == TokenKind::kEnd) {
      if (frame.macro) fail("macro body without #end");
      if (pop_finished_frame()) continue;
      if (frames_.size() == 1 && !conds_.empty()) {
        fail("an #if, #while or #switch is missing its #end");
      }
      Tok end = resolve(token);
      last_ = {end.file, end.token.line, end.token.column};
      return end;
    }
    ++frame.pos;
    count_token();
    last_ = {&frame.file->name, token.line, token.column};
    if (token.kind == TokenKind::kDirective) {
      directive(token);
      unread_pushback();
      if (pushback_) return next();
      continue;
    }
    Tok tok = resolve(token);
    if (tok.identifier && tok.value.kind == ValueKind::kMacro) {
      call_macro(token, tok.value.macro);
      continue;
    }
    if (tok.identifier && tok.value.kind == ValueKind::kArray) {
      // an element A[i][j] stands for its value wherever an identifier may
      const Token& after = frames_.back().file->tokens[frames_.back().pos];
      if (after.kind == TokenKind::kSymbol && after.text == "[") {
        Value array = std::move(tok.value);
        tok.value = index_array(array);
        last_ = {tok.file, tok.token.line, tok.token.column};
      }
    }
    return tok;
  }
}

const Tok& Parser::peek() {
  if (pushback_) return *pushback_;
  for (;;) {
    Frame& frame = frames_.back();
    const Token& token = frame.file->tokens[frame.pos];
    if (token.kind == TokenKind::kDirective) {
      if (transparent_directive(token)) {
        ++frame.pos;
        count_token();
        last_ = {&frame.file->name, token.line, token.column};
        directive(token);
        unread_pushback();
        continue;
      }
      peeked_directive_ = Tok{};
      peeked_directive_.token = token;
      peeked_directive_.file = &frame.file->name;
      return peeked_directive_;
    }
    if (token.kind == TokenKind::kEnd && pop_finished_frame()) continue;
    // nor is a macro call: it may read identifiers a pending #declare has not assigned yet
    if (token.kind == TokenKind::kWord) {
      Value* value = lookup(token.text);
      if (value && value->kind == ValueKind::kMacro) {
        peeked_directive_ = Tok{};
        peeked_directive_.token = token;
        peeked_directive_.token.kind = TokenKind::kDirective;
        peeked_directive_.file = &frame.file->name;
        return peeked_directive_;
      }
    }
    Place keep = last_;
    pushback_ = next();
    last_ = keep;
    return *pushback_;
  }
}

// A directive's expression may have looked one token past its end (`#include "a.inc" camera`).
// That token goes back to its frame, so that it is read after what the directive started (the
// included file) and resolved after what it assigned.
void Parser::unread_pushback() {
  if (!pushback_) return;
  if (pushback_->token.kind == TokenKind::kEnd) {
    pushback_.reset();  // the end of a file is never consumed: it is met again
    return;
  }
  Frame& frame = frames_.back();
  if (frame.pos == 0 || &frame.file->name != pushback_->file) return;
  const Token& previous = frame.file->tokens[frame.pos - 1];
  if (previous.line != pushback_->token.line || previous.column != pushback_->token.column) return;
  --frame.pos;
  pushback_.reset();
}

void Parser::unget(Tok tok) {
  if (pushback_) fail("internal: two tokens pushed back");
  pushback_ = std::move(tok);
}

static std::string describe(const Tok& tok) {
  switch (tok.token.kind) {
    case TokenKind::kEnd:
      return "the end of the file";
    case TokenKind::kNumber:
      return "a number";
    case TokenKind::kString:
      return "a string";
    case TokenKind::kDirective:
      return "#" + tok.token.text;
    default:
      return "'" + tok.token.text + "'";
  }
}

void Parser::expect(const char* symbol) {
  Tok tok = next();
  if (!tok.symbol(symbol)) fail(std::string("expected '") + symbol + "', found " + describe(tok));
}

bool Parser::accept(const char* symbol) {
  const Tok& tok = peek();
  if (!tok.symbol(symbol)) return false;
  next();
  return true;
}

void Parser::skip_block() {
  expect("{");
  skip_rest_of_block();
}

void Parser::skip_rest_of_block() {
  int depth = 1;
  while (depth > 0) {
    Tok tok = next();
    if (tok.token.kind == TokenKind::kEnd) fail("missing '}'");
    if (tok.symbol("{")) ++depth;
    if (tok.symbol("}")) --depth;
  }
}

void Parser::call_macro(const Token& name, std::shared_ptr<const Macro> macro) {
  if (macro_depth_ >= options_.limits.macro_depth) {
    fail("macro calls nested deeper than " + std::to_string(options_.limits.macro_depth) +
         " (limit)");
  }
  std::string call_site = here().text();
  std::unordered_map<std::string, Value> locals;
  std::vector<std::pair<std::string, std::string>> by_reference;
  expect("(");
  for (size_t i = 0; i < macro->params.size(); ++i) {
    if (i > 0) accept(",");  // POV-Ray reads arguments without a comma after an object
    // A bare identifier is passed by reference (POV-Ray manual 3.3.8.3): #declare on the
    // parameter changes the caller's identifier.
    if (!pushback_) {
      const Frame& frame = frames_.back();
      const Token& a = frame.file->tokens[frame.pos];
      const Token& b = frame.file->tokens[std::min(frame.pos + 1, frame.file->tokens.size() - 1)];
      if (a.kind == TokenKind::kWord && b.kind == TokenKind::kSymbol &&
          (b.text == "," || b.text == ")")) {
        Value* found = lookup(a.text);
        if (found && found->kind != ValueKind::kMacro)
          by_reference.emplace_back(macro->params[i], a.text);
      }
    }
    locals[macro->params[i]] = parse_rvalue();
  }
  expect(")");
  Frame frame;
  frame.file = macro->file;
  frame.pos = macro->body;
  frame.macro = true;
  frame.from = "in macro " + macro->name + " called from " + call_site;
  frame.cond_base = conds_.size();
  frame.scope = scopes_.size();
  frame.folder = frames_.back().folder;
  frame.by_reference = std::move(by_reference);
  scopes_.push_back(std::move(locals));
  frames_.push_back(std::move(frame));
  ++macro_depth_;
  counts().macro_depth = std::max(counts().macro_depth, macro_depth_);
  (void)name;
}

void Parser::end_macro() {
  Frame frame = std::move(frames_.back());
  frames_.pop_back();
  --macro_depth_;
  std::unordered_map<std::string, Value> locals = std::move(scopes_[frame.scope]);
  scopes_.resize(frame.scope);
  for (const auto& [param, caller] : frame.by_reference) {
    auto it = locals.find(param);
    if (it == locals.end()) continue;
    if (Value* target = lookup(caller)) *target = it->second;
  }
}

void Parser::assign(const std::string& name, Value value, bool local) {
  if (value.kind == ValueKind::kString) check_string(value.text);
  if (local) {
    scopes_.back()[name] = std::move(value);
    return;
  }
  // #declare changes a macro parameter or a local where one is visible (so by-reference
  // parameters work), otherwise it makes or changes a global.
  for (size_t i = scopes_.size(); i-- > 1;) {
    auto it = scopes_[i].find(name);
    if (it != scopes_[i].end()) {
      it->second = std::move(value);
      return;
    }
  }
  scopes_[0][name] = std::move(value);
}

void Parser::check_string(const std::string& s) {
  if (s.size() > options_.limits.string_bytes) {
    fail("string longer than " + std::to_string(options_.limits.string_bytes) + " bytes (limit)");
  }
}

std::string Parser::array_limit_message() const {
  return "more than " + std::to_string(options_.limits.array_elements) +
         " array elements in all (limit)";
}

void Parser::count_array_elements(uint64_t n) {
  if (n > options_.limits.array_elements - scene_.counts.array_elements) {
    fail(array_limit_message());
  }
  scene_.counts.array_elements += n;
}

void Parser::count_objects(uint64_t n) {
  scene_.counts.objects += n;
  if (n > options_.limits.objects || scene_.counts.objects > options_.limits.objects) {
    fail("more than " + std::to_string(options_.limits.objects) + " objects or triangles (limit)");
  }
}

// POV-Ray 3.7's rand(): a 32-bit linear congruential generator per seed() stream
// (parser's stream_rand: next = next * 1812433253 + 12345, value = next / 0xFFFFFFFF); checked
// against povray 3.7.0.10: seed(42) gives 0.723582911241, 0.329979259598, 0.755761670357.
uint64_t Parser::next_random(size_t stream) {
  uint32_t& state = random_streams_.at(stream);
  state = state * 1812433253u + 12345u;
  return state;
}

size_t Parser::new_random_stream(double seed) {
  if (random_streams_.size() >= 1'000'000) fail("more than 1000000 seed() streams");
  random_streams_.push_back(static_cast<uint32_t>(static_cast<int64_t>(seed)));
  return random_streams_.size() - 1;
}

}  // namespace sdl
}  // namespace fb::pov
