#include "importers/pov/sdl/lexer.h"

#include <cctype>
#include <cstdlib>

#include "core/util/error.h"

namespace fb::pov::sdl {
namespace {

bool is_word_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool is_word_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool is_digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

class Lexer {
 public:
  Lexer(const std::string& name, const std::string& source) : name_(name), src_(source) {}

  std::shared_ptr<TokenFile> run() {
    auto file = std::make_shared<TokenFile>();
    file->name = name_;
    for (;;) {
      skip_space_and_comments();
      Token token;
      token.line = line_;
      token.column = column_;
      if (pos_ >= src_.size()) {
        file->tokens.push_back(token);
        return file;
      }
      char c = src_[pos_];
      if (c == '#' && !directive_follows()) {
        advance();  // a '#' with no directive after it is ignored, as POV-Ray does
        continue;
      }
      if (is_digit(c) || (c == '.' && pos_ + 1 < src_.size() && is_digit(src_[pos_ + 1]))) {
        read_number(token);
      } else if (is_word_start(c)) {
        token.kind = TokenKind::kWord;
        token.text = read_word();
      } else if (c == '"') {
        read_string(token);
      } else if (c == '#') {
        advance();
        skip_space_and_comments();
        if (pos_ >= src_.size() || !is_word_start(src_[pos_])) {
          fail(token, "expected a directive after '#'");
        }
        token.kind = TokenKind::kDirective;
        token.text = read_word();
      } else {
        read_symbol(token);
      }
      file->tokens.push_back(std::move(token));
    }
  }

 private:
  [[noreturn]] void fail(const Token& at, const std::string& what) {
    throw_input(name_ + ":" + std::to_string(at.line) + ":" + std::to_string(at.column), "", what);
  }

  bool directive_follows() const {
    size_t p = pos_ + 1;
    while (p < src_.size() && (src_[p] == ' ' || src_[p] == '\t')) ++p;
    return p < src_.size() && is_word_start(src_[p]);
  }

  void advance() {
    if (src_[pos_] == '\n') {
      ++line_;
      column_ = 1;
    } else {
      ++column_;
    }
    ++pos_;
  }

  void skip_space_and_comments() {
    while (pos_ < src_.size()) {
      char c = src_[pos_];
      char n = pos_ + 1 < src_.size() ? src_[pos_ + 1] : '\0';
      if (std::isspace(static_cast<unsigned char>(c)) || c == '\x1a') {
        advance();
      } else if (c == '/' && n == '/') {
        while (pos_ < src_.size() && src_[pos_] != '\n') advance();
      } else if (c == '/' && n == '*') {
        skip_block_comment();
      } else {
        return;
      }
    }
  }

  // POV-Ray nests block comments (manual 3.1.3 "Comments").
  void skip_block_comment() {
    Token start;
    start.line = line_;
    start.column = column_;
    int depth = 0;
    while (pos_ < src_.size()) {
      char c = src_[pos_];
      char n = pos_ + 1 < src_.size() ? src_[pos_ + 1] : '\0';
      if (c == '/' && n == '*') {
        ++depth;
        advance();
        advance();
      } else if (c == '*' && n == '/') {
        advance();
        advance();
        if (--depth == 0) return;
      } else if (c == '/' && n == '/') {
        // a line comment inside a block comment hides a "*/" on its line, as in POV-Ray
        while (pos_ < src_.size() && src_[pos_] != '\n') advance();
      } else {
        advance();
      }
    }
    fail(start, "unterminated /* comment");
  }

  std::string read_word() {
    size_t start = pos_;
    while (pos_ < src_.size() && is_word_char(src_[pos_])) advance();
    return src_.substr(start, pos_ - start);
  }

  void read_number(Token& token) {
    size_t start = pos_;
    while (pos_ < src_.size() && is_digit(src_[pos_])) advance();
    // "1.x" is not a number followed by .x in POV-Ray either; a '.' followed by a digit or not a
    // letter belongs to the number
    if (pos_ < src_.size() && src_[pos_] == '.' &&
        !(pos_ + 1 < src_.size() && is_word_start(src_[pos_ + 1]))) {
      advance();
      while (pos_ < src_.size() && is_digit(src_[pos_])) advance();
    }
    if (pos_ < src_.size() && (src_[pos_] == 'e' || src_[pos_] == 'E')) {
      size_t save = pos_;
      uint32_t save_column = column_;
      advance();
      if (pos_ < src_.size() && (src_[pos_] == '+' || src_[pos_] == '-')) advance();
      if (pos_ < src_.size() && is_digit(src_[pos_])) {
        while (pos_ < src_.size() && is_digit(src_[pos_])) advance();
      } else {
        pos_ = save;
        column_ = save_column;
      }
    }
    token.kind = TokenKind::kNumber;
    token.number = std::strtod(src_.substr(start, pos_ - start).c_str(), nullptr);
  }

  void read_string(Token& token) {
    advance();  // opening quote
    token.kind = TokenKind::kString;
    while (true) {
      if (pos_ >= src_.size() || src_[pos_] == '\n') fail(token, "unterminated string");
      char c = src_[pos_];
      advance();
      if (c == '"') return;
      if (c != '\\' || pos_ >= src_.size()) {
        token.text.push_back(c);
        continue;
      }
      char e = src_[pos_];
      advance();
      switch (e) {
        case 'n': token.text.push_back('\n'); break;
        case 't': token.text.push_back('\t'); break;
        case 'r': token.text.push_back('\r'); break;
        case 'a': token.text.push_back('\a'); break;
        case 'b': token.text.push_back('\b'); break;
        case 'f': token.text.push_back('\f'); break;
        case 'v': token.text.push_back('\v'); break;
        case '0': token.text.push_back('\0'); break;
        default: token.text.push_back(e); break;  // \\ \" \' and unknown escapes: the character
      }
    }
  }

  void read_symbol(Token& token) {
    static const char* const kTwo[] = {"<=", ">=", "!="};
    token.kind = TokenKind::kSymbol;
    for (const char* two : kTwo) {
      if (src_.compare(pos_, 2, two) == 0) {
        token.text = two;
        advance();
        advance();
        return;
      }
    }
    char c = src_[pos_];
    if (std::string("{}()[]<>,;+-*/=!?:.&|'").find(c) == std::string::npos) {
      fail(token, std::string("unexpected character '") + c + "'");
    }
    token.text = std::string(1, c);
    advance();
  }

  std::string name_;
  const std::string& src_;
  size_t pos_ = 0;
  uint32_t line_ = 1, column_ = 1;
};

}  // namespace

std::shared_ptr<TokenFile> tokenize(const std::string& name, const std::string& source) {
  return Lexer(name, source).run();
}

}  // namespace fb::pov::sdl
