// How an 8-bit output's values are made from a render's scene-linear RGB (docs/conventions.md,
// "Images"). With a view transform this is Blender 3.4's pipeline for saving a render: scene
// linear times 2^exposure, the look and the display's view through OpenColorIO, display values
// raised to 1/gamma (intern/opencolorio/ocio_impl.cc, createDisplayProcessor), then Blender's
// dither and rounding to 8 bits (byte_quantize.h). Without one it is the plain sRGB curve
// (IEC 61966-2-1) with the same exposure, gamma, dither and rounding.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/image/image.h"
#include "core/image/view_settings.h"
#include "core/util/diagnostics.h"

namespace fb {

// Where the view settings' names came from. An unknown name typed on the command line is a usage
// error listing the config's names; one read from the scene file is a warning, and Blender's own
// fallback is used (the config's default display, the display's default view, no look), as
// Blender does when it opens a file made with another config.
struct ViewSettingsOrigin {
  std::string file, json_path;  // of the object that names them, for warnings about its names
  bool display_typed = false, view_typed = false, look_typed = false;
};

class DisplayTransform {
 public:
  // The plain sRGB curve, values clamped, no exposure, gamma or dither.
  DisplayTransform();

  // The transform for `settings`. A view transform needs an OpenColorIO config
  // (ocio_config_search.h: `ocio_config` is --ocio-config, empty for none). Throws InputError
  // when a config the user named cannot be loaded or applied, UsageError for an unknown name
  // typed on the command line. Without a config, or when Blender's cannot be loaded, it warns
  // and uses the sRGB curve (exposure, gamma and dither still applied).
  static DisplayTransform create(const ViewSettings& settings, const ViewSettingsOrigin& origin,
                                 const std::filesystem::path& ocio_config,
                                 Diagnostics& diagnostics);

  // The image's first three channels (missing ones read as 0) as 8-bit RGB, top row first.
  std::vector<uint8_t> encode(const Image& image) const;

  // What encode() does, in words, for the file's `filmback/transfer` attribute.
  const std::string& description() const { return description_; }
  // The settings applied: the display, view and look after any fallback.
  const ViewSettings& settings() const { return settings_; }
  // Whether the values are for an sRGB display (so the file may say it is sRGB).
  bool srgb_encoded() const { return settings_.display_device == "sRGB"; }

 private:
  struct Ocio;
  std::shared_ptr<const Ocio> ocio_;  // none: the sRGB curve
  ViewSettings settings_;             // as applied (display, view and look after any fallback)
  std::string description_;
};

}  // namespace fb
