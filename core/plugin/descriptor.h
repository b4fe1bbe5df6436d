// The checks a plugin's descriptor must pass before filmback uses it (docs/architecture.md, "The
// plugin ABI"), apart from opening the library: its own file so that the fuzz harness
// (tests/fuzz/fuzz_descriptor.cpp) runs exactly the code the loader runs.
#pragma once

#include <string>

#include <filmback/plugin_abi.h>

namespace fb {

// A plugin's descriptor and function table as this filmback reads them: copies of what the
// plugin's sizes cover, with the fields of layouts newer than the plugin's at their documented
// defaults (plugin_abi.h, "Growth"). Only the table of the plugin's kind is filled.
struct PluginDescriptor {
  fb_plugin plugin{};  // plugin.api still points into the plugin: read the copies below
  fb_camera_api camera{};
  fb_filter_api filter{};
  fb_integrator_api integrator{};  // hit_size, scene_size, scene_api_size as declared or defaulted
};

// Empty when `descriptor` is a well-formed filmback plugin descriptor, and then `read` holds it;
// else the one reason it is not. Each field is read only once the checks before it allow (a
// function table only after its size proved one this filmback reads, and no further than that
// size); the pointers themselves are trusted, since the plugin runs in this process and nothing in
// it can tell a stray pointer from a good one (core/plugin/crash_guard.h reports the crash such a
// pointer causes).
std::string check_descriptor(const fb_plugin* descriptor, PluginDescriptor& read);

}  // namespace fb
