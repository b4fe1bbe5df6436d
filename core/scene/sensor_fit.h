// Blender's sensor-fit words ("auto", "horizontal", "vertical") and the fb_camera_setup values
// they stand for: the one table the glTF readers and writer, the command line (--sensor-fit) and
// `filmback info` read.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace fb {

// "auto" for any value that is not a known fit.
const char* sensor_fit_name(uint32_t fit);

// The fit a word names, in any letter case (Blender's Python writes 'AUTO'); nullopt otherwise.
std::optional<uint32_t> sensor_fit_named(std::string_view word);

// "auto, horizontal or vertical", for messages that say what was expected.
std::string sensor_fit_choices();

}  // namespace fb
