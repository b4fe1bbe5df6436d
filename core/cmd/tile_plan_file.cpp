#include "core/cmd/tile_plan_file.h"

#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/film/part_coverage.h"
#include "core/util/error.h"
#include "core/util/temporary_file.h"

namespace fb {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr const char* kFormat = "filmback-tile-plan";
constexpr int kTilePlanVersion = 1;
constexpr uint64_t kMaxSide = 32768;  // as --res
constexpr uintmax_t kMaxBytes = 16 << 20;

// Crops inside the frame, disjoint and covering it; the JSON path of the first that is not.
void check_plan(const TilePlan& plan, const fs::path& file) {
  if (plan.parts.empty() || plan.parts.size() > kMaxParts)
    throw_input(file.string(), "parts",
                "expected 1 to " + std::to_string(kMaxParts) + " parts, found " +
                    std::to_string(plan.parts.size()));
  std::vector<PixelRect> crops;
  for (const TilePlan::Part& p : plan.parts)
    crops.push_back(p.crop);
  const std::optional<CoverageProblem> problem = check_coverage(crops, plan.width, plan.height);
  if (!problem) return;
  const std::string part = "parts[" + std::to_string(problem->part) + "].crop";
  switch (problem->kind) {
    case CoverageProblem::Kind::kOutside:
      throw_input(file.string(), part,
                  "[" + problem->where.text() + "] is not a non-empty rectangle inside the " +
                      std::to_string(plan.width) + "x" + std::to_string(plan.height) + " frame");
    case CoverageProblem::Kind::kOverlap:
      throw_input(file.string(), part,
                  "overlaps parts[" + std::to_string(problem->other) + "].crop at pixels " +
                      problem->where.text() + ": expected disjoint crops");
    case CoverageProblem::Kind::kGap:
      throw_input(file.string(), "parts",
                  "no crop covers pixels " + problem->where.text() +
                      ": expected crops that cover the frame");
  }
}

uint32_t pixels_at(const json& value, const fs::path& file, const std::string& where, uint64_t lo,
                   uint64_t hi) {
  if (!value.is_number_unsigned() || value.get<uint64_t>() < lo || value.get<uint64_t>() > hi)
    throw_input(file.string(), where,
                "expected an integer from " + std::to_string(lo) + " to " + std::to_string(hi));
  return uint32_t(value.get<uint64_t>());
}

}  // namespace

TilePlan read_tile_plan(const fs::path& file) {
  std::error_code error;
  const uintmax_t size = fs::file_size(file, error);
  if (error) throw_input(file.string(), "", "cannot be read: " + error.message());
  if (size > kMaxBytes)
    throw_input(file.string(), "", "larger than " + std::to_string(kMaxBytes) + " bytes");
  std::ifstream in(file, std::ios::binary);
  const json doc = json::parse(in, nullptr, false);
  if (doc.is_discarded() || !doc.is_object())
    throw_input(file.string(), "", "expected a JSON object (a filmback tile plan)");
  if (doc.value("format", json()) != kFormat)
    throw_input(file.string(), "format", std::string("expected \"") + kFormat + "\"");
  if (doc.value("version", json()) != kTilePlanVersion)
    throw_input(file.string(), "version", "expected " + std::to_string(kTilePlanVersion));
  TilePlan plan;
  plan.width = pixels_at(doc.value("width", json()), file, "width", 1, kMaxSide);
  plan.height = pixels_at(doc.value("height", json()), file, "height", 1, kMaxSide);
  const json& parts = doc.contains("parts") ? doc["parts"] : json();
  if (!parts.is_array()) throw_input(file.string(), "parts", "expected an array of parts");
  if (parts.size() > kMaxParts)
    throw_input(file.string(), "parts", "expected at most " + std::to_string(kMaxParts) + " parts");
  for (size_t i = 0; i < parts.size(); ++i) {
    const std::string where = "parts[" + std::to_string(i) + "]";
    const json& part = parts[i];
    if (!part.is_object()) throw_input(file.string(), where, "expected an object");
    const json crop = part.value("crop", json());
    if (!crop.is_array() || crop.size() != 4)
      throw_input(file.string(), where + ".crop", "expected [x0, y0, x1, y1]");
    TilePlan::Part p;
    p.crop = {pixels_at(crop[0], file, where + ".crop[0]", 0, plan.width),
              pixels_at(crop[1], file, where + ".crop[1]", 0, plan.height),
              pixels_at(crop[2], file, where + ".crop[2]", 0, plan.width),
              pixels_at(crop[3], file, where + ".crop[3]", 0, plan.height)};
    const json seconds = part.value("estimated_seconds", json());
    if (!seconds.is_number() || !(seconds.get<double>() >= 0) ||
        !(seconds.get<double>() < std::numeric_limits<double>::infinity()))
      throw_input(file.string(), where + ".estimated_seconds", "expected a number of seconds >= 0");
    p.estimated_seconds = seconds.get<double>();
    plan.parts.push_back(p);
  }
  check_plan(plan, file);
  return plan;
}

void write_tile_plan(const TilePlan& plan, const fs::path& file) {
  check_plan(plan, file);
  json doc = {{"format", kFormat},
              {"version", kTilePlanVersion},
              {"width", plan.width},
              {"height", plan.height},
              {"parts", json::array()}};
  for (const TilePlan::Part& p : plan.parts)
    doc["parts"].push_back({{"crop", {p.crop.x0, p.crop.y0, p.crop.x1, p.crop.y1}},
                            {"estimated_seconds", p.estimated_seconds}});
  const std::string text = doc.dump(1) + "\n";
  write_atomically(file, [&](const fs::path& temporary) -> std::string {
    std::ofstream out(temporary, std::ios::binary);
    out << text;
    out.close();
    return out ? "" : "write failed";
  });
}

}  // namespace fb
