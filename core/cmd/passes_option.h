// --passes LIST (docs/cli.md, `--passes`): Blender's pass names, checked before the scene is
// read, and the options a render with passes cannot be combined with.
#pragma once

#include <string>
#include <vector>

namespace fb {

struct RenderCommand;

// The passes in `list` (comma-separated, Blender's names) beyond the beauty, in the order typed,
// each once; Combined, the beauty, is always written. A name filmback does not write is a
// UsageError naming it.
std::vector<std::string> parse_passes_option(const std::string& list);

// Passes are kept only by a whole render resolved from its film as it ends: refuses --tile/--crop,
// checkpoints (their film state holds the sums, not the nearest samples) and splatting.
void check_passes_combinations(const RenderCommand& c);

}  // namespace fb
