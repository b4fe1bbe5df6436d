#include "core/plugin/params.h"

#include <cmath>
#include <optional>
#include <sstream>

#include "core/util/error.h"
#include "core/util/parse_number.h"

namespace fb {
namespace {

std::vector<std::string_view> split_top_level(std::string_view text, char separator) {
  std::vector<std::string_view> parts;
  int depth = 0;
  size_t start = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '[') ++depth;
    if (text[i] == ']') --depth;
    if (text[i] == separator && depth == 0) {
      parts.push_back(text.substr(start, i - start));
      start = i + 1;
    }
  }
  parts.push_back(text.substr(start));
  return parts;
}

bool is_identifier(std::string_view s) {
  if (s.empty()) return false;
  for (char c : s)
    if (!(std::islower(static_cast<unsigned char>(c)) ||
          std::isdigit(static_cast<unsigned char>(c)) || c == '_' || c == '-'))
      return false;
  return true;
}

std::string describe_bounds(const fb_param_desc& desc) {
  std::ostringstream out;
  if (std::isfinite(desc.min_value) && std::isfinite(desc.max_value))
    out << " in [" << desc.min_value << ", " << desc.max_value << "]";
  else if (std::isfinite(desc.min_value))
    out << " >= " << desc.min_value;
  else if (std::isfinite(desc.max_value))
    out << " <= " << desc.max_value;
  return out.str();
}

}  // namespace

PluginSpec parse_plugin_spec(std::string_view text, std::string_view option) {
  auto bad = [&](std::string_view what) -> UsageError {
    return UsageError(std::string(option) + " '" + std::string(text) + "': " + std::string(what));
  };
  PluginSpec spec;
  const size_t colon = text.find(':');
  spec.name = std::string(text.substr(0, colon));
  if (!is_identifier(spec.name))
    throw bad("expected a plugin name (lower-case letters, digits, '_') before any ':'");
  if (colon == std::string_view::npos) return spec;
  for (std::string_view item : split_top_level(text.substr(colon + 1), ',')) {
    const size_t eq = item.find('=');
    if (eq == std::string_view::npos || eq == 0)
      throw bad("expected key=value, found '" + std::string(item) + "'");
    spec.settings.emplace_back(std::string(item.substr(0, eq)), std::string(item.substr(eq + 1)));
  }
  return spec;
}

std::string parse_param_value(const fb_param_desc& desc, std::string_view text, fb_value& value) {
  value = fb_value{};
  switch (desc.type) {
    case FB_PARAM_FLOAT:
    case FB_PARAM_INT: {
      const std::optional<double> number = parse_number(text);
      const bool whole = desc.type == FB_PARAM_INT;
      if (!number || (whole && *number != std::floor(*number)))
        return whole ? "a whole number" : "a finite number";
      const double x = *number;
      if (x < desc.min_value || x > desc.max_value)
        return std::string(whole ? "a whole number" : "a number") + describe_bounds(desc);
      value.number[0] = x;
      return {};
    }
    case FB_PARAM_BOOL:
      if (text == "true" || text == "1" || text == "yes" || text == "on")
        value.number[0] = 1;
      else if (text != "false" && text != "0" && text != "no" && text != "off")
        return "true or false";
      return {};
    case FB_PARAM_RGB: {
      std::string_view inner = text;
      const bool bracketed = text.size() >= 2 && text.front() == '[' && text.back() == ']';
      if (bracketed) inner = text.substr(1, text.size() - 2);
      const auto parts = split_top_level(inner, ',');
      if ((parts.size() != 1 && parts.size() != 3) || (parts.size() == 3 && !bracketed))
        return "a colour: one number, or [r,g,b]";
      for (size_t i = 0; i < 3; ++i) {
        const std::optional<double> x = parse_number(parts[parts.size() == 1 ? 0 : i]);
        if (!x) return "a colour: one number, or [r,g,b]";
        if (*x < desc.min_value || *x > desc.max_value)
          return "colour components" + describe_bounds(desc);
        value.number[i] = *x;
      }
      return {};
    }
    case FB_PARAM_STRING: {
      if (!desc.choices) return {};
      for (std::string_view choice : split_top_level(desc.choices, '|'))
        if (choice == text) return {};
      return std::string("one of ") + desc.choices;
    }
  }
  return "a parameter of a known type";
}

BoundParams::BoundParams(const fb_plugin& plugin,
                         const std::vector<std::pair<std::string, std::string>>& settings) {
  std::vector<std::string_view> given(plugin.param_count);
  for (const auto& [key, text] : settings) {
    uint32_t index = 0;
    while (index < plugin.param_count && key != plugin.params[index].name)
      ++index;
    if (index == plugin.param_count) {
      std::string known;
      for (uint32_t i = 0; i < plugin.param_count; ++i)
        known += (i ? ", " : "") + std::string(plugin.params[i].name);
      throw UsageError("unknown parameter '" + key + "' (" +
                       (known.empty() ? "it takes no parameters" : "expected one of: " + known) +
                       ")");
    }
    if (given[index].data()) throw UsageError("parameter '" + key + "' given twice");
    given[index] = text;
  }
  values_.resize(plugin.param_count);
  texts_.resize(plugin.param_count);
  for (uint32_t i = 0; i < plugin.param_count; ++i) {
    const fb_param_desc& desc = plugin.params[i];
    const bool user = given[i].data() != nullptr;
    texts_[i] = std::string(user ? given[i] : std::string_view(desc.default_value));
    if (std::string expected = parse_param_value(desc, texts_[i], values_[i]); !expected.empty()) {
      const std::string what =
          "parameter '" + std::string(desc.name) + "' = '" + texts_[i] + "': expected " + expected;
      if (user) throw UsageError(what);
      throw InputError(std::string(plugin.name) + ": its default " + what);
    }
  }
  for (uint32_t i = 0; i < plugin.param_count; ++i)
    values_[i].text = texts_[i].c_str();
}

std::string BoundParams::set_number(const fb_plugin& plugin, std::string_view key, double x) {
  for (uint32_t i = 0; i < plugin.param_count; ++i) {
    const fb_param_desc& desc = plugin.params[i];
    if (key != desc.name) continue;
    const bool whole = desc.type == FB_PARAM_INT;
    if (desc.type != FB_PARAM_FLOAT && !whole) return "a parameter of type float or int";
    if (!std::isfinite(x) || (whole && x != std::floor(x)))
      return whole ? "a whole number" : "a finite number";
    if (x < desc.min_value || x > desc.max_value)
      return std::string(whole ? "a whole number" : "a number") + describe_bounds(desc);
    values_[i] = fb_value{{x, 0, 0}, ""};  // no text: the value was never text
    texts_[i].clear();
    return {};
  }
  return "a parameter the plugin has";
}

const char* param_type_name(uint32_t type) {
  switch (type) {
    case FB_PARAM_FLOAT:
      return "float";
    case FB_PARAM_INT:
      return "int";
    case FB_PARAM_BOOL:
      return "bool";
    case FB_PARAM_STRING:
      return "string";
    case FB_PARAM_RGB:
      return "rgb";
  }
  return "unknown";
}

}  // namespace fb
