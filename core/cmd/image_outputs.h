// The last step of `filmback render` and `filmback merge`: the finished image into every output,
// 8-bit ones through the view settings' display transform, with the metadata (docs/cli.md,
// "Colour"). One code path, so that a merged frame's files are the whole render's.
#pragma once

#include <filesystem>
#include <vector>

#include "core/image/display_transform.h"
#include "core/image/image_io.h"
#include "core/image/view_settings.h"
#include "core/util/diagnostics.h"

namespace fb {

// How the outputs show the render: the view settings, and the display transform of 8-bit outputs.
struct OutputView {
  ViewSettings view;
  bool eight_bit = false;    // some output is a PNG or JPEG
  DisplayTransform display;  // made only when eight_bit
  // What the outputs apply, for the EXR's metadata too.
  const ViewSettings& applied() const { return eight_bit ? display.settings() : view; }
};

// UsageError, before anything is rendered or read: an unknown extension, the same file twice, a
// missing folder, a folder named as a file.
void check_outputs(const std::vector<std::filesystem::path>& outputs);

// Made before the render, so that a bad config or name fails at once: only 8-bit outputs need it.
OutputView output_view(const ViewSettings& view, const ViewSettingsOrigin& origin,
                       const std::vector<std::filesystem::path>& outputs,
                       const std::filesystem::path& ocio_config, Diagnostics& diagnostics);

// Every output, or none (write_images), with `metadata` and what the view applies.
void write_outputs(const Image& image, ImageMetadata metadata, const OutputView& view,
                   const std::vector<std::filesystem::path>& outputs);

}  // namespace fb
