// libFuzzer harness: the loader's checks of a plugin's descriptor (core/plugin/descriptor.cpp, the
// code PluginLibrary runs on what a plugin's filmback_plugin_v1() returns), then what a render does
// next with a descriptor that passed: bind its parameters' defaults (BoundParams).
//
// What it covers, honestly: every value the loader interprets (ABI version, sizes, kind, names and
// their characters, version and summary, each parameter's type, default, bounds and choices, the
// function table's size, which functions are missing, the hit record's size) comes from the fuzzer,
// and each pointer is either null or points at memory that really holds what it claims (strings
// end, an array has param_count entries, a table is as large as this filmback's largest). A
// descriptor whose pointers lie cannot be checked by any reader in the same process; such a plugin
// crashes in its own memory, which core/plugin/crash_guard.h reports (tests/plugin_abi). Opening
// the library (dlopen, dlsym) is not fuzzed: its input is an ELF file, glibc's to parse.
#include <fuzzer/FuzzedDataProvider.h>

#include <deque>
#include <string>
#include <vector>

#include <filmback/plugin_abi.h>

#include "core/plugin/descriptor.h"
#include "core/plugin/loader.h"
#include "core/plugin/params.h"

namespace {

void never_called() {}

class DescriptorBuilder {
 public:
  explicit DescriptorBuilder(FuzzedDataProvider& in) : in_(in) {}

  // A string the fuzzer chose (any bytes, NUL-terminated), or null.
  const char* text() {
    if (in_.ConsumeBool()) return nullptr;
    strings_.push_back(in_.ConsumeRandomLengthString(48));
    return strings_.back().c_str();
  }
  // Either the value the loader expects or any other.
  uint32_t number(uint32_t expected) {
    return in_.ConsumeBool() ? expected : in_.ConsumeIntegral<uint32_t>();
  }
  template <typename Function>
  void function(Function& slot) {
    slot = in_.ConsumeBool() ? reinterpret_cast<Function>(&never_called) : nullptr;
  }

  fb_plugin build() {
    fb_plugin p{};
    p.abi_version = number(FB_ABI_VERSION);
    p.struct_size = number(sizeof(fb_plugin));
    p.kind = number(in_.ConsumeIntegralInRange<uint32_t>(FB_KIND_CAMERA, FB_KIND_INTEGRATOR));
    p.name = text();
    p.version = text();
    p.summary = text();
    params_.resize(in_.ConsumeIntegralInRange<size_t>(0, 6));
    for (fb_param_desc& d : params_) {
      d.name = text();
      d.type = number(in_.ConsumeIntegralInRange<uint32_t>(FB_PARAM_FLOAT, FB_PARAM_RGB));
      d.default_value = text();
      d.unit = text();
      d.choices = text();
      d.min_value = in_.ConsumeFloatingPoint<double>();
      d.max_value = in_.ConsumeFloatingPoint<double>();
      d.doc = text();
    }
    p.param_count = uint32_t(params_.size());
    p.params = in_.ConsumeBool() ? nullptr : params_.data();
    switch (in_.ConsumeIntegralInRange(0, 2)) {
      case 0:
        table_.camera.struct_size = number(sizeof(fb_camera_api));
        function(table_.camera.create), function(table_.camera.destroy);
        function(table_.camera.needs), function(table_.camera.generate_rays);
        break;
      case 1:
        table_.filter.struct_size = number(sizeof(fb_filter_api));
        function(table_.filter.create), function(table_.filter.destroy);
        function(table_.filter.radius), function(table_.filter.evaluate);
        function(table_.filter.integral), function(table_.filter.sample);
        break;
      default:
        table_.integrator.struct_size = number(sizeof(fb_integrator_api));
        function(table_.integrator.create), function(table_.integrator.destroy);
        function(table_.integrator.channels), function(table_.integrator.radiance);
        table_.integrator.hit_size = number(sizeof(fb_hit));
        table_.integrator.scene_size = number(sizeof(fb_scene));
        table_.integrator.scene_api_size = number(sizeof(fb_scene_api));
    }
    p.api = in_.ConsumeBool() ? nullptr : &table_;
    return p;
  }

 private:
  FuzzedDataProvider& in_;
  std::deque<std::string> strings_;  // a deque: c_str() stays valid as it grows
  std::vector<fb_param_desc> params_;
  // As large as the largest kind's table, whichever kind the descriptor then claims.
  union {
    fb_camera_api camera;
    fb_filter_api filter;
    fb_integrator_api integrator;
  } table_{};
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  DescriptorBuilder builder(in);
  const fb_plugin descriptor = builder.build();
  fb::PluginDescriptor read;
  if (fb::check_descriptor(&descriptor, read).empty()) {
    // Accepted: its file name can be formed, and its defaults bind (an InputError here would
    // escape and be reported: the checks let through a descriptor a render then refuses).
    fb::plugin_file_name(descriptor.kind, descriptor.name);
    fb::BoundParams bound(read.plugin, {});
  }
  return 0;
}
