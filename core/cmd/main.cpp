// filmback's command-line front end: `render`, `info`, `convert`, `plugins`, `bench` (docs/cli.md).
#include <CLI/CLI.hpp>
#include <functional>
#include <optional>

#include <iostream>

#include "core/cmd/commands.h"
#include "core/cmd/submit_command.h"
#include "core/cmd/tile_plan_command.h"
#include "core/util/error.h"
#include "core/util/malloc_tuning.h"

namespace {

// What a POV-Ray scene asks of the render while it is read (POV-Ray's +L and +K).
void add_import_options(CLI::App* command, fb::ImportOptions& options) {
  command->add_option("-L,--library-path", options.library_paths,
                      "POV-Ray: folder searched for #include files (repeatable; default: "
                      "POV-Ray's standard include folder when installed)");
  command->add_option("--clock", options.clock, "POV-Ray: the value of `clock` (default 0)");
}

// `render`: the scene, the outputs, the sample count and size, and the plugins.
void add_scene_and_plugin_options(CLI::App* render_cmd, fb::RenderCommand& render) {
  render_cmd
      ->add_option("scene", render.scene,
                   "scene file (.gltf, .glb, .pov), or a POV-Ray .ini naming its scene "
                   "(scene.ini or scene.ini[Section])")
      ->required();
  render_cmd->add_option(
      "-o,--output", render.outputs,
      "output image, .exr, .png or .jpg (repeatable; required unless an .ini names one)");
  render_cmd->add_option("--ini", render.ini,
                         "POV-Ray: the options of this .ini (FILE or FILE[Section]) for the .pov "
                         "scene; the command line's own options win");
  render_cmd
      ->add_option("--spp", render.options.samples_per_pixel, "samples per pixel (default 64)")
      ->check(CLI::Range(1u, 1000000u));
  render_cmd->add_option("--res", render.resolution,
                         "image size WxH in pixels (default: the shot's, else long side 1280 at "
                         "the shot's aspect)");
  render_cmd->add_option("--camera", render.options.camera,
                         "scene camera by name (default: the first in node order)");
  render_cmd->add_option(
      "--camera-model", render.options.camera_model,
      "camera plugin NAME[:k=v,...]; the shot's lens values fill its parameters of those names "
      "(default: thinlens with an aperture, else perspective or orthographic, as the shot's "
      "camera)");
  render_cmd->add_option("--filter", render.options.filter,
                         "pixel filter NAME[:k=v,...] (default: the shot's, else gaussian)");
  render_cmd
      ->add_option("--reconstruction", render.reconstruction,
                   "importance: each sample in its own pixel, weighted h/pdf; splat: spread to "
                   "every pixel within the filter radius (default importance; docs/filters.md)")
      ->check(CLI::IsMember({"importance", "splat"}));
  render_cmd->add_option("--integrator", render.options.integrator,
                         "integrator NAME[:k=v,...] (default path)");
  render_cmd->add_option(
      "--passes", render.passes,
      "Blender render passes written beside the beauty into the EXR as "
      "ViewLayer.<Pass>.<Channel>, comma-separated: Depth, Normal, DiffCol, GlossCol, "
      "Emit, Denoising Albedo, Denoising Normal, Vector, CryptoObject, CryptoMaterial, "
      "CryptoAsset (default: the beauty alone)");
  render_cmd->add_option("--cryptomatte-levels", render.options.cryptomatte_levels,
                         "with Cryptomatte passes: the ranks written per pixel, an even number "
                         "from 2 to 16 (Blender's Cryptomatte Levels; default 6)");
  render_cmd->add_option("--view-layer", render.options.view_layer,
                         "with --passes: the view layer the passes' channels are named after, "
                         "<NAME>.<Pass>.<Channel> (Blender's view layer; default ViewLayer)");
  render_cmd
      ->add_option("--adaptive-threshold", render.options.adaptive_threshold,
                   "adaptive sampling's noise threshold, as Cycles' (0: off; default: the "
                   "shot's, else off; docs/sampling.md)")
      ->check(CLI::Range(0.0, 1.0));
  render_cmd
      ->add_option("--adaptive-min-samples", render.options.adaptive_min_samples,
                   "samples every pixel takes before adaptive sampling may stop it (0: Cycles' "
                   "automatic ceil(16 / threshold^0.3); default: the shot's, else 0)")
      ->check(CLI::Range(0u, 1000000u));
  render_cmd->add_option("--background", render.background,
                         "uniform background radiance: one value or r,g,b (W/sr/m^2)");
}

// `render`: the lens, sensor, shutter and frame, each replacing the shot's (docs/cli.md).
void add_physical_camera_options(CLI::App* render_cmd, fb::RenderCommand& render) {
  CLI::Option_group* camera_group = render_cmd->add_option_group(
      "physical camera", "each replaces the value the shot carries (docs/cli.md)");
  camera_group->add_option("--focal-length", render.focal_length, "focal length in mm");
  camera_group->add_option("--fstop", render.fstop,
                           "f-number N (aperture diameter f/N); 0 or inf: a pinhole");
  camera_group->add_option("--focus-distance", render.focus_distance,
                           "focus distance in m along the view axis, or inf");
  camera_group->add_option("--sensor", render.sensor, "sensor size WxH in mm (e.g. 36x24)");
  camera_group->add_option("--sensor-fit", render.sensor_fit,
                           "which image side the sensor size spans: auto, horizontal, vertical");
  camera_group->add_option("--shift", render.shift,
                           "lens shift X,Y as fractions of the fitted image side (Blender's)");
  camera_group->add_option("--shutter", render.shutter,
                           "shutter OPEN,CLOSE in s relative to the frame's time (default closed)");
  camera_group->add_option("--shutter-curve", render.options.shutter_curve,
                           "how the shutter weighs time: box (default), trapezoid[:ramp=R] or "
                           "table:values=[w0,w1,...]");
  camera_group->add_option("--rolling-shutter", render.rolling_shutter,
                           "rolling shutter, rows read top to bottom: each row's share of the open "
                           "shutter in [0, 1] (Cycles' duration), or none (default: the shot's)");
  camera_group->add_option("--frame", render.frame,
                           "frame to render, time = frame / fps (default: the scene's, else 0)");
  camera_group
      ->add_option("--frames", render.frames,
                   "render frames A to B (every STEP-th), or frame N: A-B[:STEP] or N; each -o "
                   "holds a run of # for the frame number (shot.####.exr)")
      ->excludes("--frame");
  camera_group->add_option("--fps", render.fps,
                           "frames per second of the animation (default: the scene's, else 24)");
  camera_group->add_option("--sensor-model", render.sensor_model,
                           "simple (pixel = radiance, as Cycles; default) or physical (exposure)");
  camera_group->add_option("--iso", render.iso, "physical sensor: ISO speed (default 100)");
}

// `render`: the view of 8-bit outputs, as Blender saves a render (docs/cli.md).
void add_colour_options(CLI::App* render_cmd, fb::RenderCommand& render) {
  CLI::Option_group* colour_group = render_cmd->add_option_group(
      "colour", "8-bit outputs (PNG, JPEG) as Blender saves a render; each replaces the shot's");
  colour_group->add_option("--view-transform", render.view_transform,
                           "OpenColorIO view: Standard, Filmic, ... (default: the shot's; none: "
                           "the plain sRGB curve)");
  colour_group->add_option("--look", render.look, "OpenColorIO look, or None");
  colour_group->add_option("--exposure", render.exposure,
                           "stops: scene-linear values times 2^stops before the view");
  colour_group->add_option("--gamma", render.gamma, "display values v become v^(1/gamma)");
  colour_group->add_option("--display", render.display, "OpenColorIO display (default sRGB)");
  colour_group->add_option("--dither", render.dither,
                           "Blender's dither intensity, 0 to 2 (default: the shot's, else 0)");
  colour_group->add_option("--ocio-config", render.ocio_config,
                           "OpenColorIO config (default: $OCIO, else the installed Blender's)");
}

// `render`: how the render runs: subdivision, memory, threads, sampler, progress, checkpoints and
// the JSON report.
void add_run_options(CLI::App* render_cmd, fb::RenderCommand& render) {
  render_cmd
      ->add_option("--subdiv", render.subdiv,
                   "subdivision surfaces: render (Blender's render level, default) or adaptive "
                   "(cage edges cut to about one pixel through the camera)")
      ->check(CLI::IsMember({"render", "adaptive"}));
  render_cmd->add_option("--memory-limit", render.memory_limit,
                         "refuse a render estimated to need more memory: 8G, 512M, ... (default: "
                         "half of this machine's memory)");
  render_cmd->add_option("--threads", render.threads, "worker threads (default 0: all cores)")
      ->check(CLI::Range(0u, 4096u));
  render_cmd->add_option("--seed", render.options.seed, "sampler seed (default 0)");
  render_cmd->add_option("--sampler", render.sampler,
                         "independent, stratified, sobol (default) or zsobol (docs/sampling.md)");
  render_cmd
      ->add_option("--light-sampler", render.light_sampler,
                   "how next-event estimation picks a light: tree (a light BVH, by what each "
                   "brings to the point), power, or auto (default: the tree from " +
                       std::to_string(fb::LightChoice::kTreeFromLights) +
                       " lights with a place on; docs/sampling.md)")
      ->check(CLI::IsMember({"auto", "tree", "power"}));
  render_cmd->add_flag("-q,--quiet", render.quiet, "no progress bar and no plan line");
  render_cmd->add_option("--progress-every", render.progress_every,
                         "a plain progress line on stderr this often (e.g. 0.5s), even with no "
                         "terminal or with --quiet");
  render_cmd->add_option("--checkpoint-every", render.checkpoint_every,
                         "save a resumable checkpoint this often, e.g. 30s, 5m, 2h");
  render_cmd->add_option("--checkpoint", render.checkpoint,
                         "checkpoint file (default: the first output's name, .checkpoint.exr)");
  render_cmd->add_flag("--resume", render.resume,
                       "continue from the checkpoint: the same image as an uninterrupted render");
  render_cmd->add_option("--preview", render.preview,
                         "an .exr of the image so far, replaced while rendering (with "
                         "--preview-every)");
  render_cmd->add_option("--preview-every", render.preview_every,
                         "write the --preview image this often, e.g. 1s");
  render_cmd->add_option("--stats-json", render.stats_json,
                         "write timings, counts, warnings and the chosen models as JSON");
  render_cmd->add_flag("--overwrite", render.overwrite,
                       "--frames: render again the frames whose outputs all exist (default: skip)");
  CLI::Option_group* part_group = render_cmd->add_option_group(
      "Parts of a render", "one part of the frame into a partial film for `filmback merge`");
  part_group->add_option("--tile", render.part.tile,
                         "I/N: part I (from 0) of N (bands of 16-pixel tile rows, or the plan's)");
  part_group->add_option("--crop", render.part.crop, "X0,Y0,X1,Y1: these pixels (X1, Y1 excluded)");
  part_group->add_option("--tile-plan", render.part.tile_plan,
                         "with --tile: the plan's part I (filmback tile-plan)");
}

CLI::App* add_merge_command(CLI::App& app, fb::MergeCommand& merge) {
  CLI::App* merge_cmd = app.add_subcommand(
      "merge", "the partial films of a render's parts into its images (as render writes them)");
  merge_cmd->add_option("parts", merge.parts, "partial films (render --tile/--crop)")->required();
  merge_cmd
      ->add_option("-o,--output", merge.outputs, "output image, .exr, .png or .jpg (repeatable)")
      ->required();
  merge_cmd->add_option("--ocio-config", merge.ocio_config,
                        "OpenColorIO config for 8-bit outputs' view (as render's)");
  return merge_cmd;
}

CLI::App* add_tile_plan_command(CLI::App& app, fb::TilePlanCommand& plan) {
  CLI::App* plan_cmd = app.add_subcommand(
      "tile-plan", "split a frame into parts of near-equal cost for render --tile I/N --tile-plan");
  plan_cmd->add_option("scene", plan.scene,
                       "scene file, as render takes it (for the pre-pass; not with --report or "
                       "--previous)");
  plan_cmd->add_option("--tiles", plan.parts, "parts (1 to 1024)")
      ->required()
      ->check(CLI::Range(1u, 1024u));
  plan_cmd->add_option("-o,--output", plan.output, "the plan, .json")->required();
  plan_cmd->add_option("--previous", plan.previous,
                       "costs from the partial films of an earlier frame (its tile seconds)");
  plan_cmd->add_option("--report", plan.report,
                       "costs from an earlier render's --stats-json (its tile seconds)");
  plan_cmd
      ->add_option("--pre-pass-spp", plan.pre_pass_spp,
                   "samples per pixel of the pre-pass that measures the costs (default 4)")
      ->check(CLI::Range(1u, 1024u));
  plan_cmd->add_option("render-options", plan.render_arguments,
                       "after --: the render's options (the pre-pass renders with them)");
  return plan_cmd;
}

CLI::App* add_render_command(CLI::App& app, fb::RenderCommand& render) {
  CLI::App* render_cmd = app.add_subcommand("render", "render a scene to EXR, PNG and/or JPEG");
  add_scene_and_plugin_options(render_cmd, render);
  add_physical_camera_options(render_cmd, render);
  add_colour_options(render_cmd, render);
  add_run_options(render_cmd, render);
  add_import_options(render_cmd, render.import);
  return render_cmd;
}

// What `filmback info` is asked: the resolution stays text until the command runs, so that a bad
// one is reported as every other usage error is.
struct InfoCommand {
  std::filesystem::path scene;
  std::optional<std::string> camera;
  std::optional<std::string> camera_model;
  std::string resolution;
  fb::ImportOptions import;
};

CLI::App* add_info_command(CLI::App& app, InfoCommand& info) {
  CLI::App* info_cmd =
      app.add_subcommand("info", "print what a scene holds, with derived camera quantities");
  info_cmd->add_option("scene", info.scene, "scene file (.gltf, .glb, .pov)")->required();
  info_cmd->add_option("--camera", info.camera, "list only the camera of this name");
  info_cmd->add_option("--camera-model", info.camera_model,
                       "plan with this camera plugin NAME[:k=v,...], as render does, and print "
                       "what it derives (a lens' focal length and pupils)");
  info_cmd->add_option("--res", info.resolution,
                       "image size WxH the camera is described for (POV-Ray: image_width/height)");
  add_import_options(info_cmd, info.import);
  return info_cmd;
}

int run_info_command(InfoCommand& info) {
  if (!info.resolution.empty()) info.import.resolution = fb::parse_resolution(info.resolution);
  return fb::run_info(info.scene, info.import, info.camera, info.camera_model);
}

CLI::App* add_convert_command(CLI::App& app, fb::ConvertCommand& convert) {
  CLI::App* convert_cmd =
      app.add_subcommand("convert", "write a scene as glTF 2.0 (analytic shapes tessellated)");
  convert_cmd->add_option("input", convert.input, "scene file (.pov, .gltf, .glb)")->required();
  convert_cmd->add_option("output", convert.output, "glTF file to write (.gltf)")->required();
  convert_cmd->add_option("--res", convert.resolution,
                          "image size WxH (POV-Ray: image_width/height; default 800x600)");
  convert_cmd
      ->add_option("--tolerance", convert.tolerance_m,
                   "largest distance between an analytic surface and its triangles, m "
                   "(default: a thousandth of each shape's size)")
      ->check(CLI::Range(1e-6, 1e3));
  add_import_options(convert_cmd, convert.import);
  return convert_cmd;
}

CLI::App* add_bench_command(CLI::App& app, fb::BenchCommand& bench) {
  CLI::App* bench_cmd = app.add_subcommand(
      "bench",
      "render scenes at increasing sample counts: error against time, convergence "
      "rates, memory; optionally against Cycles (docs/cli.md)");
  bench_cmd
      ->add_option(
          "scene", bench.scenes,
          "scene files (.gltf, .glb, .pov; Blender shots: .blend, or a .py that builds one)")
      ->required();
  bench_cmd->add_option("-o,--output", bench.output, "report folder (created if its parent exists)")
      ->required();
  // Each list option takes one argument per occurrence, so that it never swallows a scene.
  bench_cmd
      ->add_option("--spp", bench.spp, "sample counts, comma-separated (default 1,2,4,...,256)")
      ->delimiter(',')
      ->allow_extra_args(false)
      ->check(CLI::Range(1u, 1000000u));
  bench_cmd
      ->add_option("--sampler", bench.samplers,
                   "samplers, comma-separated or repeated: independent, stratified, sobol, zsobol "
                   "(default sobol)")
      ->delimiter(',')
      ->allow_extra_args(false);
  bench_cmd
      ->add_option("--filter", bench.filters,
                   "a pixel filter NAME[:k=v,...], one per --filter, repeatable (default: the "
                   "scene's)")
      ->allow_extra_args(false);
  CLI::Option* reference =
      bench_cmd
          ->add_option("--reference", bench.references,
                       "the reference image (EXR) of each scene, one per --reference, in order")
          ->allow_extra_args(false);
  bench_cmd
      ->add_option("--reference-spp", bench.reference_spp,
                   "samples of filmback's (and Cycles') own references, even (default 16 x the "
                   "highest --spp)")
      ->check(CLI::Range(2u, 1000000u))
      ->excludes(reference);
  bench_cmd->add_option("--res", bench.resolution, "image size WxH (default: each scene's)");
  bench_cmd
      ->add_option("--target-error", bench.target_error,
                   "the RMSE whose time is compared (default: the largest any configuration has "
                   "at its highest spp)")
      ->check(CLI::PositiveNumber);
  bench_cmd
      ->add_option("--against", bench.against,
                   "cycles: render the Blender shots with Cycles too (blender on PATH)")
      ->check(CLI::IsMember({"cycles"}));
  bench_cmd
      ->add_option("--seeds", bench.seeds,
                   "measured renders per configuration and sample count, seeds --seed, --seed + "
                   "1, ...: the report keeps the median error and its spread (default 1)")
      ->check(CLI::Range(1u, 64u));
  bench_cmd
      ->add_option("--adaptive", bench.adaptive_thresholds,
                   "adaptive sampling thresholds, comma-separated, 0 for off: each a configuration "
                   "of filmback and, with --against cycles, of Cycles (default 0)")
      ->delimiter(',')
      ->allow_extra_args(false)
      ->check(CLI::Range(0.0, 1.0));
  bench_cmd
      ->add_option("--seed", bench.seed,
                   "seed of the measured renders; references use seed+1 and seed+2 (default 0)")
      ->check(CLI::Range(uint64_t(0), uint64_t(2147483645)));  // Cycles' seed is an int
  bench_cmd
      ->add_option("--threads", bench.threads, "worker threads of both renderers (default 0: all)")
      ->check(CLI::Range(0u, 4096u));
  add_import_options(bench_cmd, bench.import);
  return bench_cmd;
}

// The command line as typed, for the bench report.
std::string command_line(int argc, char** argv) {
  std::string line = "filmback";
  for (int i = 1; i < argc; ++i)
    line += std::string(" ") + argv[i];
  return line;
}

// The exit status when the command line does not parse (2), or asks for help (0); none when it
// parses.
std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == int(CLI::ExitCodes::Success)) return app.exit(e);  // --help
    // One line, in the same form as every other error (docs/conventions.md, "Errors").
    std::cerr << "filmback: error: " << e.what() << " (see filmback --help)\n";
    return 2;
  }
  return std::nullopt;
}

// A command's exit status, its error printed as one line: 2 for bad usage, 1 for bad input and
// every other failure (docs/cli.md, "Exit status").
int exit_status_of(const std::function<int()>& run_command) {
  try {
    return run_command();
  } catch (const fb::UsageError& e) {
    std::cerr << "filmback: error: " << e.what() << '\n';
    return 2;
  } catch (const fb::InputError& e) {
    std::cerr << "filmback: error: " << e.what() << '\n';
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << "filmback: error: out of memory\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "filmback: error: " << e.what() << '\n';
    return 1;
  }
}

struct Subcommand {
  CLI::App* command;
  std::function<int()> run;
};

}  // namespace

int main(int argc, char** argv) {
  fb::keep_large_allocations_in_mmap();
  CLI::App app{"filmback: a physically based renderer that keeps the camera of the shot"};
  app.require_subcommand(1);
  fb::RenderCommand render;
  InfoCommand info;
  fb::ConvertCommand convert;
  fb::BenchCommand bench;
  fb::MergeCommand merge;
  fb::TilePlanCommand tile_plan;
  fb::SubmitCommand submit;
  // In the order `filmback --help` lists them (a braced list is evaluated left to right).
  const Subcommand subcommands[] = {
      {add_render_command(app, render), [&] { return fb::run_render(render); }},
      {add_merge_command(app, merge), [&] { return fb::run_merge(merge); }},
      {add_tile_plan_command(app, tile_plan), [&] { return fb::run_tile_plan(tile_plan); }},
      {add_info_command(app, info), [&] { return run_info_command(info); }},
      {add_convert_command(app, convert), [&] { return fb::run_convert(convert); }},
      {app.add_subcommand("plugins", "list every plugin found, with its parameters"),
       [] { return fb::run_plugins(); }},
      {add_bench_command(app, bench),
       [&] {
         bench.command_line = command_line(argc, argv);
         return fb::run_bench(bench);
       }},
      {fb::add_submit_command(app, submit), [&] { return fb::run_submit(submit); }},
  };
  if (const std::optional<int> status = parse_command_line(app, argc, argv)) return *status;
  for (const Subcommand& subcommand : subcommands)
    if (subcommand.command->parsed()) return exit_status_of(subcommand.run);
  return 2;  // not reached: exactly one subcommand is required
}
