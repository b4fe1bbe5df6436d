// Conveniences for writing a plugin in C++. Everything here is inline: a plugin links nothing of
// filmback's, it only includes headers (docs/plugins.md).
#pragma once

#include <cstdarg>
#include <cstdio>
#include <new>
#include <utility>

#include "plugin_abi.h"

namespace fb {

// printf-style one-line reason for a failed create().
inline int fail(fb_error_buffer error, const char* format, ...) {
  if (error.text && error.capacity > 0) {
    va_list args;
    va_start(args, format);
    std::vsnprintf(error.text, error.capacity, format, args);
    va_end(args);
  }
  return 1;
}

// create() for a class constructible from its validated parameters; no exception leaves it.
template <typename T, typename... Args>
int create_instance(void** instance, fb_error_buffer error, Args&&... args) {
  try {
    *instance = new T(std::forward<Args>(args)...);
    return 0;
  } catch (const std::exception& e) {
    return fail(error, "%s", e.what());
  } catch (...) {
    return fail(error, "unknown error while creating the plugin instance");
  }
}

template <typename T>
void destroy_instance(void* instance) {
  delete static_cast<T*>(instance);
}

}  // namespace fb
