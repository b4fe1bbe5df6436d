// POV-Ray SDL tokens: the whole file is tokenised once, so #while/#macro can jump back by index.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace fb::pov::sdl {

enum class TokenKind : uint8_t {
  kEnd,         // end of file
  kNumber,      // `number`
  kString,      // `text` holds the decoded string
  kWord,        // identifier or reserved word, in `text`
  kDirective,   // `#word`: `text` holds the word
  kSymbol,      // punctuation in `text`: { } ( ) [ ] < > , ; + - * / = ! ? : . & | <= >= !=
};

struct Token {
  TokenKind kind = TokenKind::kEnd;
  std::string text;
  double number = 0;
  uint32_t line = 0, column = 0;
};

// One source file, tokenised. `name` is the file as messages show it.
struct TokenFile {
  std::string name;
  std::vector<Token> tokens;  // always ends with a kEnd token
};

// Tokenises `source`; comments (`//`, nested `/* */`) are dropped. Throws fb::InputError with
// "name:line:column" for an unterminated string or comment or a character POV-Ray does not know.
std::shared_ptr<TokenFile> tokenize(const std::string& name, const std::string& source);

}  // namespace fb::pov::sdl
