#include "core/cmd/bench_report.h"

#include <cstdio>
#include <sstream>

#include "core/cmd/bench_analysis.h"

namespace fb {
namespace {

// "%.4g" and friends, as text.
std::string format(const char* spec, double value) {
  char text[64];
  std::snprintf(text, sizeof text, spec, value);
  return text;
}

std::string g6(double value) {
  return format("%.6g", value);
}

std::string optional_g6(const std::optional<double>& value) {
  return value ? g6(*value) : "";
}

std::string mib(size_t bytes) {
  return format("%.1f", double(bytes) / (1024.0 * 1024.0)) + " MiB";
}

// RFC 4180: a field with a comma, quote or line break is quoted, its quotes doubled.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text)
    out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string csv_line(const std::vector<std::string>& fields) {
  std::string line;
  for (size_t i = 0; i < fields.size(); ++i) {
    if (i) line += ',';
    line += csv_field(fields[i]);
  }
  return line + "\n";
}

std::string rate(const std::optional<LogLogFit>& fit) {
  return fit ? format("%.2f", fit->slope) : "n/a";
}

std::string seconds(const std::optional<double>& s) {
  return s ? format("%.3g", *s) + " s" : "n/a";
}

void write_scene_header(std::ostringstream& md, const SceneReport& scene) {
  md << "\n## " << scene.name << "\n\n";
  md << "`" << scene.file.string() << "`, " << scene.width << "x" << scene.height << " px";
  if (scene.prepare_s)
    md << "; prepared by Blender in " << format("%.2f", *scene.prepare_s)
       << " s (built or opened, saved, exported with filmback's add-on)";
  md << ".\n\n";
  // The plan line names its program itself: "filmback: camera ...".
  md << "- " << scene.plan << "\n";
  md << "- import " << format("%.3f", scene.import_s)
     << " s; RenderJob construction (plugins, render-space geometry, BVH, lights) "
     << format("%.3f", scene.build_s) << " s (median of the scene's jobs)\n";
  if (scene.cycles) md << "- " << scene.cycles->settings << "\n";
}

void write_references(std::ostringstream& md, const SceneReport& scene) {
  md << "\n| reference | filter | made from | its own RMSE | its own relMSE |\n"
        "|---|---|---|---|---|\n";
  for (const ReferenceNote& r : scene.references)
    md << "| " << r.renderer << " | " << r.filter << " | " << r.source << " | "
       << (r.noise ? format("%.3g", r.noise->rmse) : "not measured") << " | "
       << (r.noise ? format("%.3g", r.noise->relmse) : "not measured") << " |\n";
  const auto& c = scene.cycles;
  if (!c) return;
  if (!c->agreement) {
    md << "\nNo filmback configuration uses the shot's pixel filter, so the renderers' references "
          "are not compared and filmback is not measured against Cycles' reference.\n";
    return;
  }
  const ReferenceAgreement& a = *c->agreement;
  const ImageComparison& m = a.comparison;
  const bool agree = references_agree(a);
  md << "\nThe two references (filmback's with " << c->agreement_filter
     << " against Cycles'): filmback / Cycles mean " << format("%.4f", m.mean_ratio)
     << "; mean relative difference " << format("%.2f", 100 * m.mean_relative)
     << " % (their noise alone: " << format("%.2f", 100 * m.noise_mean_relative)
     << " %); worst 16x16 block " << format("%.2f", 100 * m.worst_block) << " % at ("
     << m.worst_block_x << ", " << m.worst_block_y << "), filmback / Cycles "
     << format("%.3f", m.worst_block_ratio)
     << " there (noise alone: " << format("%.2f", 100 * m.worst_noise_block) << " %); RMSE "
     << format("%.3g", a.between.rmse) << " (noise alone: " << format("%.3g", a.noise_rmse)
     << "), relMSE " << format("%.3g", a.between.relmse) << ". By issue 14's bar (the mean at most "
     << format("%g", 100 * kAgreeMeanAboveNoise) << " % and every block at most "
     << format("%g", 100 * kAgreeBlockAboveNoise) << " % above their noise) they "
     << (agree ? "agree: measured against Cycles' reference, both renderers' errors are "
                 "convergence."
               : "do **not** agree: measured against Cycles' reference, filmback's error includes "
                 "that difference, which no sample count removes.")
     << "\n";
}

void write_memory(std::ostringstream& md, const SceneReport& scene) {
  const MemoryNote& m = scene.memory;
  const size_t accounted = m.geometry_bytes + m.film_bytes;
  md << "\nMemory: geometry and BVH " << mib(m.geometry_bytes)
     << " (RenderGeometry::live_bytes(): render-space arrays and Embree's memory monitor), film "
     << mib(m.film_bytes)
     << " (sums and weights in double, sample counts, the resolved image in float): "
     << mib(accounted) << " accounted.";
  if (m.before && m.after) {
    const size_t grown = m.after->peak > m.before->current ? m.after->peak - m.before->current : 0;
    md << " Peak resident set " << mib(m.after->peak)
       << (m.peak_is_the_scene_s
               ? " during this scene"
               : " of the process so far (the kernel refused to restart the peak)")
       << ", " << mib(m.before->current) << " before its import: " << mib(grown)
       << " for the scene (its import, the references, every render), "
       << format("%.2f", accounted ? double(grown) / double(accounted) : 0.0)
       << " x the accounted size.";
  }
  md << "\n";
}

// How fits.csv and scenes.csv name a reference.
std::string reference_key(ReferenceKind kind) {
  return kind == ReferenceKind::kCycles ? "cycles" : "own";
}

// "Cycles' reference (for both renderers)" or "each configuration's own reference".
std::string reference_name(ReferenceKind kind) {
  return kind == ReferenceKind::kCycles ? "Cycles' reference (one reference for both renderers)"
                                        : "each renderer's own reference";
}

void write_fits(std::ostringstream& md, const std::vector<ConfigurationFit>& fits,
                const TargetError& target, ReferenceKind reference) {
  md << "\nConvergence, errors against " << reference_name(reference)
     << ": the slope of log RMSE against log time (and against log spp) by least "
        "squares over the renders whose RMSE is at least "
     << format("%g", kFitAboveReferenceNoise) << " x their reference's own. Time to reach RMSE "
     << format("%.4g", target.rmse) << " (" << target.why
     << "): the render time read off the fitted line; the total adds the "
        "configuration's fixed cost (the median of total minus render time over its renders), "
        "which does not shrink with the sample count.\n\n";
  md << "| configuration | renders fitted | rate vs render time | rate vs spp | RMSE at highest "
        "spp | time to RMSE "
     << format("%.3g", target.rmse) << ": render | total |\n|---|---|---|---|---|---|---|\n";
  for (const ConfigurationFit& fit : fits) {
    const TimeToError t = time_to_error(fit, target.rmse);
    const RenderRow& last = *fit.rows.back();
    md << "| " << (fit.renderer == "cycles" ? "**" + fit.configuration + "**" : fit.configuration)
       << " | " << fit.fitted << " of " << fit.rows.size() << " | " << rate(fit.by_render_s)
       << " | " << rate(fit.by_spp) << " | " << format("%.4g", last.measured(reference)->error.rmse)
       << " (" << last.spp << " spp) | " << seconds(t.render_s) << " | " << seconds(t.total_s)
       << (t.extrapolated ? " (extrapolated)" : "") << " |\n";
  }
}

void write_cycles_ratio(std::ostringstream& md, const std::vector<ConfigurationFit>& fits,
                        const RenderRow& cycles, const std::optional<CyclesNote>& note,
                        ReferenceKind reference) {
  const ImageError& goal = cycles.own.error;
  if (reference == ReferenceKind::kCycles)
    md << "\n### Against Cycles, on one reference\n\nBoth renderers' errors are against Cycles' "
          "reference. ";
  else
    md << "\n### Against Cycles, each against its own reference\n\nThe measure used before "
          "filmback rendered Blender's materials as Cycles does, kept for continuity: each "
          "renderer's error is against its own reference, so a difference of the models does not "
          "count. ";
  md << "**" << cycles.configuration << "** at " << cycles.spp << " spp: RMSE "
     << format("%.4g", goal.rmse) << ", relMSE " << format("%.4g", goal.relmse) << " (render "
     << format("%.3g", cycles.render_s) << " s, whole process " << format("%.3g", cycles.total_s)
     << " s). RMSE is absolute, so it favours the darker image";
  if (note && note->agreement)
    md << " (filmback / Cycles mean " << format("%.3f", note->agreement->comparison.mean_ratio)
       << ")";
  md << "; relMSE is relative per pixel and does not.\n\n"
     << "| filmback configuration | at Cycles' RMSE: render | total | **total / Cycles' "
        "process** | render / Cycles' render | at Cycles' relMSE: total | **total / Cycles' "
        "process** |\n|---|---|---|---|---|---|---|\n";
  const auto ratio = [](const std::optional<double>& ours, double theirs) {
    return ours ? format("%.3g", *ours / theirs) : std::string("n/a");
  };
  const auto flag = [](const TimeToError& t) { return t.extrapolated ? " (extrapolated)" : ""; };
  for (const ConfigurationFit& fit : fits) {
    if (fit.renderer != "filmback") continue;
    const TimeToError t = time_to_error(fit, goal.rmse);
    const TimeToError r = time_to_relmse(fit, goal.relmse);
    md << "| " << fit.configuration << " | " << seconds(t.render_s) << " | " << seconds(t.total_s)
       << flag(t) << " | **" << ratio(t.total_s, cycles.total_s) << "** | "
       << ratio(t.render_s, cycles.render_s) << " | " << seconds(r.total_s) << flag(r) << " | **"
       << ratio(r.total_s, cycles.total_s) << "** |\n";
  }
}

}  // namespace

std::string renders_csv(const std::vector<SceneReport>& scenes) {
  std::string out = csv_line({"scene",
                              "renderer",
                              "configuration",
                              "sampler",
                              "filter",
                              "spp",
                              "runs",
                              "render_s",
                              "total_s",
                              "samples_per_s",
                              "rays_per_s",
                              "rmse",
                              "relmse",
                              "max_abs_error",
                              "nonfinite_dropped",
                              "reference_noise_rmse",
                              "cycles_ref_rmse",
                              "cycles_ref_relmse",
                              "cycles_ref_max_abs_error",
                              "cycles_ref_noise_rmse",
                              "seeds",
                              "rmse_lowest",
                              "rmse_highest",
                              "cycles_ref_rmse_lowest",
                              "cycles_ref_rmse_highest"});
  for (const SceneReport& scene : scenes)
    for (const RenderRow& r : scene.rows) {
      const std::optional<MeasuredError>& c = r.cycles_reference;
      const std::optional<std::pair<double, double>>& s = r.cycles_reference_rmse_spread;
      out += csv_line({scene.name,
                       r.renderer,
                       r.configuration,
                       r.sampler,
                       r.filter,
                       std::to_string(r.spp),
                       std::to_string(r.runs),
                       g6(r.render_s),
                       g6(r.total_s),
                       g6(r.samples_per_s),
                       optional_g6(r.rays_per_s),
                       g6(r.own.error.rmse),
                       g6(r.own.error.relmse),
                       g6(r.own.error.max_abs),
                       r.dropped ? std::to_string(*r.dropped) : "",
                       optional_g6(r.own.reference_noise),
                       c ? g6(c->error.rmse) : "",
                       c ? g6(c->error.relmse) : "",
                       c ? g6(c->error.max_abs) : "",
                       c ? optional_g6(c->reference_noise) : "",
                       std::to_string(r.seeds),
                       g6(r.rmse_spread.first),
                       g6(r.rmse_spread.second),
                       s ? g6(s->first) : "",
                       s ? g6(s->second) : ""});
    }
  return out;
}

std::string fits_csv(const std::vector<SceneReport>& scenes) {
  std::string out = csv_line({"scene", "renderer", "configuration", "reference", "error", "x",
                              "slope", "intercept", "x_min", "x_max", "points", "fixed_s"});
  struct Line {
    const char* error;
    const char* x;
    const std::optional<LogLogFit>& fit;
  };
  for (const SceneReport& scene : scenes)
    for (ReferenceKind reference : {ReferenceKind::kOwn, ReferenceKind::kCycles})
      for (const ConfigurationFit& fit : fit_configurations(scene, reference))
        for (const Line& line :
             {Line{"rmse", "render_s", fit.by_render_s}, Line{"rmse", "spp", fit.by_spp},
              Line{"relmse", "render_s", fit.relmse_by_render_s}})
          if (line.fit)
            out += csv_line({scene.name, fit.renderer, fit.configuration, reference_key(reference),
                             line.error, line.x, g6(line.fit->slope), g6(line.fit->intercept),
                             g6(line.fit->x_min), g6(line.fit->x_max),
                             std::to_string(line.fit->points), g6(fit.fixed_s)});
  return out;
}

std::string scenes_csv(const std::vector<SceneReport>& scenes, const BenchContext& context) {
  std::string out = csv_line({"scene",
                              "file",
                              "width",
                              "height",
                              "import_s",
                              "build_s",
                              "prepare_s",
                              "rss_before_bytes",
                              "peak_rss_bytes",
                              "peak_is_scene",
                              "geometry_bvh_bytes",
                              "film_bytes",
                              "target_reference",
                              "target_rmse",
                              "cycles_spp",
                              "cycles_rmse",
                              "bias_rmse",
                              "bias_noise_rmse",
                              "mean_ratio",
                              "mean_relative_difference",
                              "mean_relative_noise",
                              "worst_block",
                              "worst_block_noise",
                              "worst_block_x",
                              "worst_block_y",
                              "worst_block_ratio",
                              "references_agree"});
  for (const SceneReport& scene : scenes) {
    const ReferenceKind primary = primary_reference(scene);
    const std::vector<ConfigurationFit> fits = fit_configurations(scene, primary);
    const RenderRow* cycles = cycles_reference_render(fits);
    const MemoryNote& m = scene.memory;
    const ReferenceAgreement* a =
        scene.cycles && scene.cycles->agreement ? &*scene.cycles->agreement : nullptr;
    const auto agreement = [&](auto value) { return a ? value(*a) : std::string(); };
    out += csv_line(
        {scene.name,
         scene.file.string(),
         std::to_string(scene.width),
         std::to_string(scene.height),
         g6(scene.import_s),
         g6(scene.build_s),
         optional_g6(scene.prepare_s),
         m.before ? std::to_string(m.before->current) : "",
         m.after ? std::to_string(m.after->peak) : "",
         m.peak_is_the_scene_s ? "1" : "0",
         std::to_string(m.geometry_bytes),
         std::to_string(m.film_bytes),
         reference_key(primary),
         g6(default_target(fits, context.target_error).rmse),
         cycles ? std::to_string(cycles->spp) : "",
         cycles ? g6(cycles->own.error.rmse) : "",
         agreement([](const auto& x) { return g6(x.between.rmse); }),
         agreement([](const auto& x) { return g6(x.noise_rmse); }),
         agreement([](const auto& x) { return g6(x.comparison.mean_ratio); }),
         agreement([](const auto& x) { return g6(x.comparison.mean_relative); }),
         agreement([](const auto& x) { return g6(x.comparison.noise_mean_relative); }),
         agreement([](const auto& x) { return g6(x.comparison.worst_block); }),
         agreement([](const auto& x) { return g6(x.comparison.worst_noise_block); }),
         agreement([](const auto& x) { return std::to_string(x.comparison.worst_block_x); }),
         agreement([](const auto& x) { return std::to_string(x.comparison.worst_block_y); }),
         agreement([](const auto& x) { return g6(x.comparison.worst_block_ratio); }),
         agreement([](const auto& x) { return std::string(references_agree(x) ? "1" : "0"); })});
  }
  return out;
}

std::string summary_markdown(const std::vector<SceneReport>& scenes, const BenchContext& context,
                             const std::vector<std::string>& plots) {
  std::ostringstream md;
  const auto load = [](const std::optional<double>& l) {
    return l ? format("%.2f", *l) : std::string("unknown");
  };
  md << "# filmback bench\n\n"
     << "- Run " << context.started << " to " << context.finished << " on " << context.processor
     << "; " << (context.threads ? std::to_string(context.threads) : std::string("all"))
     << " threads for both renderers; load average (1 min) " << load(context.load_before)
     << " before, " << load(context.load_after) << " after.\n"
     << "- Command: `" << context.command_line << "`\n"
     << "- Times are wall times. filmback's *render* is `RenderJob::run()` (film allocation, the "
        "tile loop, the film's resolve), the median of up to 5 runs while they add up to less "
        "than 1 s; its *total* adds the scene's import and that render's RenderJob construction "
        "(plugins, geometry, BVH, lights), what a `filmback render` process spends but for its "
        "start and the image it writes. Cycles' *render* is `bpy.ops.render.render()` (scene "
        "sync, BVH, sampling); its *total* is the whole Blender process, from its start to the "
        "EXR written.\n"
     << "- Errors are over R, G and B of every pixel against a reference: with Cycles, Cycles' "
        "reference for both renderers (filmback's configurations with the shot's pixel filter), "
        "and beside it each renderer's own (the columns rmse, relmse of renders.csv; "
        "cycles_ref_* are against Cycles'); else the configuration's own. "
        "RMSE, relMSE = mean (x - r)^2 / (r^2 + "
     << format("%g", kRelMseEpsilon)
     << "), the largest absolute error. A reference is the mean of two renders at half its "
        "sample count with other seeds than the measured renders; half the RMSE of their "
        "difference is its own RMSE, below which measured errors mean nothing.\n"
     << "- Per render: renders.csv; fitted lines: fits.csv; per scene: scenes.csv.\n";
  if (!context.plot_interpreter.empty())
    md << "- Plots drawn by `" << context.plot_interpreter << "` (share/filmback/bench/plot.py).\n";
  for (size_t i = 0; i < scenes.size(); ++i) {
    const SceneReport& scene = scenes[i];
    const ReferenceKind primary = primary_reference(scene);
    const std::vector<ConfigurationFit> fits = fit_configurations(scene, primary);
    write_scene_header(md, scene);
    write_references(md, scene);
    write_memory(md, scene);
    write_fits(md, fits, default_target(fits, context.target_error), primary);
    // One table per Cycles configuration (adaptive sampling off, and on at each --adaptive).
    for (const RenderRow* cycles : cycles_goal_renders(fits)) {
      write_cycles_ratio(md, fits, *cycles, scene.cycles, primary);
      if (primary != ReferenceKind::kOwn)
        write_cycles_ratio(md, fit_configurations(scene, ReferenceKind::kOwn), *cycles,
                           scene.cycles, ReferenceKind::kOwn);
    }
    if (!plots[i].empty()) md << "\n![" << scene.name << "](" << plots[i] << ")\n";
  }
  return md.str();
}

}  // namespace fb
