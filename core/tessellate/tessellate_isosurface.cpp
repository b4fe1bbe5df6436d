#include "core/tessellate/tessellate_isosurface.h"

#include "core/function/isosurface_function.h"
#include "core/tessellate/marching_tetrahedra.h"

namespace fb {

namespace {

// The set: below the threshold, within the container. Open, the container is not the set's
// boundary: the grid, which spans the container's box, ends the surface there, and a sphere
// container cuts it by whole triangles.
class MarchedIsosurface final : public MarchedSet {
 public:
  MarchedIsosurface(const Isosurface& iso, bool open) : iso_(iso), open_(open) {}

  bool holds(Vec3d p) const override {
    return open_ ? isosurface_value(iso_, p) < 0 : isosurface_contains(iso_, p);
  }
  // On the container's wall when the step out of the set leaves the container.
  Vec3d normal(Vec3d p, Vec3d outside) const override {
    const bool wall = !open_ && !isosurface_container_holds(iso_, outside);
    return wall ? isosurface_container_normal(iso_, p) : isosurface_gradient(iso_, p);
  }
  bool keeps(Vec3d centre) const override {
    return !open_ || isosurface_container_holds(iso_, centre);
  }

 private:
  const Isosurface& iso_;
  const bool open_;
};

}  // namespace

void tessellate_isosurface(const Isosurface& iso, bool open, uint32_t cells, TriangleMesh& mesh) {
  march_tetrahedra(MarchedIsosurface(iso, open), isosurface_bounds(iso), cells, !open, mesh);
}

}  // namespace fb
