// bicubic_patch { type 0 | 1 [u_steps U] [v_steps V] [flatness F] [accuracy A] [uv_vectors ...]
// <P1>, ..., <P16> }
// (POV-Ray 3.7 reference, "Bicubic Patch"; Parse_Bicubic_Patch, bezier.cpp): the Bézier surface
// over 16 control points, four rows of four (row i weighted by u, column j by v), drawn as
// POV-Ray draws it: as triangles over its subdivision into 2^U x 2^V sub-patches, each split
// from its (u0, v0) corner to its (u1, v1) corner, with the surface's normals at the corners
// (bezier_tree_builder, bezier_subpatch_intersect). POV-Ray stops subdividing a sub-patch early
// when it is within `flatness` of flat; here the grid is always whole, at least as fine. Being
// triangles, it has no inside; `filmback convert` writes the same triangles.
#include <algorithm>
#include <array>
#include <cmath>

#include "importers/pov/sdl/parser.h"

namespace fb::pov::sdl {

namespace {

// 2^10 x 2^10 sub-patches are two million triangles, the default object limit: a scene asking
// for more is bounded here, with a warning, rather than refused.
constexpr int kPatchMostSteps = 10;

using ControlPoints = std::array<std::array<Vec3d, 4>, 4>;

// The Bernstein weights of degree 3 at t and their derivatives.
void bernstein(double t, double b[4], double db[4]) {
  const double s = 1 - t;
  b[0] = s * s * s, b[1] = 3 * t * s * s, b[2] = 3 * t * t * s, b[3] = t * t * t;
  db[0] = -3 * s * s, db[1] = 3 * s * s - 6 * t * s, db[2] = 6 * t * s - 3 * t * t,
  db[3] = 3 * t * t;
}

// The surface point at (u, v) and its unit normal, d/du x d/dv (bezier_value); where that
// vanishes (control points run together, as at a teapot lid's pole) the normal of a point a
// little towards the patch's middle.
void patch_point(const ControlPoints& p, double u, double v, Vec3d& point, Vec3d& normal) {
  for (int attempt = 0; attempt < 2; ++attempt) {
    double bu[4], dbu[4], bv[4], dbv[4];
    bernstein(u, bu, dbu);
    bernstein(v, bv, dbv);
    Vec3d q{0, 0, 0}, du{0, 0, 0}, dv{0, 0, 0};
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        q = q + p[i][j] * (bu[i] * bv[j]);
        du = du + p[i][j] * (dbu[i] * bv[j]);
        dv = dv + p[i][j] * (bu[i] * dbv[j]);
      }
    if (attempt == 0) point = q;
    const Vec3d n = cross(du, dv);
    if (dot(n, n) > 1e-24 * dot(du, du) * dot(dv, dv) && dot(n, n) > 0) {
      normal = n / length(n);
      return;
    }
    u += (0.5 - u) * 1e-3, v += (0.5 - v) * 1e-3;
  }
  normal = {1, 0, 0};  // flat in every direction: POV-Ray's own fallback
}

// A step count as written: negative counts as 0 (POV-Ray then splits no further), more than
// kPatchMostSteps is bounded with a warning.
int patch_steps(Parser& p, const char* keyword) {
  const SourceLocation where = p.location_of(p.peek());
  const double steps = p.parse_count();  // no comparison: a '<' opens the first point
  if (!std::isfinite(steps)) p.fail_at(where, std::string(keyword) + " is not finite");
  const int whole = int(std::clamp(std::trunc(steps), 0.0, double(kPatchMostSteps)));
  if (steps >= kPatchMostSteps + 1)
    p.warn_at(where, std::string(keyword) + " " + number_string(steps) + " bounded to " +
                         std::to_string(kPatchMostSteps) + " (" +
                         std::to_string(1 << kPatchMostSteps) + " rows of sub-patches)");
  return whole;
}

}  // namespace

void Parser::parse_bicubic_patch(Object& o) {
  o.shape = Shape::kMesh;
  int type = -1, u_steps = 0, v_steps = 0;
  SourceLocation type_at = location_of(peek());
  for (;;) {
    const Tok& tok = peek();
    if (tok.word("type")) {
      next();
      type_at = location_of(peek());
      const double t = parse_count();
      type = std::isfinite(t) ? int(std::clamp(t, -1.0, 4.0)) : -1;
      if (type == 2 || type == 3) {
        warn_at(type_at, "bicubic_patch type " + std::to_string(type) +
                             " is no longer supported: type 1 is used, as POV-Ray does");
        type = 1;
      }
    } else if (tok.word("u_steps")) {
      next();
      u_steps = patch_steps(*this, "u_steps");
    } else if (tok.word("v_steps")) {
      next();
      v_steps = patch_steps(*this, "v_steps");
    } else if (tok.word("uv_vectors")) {
      // Where the patch's corners sit in uv_mapping's texture space: the look, not the shape.
      unsupported("bicubic_patch uv_vectors", location_of(next()));
      for (int corner = 0; corner < 4; ++corner) {
        if (corner) accept(",");
        parse_additive();  // no comparison: the next corner opens with a '<'
      }
    } else if (tok.word("flatness") || tok.word("accuracy")) {
      next();  // the grid is always whole (see above)
      parse_count();
    } else {
      break;
    }
  }
  if (type != 0 && type != 1)
    fail_at(type_at, "bicubic_patch needs `type 0` or `type 1` before its points");
  accept(",");
  ControlPoints p;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      if (i || j) accept(",");
      const SourceLocation where = location_of(peek());
      p[i][j] = parse_vector();
      if (!std::isfinite(p[i][j].x) || !std::isfinite(p[i][j].y) || !std::isfinite(p[i][j].z))
        fail_at(where, "bicubic_patch control point is not finite");
    }
  const uint32_t rows = 1u << u_steps, columns = 1u << v_steps;
  count_objects(2 * uint64_t(rows) * columns);
  for (uint32_t i = 0; i <= rows; ++i)
    for (uint32_t j = 0; j <= columns; ++j) {
      Vec3d point, normal;
      patch_point(p, double(i) / rows, double(j) / columns, point, normal);
      o.vertices.push_back(point);
      o.normals.push_back(normal);
    }
  for (uint32_t i = 0; i < rows; ++i)
    for (uint32_t j = 0; j < columns; ++j) {
      const uint32_t a = i * (columns + 1) + j, b = a + 1, c = b + columns + 1, d = a + columns + 1;
      o.indices.insert(o.indices.end(), {a, b, c, a, c, d});
    }
}

}  // namespace fb::pov::sdl
