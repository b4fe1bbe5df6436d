#include "core/cmd/render_report.h"

#include <fstream>
#include <nlohmann/json.hpp>

#include "core/util/temporary_file.h"

namespace fb {

namespace {

using nlohmann::json;

json report_json(const RenderReport& r) {
  json out = {
      {"filmback_version", FILMBACK_VERSION}, {"scene", r.scene.string()}, {"status", r.status},
      {"exit_status", r.exit_status},         {"outputs", json::array()},  {"warnings", r.warnings},
      {"timings_s", {{"total", r.total_s}}}};
  if (r.frame) out["frame"] = *r.frame;
  for (const auto& output : r.outputs)
    out["outputs"].push_back(output.string());
  if (!r.error.empty()) out["error"] = r.error;
  json& timings = out["timings_s"];
  const std::pair<const char*, const std::optional<double>&> stages[] = {
      {"import", r.import_s}, {"setup", r.setup_s}, {"render", r.render_s}, {"write", r.write_s}};
  for (const auto& [name, seconds] : stages)
    if (seconds) timings[name] = *seconds;
  if (r.choices) {
    const RenderChoices& c = *r.choices;
    out["image"] = {{"width", r.width},
                    {"height", r.height},
                    {"samples_per_pixel", r.samples_per_pixel},
                    {"seed", r.seed}};
    out["models"] = {{"camera", c.camera},
                     {"camera_source", c.camera_source},
                     {"camera_model", c.camera_model},
                     {"lens", c.lens},
                     {"filter", c.filter},
                     {"reconstruction", c.reconstruction},
                     {"integrator", c.integrator},
                     {"sampler", c.sampler},
                     {"time", c.time},
                     {"subdivision", c.subdivision}};
    out["scene_counts"] = {{"triangles", c.triangles},
                           {"lights", c.lights},
                           {"emissive_triangles", c.emissive_triangles}};
  }
  if (r.stats)
    out["counts"] = {{"samples", r.stats->samples},
                     {"rays", r.stats->rays},
                     {"non_finite_samples_dropped", r.stats->dropped_samples},
                     {"fewest_samples_in_a_pixel", r.fewest_samples},
                     {"most_samples_in_a_pixel", r.most_samples}};
  if (r.signal != 0)
    out["interrupt"] = {{"signal", r.signal}, {"stop_latency_s", r.stop_latency_s}};
  if (!r.checkpoint.empty())
    out["checkpoint"] = {{"file", r.checkpoint.string()},
                         {"resumed", r.resumed},
                         {"written", r.checkpoints_written}};
  return out;
}

void write_json(const json& out, const std::filesystem::path& file) {
  const std::string text = out.dump(2) + "\n";
  write_atomically(file, [&](const std::filesystem::path& temporary) {
    std::ofstream stream(temporary, std::ios::binary);
    stream << text;
    stream.close();
    return stream ? std::string() : std::string("write failed");
  });
}

}  // namespace

void write_render_report(const RenderReport& r, const std::filesystem::path& file) {
  write_json(report_json(r), file);
}

// The sequence's own fields, then one object per frame reached, each as a single render's report
// (with its "frame"): a skipped frame's has its outputs and status only.
void write_sequence_report(const SequenceReport& r, const std::filesystem::path& file) {
  json out = {{"filmback_version", FILMBACK_VERSION},
              {"scene", r.scene.string()},
              {"frames", r.frames},
              {"status", r.status},
              {"exit_status", r.exit_status},
              {"timings_s", {{"total", r.total_s}}},
              {"frame_reports", json::array()}};
  if (!r.error.empty()) out["error"] = r.error;
  for (const RenderReport& frame : r.frame_reports)
    out["frame_reports"].push_back(report_json(frame));
  write_json(out, file);
}

}  // namespace fb
