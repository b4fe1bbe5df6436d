#include "core/tessellate/tessellate_julia.h"

#include "core/tessellate/marching_tetrahedra.h"

namespace fb {

namespace {

// The set lies inside its bounding sphere, so the grid over the sphere's box meets its whole
// boundary without padding.
class MarchedJulia final : public MarchedSet {
 public:
  explicit MarchedJulia(const JuliaFractal& julia) : julia_(julia) {}
  bool holds(Vec3d p) const override { return julia_fractal_contains(julia_, p); }
  Vec3d normal(Vec3d /*p*/, Vec3d outside) const override {
    // The vertex may lie just inside; the bisection's outside end, a 2^-24 cell away, names the
    // iterate that escapes there first, whose gradient is the normal.
    return julia_fractal_gradient(julia_, outside);
  }

 private:
  const JuliaFractal& julia_;
};

}  // namespace

void tessellate_julia_fractal(const JuliaFractal& julia, uint32_t cells, TriangleMesh& mesh) {
  march_tetrahedra(MarchedJulia(julia), julia_fractal_bounds(julia), cells, false, mesh);
}

}  // namespace fb
