// The front end's commands. Each returns the process exit status; errors are thrown as
// InputError (1) or UsageError (2) and reported by main().
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/cmd/render_part.h"
#include "core/render/render_job.h"
#include "importers/import_scene.h"

namespace fb {

struct RenderCommand {
  std::filesystem::path scene;  // .gltf, .glb, .pov, or a POV-Ray .ini naming its scene
  std::string ini;  // --ini: a POV-Ray .ini ("FILE" or "FILE[Section]") beside a .pov scene
  // The .ini's warnings (unknown options), filled by run_render: reported with every frame's.
  std::vector<std::string> ini_warnings;
  std::vector<std::filesystem::path> outputs;
  std::string resolution;  // "WxH"
  std::string background;  // "r,g,b" or one grey value
  // How samples become pixels: "importance" or "splat" (docs/filters.md).
  std::string reconstruction = "importance";
  std::string subdiv = "render";       // or "adaptive" (docs/cli.md)
  std::string sampler;                 // a SamplerKind's name; empty: the default
  std::string light_sampler = "auto";  // "auto", "tree" or "power" (docs/cli.md)
  std::string passes;                  // --passes: Blender pass names, comma-separated, as typed
  // The physical camera and shutter, as typed (parsed and checked by run_render).
  std::string focal_length, fstop, focus_distance, sensor, sensor_fit, shift;
  std::string shutter, rolling_shutter, frame, fps, sensor_model, iso;
  // The view settings of 8-bit outputs (docs/cli.md, "Colour"): each replaces the shot's. Names
  // as typed; numbers as typed, parsed by run_render.
  std::optional<std::string> view_transform, look, display;
  std::string exposure, gamma, dither;
  std::filesystem::path ocio_config;
  std::string memory_limit;  // "8G"; empty: half of the machine's memory
  unsigned threads = 0;      // 0: all cores
  bool quiet = false;
  std::string progress_every;  // --progress-every: a duration; empty: the default reporting
  // Interrupts and checkpoints (docs/cli.md): a duration ("5m"), the checkpoint file (default
  // next to the first output), whether to continue from it; and the --stats-json file.
  std::string checkpoint_every;
  std::filesystem::path checkpoint;
  bool resume = false;
  std::filesystem::path stats_json;
  // The live image (docs/cli.md, "--preview"): an EXR written this often while rendering; both
  // or neither.
  std::filesystem::path preview;
  std::string preview_every;
  // A frame sequence (docs/cli.md, "Frame sequences"): "A-B[:STEP]" or "N" as typed; empty: one
  // frame. `overwrite`: render again the frames whose outputs are all there.
  std::string frames;
  bool overwrite = false;
  PartRequest part;  // --tile/--crop/--tile-plan: one part of the frame, a partial film
  RenderOptions options;
  ImportOptions import;  // its resolution is filled from --res by run_render
};

// A filmback-made scene file from any scene filmback reads (docs/cli.md "convert").
struct ConvertCommand {
  std::filesystem::path input, output;
  std::string resolution;  // "WxH": what a POV-Ray scene's image_width/image_height read
  // Chord error of tessellated analytic shapes, m; unset: a thousandth of each shape's size.
  std::optional<double> tolerance_m;
  ImportOptions import;
};

// `filmback bench` (docs/cli.md "bench"): every scene at every sample count and configuration
// (samplers x filters), errors against references, times, memory; optionally Cycles beside it.
struct BenchCommand {
  std::vector<std::filesystem::path> scenes;  // .gltf, .glb, .pov; Blender shots .blend, .py
  std::filesystem::path output;               // the report folder
  std::vector<uint32_t> spp{1, 2, 4, 8, 16, 32, 64, 128, 256};
  std::vector<std::string> samplers;              // names; none: the default
  std::vector<std::string> filters;               // one plugin spec per --filter; none: the scene's
  std::vector<std::filesystem::path> references;  // one per scene, or none
  std::optional<uint32_t> reference_spp;          // none: 16 x the highest of `spp`
  std::string resolution;                         // "WxH"; empty: each scene's
  std::optional<double> target_error;
  std::string against;  // "cycles", or empty
  uint64_t seed = 0;
  uint32_t seeds = 1;                       // measured renders per point: seed, seed + 1, ...
  std::vector<double> adaptive_thresholds;  // none: adaptive sampling off (0) only
  unsigned threads = 0;                     // 0: all cores
  ImportOptions import;
  std::string command_line;  // as typed, for the report
};

// The most pixels an image may have: 268 Mpx, 16K x 16K.
constexpr uint64_t kMaxImagePixels = uint64_t(1) << 28;

// "WxH" as typed after --res, each side 1..32768 and at most kMaxImagePixels (UsageError).
std::pair<uint32_t, uint32_t> parse_resolution(const std::string& text);

int run_render(RenderCommand& command);
// `filmback merge PARTS... -o OUT...` (docs/cli.md, "Parts of a render").
struct MergeCommand {
  std::vector<std::filesystem::path> parts, outputs;
  std::filesystem::path ocio_config;
};
int run_merge(const MergeCommand& command);
// `camera`: list only that camera (a UsageError naming the cameras there are when absent);
// `camera_model`: plan with that camera plugin, as --camera-model of render.
int run_info(const std::filesystem::path& scene, const ImportOptions& options,
             const std::optional<std::string>& camera,
             const std::optional<std::string>& camera_model);
int run_convert(ConvertCommand& command);
int run_plugins();
int run_bench(BenchCommand& command);

}  // namespace fb
