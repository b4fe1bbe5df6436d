// Warnings about what an importer or the render skipped. Each distinct message is kept once with
// a count, and the whole list is printed once (docs/conventions.md, "Errors").
#pragma once

#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace fb {

class Diagnostics {
 public:
  void warn(const std::string& message);
  size_t count() const { return order_.size(); }
  const std::vector<std::string>& messages() const { return order_; }
  void print(std::ostream& out) const;

 private:
  std::vector<std::string> order_;
  std::map<std::string, int> repeats_;
};

}  // namespace fb
