#include "core/util/diagnostics.h"

namespace fb {

void Diagnostics::warn(const std::string& message) {
  if (repeats_[message]++ == 0) order_.push_back(message);
}

void Diagnostics::print(std::ostream& out) const {
  for (const std::string& message : order_) {
    out << "warning: " << message;
    if (const int n = repeats_.at(message); n > 1) out << " (" << n << " times)";
    out << '\n';
  }
}

}  // namespace fb
