#include "core/cmd/passes_option.h"

#include <filmback/render_passes.h>

#include <algorithm>
#include <string_view>

#include "core/cmd/commands.h"
#include "core/film/cryptomatte.h"
#include "core/render/motion_vectors.h"
#include "core/util/error.h"

namespace fb {
namespace {

// Cycles 3.4's passes that filmback does not write, named so that asking for one says so rather
// than calling it unknown (docs/blender.md, "Passes").
constexpr std::string_view kUnwrittenPasses[] = {
    "TransCol", "DiffDir",   "DiffInd",   "GlossDir", "GlossInd", "TransDir",
    "TransInd", "VolumeDir", "VolumeInd", "AO",       "Shadow",   "Env",
    "Mist",     "IndexOB",   "IndexMA",   "UV",       "Position"};

std::string written_pass_names() {
  std::string names = "Combined";
  for (const RenderPass& pass : kRenderPasses)
    names += std::string(", ") + pass.name;
  return names + ", Vector, CryptoObject, CryptoMaterial, CryptoAsset";
}

}  // namespace

std::vector<std::string> parse_passes_option(const std::string& list) {
  std::vector<std::string> passes;
  for (size_t start = 0; start <= list.size();) {
    const size_t comma = std::min(list.find(',', start), list.size());
    const std::string name = list.substr(start, comma - start);
    start = comma + 1;
    if (name == "Combined" || std::find(passes.begin(), passes.end(), name) != passes.end())
      continue;
    if (std::find(std::begin(kUnwrittenPasses), std::end(kUnwrittenPasses), name) !=
        std::end(kUnwrittenPasses))
      throw UsageError("--passes: '" + name + "' is a Blender pass filmback does not write; " +
                       "expected some of " + written_pass_names());
    if (!find_render_pass(name) && !find_cryptomatte_pass(name) && name != kVectorPass)
      throw UsageError("--passes: unknown pass '" + name + "'; expected some of " +
                       written_pass_names() + " (Blender's names, comma-separated)");
    passes.push_back(name);
  }
  return passes;
}

void check_passes_combinations(const RenderCommand& c) {
  if (c.options.view_layer.empty())
    throw UsageError("--view-layer: an empty name; expected Blender's view layer name");
  if (const auto levels = c.options.cryptomatte_levels) {
    if (!valid_cryptomatte_levels(*levels))
      throw UsageError("--cryptomatte-levels: " + std::to_string(*levels) +
                       "; expected an even number from 2 to " +
                       std::to_string(kMaxCryptomatteLevels) + " (Blender's Cryptomatte Levels)");
    if (std::none_of(c.options.passes.begin(), c.options.passes.end(),
                     [](const std::string& pass) { return find_cryptomatte_pass(pass); }))
      throw UsageError(
          "--cryptomatte-levels without a Cryptomatte pass; expected --passes with CryptoObject, "
          "CryptoMaterial or CryptoAsset");
  }
  if (c.options.passes.empty()) {
    if (c.options.view_layer != kViewLayer)
      throw UsageError(
          "--view-layer without --passes: it names the passes' layer; expected "
          "--passes too");
    return;
  }
  if (c.part.any())
    throw UsageError(
        "--passes with --tile/--crop: partial films do not carry passes yet; "
        "render the passes in one whole render");
  if (!c.checkpoint_every.empty() || c.resume || !c.checkpoint.empty())
    throw UsageError(
        "--passes with checkpoints (--checkpoint-every, --checkpoint, --resume): "
        "checkpoints do not carry passes yet");
  if (c.options.reconstruction == Reconstruction::kSplat)
    throw UsageError(
        "--passes with --reconstruction splat: passes are resolved from each "
        "pixel's own samples; expected importance reconstruction");
}

}  // namespace fb
