// Directives: #declare/#local/#undef, #if/#ifdef/#ifndef/#else/#elseif, #while/#for, #switch,
// #macro, #include, #default, #version, #debug/#warning/#error, #fclose (#fopen, #read and #write:
// file_io.cpp).
#include <cmath>
#include <cstdio>

#include "importers/pov/sdl/keyword_table.h"
#include "importers/pov/sdl/parser.h"

namespace fb::pov::sdl {
namespace {

bool opens_block(const std::string& d) {
  return d == "if" || d == "ifdef" || d == "ifndef" || d == "while" || d == "for" ||
         d == "switch" || d == "macro";
}

}  // namespace

bool Parser::parse_condition() {
  expect("(");
  Value value = parse_expression();
  expect(")");
  if (value.kind != ValueKind::kFloat) fail("expected a float condition");
  return std::abs(value.v[0]) > 1e-10;  // POV-Ray's "true": |x| > EPSILON
}

// Skips raw tokens of the current frame until the #end that closes `levels` open blocks.
void Parser::skip_levels(int levels) {
  int depth = levels;
  for (;;) {
    Token token = raw_next();
    if (token.kind == TokenKind::kEnd) fail("missing #end");
    if (token.kind != TokenKind::kDirective) continue;
    if (opens_block(token.text)) ++depth;
    if (token.text == "end" && --depth == 0) return;
  }
}

// After a false #if/#ifdef/#elseif: skips to the branch that runs (#else, a true #elseif) or past
// the #end. A branch that runs pushes its kIf.
void Parser::skip_to_branch(bool) {
  int depth = 0;
  for (;;) {
    Token token = raw_next();
    if (token.kind == TokenKind::kEnd) fail("#if without #end");
    if (token.kind != TokenKind::kDirective) continue;
    if (opens_block(token.text)) {
      ++depth;
    } else if (token.text == "end") {
      if (depth-- == 0) return;
    } else if (depth == 0 && token.text == "else") {
      conds_.emplace_back();  // a kIf
      return;
    } else if (depth == 0 && token.text == "elseif") {
      if (parse_condition()) {
        conds_.emplace_back();  // a kIf
        return;
      }
    }
  }
}

// #switch looking for its #case/#range/#else: skips raw tokens, testing each label.
void Parser::run_switch_search() {
  int depth = 0;
  for (;;) {
    Token token = raw_next();
    if (token.kind == TokenKind::kEnd) fail("#switch without #end");
    if (token.kind != TokenKind::kDirective) continue;
    if (opens_block(token.text)) {
      ++depth;
      continue;
    }
    if (token.text == "end") {
      if (depth-- == 0) {
        conds_.pop_back();
        return;
      }
      continue;
    }
    if (depth > 0) continue;
    Cond& cond = conds_.back();
    if (token.text == "else") {
      cond.switch_running = true;
      return;
    }
    if (token.text == "case") {
      expect("(");
      double value = parse_float();
      expect(")");
      if (std::abs(value - cond.switch_value) < 1e-10) {
        conds_.back().switch_running = true;
        return;
      }
    } else if (token.text == "range") {
      expect("(");
      double low = parse_float();
      expect(",");
      double high = parse_float();
      expect(")");
      if (cond.switch_value >= low && cond.switch_value <= high) {
        conds_.back().switch_running = true;
        return;
      }
    }
  }
}

void Parser::skip_parenthesised() {
  expect("(");
  int depth = 1;
  while (depth > 0) {
    Tok tok = next();
    if (tok.token.kind == TokenKind::kEnd) fail("missing ')'");
    if (tok.symbol("(")) ++depth;
    if (tok.symbol(")")) --depth;
  }
}

void Parser::run_end() {
  Frame& frame = frames_.back();
  if (conds_.size() == frame.cond_base) {
    if (frame.macro) return end_macro();
    fail("#end without #if, #while, #switch or #macro");
  }
  Cond& cond = conds_.back();
  auto count_loop = [&] {
    if (++counts().loop_iterations > options_.limits.loop_iterations) {
      fail("more than " + std::to_string(options_.limits.loop_iterations) +
           " loop iterations (limit)");
    }
  };
  switch (cond.kind) {
    case CondKind::kIf:
    case CondKind::kSwitch:
      conds_.pop_back();
      return;
    case CondKind::kWhile:
      count_loop();
      frame.pos = cond.loop_pos;  // back to the #while, which tests again
      conds_.pop_back();
      return;
    case CondKind::kFor: {
      count_loop();
      Value* variable = lookup(cond.variable);
      if (!variable || variable->kind != ValueKind::kFloat) fail("#for variable changed its type");
      double value = variable->v[0] + cond.step;
      *variable = Value::number(value);
      if (cond.step > 0 ? value <= cond.end + 1e-10 : value >= cond.end - 1e-10) {
        frame.pos = cond.loop_pos;
      } else {
        conds_.pop_back();
      }
      return;
    }
  }
}

void Parser::run_declare(bool local) {
  Token name = raw_next();
  if (name.kind == TokenKind::kWord && name.text == "deprecated") {
    // 3.7: #declare deprecated [once] "message" Name = ...
    if (raw().kind == TokenKind::kWord && raw().text == "once") raw_next();
    if (raw().kind == TokenKind::kString) raw_next();
    name = raw_next();
  }
  if (name.kind != TokenKind::kWord) fail("expected an identifier after #declare");
  Value* existing = lookup(name.text);
  // #declare A[i][j] = ...
  if (existing && existing->kind == ValueKind::kArray && raw().kind == TokenKind::kSymbol &&
      raw().text == "[") {
    std::shared_ptr<ArrayValue> array = existing->array;
    size_t index = 0;
    for (size_t d = 0; d < array->sizes.size(); ++d) {
      expect("[");
      double i = parse_float();
      expect("]");
      if (!(i >= 0 && i < static_cast<double>(array->sizes[d]))) {
        fail("array index " + std::to_string(static_cast<long long>(i)) + " out of range 0.." +
             std::to_string(array->sizes[d] - 1));
      }
      index = index * array->sizes[d] + static_cast<size_t>(i);
    }
    expect("=");
    Value value = parse_rvalue();
    accept(";");
    if (value.kind == ValueKind::kString) check_string(value.text);
    array->elements[index] = std::move(value);
    return;
  }
  expect("=");
  // a macro called on the right may still be running when the value ends (`#local A = M();`
  // with a ';' inside M): the identifier belongs to the scope the directive was written in
  size_t scope = scopes_.size() - 1;
  Value value = parse_rvalue();
  accept(";");
  if (value.kind == ValueKind::kNone) fail("nothing to declare");
  if (local && scope < scopes_.size()) {
    if (value.kind == ValueKind::kString) check_string(value.text);
    scopes_[scope][name.text] = std::move(value);
    return;
  }
  assign(name.text, std::move(value), local);
}

void Parser::run_include() {
  Value name = parse_expression();
  if (name.kind != ValueKind::kString) fail("#include expects a file name string");
  if (include_depth_ >= options_.limits.include_depth) {
    fail("includes nested deeper than " + std::to_string(options_.limits.include_depth) +
         " (limit)");
  }
  if (std::filesystem::path(name.text).is_absolute())
    fail("cannot include \"" + name.text +
         "\": an absolute path is refused (files are read only from the scene's folder and the "
         "library paths)");
  std::filesystem::path folder;
  auto path = resolve_include(name.text, &folder, false);
  if (!path) {
    fail("cannot include \"" + name.text +
         "\": not found in the scene's folder or a library path (paths leaving those folders, "
         "through '..' or a symbolic link, are refused)");
  }
  std::string display = path->lexically_relative(scene_folder_.lexically_normal()).string();
  if (display.empty() || display.rfind("..", 0) == 0) display = path->string();
  std::string from = "included from " + here().text();
  unread_pushback();
  Frame frame;
  frame.file = load(*path, display);
  frame.from = from;
  frame.cond_base = conds_.size();
  frame.scope = scopes_.size();
  frame.folder = folder;
  scopes_.emplace_back();
  frames_.push_back(std::move(frame));
  ++include_depth_;
  counts().include_depth = std::max(counts().include_depth, include_depth_);
}

void Parser::run_macro_definition() {
  Token name = raw_next();
  if (name.kind != TokenKind::kWord) fail("expected the macro's name");
  auto macro = std::make_shared<Macro>();
  macro->name = name.text;
  macro->where = here();
  macro->file = frames_.back().file;
  Token open = raw_next();
  if (!(open.kind == TokenKind::kSymbol && open.text == "(")) fail("expected '(' after macro name");
  for (;;) {
    Token token = raw_next();
    if (token.kind == TokenKind::kSymbol && token.text == ")") break;
    if (token.kind == TokenKind::kSymbol && token.text == ",") continue;
    if (token.kind == TokenKind::kWord && token.text == "optional") continue;
    if (token.kind != TokenKind::kWord) fail("expected a macro parameter name");
    macro->params.push_back(token.text);
  }
  macro->body = frames_.back().pos;
  skip_levels(1);
  Value value;
  value.kind = ValueKind::kMacro;
  value.macro = macro;
  scopes_[0][name.text] = std::move(value);  // macros are global (POV-Ray manual 3.3.8)
}

void Parser::directive(const Token& token) {
  // A directive met while another one reads its arguments runs inside it (`#case (1 #case (...`):
  // that recursion counts towards the nesting limit like an expression's, or a hostile scene
  // would overflow the stack (found by tests/fuzz/fuzz_pov.cpp).
  Nesting guard(*this);
  // Peeking past the end of the directive's own file must not pop it: a file that includes itself
  // would pop and push one frame for ever instead of nesting to the include limit.
  struct Restore {
    size_t& frames;
    size_t saved;
    ~Restore() { frames = saved; }
  } restore{directive_frames_, directive_frames_};
  directive_frames_ = frames_.size();
  run_directive(token);
}

// The directives by name, one line each (POV-Ray 3.7 reference, "Language Directives"); each
// family's handler reads its own arguments. The lambdas are written inside a member, so they reach
// the private handlers.
void Parser::run_directive(const Token& token) {
  struct Entry {
    std::string_view name;
    void (*run)(Parser&, const std::string& which);
  };
  using P = Parser&;
  using W = const std::string&;
  static constexpr Entry kDirectives[] = {
      {"declare", [](P p, W) { p.run_declare(false); }},
      {"local", [](P p, W) { p.run_declare(true); }},
      {"if", [](P p, W) { p.run_if(); }},
      {"ifdef", [](P p, W) { p.run_ifdef(true); }},
      {"ifndef", [](P p, W) { p.run_ifdef(false); }},
      {"else", [](P p, W which) { p.run_else(which); }},
      {"elseif", [](P p, W which) { p.run_else(which); }},
      {"end", [](P p, W) { p.run_end(); }},
      {"while", [](P p, W) { p.run_while(); }},
      {"for", [](P p, W) { p.run_for(); }},
      {"switch", [](P p, W) { p.run_switch(); }},
      {"case", [](P p, W which) { p.run_case(which); }},
      {"range", [](P p, W which) { p.run_case(which); }},
      {"break", [](P p, W) { p.run_break(); }},
      {"macro", [](P p, W) { p.run_macro_definition(); }},
      {"include", [](P p, W) { p.run_include(); }},
      {"undef", [](P p, W) { p.run_undef(); }},
      {"version", [](P p, W) { p.run_version(); }},
      {"debug", [](P p, W which) { p.run_message(which); }},
      {"warning", [](P p, W which) { p.run_message(which); }},
      {"error", [](P p, W which) { p.run_message(which); }},
      {"render", [](P p, W which) { p.run_message(which); }},
      {"statistics", [](P p, W which) { p.run_message(which); }},
      {"default", [](P p, W) { p.run_default(); }},
      {"fopen", [](P p, W) { p.run_fopen(); }},
      {"fclose", [](P p, W) { p.run_fclose(); }},
      {"read", [](P p, W) { p.run_read(); }},
      {"write", [](P p, W) { p.run_write(); }},
  };
  const std::string& which = token.text;
  if (const Entry* entry = find_keyword(kDirectives, which)) return entry->run(*this, which);
  fail("unknown directive #" + which);
}

void Parser::run_if() {
  if (parse_condition()) {
    conds_.emplace_back();  // a kIf
  } else {
    skip_to_branch(true);
  }
}

// #ifdef (A) / #ifdef (A[i]...): the name is read raw, since a lookup would fail on it.
void Parser::run_ifdef(bool runs_if_defined) {
  expect("(");
  Token name = raw_next();
  bool defined = name.kind == TokenKind::kWord && lookup(name.text) != nullptr;
  if (defined && raw().kind == TokenKind::kSymbol && raw().text == "[") {
    Value* array = lookup(name.text);
    size_t index = 0;
    bool inside = array->kind == ValueKind::kArray;
    for (size_t dim = 0; inside && dim < array->array->sizes.size(); ++dim) {
      expect("[");
      double i = parse_float();
      expect("]");
      inside = i >= 0 && i < static_cast<double>(array->array->sizes[dim]);
      if (inside) index = index * array->array->sizes[dim] + static_cast<size_t>(i);
    }
    defined = inside && array->array->elements[index].has_value();
  }
  expect(")");
  if (defined == runs_if_defined) {
    conds_.emplace_back();  // a kIf
  } else {
    skip_to_branch(true);
  }
}

// #else / #elseif reached from a branch that ran: skips the rest up to the #end.
void Parser::run_else(const std::string& which) {
  if (conds_.size() == frames_.back().cond_base) fail("#" + which + " without #if");
  Cond& cond = conds_.back();
  if (which == "elseif" && cond.kind != CondKind::kIf) fail("#elseif without #if");
  conds_.pop_back();
  skip_levels(1);
}

void Parser::run_while() {
  size_t at = frames_.back().pos - 1;
  if (parse_condition()) {
    Cond cond;
    cond.kind = CondKind::kWhile;
    cond.loop_pos = at;
    conds_.push_back(cond);
  } else {
    skip_levels(1);
  }
}

// #for (Variable, Start, End [, Step]): the body runs while Variable has not passed End.
void Parser::run_for() {
  expect("(");
  Token variable = raw_next();
  if (variable.kind != TokenKind::kWord) fail("expected the #for variable");
  expect(",");
  double start = parse_float();
  expect(",");
  double end = parse_float();
  double step = accept(",") ? parse_float() : 1;
  expect(")");
  if (step == 0) fail("#for step 0 never ends");
  assign(variable.text, Value::number(start), false);
  if (step > 0 ? start <= end : start >= end) {
    Cond cond;
    cond.kind = CondKind::kFor;
    cond.loop_pos = frames_.back().pos;
    cond.variable = variable.text;
    cond.end = end;
    cond.step = step;
    conds_.push_back(cond);
  } else {
    skip_levels(1);
  }
}

void Parser::run_switch() {
  expect("(");
  Cond cond;
  cond.kind = CondKind::kSwitch;
  cond.switch_value = parse_float();
  expect(")");
  conds_.push_back(cond);
  run_switch_search();
}

// #case / #range met while a case runs: falls through (POV-Ray runs on to #break).
void Parser::run_case(const std::string& which) {
  if (conds_.size() == frames_.back().cond_base || conds_.back().kind != CondKind::kSwitch) {
    fail("#" + which + " outside #switch");
  }
  skip_parenthesised();
}

// Leaves the innermost #switch, #while or #for.
void Parser::run_break() {
  int levels = 0;
  for (size_t i = conds_.size(); i-- > frames_.back().cond_base;) {
    ++levels;
    if (conds_[i].kind != CondKind::kIf) {
      conds_.resize(i);
      return skip_levels(levels);
    }
  }
  fail("#break outside #switch, #while or #for");
}

void Parser::run_undef() {
  Token name = raw_next();
  for (size_t i = scopes_.size(); i-- > 0;) {
    if (scopes_[i].erase(name.text)) break;
  }
}

void Parser::run_version() {
  double version = parse_float();
  accept(";");
  scene_.version = version;
  Value v = Value::number(version);
  scopes_[0]["version"] = v;
}

// #debug, #warning, #error, #render, #statistics: only #warning and #error have an effect here.
void Parser::run_message(const std::string& which) {
  Value text = parse_expression();
  if (text.kind != ValueKind::kString) fail("#" + which + " expects a string");
  if (which == "warning") warn(text.text);
  if (which == "error") fail("#error: " + text.text);
}

// #default { texture | pigment | finish | normal ... }.
void Parser::run_default() {
  expect("{");
  for (;;) {
    Tok tok = next();
    if (tok.symbol("}")) break;
    if (tok.word("texture")) {
      default_texture_ = parse_texture();
    } else if (tok.word("pigment")) {
      default_texture_.pigment = parse_pigment();
    } else if (tok.word("finish")) {
      default_texture_.finish = parse_finish(default_texture_.finish);
    } else if (tok.word("normal")) {
      default_texture_.normal = parse_normal();
    } else {
      fail("expected texture, pigment, finish or normal in #default");
    }
  }
}

void Parser::run_fclose() {
  Token name = raw_next();
  for (auto& scope : scopes_)
    scope.erase(name.text);
}

}  // namespace fb::pov::sdl
