// parametric { function { X(u, v) }, function { Y(u, v) }, function { Z(u, v) } <u1, v1>,
// <u2, v2> [contained_by { box | sphere }] [max_gradient G] [accuracy A] [precompute D, x, y, z] }
// (POV-Ray 3.7 reference, "Parametric"). POV-Ray intersects the surface by subdividing the (u, v)
// rectangle under interval bounds; here the rectangle is sampled on a fixed grid into a smooth
// triangle mesh (a mesh from here on, as height fields are), which strays from the surface by the
// grid's chord error: docs/pov.md, "Parametric", gives it, and parametric_test measures it.
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/function/user_function.h"
#include "importers/pov/sdl/parser.h"

namespace fb::pov::sdl {

namespace {

// Cells per side of the (u, v) grid: 2 x 256^2 triangles, whose chord error is about
// (span / 256)^2 / 8 times the surface's curvature (a unit sphere over its whole
// rectangle: 7.5e-5).
constexpr int kParametricCells = 256;

struct ParametricMap {
  std::shared_ptr<const UserFunction> xyz[3];
  Vec3d operator()(double u, double v) const {
    return {xyz[0]->evaluate(u, v, 0), xyz[1]->evaluate(u, v, 0), xyz[2]->evaluate(u, v, 0)};
  }
};

// dP/du x dP/dv by central differences a hundredth of a cell wide, nudged a quarter cell towards
// the rectangle's middle where that is degenerate (a sphere's poles, where dP/du vanishes).
Vec3d parametric_normal(const ParametricMap& map, double u, double v, Vec3d lo, Vec3d cell) {
  const double hu = cell.x * 0.01, hv = cell.y * 0.01;
  for (int attempt = 0; attempt < 2; ++attempt) {
    const Vec3d du = map(u + hu, v) - map(u - hu, v), dv = map(u, v + hv) - map(u, v - hv);
    const Vec3d n = cross(du, dv);
    if (dot(n, n) > 0 && std::isfinite(dot(n, n))) return normalize(n);
    const Vec3d middle = lo + cell * (0.5 * kParametricCells);
    u += std::copysign(0.25 * std::abs(cell.x), middle.x - u);
    v += std::copysign(0.25 * std::abs(cell.y), middle.y - v);
  }
  return {0, 0, 0};
}

bool finite(Vec3d p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

// Keeps the vertices the triangles use, in order: the others may be NaN or outside the container,
// and would count in the object's bounds.
void drop_unused_vertices(Object& o) {
  std::vector<uint32_t> index(o.vertices.size(), UINT32_MAX);
  for (uint32_t v : o.indices)
    index[v] = 0;
  uint32_t kept = 0;
  for (size_t v = 0; v < o.vertices.size(); ++v) {
    if (index[v] == UINT32_MAX) continue;
    index[v] = kept;
    o.vertices[kept] = o.vertices[v];
    if (!o.normals.empty()) o.normals[kept] = o.normals[v];
    ++kept;
  }
  o.vertices.resize(kept);
  if (!o.normals.empty()) o.normals.resize(kept);
  for (uint32_t& v : o.indices)
    v = index[v];
}

}  // namespace

void Parser::parse_parametric(Object& o) {
  o.shape = Shape::kMesh;
  ParametricMap map;
  for (int i = 0; i < 3; ++i) {
    if (i) accept(",");
    const Tok keyword = next();
    const SourceLocation where = location_of(keyword);
    if (!keyword.word("function")) fail_at(where, "parametric expects three functions of u and v");
    const FunctionValue f = parse_function_body({"x", "y", "z"}, true);
    if (!f.unsupported.empty()) unsupported("function " + f.unsupported, where);
    map.xyz[i] = f.program;
  }
  const SourceLocation range_where = location_of(peek());
  const Vec3d lo = parse_vector();  // <u1, v1>, promoted
  accept(",");
  const Vec3d hi = parse_vector();
  if (!(std::isfinite(lo.x) && std::isfinite(lo.y) && std::isfinite(hi.x) && std::isfinite(hi.y) &&
        hi.x != lo.x && hi.y != lo.y))
    fail_at(range_where, "parametric range <" + number_string(lo.x) + ", " + number_string(lo.y) +
                             ">, <" + number_string(hi.x) + ", " + number_string(hi.y) +
                             ">: it must be finite and of non-zero width in u and v");
  Isosurface container;  // POV-Ray's default container, the box -1 to 1
  for (;;) {
    Tok tok = next();  // directives run
    if (tok.word("contained_by")) {
      parse_contained_by(container);
    } else if (tok.word("max_gradient") || tok.word("accuracy")) {
      parse_float();  // the grid does not subdivide
    } else if (tok.word("precompute")) {
      parse_float();
      while (peek().word("x") || peek().word("y") || peek().word("z") || peek().symbol(","))
        next();
    } else {
      unget(std::move(tok));
      break;
    }
  }
  count_objects(2 * uint64_t(kParametricCells) * kParametricCells);
  const int n = kParametricCells + 1;
  const Vec3d cell{(hi.x - lo.x) / kParametricCells, (hi.y - lo.y) / kParametricCells, 0};
  bool smooth = true;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double u = lo.x + cell.x * i, v = lo.y + cell.y * j;
      o.vertices.push_back(map(u, v));
      o.normals.push_back(parametric_normal(map, u, v, lo, cell));
      smooth = smooth && dot(o.normals.back(), o.normals.back()) > 0;
    }
  if (!smooth) o.normals.clear();  // flat triangles rather than a wrong normal somewhere
  // Two triangles a cell, left out where a corner is not a number or the middle is outside the
  // container (POV-Ray cuts the surface at the container; this cut follows the grid).
  const auto add = [&](uint32_t a, uint32_t b, uint32_t c) {
    const Vec3d pa = o.vertices[a], pb = o.vertices[b], pc = o.vertices[c];
    if (!finite(pa) || !finite(pb) || !finite(pc)) return;
    if (!isosurface_container_holds(container, (pa + pb + pc) / 3.0)) return;
    o.indices.insert(o.indices.end(), {a, b, c});
  };
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const uint32_t a = uint32_t(j * n + i), b = a + 1, c = a + uint32_t(n), d = c + 1;
      add(a, b, d);
      add(a, d, c);
    }
  drop_unused_vertices(o);
}

}  // namespace fb::pov::sdl
