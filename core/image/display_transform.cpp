#include "core/image/display_transform.h"

#include <OpenColorIO/OpenColorIO.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "core/image/byte_quantize.h"
#include "core/image/ocio_config_search.h"
#include "core/util/error.h"

namespace fb {

namespace OCIO = OCIO_NAMESPACE;

struct DisplayTransform::Ocio {
  OCIO::ConstCPUProcessorRcPtr processor;  // immutable: apply() is safe from any thread
};

namespace {

namespace fs = std::filesystem;

// Rows converted together: a bound on the working copy, which is RGBA float as OpenColorIO and
// Blender take it.
constexpr uint32_t kRowsPerTask = 64;

// IEC 61966-2-1 sRGB transfer function.
float srgb_encode(float linear) {
  const float v = std::clamp(linear, 0.f, 1.f);
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.f / 2.4f) - 0.055f;
}

// Blender's scale and exponent, computed in float as it computes them (colormanagement.cc,
// create_display_buffer_processor): 2^exposure, and 1/gamma with gamma at least FLT_EPSILON.
float exposure_scale(const ViewSettings& s) {
  return s.exposure_stops == 0 ? 1.f : std::pow(2.f, float(s.exposure_stops));
}
float gamma_exponent(const ViewSettings& s) {
  return s.gamma == 1 ? 1.f : 1.f / std::max(FLT_EPSILON, float(s.gamma));
}

std::string quoted_list(const std::vector<std::string>& names) {
  std::string out;
  for (size_t i = 0; i < names.size(); ++i)
    out += (i ? ", '" : "'") + names[i] + "'";
  return out;
}

std::string paths_list(const std::vector<fs::path>& paths) {
  std::vector<std::string> names;
  for (const fs::path& p : paths)
    names.push_back(p.string());
  return quoted_list(names);
}

std::vector<std::string> displays_of(const OCIO::ConstConfigRcPtr& config) {
  std::vector<std::string> out;
  for (int i = 0; i < config->getNumDisplays(); ++i)
    out.push_back(config->getDisplay(i));
  return out;
}
std::vector<std::string> views_of(const OCIO::ConstConfigRcPtr& config,
                                  const std::string& display) {
  std::vector<std::string> out;
  for (int i = 0; i < config->getNumViews(display.c_str()); ++i)
    out.push_back(config->getView(display.c_str(), i));
  return out;
}
// Blender lists "None" first, then the config's looks (colormanage_load_config).
std::vector<std::string> looks_of(const OCIO::ConstConfigRcPtr& config) {
  std::vector<std::string> out{"None"};
  for (int i = 0; i < config->getNumLooks(); ++i)
    out.push_back(config->getLookNameByIndex(i));
  return out;
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

// `name` if the config has it; else a usage error when it was typed, or a warning about the file
// and `fallback`.
std::string resolve(const std::string& name, const std::vector<std::string>& valid, bool typed,
                    const char* option, const char* key, const std::string& what,
                    const std::string& fallback, const ViewSettingsOrigin& origin,
                    const fs::path& config_file, Diagnostics& diagnostics) {
  if (contains(valid, name)) return name;
  const std::string expected = "expected " + what + ": " + quoted_list(valid) +
                               " (OpenColorIO config '" + config_file.string() + "')";
  if (typed) throw UsageError(std::string(option) + " '" + name + "': " + expected);
  diagnostics.warn(
      located(origin.file, origin.json_path.empty() ? key : origin.json_path + "." + key,
              "'" + name + "': " + expected + "; using '" + fallback + "' as Blender does"));
  return fallback;
}

// Blender's display processor (intern/opencolorio/ocio_impl.cc, createDisplayProcessor): exposure
// as a scale in scene linear, the look into its process space, the display's view with its own
// looks bypassed when one was applied, then the exponent on display values.
OCIO::ConstCPUProcessorRcPtr blender_display_processor(const OCIO::ConstConfigRcPtr& config,
                                                       const ViewSettings& s) {
  OCIO::GroupTransformRcPtr group = OCIO::GroupTransform::Create();
  std::string input = OCIO::ROLE_SCENE_LINEAR;  // what a render's float buffer is in
  if (const float scale = exposure_scale(s); scale != 1.f) {
    OCIO::ColorSpaceTransformRcPtr to_linear = OCIO::ColorSpaceTransform::Create();
    to_linear->setSrc(input.c_str());
    to_linear->setDst(OCIO::ROLE_SCENE_LINEAR);
    group->appendTransform(to_linear);
    OCIO::MatrixTransformRcPtr gain = OCIO::MatrixTransform::Create();
    const double m[16] = {scale, 0, 0, 0, 0, scale, 0, 0, 0, 0, scale, 0, 0, 0, 0, 1};
    gain->setMatrix(m);
    group->appendTransform(gain);
  }
  bool use_look = s.look != "None" && !s.look.empty();
  if (use_look) {
    const char* look_space = OCIO::LookTransform::GetLooksResultColorSpace(
        config, config->getCurrentContext(), s.look.c_str());
    if (look_space && *look_space) {
      OCIO::LookTransformRcPtr look = OCIO::LookTransform::Create();
      look->setSrc(input.c_str());
      look->setDst(look_space);
      look->setLooks(s.look.c_str());
      group->appendTransform(look);
      input = look_space;
    } else {
      use_look = false;  // an empty look has no result space: nothing to apply
    }
  }
  OCIO::DisplayViewTransformRcPtr view = OCIO::DisplayViewTransform::Create();
  view->setSrc(input.c_str());
  view->setLooksBypass(use_look);
  view->setView(s.view_transform.c_str());
  view->setDisplay(s.display_device.c_str());
  group->appendTransform(view);
  if (const double e = gamma_exponent(s); e != 1.0) {
    OCIO::ExponentTransformRcPtr power = OCIO::ExponentTransform::Create();
    const double value[4] = {e, e, e, 1.0};
    power->setValue(value);
    group->appendTransform(power);
  }
  return config->getProcessor(group)->getDefaultCPUProcessor();
}

std::string settings_text(const ViewSettings& s) {
  return "exposure " + number_text(s.exposure_stops) + " stops, gamma " + number_text(s.gamma) +
         ", Blender 3.4's rounding to 8 bits with dither " + number_text(s.dither_intensity);
}

std::string curve_description(const ViewSettings& s) {
  return "sRGB transfer function (IEC 61966-2-1), values clamped to [0,1]; " + settings_text(s);
}

}  // namespace

DisplayTransform::DisplayTransform() : description_(curve_description(settings_)) {}

DisplayTransform DisplayTransform::create(const ViewSettings& settings,
                                          const ViewSettingsOrigin& origin,
                                          const fs::path& ocio_config, Diagnostics& diagnostics) {
  DisplayTransform t;
  t.settings_ = settings;
  t.description_ = curve_description(settings);
  if (!settings.names_view()) {
    if (settings.look != "None")
      diagnostics.warn("look '" + settings.look +
                       "' without a view transform: not applied (8-bit outputs use the plain sRGB "
                       "curve)");
    return t;
  }
  const auto fall_back = [&](const std::string& why) {
    diagnostics.warn(why + ": 8-bit outputs use the plain sRGB curve, without view transform '" +
                     settings.view_transform + "' and look '" + settings.look +
                     "' (exposure, gamma and dither still apply)");
    t.description_ += "; in place of view transform '" + settings.view_transform + "', look '" +
                      settings.look + "': " + why;
    return t;
  };
  std::vector<fs::path> searched;
  const std::optional<OcioConfigChoice> choice = choose_ocio_config(ocio_config, searched);
  if (!choice)
    return fall_back("no OpenColorIO config (no --ocio-config, no $OCIO, and no Blender's among " +
                     paths_list(searched) + ")");
  const std::string file = choice->file.string();
  const auto failed = [&](const std::string& what) {
    if (choice->named_by_user)
      throw InputError(
          located(file, "", "the OpenColorIO config (" + choice->origin + ") " + what));
    return fall_back("Blender's OpenColorIO config '" + file + "' " + what);
  };
  OCIO::ConstConfigRcPtr config;
  try {
    config = OCIO::Config::CreateFromFile(file.c_str());
  } catch (const OCIO::Exception& e) {
    return failed(std::string("cannot be loaded: ") + e.what());
  }
  ViewSettings& s = t.settings_;
  s.display_device = resolve(s.display_device, displays_of(config), origin.display_typed,
                             "--display", "display_device", "a display",
                             config->getDefaultDisplay(), origin, file, diagnostics);
  s.view_transform =
      resolve(s.view_transform, views_of(config, s.display_device), origin.view_typed,
              "--view-transform", "view_transform", "a view of display '" + s.display_device + "'",
              config->getDefaultView(s.display_device.c_str()), origin, file, diagnostics);
  s.look = resolve(s.look, looks_of(config), origin.look_typed, "--look", "look", "a look", "None",
                   origin, file, diagnostics);
  try {
    t.ocio_ = std::make_shared<const Ocio>(Ocio{blender_display_processor(config, s)});
  } catch (const OCIO::Exception& e) {
    return failed(std::string("cannot make the view transform: ") + e.what());
  }
  t.description_ = "OpenColorIO config '" + file + "' (" + choice->origin + "): display '" +
                   s.display_device + "', view '" + s.view_transform + "', look '" + s.look +
                   "'; " + settings_text(s);
  return t;
}

std::vector<uint8_t> DisplayTransform::encode(const Image& image) const {
  const uint32_t width = image.width, height = image.height;
  const size_t n = image.channels.size();
  std::vector<uint8_t> out(size_t(width) * height * 3);
  const float scale = exposure_scale(settings_), exponent = gamma_exponent(settings_);
  const float dither = float(settings_.dither_intensity);
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, height, kRowsPerTask),
                    [&](const tbb::blocked_range<uint32_t>& rows) {
                      std::vector<float> rgba(size_t(width) * rows.size() * 4);
                      for (uint32_t y = rows.begin(); y < rows.end(); ++y)
                        for (uint32_t x = 0; x < width; ++x) {
                          float* p = &rgba[(size_t(y - rows.begin()) * width + x) * 4];
                          const size_t i = size_t(y) * width + x;
                          for (size_t c = 0; c < 3; ++c)
                            p[c] = c < n ? image.pixels[i * n + c] : 0.f;
                          p[3] = 1.f;
                        }
                      if (ocio_) {
                        OCIO::PackedImageDesc desc(rgba.data(), long(width), long(rows.size()), 4);
                        ocio_->processor->apply(desc);
                      } else {
                        for (size_t k = 0; k < rgba.size(); k += 4)
                          for (size_t c = 0; c < 3; ++c) {
                            const float v = srgb_encode(rgba[k + c] * scale);
                            rgba[k + c] = exponent == 1.f ? v : std::pow(v, exponent);
                          }
                      }
                      for (uint32_t y = rows.begin(); y < rows.end(); ++y)
                        for (uint32_t x = 0; x < width; ++x) {
                          const float offset =
                              blender_dither_offset(x, height - 1 - y, width, height, dither);
                          const float* p = &rgba[(size_t(y - rows.begin()) * width + x) * 4];
                          uint8_t* o = &out[(size_t(y) * width + x) * 3];
                          for (size_t c = 0; c < 3; ++c)
                            o[c] = unit_float_to_byte(offset + p[c]);
                        }
                    });
  return out;
}

}  // namespace fb
