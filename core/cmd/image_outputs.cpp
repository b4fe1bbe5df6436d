#include "core/cmd/image_outputs.h"

#include <algorithm>

#include "core/util/error.h"

namespace fb {
namespace {

// What an 8-bit output of this render applies (Blender's would), in the EXR's metadata too
// (docs/conventions.md, "Images"); nothing for a shot that names no view and changes nothing.
void add_view_metadata(const ViewSettings& v, ImageMetadata& m) {
  const ViewSettings defaults;
  if (!v.names_view() && v.exposure_stops == 0 && v.gamma == 1 && v.dither_intensity == 0 &&
      v.look == defaults.look && v.display_device == defaults.display_device)
    return;
  m.strings.insert(m.strings.end(), {{"filmback/display_device", v.display_device},
                                     {"filmback/view_transform", v.view_transform},
                                     {"filmback/look", v.look}});
  m.floats.insert(m.floats.end(), {{"filmback/exposure_stops", float(v.exposure_stops)},
                                   {"filmback/gamma", float(v.gamma)},
                                   {"filmback/dither_intensity", float(v.dither_intensity)}});
}

}  // namespace

void check_outputs(const std::vector<std::filesystem::path>& outputs) {
  for (size_t i = 0; i < outputs.size(); ++i) {
    const std::filesystem::path& out = outputs[i];
    image_format_for(out);
    for (size_t j = 0; j < i; ++j)
      if (std::filesystem::weakly_canonical(outputs[j]) == std::filesystem::weakly_canonical(out))
        throw UsageError("output '" + out.string() + "': the same file as output '" +
                         outputs[j].string() + "'");
    const std::filesystem::path folder = out.has_parent_path() ? out.parent_path() : ".";
    if (!std::filesystem::is_directory(folder))
      throw UsageError("output '" + out.string() + "': the folder '" + folder.string() +
                       "' does not exist");
    // Checked before rendering: failing at the second write would leave the first output behind.
    if (std::filesystem::is_directory(out))
      throw UsageError("output '" + out.string() + "': is a folder, expected an image file name");
  }
}

OutputView output_view(const ViewSettings& view, const ViewSettingsOrigin& origin,
                       const std::vector<std::filesystem::path>& outputs,
                       const std::filesystem::path& ocio_config, Diagnostics& diagnostics) {
  OutputView out;
  out.view = view;
  out.eight_bit = std::any_of(outputs.begin(), outputs.end(), [](const auto& output) {
    return is_8_bit(image_format_for(output));
  });
  if (out.eight_bit) out.display = DisplayTransform::create(view, origin, ocio_config, diagnostics);
  return out;
}

void write_outputs(const Image& image, ImageMetadata metadata, const OutputView& view,
                   const std::vector<std::filesystem::path>& outputs) {
  add_view_metadata(view.applied(), metadata);
  write_images(image, outputs, metadata, view.display);
}

}  // namespace fb
