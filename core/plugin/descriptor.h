// The checks a plugin's descriptor must pass before filmback uses it (docs/architecture.md, "The
// plugin ABI"), apart from opening the library: its own file so that the fuzz harness
// (tests/fuzz/fuzz_descriptor.cpp) runs exactly the code the loader runs.
#pragma once

#include <string>

#include <filmback/plugin_abi.h>

namespace fb {

// Empty when `descriptor` is a well-formed filmback plugin descriptor, else the one reason it is
// not. Each field is read only once the checks before it allow (a function table only after its
// size matched this filmback's); the pointers themselves are trusted, since the plugin runs in this
// process and nothing in it can tell a stray pointer from a good one (core/plugin/crash_guard.h
// reports the crash such a pointer causes).
std::string check_descriptor(const fb_plugin* descriptor);

}  // namespace fb
