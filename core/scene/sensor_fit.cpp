#include "core/scene/sensor_fit.h"

#include <cctype>
#include <iterator>
#include <utility>

#include <filmback/plugin_abi.h>

namespace fb {
namespace {

constexpr std::pair<uint32_t, const char*> kSensorFits[] = {
    {FB_SENSOR_FIT_AUTO, "auto"},
    {FB_SENSOR_FIT_HORIZONTAL, "horizontal"},
    {FB_SENSOR_FIT_VERTICAL, "vertical"},
};

bool same_word_any_case(std::string_view word, std::string_view lower_case) {
  if (word.size() != lower_case.size()) return false;
  for (size_t i = 0; i < word.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(word[i])) != lower_case[i]) return false;
  return true;
}

}  // namespace

const char* sensor_fit_name(uint32_t fit) {
  for (const auto& [value, name] : kSensorFits)
    if (value == fit) return name;
  return kSensorFits[0].second;
}

std::optional<uint32_t> sensor_fit_named(std::string_view word) {
  for (const auto& [value, name] : kSensorFits)
    if (same_word_any_case(word, name)) return value;
  return std::nullopt;
}

std::string sensor_fit_choices() {
  std::string choices;
  for (size_t i = 0; i < std::size(kSensorFits); ++i) {
    if (i > 0) choices += i + 1 == std::size(kSensorFits) ? " or " : ", ";
    choices += kSensorFits[i].second;
  }
  return choices;
}

}  // namespace fb
