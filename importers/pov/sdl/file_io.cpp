// File I/O: #fopen, #read and #write. Files opened for writing live in memory for the rest of the
// evaluation (a scene may write a file and read it back); nothing is written to disk, and files
// are read only inside the scene's folder.
#include "importers/pov/sdl/parser.h"

namespace fb::pov::sdl {

void Parser::run_fopen() {
  Token name = raw_next();
  if (name.kind != TokenKind::kWord) fail("expected a file identifier after #fopen");
  Value file_name = parse_expression();
  if (file_name.kind != ValueKind::kString) fail("#fopen expects a file name string");
  Tok mode = next();
  Value handle;
  handle.kind = ValueKind::kFile;
  if (mode.word("write") || mode.word("append")) {
    // written in memory only, for #read later in the same scene (fileio.pov writes a file and
    // reads it back); nothing reaches the disk
    std::string& text = written_files_[file_name.text];
    if (mode.word("write")) text.clear();
    handle.text = file_name.text;
    assign(name.text, std::move(handle), false);
    return;
  }
  if (!mode.word("read")) fail("expected read, write or append");
  handle.file = std::make_shared<ReadFile>();
  if (auto written = written_files_.find(file_name.text); written != written_files_.end()) {
    handle.file->tokens = tokenize(file_name.text, written->second);
  } else {
    auto path = resolve_include(file_name.text, nullptr, true);
    if (!path) {
      fail("cannot #fopen \"" + file_name.text + "\" for reading inside the scene's folder");
    }
    handle.file->tokens = load(*path, file_name.text);
  }
  assign(name.text, std::move(handle), false);
}

// #write (File, values ...): strings as they are, floats and vectors as POV-Ray 3.7 writes them
// (%g, vectors as <x,y,z>), appended to the file's text in memory.
void Parser::run_write() {
  expect("(");
  Token handle_name = raw_next();
  Value* handle = lookup(handle_name.text);
  if (!handle || handle->kind != ValueKind::kFile || handle->file) {
    fail("#write needs a file opened for writing");
  }
  std::string& text = written_files_[handle->text];
  for (;;) {
    accept(",");  // POV-Ray also takes `#write (File "text")`
    if (accept(")")) break;
    Value value = parse_expression();
    if (value.kind == ValueKind::kString) {
      text += value.text;
    } else if (value.kind == ValueKind::kFloat) {
      text += number_string(value.v[0]);
    } else if (value.numeric()) {
      text += "<";
      for (int i = 0; i < value.dims; ++i) {
        if (i > 0) text += ',';
        text += number_string(value.v[i]);
      }
      text += ">";
    } else {
      fail("#write writes strings, floats and vectors");
    }
    if (text.size() > 64 * options_.limits.string_bytes) {
      fail("#write: file longer than " + std::to_string(64 * options_.limits.string_bytes) +
           " bytes (limit)");
    }
  }
}

// #read (File, A, B ...): each identifier takes the next comma-separated value of the file; at
// the end of the file the handle becomes undefined (POV-Ray's `#while (defined(File))` idiom).
void Parser::run_read() {
  expect("(");
  Token handle_name = raw_next();
  Value* handle = lookup(handle_name.text);
  if (!handle || handle->kind != ValueKind::kFile || !handle->file)
    fail("#read needs a file opened for reading");
  std::shared_ptr<ReadFile> file = handle->file;
  const std::vector<Token>& tokens = file->tokens->tokens;
  while (accept(",")) {
    Token target = raw_next();
    if (target.kind != TokenKind::kWord) fail("expected an identifier in #read");
    while (file->pos < tokens.size() && tokens[file->pos].kind == TokenKind::kSymbol &&
           tokens[file->pos].text == ",") {
      ++file->pos;
    }
    if (tokens[file->pos].kind == TokenKind::kEnd) break;
    const Token& t = tokens[file->pos];
    Value value;
    auto read_number = [&]() -> double {
      double sign = 1;
      while (tokens[file->pos].kind == TokenKind::kSymbol && tokens[file->pos].text == "-") {
        sign = -sign;
        ++file->pos;
      }
      if (tokens[file->pos].kind != TokenKind::kNumber) fail("#read: expected a number");
      return sign * tokens[file->pos++].number;
    };
    if (t.kind == TokenKind::kString) {
      value = Value::string(t.text);
      ++file->pos;
    } else if (t.kind == TokenKind::kSymbol && t.text == "<") {
      ++file->pos;
      value.kind = ValueKind::kVector;
      value.dims = 0;
      for (;;) {
        if (value.dims == 5) fail("#read: vector with more than 5 components");
        value.v[value.dims++] = read_number();
        const Token& sep = tokens[file->pos++];
        if (sep.kind == TokenKind::kSymbol && sep.text == ">") break;
        if (!(sep.kind == TokenKind::kSymbol && sep.text == ",")) fail("#read: bad vector");
      }
    } else {
      value = Value::number(read_number());
    }
    assign(target.text, std::move(value), false);
  }
  expect(")");
  while (file->pos < tokens.size() && tokens[file->pos].kind == TokenKind::kSymbol &&
         tokens[file->pos].text == ",") {
    ++file->pos;
  }
  if (tokens[file->pos].kind == TokenKind::kEnd) {
    for (auto& scope : scopes_)
      scope.erase(handle_name.text);
  }
}

}  // namespace fb::pov::sdl
