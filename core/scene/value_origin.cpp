#include "core/scene/value_origin.h"

#include "core/util/error.h"

namespace fb {

ValueOrigin ValueOrigin::from_file(std::string file, std::string path, std::string how) {
  return {std::move(file), std::move(path), std::move(how)};
}

ValueOrigin ValueOrigin::from_option(std::string option) {
  return {{}, std::move(option), {}};
}

ValueOrigin ValueOrigin::by_default(std::string how) {
  return {{}, {}, std::move(how)};
}

std::string ValueOrigin::text() const {
  if (typed()) return path;
  if (file.empty()) return "default" + (how.empty() ? std::string() : " (" + how + ")");
  return file + (path.empty() ? "" : ": " + path) + (how.empty() ? "" : " (" + how + ")");
}

void ValueOrigin::fail(std::string_view what) const {
  if (typed()) throw UsageError(path + ": " + std::string(what));
  if (file.empty()) throw InputError(text() + ": " + std::string(what));
  throw_input(file, path, what);
}

}  // namespace fb
