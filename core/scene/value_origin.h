// Where a shot value came from: a scene file and the JSON path of the value, a command-line option,
// or a default. `filmback info` prints it, and every error about the value names it: one from a
// file is bad input (exit 1), one typed as an option bad usage (exit 2; docs/conventions.md).
#pragma once

#include <string>
#include <string_view>

namespace fb {

struct ValueOrigin {
  std::string file;  // the scene file; empty for an option or a default
  std::string path;  // the JSON path in `file`, or the option ("--fstop"); empty for a default
  std::string how;   // how the value was derived when not read as is; empty when read as is

  static ValueOrigin from_file(std::string file, std::string path, std::string how = {});
  static ValueOrigin from_option(std::string option);
  static ValueOrigin by_default(std::string how);

  bool typed() const { return file.empty() && !path.empty(); }
  // "shot.gltf: cameras[0].extensions.FILMBACK_blender.fstop", "--fstop", "default (why)".
  std::string text() const;
  // Throws the error this value's origin calls for: UsageError "--option: what" for an option,
  // else InputError "file: path: what".
  [[noreturn]] void fail(std::string_view what) const;
};

// A number under the name of the plugin parameter it is for, with where it came from: a shot's
// lens values, a panorama's field of view, a filter's width. Typed data, never printed and parsed
// back.
struct NamedNumber {
  std::string key;
  double value = 0;
  ValueOrigin origin;  // the scene value (file and JSON path) or option it came from
  // The plugin must declare it: a value that changes where things land (a tracked lens
  // distortion) is never dropped by a plugin without the parameter.
  bool required = false;
};

}  // namespace fb
