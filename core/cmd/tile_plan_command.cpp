#include "core/cmd/tile_plan_command.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "core/cmd/bench_process.h"
#include "core/cmd/pre_pass_arguments.h"
#include "core/cmd/render_part.h"
#include "core/cmd/tile_plan_file.h"
#include "core/film/partial_film.h"
#include "core/render/render_loop.h"
#include "core/render/tile_partition.h"
#include "core/util/error.h"

namespace fb {
namespace fs = std::filesystem;
namespace {

// Per render tile, the seconds the pre-pass's report (`render --stats-json`) recorded.
TileCosts costs_from_report(const fs::path& report) {
  std::ifstream stream(report);
  if (!stream) throw_input(report.string(), "", "cannot be read");
  try {
    nlohmann::json json;
    stream >> json;
    const auto& tiles = json.at("tiles");
    TileCosts costs{json.at("image").at("width").get<uint32_t>(),
                    json.at("image").at("height").get<uint32_t>(), tiles.at("size").get<uint32_t>(),
                    tiles.at("seconds").get<std::vector<double>>()};
    if (costs.tile_size_px == 0 || costs.width_px == 0 || costs.height_px == 0 ||
        costs.cost.size() != uint64_t(costs.tiles_x()) * costs.tiles_y())
      throw_input(report.string(), "tiles", "per-tile seconds that do not match the image's tiles");
    for (size_t i = 0; i < costs.cost.size(); ++i)
      if (!(costs.cost[i] >= 0) || !std::isfinite(costs.cost[i]))
        throw_input(report.string(), "tiles.seconds[" + std::to_string(i) + "]",
                    "expected a finite number of seconds >= 0");
    return costs;
  } catch (const nlohmann::json::parse_error& e) {
    // Not e.what(): it quotes the bytes it read, which in a binary file are not text.
    throw_input(
        report.string(), "",
        "expected a render's --stats-json report; not JSON (byte " + std::to_string(e.byte) + ")");
  } catch (const nlohmann::json::exception& e) {
    throw_input(report.string(), "",
                std::string("expected a render's --stats-json report with per-tile seconds (") +
                    e.what() + ")");
  }
}

// Per render tile, the seconds the parts of an earlier render (a previous frame) took: a tile two
// parts rendered (crops not on tile lines) counts the mean of their times.
TileCosts costs_from_parts(const std::vector<fs::path>& parts) {
  TileCosts costs;
  std::vector<uint32_t> seen;
  for (const fs::path& file : parts) {
    const PartialFilmHeader h = read_partial_film_header(file);
    if (costs.tile_size_px == 0) {
      costs = {h.width, h.height, kTileSize, {}};
      costs.cost.assign(size_t(costs.tiles_x()) * costs.tiles_y(), 0.0);
      seen.assign(costs.cost.size(), 0);
    } else if (h.width != costs.width_px || h.height != costs.height_px) {
      throw_input(file.string(), "",
                  "a part of a " + std::to_string(h.width) + "x" + std::to_string(h.height) +
                      " frame among parts of " + std::to_string(costs.width_px) + "x" +
                      std::to_string(costs.height_px));
    }
    if (h.tile_seconds.size() != h.tiles.area())
      throw_input(file.string(), "", "its tile times do not match its tiles");
    size_t i = 0;
    for (uint32_t ty = h.tiles.y0; ty < h.tiles.y1; ++ty)
      for (uint32_t tx = h.tiles.x0; tx < h.tiles.x1; ++tx, ++i) {
        const size_t t = size_t(ty) * costs.tiles_x() + tx;
        costs.cost[t] += h.tile_seconds[i];
        ++seen[t];
      }
  }
  for (size_t t = 0; t < costs.cost.size(); ++t) {
    if (seen[t] == 0)
      throw InputError("tile-plan: --previous: no part covers the tile at pixel (" +
                       std::to_string(t % costs.tiles_x() * kTileSize) + ", " +
                       std::to_string(t / costs.tiles_x() * kTileSize) + ")");
    costs.cost[t] /= seen[t];
  }
  return costs;
}

TileCosts costs_from_pre_pass(const TilePlanCommand& c) {
  const fs::path program = this_program();
  if (program.empty()) throw InputError("tile-plan: cannot find filmback's own executable");
  char pattern[] = "/tmp/filmback-tile-plan-XXXXXX";
  if (!mkdtemp(pattern)) throw InputError("tile-plan: cannot create a temporary folder in /tmp");
  const fs::path folder = pattern;
  struct RemoveFolder {
    fs::path f;
    ~RemoveFolder() {
      std::error_code ec;
      fs::remove_all(f, ec);
    }
  } remove{folder};
  std::vector<std::string> argv = {program.string()};
  const auto args = pre_pass_arguments(c.scene, c.render_arguments, c.pre_pass_spp,
                                       folder / "pre_pass.exr", folder / "pre_pass.json");
  argv.insert(argv.end(), args.begin(), args.end());
  const fs::path log = folder / "pre_pass.log";
  const ProgramRun run = run_program(argv, log);
  if (run.exit_status != 0) {
    std::ifstream text(log);
    std::cerr << text.rdbuf();
    throw InputError("tile-plan: the pre-pass render of '" + c.scene.string() + "' failed (exit " +
                     std::to_string(run.exit_status) + ")");
  }
  return costs_from_report(folder / "pre_pass.json");
}

}  // namespace

std::string plan_tiles(const TilePlanCommand& c) {
  if (c.output.extension() != ".json")
    throw UsageError("tile-plan: output '" + c.output.string() + "': expected a .json file name");
  if (!c.previous.empty() && !c.report.empty())
    throw UsageError("tile-plan: --previous and --report are two sources of costs: give one");
  if (c.previous.empty() && c.report.empty() && c.scene.empty())
    throw UsageError("tile-plan: a scene for the pre-pass, or costs from --report or --previous");
  const TileCosts costs = !c.previous.empty() ? costs_from_parts(c.previous)
                          : !c.report.empty() ? costs_from_report(c.report)
                                              : costs_from_pre_pass(c);
  const uint64_t tiles = uint64_t(costs.tiles_x()) * costs.tiles_y();
  if (c.parts > tiles)
    throw UsageError("tile-plan: --tiles " + std::to_string(c.parts) + ": the " +
                     std::to_string(costs.width_px) + "x" + std::to_string(costs.height_px) +
                     " frame has only " + std::to_string(tiles) + " tiles of " +
                     std::to_string(costs.tile_size_px) + " px");
  const std::vector<PlannedPart> planned = partition_tiles(costs, c.parts);
  TilePlan plan{costs.width_px, costs.height_px, {}};
  for (const PlannedPart& p : planned)
    plan.parts.push_back({p.crop, p.estimated_cost});
  write_tile_plan(plan, c.output);

  // What the plan buys: the same costs over the parts `--tile I/N` takes without a plan.
  const uint32_t bands = std::min(c.parts, costs.tiles_y());
  std::vector<PlannedPart> by_area;
  for (uint32_t i = 0; i < bands; ++i) {
    const PixelRect band = equal_area_part(i, bands, costs.width_px, costs.height_px);
    by_area.push_back({band, estimated_cost(costs, band)});
  }
  const char* source = !c.previous.empty() ? "the previous parts' tile times"
                       : !c.report.empty() ? "the report's tile times"
                                           : "a pre-pass";
  char balance[160];
  std::snprintf(balance, sizeof balance,
                "the costliest part %.3f x the mean (%u bands of tile rows without a plan: %.3f x)",
                imbalance(planned), bands, imbalance(by_area));
  return "filmback: wrote " + c.output.string() + ": " + std::to_string(c.parts) + " parts of " +
         std::to_string(costs.width_px) + "x" + std::to_string(costs.height_px) + " from " +
         source + "; " + balance;
}

int run_tile_plan(TilePlanCommand& c) {
  std::cout << plan_tiles(c) << std::endl;
  return 0;
}

}  // namespace fb
