// The one error reporter. Messages follow docs/conventions.md: "file: where: what was found,
// what was expected" (JSON path or line:column for `where`), and map to the exit status:
// 1 for bad input (files, plugins), 2 for bad usage (what was typed on the command line).
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace fb {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A number as a message shows it: shortest of fixed or exponent form, 6 significant digits.
std::string number_text(double value);

// "file: where: what", dropping empty parts.
std::string located(std::string_view file, std::string_view where, std::string_view what);

[[noreturn]] inline void throw_input(std::string_view file, std::string_view where,
                                     std::string_view what) {
  throw InputError(located(file, where, what));
}

}  // namespace fb
