// `filmback merge PARTS... -o OUT...`: the partial films of one render's parts (core/film/
// partial_film.h) into the whole frame's film, finished and written as `filmback render` writes
// it: the same pixels, bit for bit (docs/cli.md, "Parts of a render").
#include <algorithm>
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

// The whole render's metadata: the first part's, with the parts' render seconds and dropped
// samples summed.
ImageMetadata merged_metadata(const std::vector<PartialFilmHeader>& parts) {
  ImageMetadata m = parts[0].metadata;
  double seconds = 0;
  uint64_t dropped = 0;
  for (const PartialFilmHeader& p : parts)
    seconds += p.render_seconds, dropped += p.dropped_samples;
  for (auto& [name, value] : m.floats)
    if (name == "filmback/render_seconds") value = float(seconds);
  for (auto& [name, value] : m.ints)
    if (name == "filmback/dropped_samples") value = int(std::min<uint64_t>(dropped, INT32_MAX));
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
  write_outputs(image, merged_metadata(parts), view, command.outputs);
  std::cout << "filmback: merged " << parts.size() << " parts into " << first.width << "x"
            << first.height << std::endl;
  return 0;
}

}  // namespace fb
