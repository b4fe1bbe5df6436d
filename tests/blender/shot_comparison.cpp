#include "tests/blender/shot_comparison.h"

#include "core/image/image_io.h"
#include "tests/support/commands.h"

namespace fb::test {

namespace fs = std::filesystem;

Image render_second_seed(const ShotRenders& renders, const fs::path& work_dir) {
  const fs::path output = work_dir / "filmback_seed1.exr";
  run_logged(quoted(FILMBACK_EXE) + " render " + quoted(work_dir / "shot.gltf") + " -o " +
                 quoted(output) + " -q --seed 1 --spp " + renders.shot.text("samples"),
             work_dir / "filmback_seed1.log");
  return read_image(output);
}

}  // namespace fb::test
