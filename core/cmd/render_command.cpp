#include <tbb/global_control.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <optional>

#include "core/cmd/commands.h"
#include "core/cmd/frame_sequence.h"
#include "core/cmd/image_outputs.h"
#include "core/cmd/interrupts.h"
#include "core/cmd/passes_option.h"
#include "core/cmd/render_ini.h"
#include "core/cmd/render_report.h"
#include "core/film/checkpoint.h"
#include "core/image/image_io.h"
#include "core/math/random.h"
#include "core/plugin/loader.h"
#include "core/plugin/params.h"
#include "core/render/memory_estimate.h"
#include "core/util/error.h"
#include "core/util/parse_number.h"
#include "importers/import_scene.h"

namespace fb {
namespace {

constexpr uint32_t kMaxSidePx = 32768;

uint32_t parse_side(std::string_view text, std::string_view whole) {
  uint32_t v = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || ptr != text.data() + text.size() || v == 0 || v > kMaxSidePx)
    throw UsageError("--res '" + std::string(whole) + "': expected WxH with each side from 1 to " +
                     std::to_string(kMaxSidePx) + " pixels");
  return v;
}

// Same syntax and checks as an rgb plugin parameter: one grey value, or r,g,b.
Rgb parse_background(const std::string& text) {
  const fb_param_desc desc{"background", FB_PARAM_RGB, "0", "W/sr/m^2", nullptr, 0, HUGE_VAL, ""};
  fb_value value;
  const std::string bracketed = text.find(',') == std::string::npos ? text : "[" + text + "]";
  if (std::string expected = parse_param_value(desc, bracketed, value); !expected.empty())
    throw UsageError("--background '" + text + "': expected " + expected);
  return Rgb(float(value.number[0]), float(value.number[1]), float(value.number[2]));
}

// "X<sep>Y" as two finite numbers, each in [lo, hi].
Vec2d parse_pair(const std::string& text, char separator, const char* option, double lo,
                 double hi) {
  const size_t at = text.find(separator);
  double v[2];
  const std::string_view parts[2] = {
      std::string_view(text).substr(0, at),
      at == std::string::npos ? std::string_view() : std::string_view(text).substr(at + 1)};
  for (int i = 0; i < 2; ++i) {
    const std::optional<double> number = parse_number(parts[i]);
    v[i] = number.value_or(NAN);
    if (at == std::string::npos || !(v[i] >= lo && v[i] <= hi))
      throw UsageError(std::string(option) + " '" + text + "': expected two numbers in [" +
                       number_text(lo) + ", " + number_text(hi) + "] separated by '" + separator +
                       "'");
  }
  return {v[0], v[1]};
}

// One number in [lo, hi]; "inf" is accepted when hi is infinite.
double option_number(const std::string& text, const char* option, double lo, double hi) {
  if (text == "inf" && std::isinf(hi)) return HUGE_VAL;
  const double v = parse_number(text).value_or(NAN);
  if (!(v >= lo && v <= hi))
    throw UsageError(std::string(option) + " '" + text + "': expected a number in [" +
                     number_text(lo) + ", " + number_text(hi) + "]");
  return v;
}

// The physical camera, shutter and sensor typed on the command line (docs/cli.md).
void parse_physical(const RenderCommand& c, RenderOptions& o) {
  CameraOverrides& cam = o.camera_overrides;
  if (!c.focal_length.empty())
    cam.focal_length_mm = option_number(c.focal_length, "--focal-length", 1e-3, 1e5);
  if (!c.fstop.empty()) {
    // "inf" as well as 0 for no aperture, as --shutter's "inf" (docs/cli.md).
    const std::optional<double> n = c.fstop == "inf" ? HUGE_VAL : parse_number(c.fstop);
    cam.fstop = n ? fstop_from(*n) : std::nullopt;
    if (!cam.fstop) throw UsageError("--fstop '" + c.fstop + "': " + kFstopExpected);
  }
  if (!c.focus_distance.empty())
    cam.focus_distance_m = option_number(c.focus_distance, "--focus-distance", 1e-6, HUGE_VAL);
  if (!c.sensor.empty()) cam.sensor_mm = parse_pair(c.sensor, 'x', "--sensor", 1e-3, 1e4);
  if (!c.shift.empty()) cam.shift = parse_pair(c.shift, ',', "--shift", -100, 100);
  if (!c.sensor_fit.empty()) {
    cam.sensor_fit = sensor_fit_named(c.sensor_fit);
    if (!cam.sensor_fit)
      throw UsageError("--sensor-fit '" + c.sensor_fit + "': expected " + sensor_fit_choices());
  }
  if (!c.shutter.empty()) {
    o.shutter_s = parse_pair(c.shutter, ',', "--shutter", -1e6, 1e6);
    if (o.shutter_s->y < o.shutter_s->x)
      throw UsageError("--shutter '" + c.shutter + "': expected OPEN,CLOSE with CLOSE >= OPEN");
  }
  if (c.rolling_shutter == "none")
    o.rolling_shutter = std::optional<RollingShutter>();
  else if (!c.rolling_shutter.empty())
    o.rolling_shutter = RollingShutter{option_number(c.rolling_shutter, "--rolling-shutter", 0, 1)};
  if (!c.frame.empty()) o.frame = option_number(c.frame, "--frame", -1e9, 1e9);
  if (!c.fps.empty()) o.fps = option_number(c.fps, "--fps", 1e-3, 1e6);
  if (!c.sensor_model.empty()) {
    if (c.sensor_model == "simple")
      o.sensor_model = FB_SENSOR_SIMPLE;
    else if (c.sensor_model == "physical")
      o.sensor_model = FB_SENSOR_PHYSICAL;
    else
      throw UsageError("--sensor-model '" + c.sensor_model + "': expected simple or physical");
  }
  if (!c.iso.empty()) o.iso = option_number(c.iso, "--iso", 1, 1e7);
}

// The command line's numbers for 8-bit outputs, checked before the scene is read.
struct ViewOverrides {
  std::optional<double> exposure_stops, gamma, dither_intensity;
};

// Blender's ranges (its RNA): exposure -32..32 stops, gamma 0..5, dither 0..2.
ViewOverrides parse_view_overrides(const RenderCommand& c) {
  ViewOverrides o;
  if (!c.exposure.empty()) o.exposure_stops = option_number(c.exposure, "--exposure", -32, 32);
  if (!c.gamma.empty()) o.gamma = option_number(c.gamma, "--gamma", 0, 5);
  if (!c.dither.empty()) o.dither_intensity = option_number(c.dither, "--dither", 0, 2);
  return o;
}

// The shot's view settings with what the command line replaces, and where each name came from.
std::pair<ViewSettings, ViewSettingsOrigin> view_settings(const RenderCommand& c,
                                                          const ViewOverrides& o,
                                                          const Scene& scene) {
  ViewSettings v = scene.settings.view;
  ViewSettingsOrigin origin{scene.file.string(), scene.settings.view_json_path};
  if (c.view_transform) v.view_transform = *c.view_transform, origin.view_typed = true;
  if (c.look) v.look = *c.look, origin.look_typed = true;
  if (c.display) v.display_device = *c.display, origin.display_typed = true;
  v.exposure_stops = o.exposure_stops.value_or(v.exposure_stops);
  v.gamma = o.gamma.value_or(v.gamma);
  v.dither_intensity = o.dither_intensity.value_or(v.dither_intensity);
  return {v, origin};
}

}  // namespace

std::pair<uint32_t, uint32_t> parse_resolution(const std::string& text) {
  const size_t x = text.find('x');
  if (x == std::string::npos)
    throw UsageError("--res '" + text + "': expected WxH, e.g. 1920x1080");
  const uint32_t width = parse_side(std::string_view(text).substr(0, x), text);
  const uint32_t height = parse_side(std::string_view(text).substr(x + 1), text);
  if (const uint64_t pixels = uint64_t(width) * height; pixels > kMaxImagePixels)
    throw UsageError("--res '" + text + "': " + std::to_string(pixels) +
                     " pixels, expected at most " + std::to_string(kMaxImagePixels));
  return {width, height};
}

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// "90", "90s", "5m", "1.5h": a positive duration.
Clock::duration parse_duration(const std::string& text, const char* option) {
  double value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  const std::string_view unit(end, text.data() + text.size() - end);
  const double scale = unit.empty() || unit == "s" ? 1 : unit == "m" ? 60 : unit == "h" ? 3600 : 0;
  if (ec != std::errc() || scale == 0 || !(value > 0) || !(value * scale < 1e9))
    throw UsageError(std::string(option) + " '" + text +
                     "': expected a duration such as 30s, 5m or 2h");
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(value * scale));
}

// Next to the first output: shot.exr -> shot.checkpoint.exr.
std::filesystem::path default_checkpoint(const std::filesystem::path& output) {
  std::filesystem::path file = output;
  return file.replace_extension(".checkpoint.exr");
}

// A hash of the scene file's bytes, so a checkpoint is never resumed on an edited scene.
std::string content_hash(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  uint64_t h = 0, word = 0;
  while (in.read(reinterpret_cast<char*>(&word), sizeof word) || in.gcount() > 0) {
    h = pcg_hash(h, word, uint64_t(in.gcount()));
    word = 0;
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

// Checkpoints of this render (docs/cli.md, "Interrupts and checkpoints"); the file is
// report.checkpoint.
struct Checkpoints {
  bool enabled = false;                             // written, resumed from, or both
  Clock::duration every = Clock::duration::zero();  // zero: only when interrupted
  // Everything that decides the samples, so that a checkpoint of another render is refused; set
  // once the job is made.
  std::string key;
  std::optional<PixelRect> region;  // a part's: RenderJob::part_tiles; none: the frame
};

// --preview: the image so far, into `file` (an EXR) at least `every` apart.
struct LivePreview {
  std::filesystem::path file;
  Clock::duration every = Clock::duration::zero();
};

// Both options or neither, and an EXR: a preview keeps the scene-linear values the final image has.
std::optional<LivePreview> parse_live_preview(const RenderCommand& c) {
  if (c.preview.empty() && c.preview_every.empty()) return std::nullopt;
  if (c.preview_every.empty())
    throw UsageError("--preview: expected --preview-every too (how often to write it, e.g. 1s)");
  if (c.preview.empty())
    throw UsageError("--preview-every: expected --preview FILE too (the .exr to write)");
  if (image_format_for(c.preview) != ImageFormat::kExr)
    throw UsageError("--preview '" + c.preview.string() + "': expected a .exr file");
  return LivePreview{c.preview, parse_duration(c.preview_every, "--preview-every")};
}

// What the command line asks beyond RenderOptions: the 8-bit view's numbers, the checkpoints, the
// live preview and the frames.
struct CommandChoices {
  ViewOverrides view_overrides;
  Checkpoints checkpoints;
  std::optional<LivePreview> preview;
  std::optional<FrameRange> frames;  // --frames; its patterns are c.outputs and c.checkpoint
};

// With --frames every output and the checkpoint are frame patterns; without, a '#' there would be
// a frame pattern that no frame fills (Blender always fills it): give --frames N.
void check_frame_patterns(const RenderCommand& c, bool frames) {
  std::vector<std::pair<std::filesystem::path, std::string>> files;
  for (const std::filesystem::path& output : c.outputs)
    files.push_back({output, "output"});
  if (!c.checkpoint.empty()) files.push_back({c.checkpoint, "--checkpoint"});
  for (const auto& [file, what] : files) {
    if (frames)
      require_frame_pattern(file, what);
    else if (is_frame_pattern(file))
      throw UsageError(what + " '" + file.string() +
                       "': '#' stands for the frame number (shot.####.exr -> shot.0012.exr); "
                       "expected --frames N or --frames A-B to render frames into it");
  }
}

// Every option checked, and put into c.options, before the scene is read: a typo fails at once.
CommandChoices parse_options(RenderCommand& c, RenderReport& report) {
  CommandChoices choices;
  if (!c.frames.empty()) choices.frames = parse_frame_range(c.frames);
  if (choices.frames && !c.frame.empty())
    throw UsageError("--frame and --frames: expected one of them (--frames N renders frame N)");
  check_frame_patterns(c, choices.frames.has_value());
  check_outputs(c.outputs);
  check_part_request(c.part);
  if (c.part.any() &&
      (c.outputs.size() != 1 || image_format_for(c.outputs.front()) != ImageFormat::kExr))
    throw UsageError("--tile/--crop: expected one output, a .exr file (the partial film)");
  if (!c.resolution.empty()) {
    const auto [width, height] = parse_resolution(c.resolution);
    c.options.width = width, c.options.height = height;
  }
  parse_physical(c, c.options);
  choices.view_overrides = parse_view_overrides(c);
  if (!c.background.empty()) c.options.background = parse_background(c.background);
  if (!c.memory_limit.empty()) c.options.memory_limit_bytes = parse_memory_size(c.memory_limit);
  if (c.reconstruction == "splat") c.options.reconstruction = Reconstruction::kSplat;
  if (!c.passes.empty()) c.options.passes = parse_passes_option(c.passes);
  check_passes_combinations(c);
  if (c.subdiv == "adaptive") c.options.subdiv = SubdivMode::kAdaptive;
  if (!c.sampler.empty()) c.options.sampler = parse_sampler_kind(c.sampler, "--sampler");
  if (c.light_sampler == "tree") c.options.light_selection = LightSelection::kTree;
  if (c.light_sampler == "power") c.options.light_selection = LightSelection::kPower;
  c.options.show_progress = !c.quiet || !c.progress_every.empty();
  if (!c.progress_every.empty())
    c.options.progress_every = parse_duration(c.progress_every, "--progress-every");
  Checkpoints& checkpoints = choices.checkpoints;
  checkpoints.enabled = !c.checkpoint_every.empty() || c.resume || !c.checkpoint.empty();
  if (!c.checkpoint_every.empty())
    checkpoints.every = parse_duration(c.checkpoint_every, "--checkpoint-every");
  if (checkpoints.enabled)
    report.checkpoint = c.checkpoint.empty() ? default_checkpoint(c.outputs.front()) : c.checkpoint;
  choices.preview = parse_live_preview(c);
  return choices;
}

// The scene, read at the resolution and frame the command line asks for.
Scene read_scene(RenderCommand& c, Diagnostics& diagnostics, RenderReport& report) {
  c.import.resolution.reset();
  if (c.options.width) c.import.resolution = {*c.options.width, *c.options.height};
  if (c.options.frame) c.import.frame = *c.options.frame;
  // An .ini's animation: the clock runs from Initial_Clock to Final_Clock over its frames.
  if (c.import.pov_animation) c.import.clock = c.import.pov_animation->clock_at(c.import.frame);
  const auto stage = Clock::now();
  Scene scene = import_scene(c.scene, c.import, diagnostics);
  report.import_s = seconds_since(stage);
  return scene;
}

// How the outputs show the render: the shot's view settings with the command line's.
OutputView output_view(const RenderCommand& c, const ViewOverrides& overrides, const Scene& scene,
                       Diagnostics& diagnostics) {
  const auto [view, view_origin] = view_settings(c, overrides, scene);
  return fb::output_view(view, view_origin, c.outputs, c.ocio_config, diagnostics);
}

// The job's choices into the report, and its plan line unless quiet.
void report_plan(const RenderJob& job, const RenderCommand& c, RenderReport& report) {
  report.choices = job.choices();
  report.width = job.width(), report.height = job.height();
  report.samples_per_pixel = job.samples_per_pixel();
  report.seed = c.options.seed;
  if (!c.quiet) std::cout << job.plan() << std::endl;
}

// The plan line names the choices; what was typed for the camera, shutter and frame is added as
// typed, since some of it only shows in the rays (a focal length, a frame's camera position).
std::string checkpoint_key(const RenderJob& job, const RenderCommand& c) {
  std::string typed;
  for (const auto& [name, value] :
       {std::pair<const char*, const std::string&>{"focal-length", c.focal_length},
        {"fstop", c.fstop},
        {"focus-distance", c.focus_distance},
        {"sensor", c.sensor},
        {"sensor-fit", c.sensor_fit},
        {"shift", c.shift},
        {"shutter", c.shutter},
        {"rolling-shutter", c.rolling_shutter},
        {"fps", c.fps},
        {"sensor-model", c.sensor_model},
        {"iso", c.iso},
        {"background", c.background},
        {"subdiv", c.subdiv},
        {"light-sampler", c.light_sampler}})
    if (!value.empty()) typed += std::string("; --") + name + " " + value;
  // The frame as rendered (--frame's, or each frame's of a sequence), exactly; a POV-Ray scene's
  // clock and an .ini's declarations, which change what the scene builds.
  char number[40];
  if (c.options.frame) {
    std::snprintf(number, sizeof number, "; frame %.17g", *c.options.frame);
    typed += number;
  }
  if (c.import.clock != 0) {
    std::snprintf(number, sizeof number, "; clock %.17g", c.import.clock);
    typed += number;
  }
  for (const auto& [name, value] : c.import.pov_declarations) {
    std::snprintf(number, sizeof number, "=%.17g", value);
    typed += "; declare " + name + number;
  }
  return job.plan() + "; seed " + std::to_string(c.options.seed) + "; scene content " +
         content_hash(c.scene) + typed;
}

// A part (--tile/--crop) writes its partial film instead of an image (docs/cli.md, "Parts of a
// render"); an interrupted part writes none, only its checkpoint when asked for.
void write_part(const RenderJob& job, const RenderResult& result, const Film& film,
                const SamplingState& state, const PixelRect& crop, const OutputView& view,
                const RenderCommand& c, const Scene& scene, const std::filesystem::path& output,
                const Checkpoints& checkpoints, RenderReport& report) {
  const auto stage = Clock::now();
  if (result.stats.interrupted) {
    if (checkpoints.enabled) {
      write_checkpoint(film, state, checkpoints.key, report.checkpoint, checkpoints.region);
      ++report.checkpoints_written;
    }
    std::cerr << "filmback: the part was interrupted: no partial film written\n";
  } else {
    PartialFilmHeader header = partial_film_header(job, result, crop, checkpoint_key(job, c),
                                                   view.view, scene.settings.film_exposure);
    header.splat_tile_count = state.splat_tiles.size();
    write_partial_film(output, header, film, state.splat_tiles);
    if (checkpoints.enabled) std::filesystem::remove(report.checkpoint);
  }
  report.write_s = seconds_since(stage);
}

// --resume: the film and sampling state the checkpoint holds, into the job's empty ones.
void load_checkpoint(const RenderJob& job, const Checkpoints& checkpoints, Film& film,
                     SamplingState& state, RenderReport& report) {
  if (!std::filesystem::exists(report.checkpoint))
    throw InputError("--resume: no checkpoint '" + report.checkpoint.string() +
                     "' (--checkpoint-every writes one)");
  read_checkpoint(report.checkpoint, checkpoints.key, job.samples_per_pixel(), kTileSize, film,
                  state, checkpoints.region);
  report.resumed = true;
}

// A signal stops the render; checkpoints and previews are written on the way when asked for.
RenderControl render_control(const InterruptGuard& interrupts, const Checkpoints& checkpoints,
                             const std::optional<LivePreview>& preview, const RenderJob& job,
                             RenderReport& report) {
  RenderControl control;
  if (preview) {
    control.preview_every = preview->every;
    control.preview = [&preview, &job](const Film& f, const SamplingState& state) {
      write_images(job.image_so_far(f, state), {preview->file}, {});
    };
  }
  control.cancel = &interrupts.requested();
  if (checkpoints.every != Clock::duration::zero()) {
    control.checkpoint_every = checkpoints.every;
    control.checkpoint = [&checkpoints, &report](const Film& f, const SamplingState& state) {
      write_checkpoint(f, state, checkpoints.key, report.checkpoint, checkpoints.region);
      ++report.checkpoints_written;
    };
  }
  return control;
}

RenderResult run_job(const RenderJob& job, Film& film, SamplingState& state,
                     const RenderControl& control, const std::optional<PixelRect>& crop,
                     const InterruptGuard& interrupts, RenderReport& report) {
  const auto stage = Clock::now();
  RenderResult result = job.run(film, state, control, crop);
  report.render_s = seconds_since(stage);
  if (result.stats.interrupted) {
    report.signal = interrupts.signal_number();
    report.stop_latency_s = interrupts.seconds_since_signal();
  }
  report.stats = result.stats;
  report.fewest_samples = result.fewest_samples, report.most_samples = result.most_samples;
  return result;
}

// What an interrupted render writes: its EXR outputs only, which say so (filmback/interrupted, a
// samples channel). A PNG or JPEG cannot: half-rendered, it would look like a finished image.
std::vector<std::filesystem::path> interrupted_outputs(
    const std::vector<std::filesystem::path>& outputs) {
  std::vector<std::filesystem::path> kept;
  for (const std::filesystem::path& output : outputs) {
    if (is_8_bit(image_format_for(output)))
      std::cerr << "filmback: interrupted: " << output.string()
                << " not written (an 8-bit image of an unfinished render would look finished)\n";
    else
      kept.push_back(output);
  }
  return kept;
}

// The image into every output (an interrupted render's into its EXRs); the checkpoint kept for
// --resume when interrupted, removed when complete.
void write_outputs(const RenderJob& job, const RenderResult& result, const Film& film,
                   const SamplingState& state, const OutputView& view,
                   const std::vector<std::filesystem::path>& outputs,
                   const Checkpoints& checkpoints, RenderReport& report) {
  const auto stage = Clock::now();
  const bool interrupted = result.stats.interrupted;
  const std::vector<std::filesystem::path> written =
      interrupted ? interrupted_outputs(outputs) : outputs;
  if (!written.empty()) fb::write_outputs(result.image, job.metadata(result), view, written);
  if (interrupted && checkpoints.enabled) {
    write_checkpoint(film, state, checkpoints.key, report.checkpoint, checkpoints.region);
    ++report.checkpoints_written;
  }
  if (!interrupted && checkpoints.enabled) std::filesystem::remove(report.checkpoint);
  report.write_s = seconds_since(stage);
}

// "70x72", or for a part its crop in the frame: "part 0,37,70,72 of 70x72".
std::string rendered_area(const RenderJob& job, const std::optional<PixelRect>& crop) {
  const std::string frame = std::to_string(job.width()) + "x" + std::to_string(job.height());
  return crop ? "part " + crop->text() + " of " + frame : frame;
}

// One line: the render's size (a part's crop), speed and dropped samples, or what an interrupted
// render holds.
void print_summary(const RenderJob& job, const RenderResult& result,
                   const std::optional<PixelRect>& crop, const InterruptGuard& interrupts,
                   const Checkpoints& checkpoints) {
  const RenderStats& s = result.stats;
  char line[360];
  std::snprintf(line, sizeof line,
                "filmback: rendered %s at %u spp in %.2f s: %.2f M samples/s, %.2f M rays/s, "
                "%llu non-finite samples dropped",
                rendered_area(job, crop).c_str(), job.samples_per_pixel(), s.seconds,
                s.samples / s.seconds * 1e-6, s.rays / s.seconds * 1e-6,
                static_cast<unsigned long long>(s.dropped_samples));
  if (s.interrupted)
    std::snprintf(line, sizeof line,
                  "filmback: interrupted (signal %d) after %.2f s: pixels of %s hold %u to %u of "
                  "%u samples%s",
                  interrupts.signal_number(), s.seconds, rendered_area(job, crop).c_str(),
                  result.fewest_samples, result.most_samples, job.samples_per_pixel(),
                  checkpoints.enabled ? "; --resume continues from the checkpoint" : "");
  std::cout << line << std::endl;
}

// What the frames of a render share (one frame without --frames): the checked options, threads,
// plugins and interrupts, and the scene with how the outputs show it, read at the first frame
// rendered and again for each frame only when reading depends on it (import_reads_frame).
struct RenderSession {
  RenderSession(RenderCommand& command, RenderReport& report)
      : c(command), choices(parse_options(command, report)) {
    if (c.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, c.threads);
  }
  RenderCommand& c;
  InterruptGuard interrupts;  // until a render runs, a signal ends the process at once
  CommandChoices choices;
  std::optional<tbb::global_control> threads;
  const PluginLoader loader{PluginLoader::default_search_dirs()};
  std::optional<Scene> scene;
  std::optional<OutputView> view;
  std::vector<std::string> warnings;  // the scene's and view's
};

// The scene as this frame reads it: read when first needed, or again if its frame changes it.
const Scene& frame_scene(RenderSession& s, RenderReport& report) {
  if (!s.scene || import_reads_frame(s.c.scene)) {
    s.view.reset(), s.scene.reset();
    Diagnostics diagnostics;
    s.scene.emplace(read_scene(s.c, diagnostics, report));
    s.view.emplace(output_view(s.c, s.choices.view_overrides, *s.scene, diagnostics));
    // Once per sequence: a frame read again prints its warnings only when they changed.
    if (diagnostics.messages() != s.warnings) diagnostics.print(std::cerr);
    s.warnings = diagnostics.messages();
  }
  report.warnings = s.c.ini_warnings;
  report.warnings.insert(report.warnings.end(), s.warnings.begin(), s.warnings.end());
  return *s.scene;
}

// One frame into `outputs`: the frame c.options.frame names, with report.checkpoint its
// checkpoint; continued from the checkpoint when `resume`.
int render_frame(RenderSession& s, const std::vector<std::filesystem::path>& outputs, bool resume,
                 RenderReport& report) {
  const Scene& scene = frame_scene(s, report);
  const auto stage = Clock::now();
  const RenderJob job(scene, s.c.options, s.loader);
  report.setup_s = seconds_since(stage);
  report_plan(job, s.c, report);

  Checkpoints& checkpoints = s.choices.checkpoints;
  const std::optional<PixelRect> crop = part_crop(s.c.part, job.width(), job.height());
  if (crop) checkpoints.region = job.part_tiles(*crop);
  if (checkpoints.enabled)
    checkpoints.key = checkpoint_key(job, s.c) + (crop ? "; part " + crop->text() : std::string());
  Film film = job.make_film();
  SamplingState state = job.make_sampling_state();
  if (resume) load_checkpoint(job, checkpoints, film, state, report);
  s.interrupts.arm();
  const RenderResult result = run_job(
      job, film, state, render_control(s.interrupts, checkpoints, s.choices.preview, job, report),
      crop, s.interrupts, report);
  const bool interrupted = result.stats.interrupted;
  if (crop)
    write_part(job, result, film, state, *crop, *s.view, s.c, scene, outputs.front(), checkpoints,
               report);
  else if (interrupted && result.most_samples == 0)
    std::cerr << "filmback: interrupted before any pixel was sampled: nothing written\n";
  else
    write_outputs(job, result, film, state, *s.view, outputs, checkpoints, report);
  print_summary(job, result, crop, s.interrupts, checkpoints);
  report.status = interrupted ? "interrupted" : "complete";
  report.exit_status = interrupted ? 128 + s.interrupts.signal_number() : 0;
  return report.exit_status;
}

int render(RenderCommand& c, RenderReport& report) {
  RenderSession session(c, report);
  return render_frame(session, c.outputs, c.resume, report);
}

// --frames: each frame as `render --frame N` renders it, into the outputs' patterns filled with
// N; with --resume, a frame that has a checkpoint continues from it, the others start afresh.
int render_frames(RenderCommand& c, SequenceReport& report) {
  RenderReport options_report;  // what parse_options derives: the checkpoint's pattern
  RenderSession session(c, options_report);
  const FrameSequence sequence{*session.choices.frames, c.outputs, options_report.checkpoint,
                               c.overwrite};
  // Two patterns may name one file from some frame on (shot.#.exr and shot.##.exr from 10): the
  // widest numbers, at the range's ends, show it before any frame is rendered.
  for (const int64_t frame : {sequence.range.first, sequence.range.last})
    check_outputs(frame_files(frame, c.outputs, {}).outputs);
  const auto render_one = [&](const FrameFiles& files, RenderReport& frame) {
    const auto start = Clock::now();
    c.options.frame = double(files.frame);
    frame.checkpoint = files.checkpoint;
    const bool resume = c.resume && std::filesystem::exists(files.checkpoint);
    const int status = render_frame(session, files.outputs, resume, frame);
    frame.total_s = seconds_since(start);
    return status;
  };
  return run_frame_sequence(sequence, session.interrupts, render_one, report);
}

// Runs `run` for its exit status and writes the --stats-json report (a RenderReport or a
// SequenceReport) after it, also when it fails: then with the error, which goes on.
template <class Report>
int run_with_report(Report& report, const std::function<int()>& run,
                    const std::function<void()>& write_report) {
  try {
    report.exit_status = run();
  } catch (const std::exception& e) {
    report.exit_status = dynamic_cast<const UsageError*>(&e) ? 2 : 1;
    report.error = e.what();
    try {
      write_report();
    } catch (const std::exception&) {  // the render's own error is the one to report
    }
    throw;
  }
  write_report();
  return report.exit_status;
}

}  // namespace

int run_render(RenderCommand& c) {
  const auto start = Clock::now();
  Diagnostics ini_diagnostics;
  apply_pov_ini(c, ini_diagnostics);
  ini_diagnostics.print(std::cerr);
  c.ini_warnings = ini_diagnostics.messages();
  if (c.outputs.empty())
    throw UsageError("render: expected -o FILE (or an .ini that names an Output_File_Name)");
  if (!c.frames.empty()) {
    SequenceReport report;
    report.scene = c.scene;
    return run_with_report(
        report, [&] { return render_frames(c, report); },
        [&] {
          report.total_s = seconds_since(start);
          if (report.error.empty())
            report.status = report.exit_status == 0 ? "complete" : "interrupted";
          if (!c.stats_json.empty()) write_sequence_report(report, c.stats_json);
        });
  }
  RenderReport report;
  report.scene = c.scene;
  report.outputs = c.outputs;
  return run_with_report(
      report, [&] { return render(c, report); },
      [&] {
        report.total_s = seconds_since(start);
        if (!c.stats_json.empty()) write_render_report(report, c.stats_json);
      });
}

}  // namespace fb
