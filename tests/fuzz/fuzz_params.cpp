// libFuzzer harness: the one parameter parser (core/plugin/params.cpp) on what a user types after
// --filter, --camera-model or --integrator, bound to a schema with one parameter of every type, and
// the shutter-curve syntax built on it (core/render/shutter.cpp). Beyond the sanitizers, it checks
// what binding promises create(): every number finite and within its declared bounds, every
// choice one of the listed ones.
#include <cmath>
#include <cstdlib>
#include <string>
#include <string_view>

#include <filmback/plugin_abi.h>

#include "core/plugin/params.h"
#include "core/render/shutter.h"
#include "core/util/error.h"

namespace {

const fb_param_desc kParams[] = {
    {"radius", FB_PARAM_FLOAT, "1.5", "px", nullptr, 1e-3, 16, "a bounded float"},
    {"count", FB_PARAM_INT, "3", "", nullptr, 1, 64, "a bounded whole number"},
    {"free", FB_PARAM_FLOAT, "0", "m", nullptr, -HUGE_VAL, HUGE_VAL, "an unbounded float"},
    {"enabled", FB_PARAM_BOOL, "true", "", nullptr, 0, 1, "a switch"},
    {"tint", FB_PARAM_RGB, "[1,0.5,0]", "", nullptr, 0, 10, "a colour"},
    {"mode", FB_PARAM_STRING, "a", "", "a|b|c", 0, 0, "one of three"},
    {"label", FB_PARAM_STRING, "", "", nullptr, 0, 0, "free text"},
};
constexpr uint32_t kCount = sizeof kParams / sizeof kParams[0];
const fb_plugin kPlugin = {FB_ABI_VERSION, sizeof(fb_plugin),          FB_KIND_FILTER, "fuzz",
                           "1.0.0",        "the parser's fuzz target", kParams,        kCount,
                           nullptr};

void check(bool condition) {
  if (!condition) std::abort();  // a finding: binding broke its promise
}

void check_bound(const fb::BoundParams& bound) {
  for (uint32_t i = 0; i < kCount; ++i) {
    const fb_param_desc& d = kParams[i];
    const fb_value& v = bound.values()[i];
    check(v.text != nullptr);
    const int numbers = d.type == FB_PARAM_RGB ? 3 : d.type == FB_PARAM_STRING ? 0 : 1;
    for (int c = 0; c < numbers; ++c)
      check(std::isfinite(v.number[c]) && v.number[c] >= d.min_value && v.number[c] <= d.max_value);
    if (d.type == FB_PARAM_INT) check(v.number[0] == std::floor(v.number[0]));
    if (d.choices) {
      const std::string_view text = v.text, choices = d.choices;
      check(choices == text || choices.starts_with(std::string(text) + "|") ||
            choices.ends_with("|" + std::string(text)) ||
            choices.find("|" + std::string(text) + "|") != std::string_view::npos);
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const fb::PluginSpec spec = fb::parse_plugin_spec(text, "--filter");
    check_bound(fb::BoundParams(kPlugin, spec.settings));
  } catch (const fb::UsageError&) {
  }
  try {
    fb::ShutterCurve::parse(text, "--shutter-curve");
  } catch (const fb::UsageError&) {
  }
  return 0;
}
