// `filmback merge PARTS... -o OUT...`: the partial films of one render's parts (core/film/
// partial_film.h) into the whole frame's film, finished and written as `filmback render` writes
// it: the same pixels, bit for bit (docs/cli.md, "Parts of a render").
#include <algorithm>
#include <cstdio>
#include <iostream>

#include "core/cmd/commands.h"
#include "core/cmd/image_outputs.h"
#include "core/cmd/tile_plan_file.h"
#include "core/film/partial_film.h"
#include "core/render/render_job.h"
#include "core/util/diagnostics.h"
#include "core/util/error.h"

namespace fb {
namespace {

namespace fs = std::filesystem;

// What the parts' renders took, summed over the parts: they ran apart (in parallel or not), so
// this is no frame's wall time.
struct PartsTime {
  double render_seconds = 0;    // each part's render loop, wall time
  double sampling_seconds = 0;  // each part's 16x16 tiles, one worker thread's time each
  uint64_t dropped_samples = 0;
};

PartsTime parts_time(const std::vector<PartialFilmHeader>& parts) {
  PartsTime t;
  for (const PartialFilmHeader& p : parts) {
    t.render_seconds += p.render_seconds, t.dropped_samples += p.dropped_samples;
    for (const double s : p.tile_seconds)
      t.sampling_seconds += s;
  }
  return t;
}

// The whole render's metadata: the first part's, with the parts' render seconds and dropped
// samples summed, and what the sum is over (filmback/parts, filmback/parts_sampling_seconds).
ImageMetadata merged_metadata(const std::vector<PartialFilmHeader>& parts, const PartsTime& t) {
  ImageMetadata m = parts[0].metadata;
  for (auto& [name, value] : m.floats)
    if (name == "filmback/render_seconds") value = float(t.render_seconds);
  for (auto& [name, value] : m.ints)
    if (name == "filmback/dropped_samples")
      value = int(std::min<uint64_t>(t.dropped_samples, INT32_MAX));
  m.ints.push_back({"filmback/parts", int(parts.size())});
  m.floats.push_back({"filmback/parts_sampling_seconds", float(t.sampling_seconds)});
  return m;
}

}  // namespace

int run_merge(const MergeCommand& command) {
  check_outputs(command.outputs);
  if (command.parts.size() > kMaxParts)
    throw UsageError("merge: " + std::to_string(command.parts.size()) +
                     " parts, expected at most " + std::to_string(kMaxParts));
  std::vector<PartialFilmHeader> parts;
  for (const fs::path& file : command.parts)
    parts.push_back(read_partial_film_header(file));
  const PartialFilmHeader& first = parts[0];
  Diagnostics diagnostics;
  const OutputView view = output_view(first.view, {command.parts[0].string(), ""}, command.outputs,
                                      command.ocio_config, diagnostics);
  diagnostics.print(std::cerr);

  const Film film = merge_partial_films(command.parts, parts);
  Image image = film.resolve();
  apply_film_exposure(image, first.film_exposure);
  const PartsTime time = parts_time(parts);
  write_outputs(image, merged_metadata(parts, time), view, command.outputs);
  char line[240];
  std::snprintf(line, sizeof line,
                "filmback: merged %zu parts into %ux%u; summed over the parts: %.2f s of render "
                "(wall time), %.2f thread-seconds of sampling",
                parts.size(), first.width, first.height, time.render_seconds,
                time.sampling_seconds);
  std::cout << line << std::endl;
  return 0;
}

}  // namespace fb
