#include "core/tessellate/tessellate.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "core/math/constants.h"
#include "core/math/lemon.h"
#include "core/math/sor.h"
#include "core/math/superellipsoid.h"
#include "core/scene/lathe.h"
#include "core/tessellate/tessellate_csg.h"
#include "core/tessellate/tessellate_isosurface.h"
#include "core/tessellate/tessellate_julia.h"
#include "core/tessellate/tessellate_outline.h"

namespace fb {

namespace {

// The largest factor by which the linear part of `t` stretches a vector: the square root of
// the largest eigenvalue of M^T M, by power iteration (M^T M is symmetric positive semi-definite,
// so it converges to that eigenvalue from almost any start).
double largest_stretch(const Transform& t) {
  Vec3d v = normalize(Vec3d{1, 0.7, 0.3});
  double stretch = 0;
  for (int i = 0; i < 100; ++i) {
    const Vec3d w = t.vector(v);
    const Vec3d back{t(0, 0) * w.x + t(1, 0) * w.y + t(2, 0) * w.z,
                     t(0, 1) * w.x + t(1, 1) * w.y + t(2, 1) * w.z,
                     t(0, 2) * w.x + t(1, 2) * w.y + t(2, 2) * w.z};  // M^T M v
    const double len = length(back);
    if (!(len > 0)) break;
    stretch = std::sqrt(len);
    v = back / len;
  }
  return stretch;
}

// A point of a profile curve in the (rho, z) half-plane that revolves about the z axis, with the
// surface's outward normal there.
struct ProfilePoint {
  double rho, z, n_rho, n_z;
};
using Piece = std::vector<ProfilePoint>;  // a smooth run; pieces meet at sharp edges

// Segments that keep the sagitta r (1 - cos(angle / 2 n)) of an arc within `error`.
uint32_t arc_segments(double angle, double radius, double error, uint32_t most) {
  if (!(radius > error)) return 1;
  const double step = 2 * std::acos(1 - error / radius);
  return std::clamp(uint32_t(std::ceil(angle / step)), 1u, most);
}

Piece arc(double rho0, double z0, double radius, double from, double to, uint32_t segments) {
  Piece piece;
  for (uint32_t i = 0; i <= segments; ++i) {
    const double a = from + (to - from) * i / segments;
    piece.push_back(
        {rho0 + radius * std::cos(a), z0 + radius * std::sin(a), std::cos(a), std::sin(a)});
  }
  return piece;
}

Piece line(double rho0, double z0, double rho1, double z1) {
  Vec3d n{z1 - z0, -(rho1 - rho0), 0};  // the profile's direction turned clockwise: outward
  n = normalize(n);
  return {{rho0, z0, n.x, n.y}, {rho1, z1, n.x, n.y}};
}

// Appends a triangle, wound counter-clockwise about its vertices' normals; degenerate ones (at
// the axis) are left out.
void triangle(TriangleMesh& mesh, uint32_t a, uint32_t b, uint32_t c) {
  const Vec3f pa = mesh.positions[a], pb = mesh.positions[b], pc = mesh.positions[c];
  const Vec3f n = cross(pb - pa, pc - pa);
  if (!(dot(n, n) > 0)) return;
  if (dot(n, mesh.normals[a] + mesh.normals[b] + mesh.normals[c]) < 0) std::swap(b, c);
  mesh.indices.insert(mesh.indices.end(), {a, b, c});
}

void revolve(const std::vector<Piece>& pieces, uint32_t segments, TriangleMesh& mesh) {
  for (const Piece& piece : pieces) {
    const uint32_t base = uint32_t(mesh.positions.size()), row = segments + 1;
    for (const ProfilePoint& p : piece)
      for (uint32_t j = 0; j <= segments; ++j) {
        const double phi = 2 * kPi * (j % segments) / segments;  // the seam shares its vertices
        const double c = std::cos(phi), s = std::sin(phi);
        mesh.positions.emplace_back(Vec3d{p.rho * c, p.rho * s, p.z});
        mesh.normals.emplace_back(Vec3d{p.n_rho * c, p.n_rho * s, p.n_z});
      }
    for (uint32_t i = 0; i + 1 < piece.size(); ++i)
      for (uint32_t j = 0; j < segments; ++j) {
        const uint32_t a = base + i * row + j, b = a + row, c = b + 1, d = a + 1;
        triangle(mesh, a, b, c);
        triangle(mesh, a, c, d);
      }
  }
}

void box(TriangleMesh& mesh) {
  for (int axis = 0; axis < 3; ++axis)
    for (double side : {-1.0, 1.0}) {
      Vec3d n{0, 0, 0}, u{0, 0, 0}, v{0, 0, 0};
      (axis == 0 ? n.x : axis == 1 ? n.y : n.z) = side;
      (axis == 0 ? u.y : axis == 1 ? u.z : u.x) = 1;
      (axis == 0 ? v.z : axis == 1 ? v.x : v.y) = 1;  // u x v = +axis
      if (side < 0) std::swap(u, v);
      const uint32_t base = uint32_t(mesh.positions.size());
      for (const auto& [a, b] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
        mesh.positions.emplace_back(n + u * double(a) + v * double(b));
        mesh.normals.emplace_back(n);
      }
      mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
}

void plane_square(const Solid& primitive, const TessellationOptions& options, TriangleMesh& mesh) {
  const Transform object_from_world = primitive.world_from_object.inverse();
  const Vec3d q = object_from_world.point(options.plane_centre);
  // Half-size in object units: the world half-size over the least stretch, the inverse's most.
  const double h = options.plane_half_size_m * largest_stretch(object_from_world);
  for (const auto& [a, b] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
    mesh.positions.emplace_back(Vec3d{q.x + a * h, q.y + b * h, 0});
    mesh.normals.emplace_back(0.f, 0.f, 1.f);
  }
  mesh.indices = {0, 1, 2, 0, 2, 3};
}

// The grid's sagitta over a latitude-longitude grid of `rows` x `columns`: the largest distance,
// along the surface's normal, between a cell edge's midpoint on the surface and on its chord (the
// parametrisation also slides points along flat faces, which is no error).
double superellipsoid_sagitta(SuperellipsoidExponents s, uint32_t rows, uint32_t columns) {
  double worst = 0;
  const auto at = [&](double i, double j) {
    return superellipsoid_point(s, -kPi / 2 + kPi * i / rows, 2 * kPi * j / columns);
  };
  const auto off_chord = [&](Vec3d mid, Vec3d a, Vec3d b) {
    return std::abs(dot(mid - (a + b) * 0.5, normalize(superellipsoid_gradient(s, mid))));
  };
  for (uint32_t i = 0; i < rows; ++i)
    for (uint32_t j = 0; j < columns; ++j) {
      const Vec3d p = at(i, j);
      worst = std::max({worst, off_chord(at(i + 0.5, j), p, at(i + 1, j)),
                        off_chord(at(i, j + 0.5), p, at(i, j + 1))});
    }
  return worst;
}

// The superellipsoid over its parametric latitude-longitude grid (superellipsoid_point), which
// gathers vertices where the surface bends most; the grid doubles until its edges' sagitta is
// within half of `error` (a cell's centre strays by about the sum of its two directions') or its
// columns would pass `most` (at most kSuperellipsoidMostColumns: 2 million triangles). Normals from
// the implicit gradient; the poles' degenerate triangles are left out.
void superellipsoid_mesh(const Solid& primitive, double error, uint32_t most, TriangleMesh& mesh) {
  const SuperellipsoidExponents s{std::abs(primitive.radius0), std::abs(primitive.radius1)};
  constexpr uint32_t kSuperellipsoidMostColumns = 1024;
  most = std::min(most, kSuperellipsoidMostColumns);
  uint32_t columns = 16;
  while (2 * columns <= most && superellipsoid_sagitta(s, columns / 2, columns) > error / 2)
    columns *= 2;
  const uint32_t rows = columns / 2, row = columns + 1;
  for (uint32_t i = 0; i <= rows; ++i)
    for (uint32_t j = 0; j <= columns; ++j) {
      // The seam and the poles share their vertices.
      const double eta = i == 0 ? -kPi / 2 : i == rows ? kPi / 2 : -kPi / 2 + kPi * i / rows;
      const Vec3d p = superellipsoid_point(s, eta, 2 * kPi * (j % columns) / columns);
      mesh.positions.emplace_back(p);
      mesh.normals.emplace_back(normalize(superellipsoid_gradient(s, p)));
    }
  for (uint32_t i = 0; i < rows; ++i)
    for (uint32_t j = 0; j < columns; ++j) {
      const uint32_t a = i * row + j, b = a + 1, c = b + row, d = a + row;
      triangle(mesh, a, b, c);
      triangle(mesh, a, c, d);
    }
}

// One ring of a sphere sweep's mesh: the circle of `radius` about `centre` in the plane normal to
// `axis`, on the sphere about `sphere` (whose outward normals it takes).
struct SweepRing {
  Vec3d centre, axis, sphere;
  double radius;
};

// c(u) or r(u) of a segment (power basis), and their derivatives.
Vec3d sweep_centre_at(const SweepSegment& s, double u) {
  return s.c[0] + (s.c[1] + (s.c[2] + s.c[3] * u) * u) * u;
}
Vec3d sweep_centre_slope(const SweepSegment& s, double u) {
  return s.c[1] + (s.c[2] * 2 + s.c[3] * (3 * u)) * u;
}
double sweep_radius_at(const SweepSegment& s, double u) {
  return s.r[0] + (s.r[1] + (s.r[2] + s.r[3] * u) * u) * u;
}
double sweep_radius_slope(const SweepSegment& s, double u) {
  return s.r[1] + (2 * s.r[2] + 3 * s.r[3] * u) * u;
}

// A sphere sweep's segments, each a closed tube whose union is the sweep (they overlap where
// segments meet, as the spheres do). The tube's rings are where the sphere at u touches the
// envelope: (p - c) . c' = -r r', a circle about c - (r r' / |c'|^2) c' of radius
// sqrt(r^2 - (r r')^2 / |c'|^2); each end is closed by the end sphere's cap beyond its ring. The
// rings' frames are carried along by parallel transport, so the tube does not twist. `error` sets
// the segments around (as for a sphere of the largest radius) and along (cubic segments: chords of
// a curve that bends no tighter than that radius; linear ones are cones, one step).
void sphere_sweep_mesh(const Solid& primitive, double error, uint32_t most, TriangleMesh& mesh) {
  for (const SweepSegment& segment : primitive.sweep->segments) {
    double widest = 0, length_along = 0;
    constexpr int kSweepProbe = 16;
    for (int i = 0; i <= kSweepProbe; ++i) {
      const double u = double(i) / kSweepProbe;
      widest = std::max(widest, sweep_radius_at(segment, u));
      if (i)
        length_along +=
            length(sweep_centre_at(segment, u) - sweep_centre_at(segment, u - 1.0 / kSweepProbe));
    }
    if (!(widest > 0)) continue;
    const bool linear = dot(segment.c[2], segment.c[2]) == 0 &&
                        dot(segment.c[3], segment.c[3]) == 0 && segment.r[2] == 0 &&
                        segment.r[3] == 0;
    const uint32_t around = std::max(arc_segments(2 * kPi, widest, error / 2, most), 3u);
    const double step = std::sqrt(8 * widest * error / 4);
    const uint32_t along =
        linear ? 1u : std::clamp(uint32_t(std::ceil(length_along / step)), 4u, most);
    std::vector<SweepRing> rings;
    Vec3d last_axis{0, 0, 1};
    const auto tube_ring = [&](double u) {
      const Vec3d c = sweep_centre_at(segment, u), slope = sweep_centre_slope(segment, u);
      const double r = sweep_radius_at(segment, u), speed = length(slope);
      if (speed > 0) last_axis = slope / speed;  // a standing centre keeps the last direction
      const double offset = speed > 0 ? -r * sweep_radius_slope(segment, u) / speed : 0;
      const double clamped = std::clamp(offset, -r, r);  // swallowed by its neighbour: a point
      return SweepRing{c + last_axis * clamped, last_axis, c,
                       std::sqrt(std::max(r * r - clamped * clamped, 0.0))};
    };
    // The cap of the end sphere beyond the ring (side -1: behind u = 0, +1: past u = 1), its pole
    // to just short of the ring (the tube's own), in order from the pole or towards it.
    const auto cap = [&](const SweepRing& ring, double side, bool from_pole) {
      const double r = sweep_radius_at(segment, side < 0 ? 0.0 : 1.0);
      const double reach = std::acos(std::clamp(
          side * dot(ring.centre - ring.sphere, ring.axis) / std::max(r, 1e-300), -1.0, 1.0));
      const uint32_t n = arc_segments(reach, r, error / 4, most);
      for (uint32_t k = 0; k < n; ++k) {  // the ring itself is the tube's
        const double phi = reach * (from_pole ? k : n - 1 - k) / n;
        rings.push_back({ring.sphere + ring.axis * (side * r * std::cos(phi)), ring.axis,
                         ring.sphere, r * std::sin(phi)});
      }
    };
    const SweepRing first = tube_ring(0);
    cap(first, -1, true);
    for (uint32_t i = 0; i <= along; ++i)
      rings.push_back(tube_ring(double(i) / along));
    const SweepRing last = rings.back();  // a copy: cap() grows `rings`
    cap(last, 1, false);
    // Each ring: `around` + 1 vertices (the seam shares its position), frames transported.
    const uint32_t base = uint32_t(mesh.positions.size()), row = around + 1;
    Vec3d e1 =
        normalize(cross(rings.front().axis,
                        std::abs(rings.front().axis.x) < 0.9 ? Vec3d{1, 0, 0} : Vec3d{0, 1, 0}));
    for (const SweepRing& ring : rings) {
      const Vec3d projected = e1 - ring.axis * dot(e1, ring.axis);
      if (length(projected) > 1e-9) e1 = normalize(projected);
      const Vec3d e2 = cross(ring.axis, e1);
      for (uint32_t j = 0; j <= around; ++j) {
        const double theta = 2 * kPi * (j % around) / around;
        const Vec3d p = ring.centre + (e1 * std::cos(theta) + e2 * std::sin(theta)) * ring.radius;
        mesh.positions.emplace_back(p);
        const Vec3d n = p - ring.sphere;
        mesh.normals.emplace_back(length(n) > 0 ? normalize(n) : ring.axis);
      }
    }
    for (uint32_t i = 0; i + 1 < rings.size(); ++i)
      for (uint32_t j = 0; j < around; ++j) {
        const uint32_t a = base + i * row + j, b = a + row, c = b + 1, d = a + 1;
        triangle(mesh, a, b, c);
        triangle(mesh, a, c, d);
      }
  }
}

// A sor's profile in the (rho, y) half-plane: each segment sampled at a count doubled until the
// radius at the samples' midpoints strays from their chord by less than `error`, its normals from
// the gradient of rho^2 - r(y)^2; the caps as lines unless open. r^2 below 0 (no surface) is
// clamped to the axis.
std::vector<Piece> sor_profile(const Solid& primitive, double error, uint32_t most) {
  const Sor& sor = primitive.sor;
  const auto point = [](const SorSegment& s, double y) {
    const double r = std::sqrt(std::max(sor_radius_2(s, y), 0.0));
    const Vec3d g = sor_side_gradient({s}, {r, y, 0});
    const double len = std::hypot(g.x, g.y);
    return len > 0 ? ProfilePoint{r, y, g.x / len, g.y / len} : ProfilePoint{r, y, 1, 0};
  };
  Piece side;
  for (const SorSegment& s : sor) {
    uint32_t steps = 4;
    const auto at = [&](double f) { return point(s, s.y0 + (s.y1 - s.y0) * f); };
    const auto straying = [&](uint32_t n) {
      double worst = 0;
      for (uint32_t i = 0; i < n; ++i)
        worst =
            std::max(worst, std::abs(at((i + 0.5) / n).rho -
                                     0.5 * (at(double(i) / n).rho + at(double(i + 1) / n).rho)));
      return worst;
    };
    while (2 * steps <= most && straying(steps) > error)
      steps *= 2;
    for (uint32_t i = side.empty() ? 0 : 1; i <= steps; ++i)
      side.push_back(at(double(i) / steps));
  }
  std::vector<Piece> pieces;
  if (!primitive.open && side.front().rho > 0)
    pieces.push_back(line(0, side.front().z, side.front().rho, side.front().z));
  pieces.push_back(side);
  if (!primitive.open && side.back().rho > 0)
    pieces.push_back(line(side.back().rho, side.back().z, 0, side.back().z));
  return pieces;
}

// A lathe's curves (core/scene/lathe.h) in the (rho, y) half-plane, a piece a segment: each
// sampled at a count doubled until the curve at the samples' midpoints strays from their chords
// by less than `error`. Normals are the tangent turned towards the outside, which for a curve
// running counter-clockwise (positive area, closing it by a chord if open) is on its right.
std::vector<Piece> lathe_pieces(const Outline& profile, double error, uint32_t most) {
  double area_2 = 0;
  const Vec2d first = profile.segments.front().start, last = profile.segments.back().end;
  area_2 += last.x * first.y - first.x * last.y;
  std::vector<std::vector<Vec2d>> samples;
  for (const OutlineSegment& s : profile.segments) {
    const auto straying = [&](uint32_t n) {
      double worst = 0;
      for (uint32_t i = 0; i < n; ++i) {
        const Vec2d mid = segment_point(s, (i + 0.5) / n);
        const Vec2d chord =
            (segment_point(s, double(i) / n) + segment_point(s, double(i + 1) / n)) * 0.5;
        worst = std::max(worst, std::hypot(mid.x - chord.x, mid.y - chord.y));
      }
      return worst;
    };
    uint32_t steps = 1;
    while (s.degree > 1 && 2 * steps <= most && (steps < 4 || straying(steps) > error))
      steps *= 2;
    std::vector<Vec2d>& points = samples.emplace_back();
    for (uint32_t i = 0; i <= steps; ++i)
      points.push_back(i == 0 ? s.start : i == steps ? s.end : segment_point(s, double(i) / steps));
    for (uint32_t i = 0; i < steps; ++i)
      area_2 += points[i].x * points[i + 1].y - points[i + 1].x * points[i].y;
  }
  const double outside = area_2 >= 0 ? 1 : -1;
  std::vector<Piece> pieces;
  for (size_t k = 0; k < samples.size(); ++k) {
    const OutlineSegment& s = profile.segments[k];
    Piece& piece = pieces.emplace_back();
    const size_t steps = samples[k].size() - 1;
    for (size_t i = 0; i <= steps; ++i) {
      const Vec2d p = samples[k][i], t = segment_tangent(s, double(i) / steps);
      const double len = std::hypot(t.x, t.y);
      piece.push_back(len > 0 ? ProfilePoint{p.x, p.y, outside * t.y / len, -outside * t.x / len}
                              : ProfilePoint{p.x, p.y, 0, 0});
    }
  }
  return pieces;
}

// revolve() turns its profile about z; a sor turns about y: swap the two, a mirror, so every
// triangle's winding is reversed to stay counter-clockwise about its normals.
void swap_y_and_z(TriangleMesh& mesh) {
  for (Vec3f& p : mesh.positions)
    std::swap(p.y, p.z);
  for (Vec3f& n : mesh.normals)
    std::swap(n.y, n.z);
  for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
    std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);
}

// The marching grid's cells on the longest side of `box` for a chord error `error` (object units).
// Flat pieces across a cell stray by about cell^2 curvature / 8. The surface's curvature is not
// known: cells of sqrt(8 error r) meet the tolerance where it curves no more than a sphere of
// radius r, taken as a quarter of the box's least half-size. The grid is capped
// (kMarchedMaxCells), past which the tolerance is not met.
uint32_t marched_cells(const Bounds3d& box, double error) {
  const Vec3d size = box.hi - box.lo;
  const double longest = std::max({size.x, size.y, size.z});
  const double radius = 0.125 * std::min({size.x, size.y, size.z});
  const double cells = std::ceil(longest / std::sqrt(8 * error * radius));
  return cells < kMarchedMaxCells ? uint32_t(cells) : kMarchedMaxCells;  // NaN: the most
}

}  // namespace

double tessellation_tolerance_m(const Solid& primitive, const TessellationOptions& options) {
  const double stretch = largest_stretch(primitive.world_from_object);
  const Bounds3d box = object_bounds(primitive);
  const double object_radius =
      box.finite() ? length(max(abs(box.lo), abs(box.hi))) : 1.0;  // a disc's unit radius
  double tolerance = HUGE_VAL;
  if (options.tolerance_m > 0) tolerance = options.tolerance_m;
  if (options.relative_tolerance > 0)
    tolerance = std::min(tolerance, options.relative_tolerance * stretch * object_radius);
  if (!std::isfinite(tolerance)) tolerance = 1e-3 * stretch * object_radius;
  return tolerance;
}

void warn_untessellated(const Solid& primitive, Diagnostics& diagnostics) {
  diagnostics.warn(primitive.name + (primitive.kind == SolidKind::kPolynomial
                                         ? ": polynomial surfaces (quadric, cubic, quartic, poly) "
                                           "have no triangle form yet: left out of the mesh"
                                     : primitive.kind == SolidKind::kBlob
                                         ? ": blobs have no triangle form yet: left out of the mesh"
                                         : ": the surface has no triangles: left out"));
}

TriangleMesh tessellate(const Solid& primitive, const TessellationOptions& options) {
  TriangleMesh mesh;
  mesh.name = primitive.name;
  mesh.material = primitive.material;
  if (primitive.kind == SolidKind::kBox) {
    box(mesh);
    return mesh;
  }
  if (primitive.kind == SolidKind::kHalfSpace) {
    plane_square(primitive, options, mesh);
    return mesh;
  }
  if (primitive.kind == SolidKind::kOutline) {
    tessellate_outline(
        primitive,
        tessellation_tolerance_m(primitive, options) / largest_stretch(primitive.world_from_object),
        std::max(options.max_segments, 1u), mesh);
    return mesh;
  }
  // The tolerance in object units. Half of it goes to the angular segments, a quarter to the
  // profile's: a flat triangle strays from the surface by about the sum of the two sagittas.
  const double stretch = largest_stretch(primitive.world_from_object);
  const double error = tessellation_tolerance_m(primitive, options) / stretch;
  const uint32_t most = std::max(options.max_segments, 3u);
  if (primitive.kind == SolidKind::kSuperellipsoid) {
    superellipsoid_mesh(primitive, error, most, mesh);
    return mesh;
  }
  if (primitive.kind == SolidKind::kSphereSweep) {
    sphere_sweep_mesh(primitive, error, most, mesh);
    return mesh;
  }
  if (primitive.kind == SolidKind::kIsosurface) {
    tessellate_isosurface(*primitive.isosurface, primitive.open,
                          marched_cells(isosurface_bounds(*primitive.isosurface), error), mesh);
    return mesh;
  }
  if (primitive.kind == SolidKind::kJuliaFractal) {
    // A fractal's folds are no gently curved surface: marched_cells' estimate leaves out sheets
    // thinner than its cells, so the set takes the finest grid (a quarter of a second).
    tessellate_julia_fractal(*primitive.julia, kMarchedMaxCells, mesh);
    return mesh;
  }
  const bool lathe = primitive.kind == SolidKind::kLathe;
  if ((primitive.kind == SolidKind::kSor && !primitive.sor.empty()) ||
      (lathe && !primitive.outline->segments.empty())) {
    // As the other surfaces of revolution: a quarter of the tolerance to the profile, half to the
    // angular segments.
    const double widest =
        lathe ? lathe_bounds(*primitive.outline).hi.x : sor_bounds(primitive.sor).hi.x;
    revolve(lathe ? lathe_pieces(*primitive.outline, error / 4, most)
                  : sor_profile(primitive, error / 4, most),
            std::max(arc_segments(2 * kPi, widest, error / 2, most), 3u), mesh);
    swap_y_and_z(mesh);
    return mesh;
  }
  const double r0 = std::abs(primitive.radius0), r1 = std::abs(primitive.radius1);
  std::vector<Piece> pieces;
  double widest = 1;  // the largest rho the profile reaches
  const bool caps = !primitive.open;
  switch (primitive.kind) {
    case SolidKind::kSphere:
      pieces.push_back(arc(0, 0, 1, -kPi / 2, kPi / 2, arc_segments(kPi, 1, error / 4, most)));
      pieces.back().front().rho = pieces.back().back().rho = 0;  // exactly on the axis
      break;
    case SolidKind::kCylinder:
    case SolidKind::kCone: {
      const bool cylinder = primitive.kind == SolidKind::kCylinder;
      const double base = cylinder ? 1 : r0, cap = cylinder ? 1 : r1;
      widest = std::max(base, cap);
      if (caps && base > 0) pieces.push_back(line(0, 0, base, 0));
      pieces.push_back(line(base, 0, cap, 1));
      if (caps && cap > 0) pieces.push_back(line(cap, 1, 0, 1));
      break;
    }
    case SolidKind::kTorus:
      widest = 1 + r1;
      pieces.push_back(arc(1, 0, r1, -kPi, kPi, arc_segments(2 * kPi, r1, error / 4, most)));
      break;
    case SolidKind::kDisc:
      pieces.push_back(line(1, 0, std::min(r1, 1.0), 0));  // outward: +z
      break;
    case SolidKind::kLemon: {
      // The minor circle's arc about (-major, 0) between the slab's planes, caps unless open.
      const Lemon& lemon = primitive.lemon;
      const double from = std::asin(std::clamp(lemon.z_low, -1.0, 1.0));
      const double to = std::asin(std::clamp(lemon.z_high, -1.0, 1.0));
      widest = lemon_widest(lemon);
      pieces.push_back(
          arc(-lemon.major, 0, 1, from, to, arc_segments(to - from, 1, error / 4, most)));
      for (ProfilePoint& p : pieces.back())
        p.rho = std::max(p.rho, 0.0);  // a cusp on the axis
      const double rho_low = pieces.back().front().rho, rho_high = pieces.back().back().rho;
      if (caps && rho_low > 0)
        pieces.insert(pieces.begin(), line(0, lemon.z_low, rho_low, lemon.z_low));
      if (caps && rho_high > 0) pieces.push_back(line(rho_high, lemon.z_high, 0, lemon.z_high));
      break;
    }
    default:
      return mesh;  // set operations are not primitives
  }
  revolve(pieces, std::max(arc_segments(2 * kPi, widest, error / 2, most), 3u), mesh);
  return mesh;
}

void tessellate_solids(Scene& scene, TessellationOptions options, Diagnostics& diagnostics) {
  const Bounds3d bounds = scene.world_bounds(0);  // solids are static
  options.plane_centre = scene.cameras.empty()
                             ? Vec3d{0, 0, 0}
                             : scene.cameras.front().world_from_camera.translation();
  if (!bounds.empty())
    options.plane_half_size_m = std::max(options.plane_half_size_m,
                                         10 * length(max(abs(bounds.lo - options.plane_centre),
                                                         abs(bounds.hi - options.plane_centre))));
  for (const Solid& s : scene.solids) {
    if (s.is_primitive() && !s.inverse) {  // its own surface, whole: exact in its object space
      TriangleMesh mesh = tessellate(s, options);
      if (mesh.indices.empty()) {
        warn_untessellated(s, diagnostics);
        continue;
      }
      scene.instances.push_back({uint32_t(scene.meshes.size()), s.world_from_object, s.name});
      scene.meshes.push_back(std::move(mesh));
      continue;
    }
    SolidTessellation t = tessellate_csg(s, options, diagnostics);
    if (t.meshes.empty()) diagnostics.warn(s.name + ": the solid has no surface: nothing to write");
    for (TriangleMesh& mesh : t.meshes) {
      scene.instances.push_back({uint32_t(scene.meshes.size()), t.world_from_mesh, s.name});
      scene.meshes.push_back(std::move(mesh));
    }
  }
  scene.solids.clear();
}

}  // namespace fb
