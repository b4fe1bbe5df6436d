#include "core/cmd/render_ini.h"

#include <cmath>

#include "core/cmd/frame_range.h"
#include "core/util/error.h"
#include "core/util/parse_number.h"
#include "importers/pov/pov_ini.h"

namespace fb {
namespace {

// POV-Ray 3.7's defaults: +R3; Debian's povray.ini renders 800x600 (docs/pov.md).
constexpr uint32_t kPovDefaultAntialiasDepth = 3;
constexpr uint32_t kPovDefaultWidth = 800, kPovDefaultHeight = 600;
// Path samples per POV-Ray eye ray: a path tracer also samples the lights, the soft shadows and
// the glossy reflections with them, which POV-Ray computes without noise (a choice, docs/pov.md
// ".ini files"; not yet measured against POV-Ray's images).
constexpr uint32_t kPathSamplesPerPovRay = 16;

// filmback's samples per pixel for POV-Ray's antialiasing: adaptive supersampling at depth d
// splits a pixel into up to d x d rays (POV-Ray 3.7 manual, "Anti-Aliasing Options", method 1);
// filmback samples every pixel at that ceiling.
uint32_t samples_for_pov_antialias(bool antialias, uint32_t depth) {
  return kPathSamplesPerPovRay * (antialias ? depth * depth : 1);
}

}  // namespace

void apply_pov_ini(RenderCommand& c, Diagnostics& diagnostics) {
  const bool scene_is_ini = pov::is_ini_argument(c.scene.string());
  if (scene_is_ini && !c.ini.empty())
    throw UsageError("--ini '" + c.ini + "': the scene '" + c.scene.string() +
                     "' is an .ini already; expected one .ini");
  if (!scene_is_ini && c.ini.empty()) return;
  const auto [file, section] = pov::split_ini_section(scene_is_ini ? c.scene.string() : c.ini);
  const pov::IniOptions ini = pov::read_ini(file, section);
  for (const std::string& warning : ini.warnings)
    diagnostics.warn(warning);
  if (scene_is_ini) {
    if (!ini.input_file)
      throw InputError(file.string() +
                       ": error: no Input_File_Name; expected one, or the scene with --ini");
    c.scene = *ini.input_file;
  }
  if (c.resolution.empty() && (ini.width || ini.height)) {
    // Each side is checked where it is read; their product, as for --res, here.
    const uint32_t width = ini.width.value_or(kPovDefaultWidth);
    const uint32_t height = ini.height.value_or(kPovDefaultHeight);
    if (const uint64_t pixels = uint64_t(width) * height; pixels > kMaxImagePixels)
      throw InputError(file.string() + ": error: Width " + std::to_string(width) + " and Height " +
                       std::to_string(height) + ": " + std::to_string(pixels) +
                       " pixels, expected at most " + std::to_string(kMaxImagePixels));
    c.resolution = std::to_string(width) + "x" + std::to_string(height);
  }
  if (!c.options.samples_per_pixel && ini.antialias)
    c.options.samples_per_pixel = samples_for_pov_antialias(
        *ini.antialias, ini.antialias_depth.value_or(kPovDefaultAntialiasDepth));
  const std::optional<pov::IniFrames> frames = pov::ini_frames(ini, file);
  if (c.frames.empty() && c.frame.empty() && frames) {
    if (frames->last - frames->first >= kMaxFramesInRange)
      throw InputError(file.string() + ": error: frames " + std::to_string(frames->first) + " to " +
                       std::to_string(frames->last) + ": expected at most " +
                       std::to_string(kMaxFramesInRange) +
                       " (Subset_Start_Frame/Subset_End_Frame or --frames choose fewer)");
    c.frames = std::to_string(frames->first) + "-" + std::to_string(frames->last);
  }
  if (c.outputs.empty())
    if (const auto pattern = pov::ini_output_pattern(ini, c.scene)) {
      // --frame N typed: the one frame's name, as POV-Ray names frame N of the sequence.
      const std::optional<double> frame = parse_number(c.frame);
      const bool whole_frame =
          frame && *frame == std::floor(*frame) && std::abs(*frame) <= double(kMaxFrameNumber);
      c.outputs.push_back(whole_frame && is_frame_pattern(*pattern)
                              ? frame_path(*pattern, int64_t(*frame))
                              : *pattern);
    }
  // Searched after -L's, as POV-Ray accumulates +L and Library_Path.
  c.import.library_paths.insert(c.import.library_paths.end(), ini.library_paths.begin(),
                                ini.library_paths.end());
  c.import.pov_declarations = ini.declarations;
  c.import.pov_animation = ini.animation;
  // A still's clock; --clock typed (other than its default 0) wins.
  if (c.import.clock == 0 && ini.clock) c.import.clock = *ini.clock;
}

}  // namespace fb
