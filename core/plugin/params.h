// The one parameter parser: "name:key=value,key=value" on the command line, each plugin's own
// default values, and --background all go through here (docs/plugins.md).
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <filmback/plugin_abi.h>

namespace fb {

struct PluginSpec {
  std::string name;
  std::vector<std::pair<std::string, std::string>> settings;  // in the order given
};

// "gaussian:radius=1.5,sigma=0.5"; values may be bracketed lists: "background=[0.1,0.2,0.3]".
// Throws UsageError naming `option` (e.g. "--filter") on malformed text.
PluginSpec parse_plugin_spec(std::string_view text, std::string_view option);

// Parses one value as `desc` says, checking bounds and choices. Returns an empty string on success,
// else what was expected. On success `value` holds the number(s); strings are left to the caller.
std::string parse_param_value(const fb_param_desc& desc, std::string_view text, fb_value& value);

// Validated values for create(), in schema order, with defaults filled in.
class BoundParams {
 public:
  // Throws UsageError for an unknown key, a repeated key or a bad value (the caller adds which
  // option it came from), InputError for a default the plugin itself got wrong.
  BoundParams(const fb_plugin& plugin,
              const std::vector<std::pair<std::string, std::string>>& settings);
  BoundParams(const BoundParams&) = delete;
  BoundParams& operator=(const BoundParams&) = delete;
  // Sets the number parameter `key` from typed data (a scene's value, never printed and parsed
  // back), checking its type and bounds. Returns an empty string on success, else what was
  // expected.
  std::string set_number(const fb_plugin& plugin, std::string_view key, double x);
  const fb_value* data() const { return values_.empty() ? nullptr : values_.data(); }
  const std::vector<fb_value>& values() const { return values_; }

 private:
  std::vector<fb_value> values_;
  std::vector<std::string> texts_;  // owns what values_[i].text points to
};

const char* param_type_name(uint32_t type);

}  // namespace fb
