#include "core/util/error.h"

#include <cstdio>

namespace fb {

std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

std::string located(std::string_view file, std::string_view where, std::string_view what) {
  std::string message;
  for (std::string_view part : {file, where}) {
    if (part.empty()) continue;
    message.append(part);
    message.append(": ");
  }
  message.append(what);
  return message;
}

}  // namespace fb
