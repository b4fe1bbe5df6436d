#include "importers/pov/pov_geometry.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "importers/pov/pov_space.h"

namespace fb::pov {

namespace {

// The affine map with these columns: canonical x, y, z axes and origin.
Transform columns(Vec3d x, Vec3d y, Vec3d z, Vec3d origin) {
  return Transform::from_rows(
      {x.x, y.x, z.x, origin.x, x.y, y.y, z.y, origin.y, x.z, y.z, z.z, origin.z, 0, 0, 0, 1});
}

// Two unit vectors completing unit `w` to an orthonormal basis (Duff et al. 2017).
std::pair<Vec3d, Vec3d> perpendiculars(Vec3d w) {
  const double sign = std::copysign(1.0, w.z), a = -1 / (sign + w.z), b = w.x * w.y * a;
  return {{1 + sign * w.x * w.x * a, sign * b, -sign * w.x}, {b, sign + w.y * w.y * a, -w.y}};
}

bool invertible(const Transform& t) {
  const double det = t.determinant3x3();
  return t.is_finite() && std::isfinite(det) && det != 0 && t.inverse().is_finite();
}

bool contains_mesh(const Object& o) {
  return o.shape == Shape::kMesh ||
         std::any_of(o.children.begin(), o.children.end(), contains_mesh);
}

class Converter {
 public:
  Converter(const MaterialFor& material_for, fb::Scene& scene, Diagnostics& diagnostics)
      : material_for_(material_for), scene_(scene), diagnostics_(diagnostics) {}

  void emit(const Object& o);

 private:
  void warn(const Object& o, const std::string& what) {
    diagnostics_.warn(o.where.text() + ": " + o.keyword + " " + what);
  }
  // Geometry that is drawn otherwise than POV-Ray draws it, or not at all: reported as an
  // unsupported object, which is what the sample-scene sweep counts as incomplete geometry.
  void incomplete(const Object& o, const std::string& what, const std::string& outcome) {
    diagnostics_.warn(o.where.text() + ": unsupported object '" + what + "': " + outcome);
  }
  static std::string name(const Object& o) { return o.keyword + " at " + o.where.text(); }
  std::optional<Solid> primitive(const Object& o);
  std::optional<Solid> ovus(const Object& o);
  std::optional<Solid> solid(const Object& o);
  void mesh(const Object& o);

  const MaterialFor& material_for_;
  fb::Scene& scene_;
  Diagnostics& diagnostics_;
};

// The shape's canonical solid (core/scene/solid.h) placed in POV-Ray's object space, then in the
// world: world_from_pov_space * world_from_object * placement.
std::optional<Solid> Converter::primitive(const Object& o) {
  Solid s;
  s.name = name(o);
  s.open = o.open;
  Transform place;
  bool degenerate = false;
  switch (o.shape) {
    case Shape::kSphere: {
      const double r = std::abs(o.r0);
      s.kind = SolidKind::kSphere;
      degenerate = !(r > 0);
      place = Transform::translate(o.a) * Transform::scale({r, r, r});
      break;
    }
    case Shape::kBox: {
      const Vec3d lo = min(o.a, o.b), hi = max(o.a, o.b), half = (hi - lo) * 0.5;
      s.kind = SolidKind::kBox;
      degenerate = !(min_component(half) > 0);
      place = Transform::translate((lo + hi) * 0.5) * Transform::scale(half);
      break;
    }
    case Shape::kPlane: {
      // Parse_Plane normalises the normal but not the distance: the surface is n.p = d for the
      // unit n, the inside n.p < d.
      const double len = length(o.a);
      s.kind = SolidKind::kHalfSpace;
      degenerate = !(len > 0);
      const Vec3d n = o.a / len;
      const auto [u, v] = perpendiculars(n);
      place = columns(u, v, n, n * o.r0);
      break;
    }
    case Shape::kCylinder:
    case Shape::kCone: {
      const Vec3d axis = o.b - o.a;
      const double len = length(axis);
      const bool cylinder = o.shape == Shape::kCylinder;
      s.kind = cylinder ? SolidKind::kCylinder : SolidKind::kCone;
      // A cylinder's radius goes into its placement, a cone's two radii into the solid.
      const double r = cylinder ? std::abs(o.r0) : 1;
      if (!cylinder) s.radius0 = std::abs(o.r0), s.radius1 = std::abs(o.r1);
      degenerate = !(len > 0) || !(r * std::max(s.radius0, s.radius1) > 0);
      const auto [u, v] = perpendiculars(axis / len);
      place = columns(u * r, v * r, axis, o.a);
      break;
    }
    case Shape::kTorus: {
      // In POV-Ray's XZ plane about +y: canonical x, y, z go to x, z, y, scaled by the major
      // radius.
      const double major = std::abs(o.r0), minor = std::abs(o.r1);
      s.kind = SolidKind::kTorus;
      degenerate = !(major > 0) || !(minor > 0);
      s.radius1 = minor / major;
      place = columns({major, 0, 0}, {0, 0, major}, {0, major, 0}, {0, 0, 0});
      break;
    }
    case Shape::kDisc: {
      const double len = length(o.b), r = std::abs(o.r0), hole = std::abs(o.r1);
      s.kind = SolidKind::kDisc;
      degenerate = !(len > 0) || !(r > hole);
      s.radius1 = hole / r;
      const Vec3d n = o.b / len;
      const auto [u, v] = perpendiculars(n);
      place = columns(u * r, v * r, n, o.a);
      break;
    }
    case Shape::kPolynomial: {
      // POV-Ray's poly order: x powers from the degree down, then y, then z
      s.kind = SolidKind::kPolynomial;
      size_t n = 0;
      for (int i = o.order; i >= 0; --i)
        for (int j = o.order - i; j >= 0; --j)
          for (int k = o.order - i - j; k >= 0; --k, ++n)
            if (n < o.coefficients.size() && o.coefficients[n] != 0)
              s.polynomial.push_back({o.coefficients[n], uint8_t(i), uint8_t(j), uint8_t(k)});
      degenerate = polynomial3_degree(s.polynomial) == 0;
      break;
    }
    case Shape::kPrism: {
      if (!o.outline) return std::nullopt;  // not closed: the parser said so, as POV-Ray does
      // The outline's <x, z> are canonical x, y. Linear: canonical z from 0 to 1 is y from r0 to
      // r1. Conic: canonical z is y, the outline scaled by it (POV-Ray's points <x y, y, z y>).
      s.kind = SolidKind::kOutline;
      s.outline = o.outline;
      s.conic = o.conic;
      s.radius0 = std::min(o.r0, o.r1), s.radius1 = std::max(o.r0, o.r1);
      degenerate = !(std::abs(o.r1 - o.r0) > 0) || !(o.outline->hi.x > o.outline->lo.x) ||
                   !(o.outline->hi.y > o.outline->lo.y) || (o.conic && !(o.r0 * o.r1 >= 0));
      place = o.conic ? columns({1, 0, 0}, {0, 0, 1}, {0, 1, 0}, {0, 0, 0})
                      : columns({1, 0, 0}, {0, 0, 1}, {0, o.r1 - o.r0, 0}, {0, o.r0, 0});
      break;
    }
    case Shape::kSuperellipsoid:  // POV-Ray's own object space: the parser bounded e and n
      s.kind = SolidKind::kSuperellipsoid;
      s.radius0 = o.r0, s.radius1 = o.r1;
      degenerate = !(o.r0 > 0 && o.r1 > 0);
      break;
    case Shape::kBlob:  // POV-Ray's object space; each component placed by its own transforms
      s.kind = SolidKind::kBlob;
      s.blob.threshold = o.r0;
      for (const BlobComponentStatement& c : o.blob_components)
        s.blob.components.push_back(
            {c.blob_from_component.inverse(), c.a, c.b, c.radius, c.strength, c.cylinder});
      degenerate = blob_bounds(s.blob).empty();  // no component of positive strength
      break;
    case Shape::kSor:  // POV-Ray's object space, about its y axis; the parser checked the points
      s.kind = SolidKind::kSor;
      s.sor = sor_from_points(o.profile);
      degenerate = s.sor.empty() || !(sor_bounds(s.sor).hi.x > 0);
      break;
    case Shape::kLathe:  // POV-Ray's object space: the profile's (radius, height) about y
      s.kind = SolidKind::kLathe;
      s.outline = o.outline;
      degenerate = !(o.outline->hi.x > 0);  // all on the axis: no surface
      break;
    case Shape::kSphereSweep: {  // POV-Ray's object space; the parser built the segments
      s.kind = SolidKind::kSphereSweep;
      s.sweep = o.sweep;
      degenerate = true;  // unless some sphere has a radius
      for (const SweepSegment& segment : o.sweep->segments)
        for (double r : segment.r)
          degenerate = degenerate && r == 0;
      break;
    }
    case Shape::kLemon: {
      // Compute_Lemon_Data: in units of the axis's length, base at height 0 with radius a, apex
      // at 1 with radius b, the minor circle of radius r through both rims has its centre at
      // (h, v), h <= 0 (the parser raised r so that it is): with f = sqrt((4 r^2 - (a - b)^2 -
      // 1) / ((a - b)^2 + 1)), h = (a + b - f) / 2 and v = ((b - a) f + 1) / 2. The canonical
      // lemon is that circle's, scaled to radius 1 and centred at height 0.
      const Vec3d axis = o.a - o.b;
      const double len = length(axis);
      const double a = o.r1 / len, b = o.r0 / len, r = o.r2 / len, k = (a - b) * (a - b) + 1;
      const double f = std::sqrt(std::max(4 * r * r - k, 0.0) / k);
      const double h = std::min((a + b - f) / 2, 0.0), v = ((b - a) * f + 1) / 2;
      s.kind = SolidKind::kLemon;
      s.lemon = {-h / r, -v / r, (1 - v) / r};
      degenerate = !(len > 0) || !(r > 0) || lemon_bounds(s.lemon).empty();
      const Vec3d w = axis / len;
      const auto [u, u2] = perpendiculars(w);
      place = columns(u * (len * r), u2 * (len * r), w * (len * r), o.b + w * (len * v));
      break;
    }
    case Shape::kIsosurface:  // POV-Ray's object space; the parser checked the bounds
      s.kind = SolidKind::kIsosurface;
      s.isosurface = o.isosurface;
      break;
    case Shape::kJuliaFractal:  // POV-Ray's object space; the parser checked the parameters
      s.kind = SolidKind::kJuliaFractal;
      s.julia = o.julia;
      break;
    default:
      return std::nullopt;
  }
  s.world_from_object = world_from_pov_space() * o.world_from_object * place;
  if (degenerate || !invertible(s.world_from_object)) {
    warn(o, "is degenerate (zero size or a singular transform): left out");
    return std::nullopt;
  }
  s.material = material_for_(o.texture, o.interior);
  return s;
}

// POV-Ray 3.7's ovus (Parse_Ovus, ovus.cpp): the bottom sphere about the origin, the top one about
// (0, bottom, 0), joined by a collar of the spindle torus whose minor circle (radius twice the
// larger sphere's) touches both from outside the axis: their merge, which is POV-Ray's inside.
// The collar's planes are where the circle touches the spheres, so they are no surface. A top
// radius of twice the bottom's or more swallows the bottom sphere: POV-Ray draws the top sphere.
std::optional<Solid> Converter::ovus(const Object& o) {
  const double bottom = o.r0, top = o.r1;
  const Transform world_from_object = world_from_pov_space() * o.world_from_object;
  if (!invertible(world_from_object) || !(std::max(bottom, top) > 0)) {
    warn(o, "is degenerate (zero size or a singular transform): left out");
    return std::nullopt;
  }
  Solid u;
  u.kind = SolidKind::kUnion;
  u.name = name(o);
  const uint32_t material = material_for_(o.texture, o.interior);
  const auto add = [&](SolidKind kind, const Transform& place) -> Solid& {
    Solid& s = u.children.emplace_back();
    s.kind = kind;
    s.name = u.name;
    s.material = material;
    s.world_from_object = world_from_object * place;
    return s;
  };
  const auto sphere = [&](double y, double r) {
    if (r > 0)
      add(SolidKind::kSphere, Transform::translate({0, y, 0}) * Transform::scale({r, r, r}));
  };
  if (!(top < 2 * bottom)) {
    warn(o,
         "top radius is not below twice the bottom radius: drawn as its top sphere, as POV-Ray "
         "draws it");
    sphere(bottom, top);
    return std::move(u.children.front());
  }
  sphere(0, bottom);
  sphere(bottom, top);
  // The torus's minor circle: radius c, centre at height v and at h on the far side of the axis;
  // it touches the spheres at the heights low and high.
  double c, v, h, low, high;
  if (bottom > top) {
    c = 2 * bottom;
    v = 2 * top - bottom - top * top / (2 * bottom);
    h = std::sqrt(std::max(bottom * bottom - v * v, 0.0));
    low = -v;
    high = (bottom - v) * top / (c - top) + bottom;
  } else {
    c = 2 * top;
    v = -2 * top + bottom + 1.5 * top * top / bottom;
    h = std::sqrt(std::max(top * top - (v - bottom) * (v - bottom), 0.0));
    high = 2 * bottom - v;
    low = -v * bottom / (c - bottom);
  }
  const Lemon collar{h / c, (low - v) / c, (high - v) / c};
  if (!lemon_bounds(collar).empty()) {
    // canonical z is POV-Ray's y, as for the torus
    Solid& s = add(SolidKind::kLemon, columns({c, 0, 0}, {0, 0, c}, {0, c, 0}, {0, v, 0}));
    s.lemon = collar;
    s.open = true;
  }
  return u;
}

std::optional<Solid> Converter::solid(const Object& o) {
  std::optional<Solid> s;
  switch (o.shape) {
    case Shape::kMesh:
      incomplete(o, o.keyword + " inside CSG", "left out (its triangles have no inside here)");
      return std::nullopt;
    case Shape::kUnion:
    case Shape::kMerge:
    case Shape::kIntersection:
    case Shape::kDifference: {
      s.emplace();
      s->name = name(o);
      // A difference is the base intersected with the complements of the rest, as POV-Ray's
      // Parse_CSG builds it.
      s->kind = o.shape == Shape::kIntersection || o.shape == Shape::kDifference
                    ? SolidKind::kIntersection
                    : SolidKind::kUnion;
      for (size_t i = 0; i < o.children.size(); ++i) {
        std::optional<Solid> child = solid(o.children[i]);
        if (!child) {
          if (o.shape == Shape::kDifference && i == 0) return std::nullopt;
          continue;
        }
        if (o.shape == Shape::kDifference && i > 0) child->inverse = !child->inverse;
        s->children.push_back(std::move(*child));
      }
      if (s->children.empty()) return std::nullopt;
      break;
    }
    case Shape::kOvus:
      s = ovus(o);
      if (!s) return std::nullopt;
      break;
    default:
      s = primitive(o);
      if (!s) return std::nullopt;
  }
  s->inverse = s->inverse != o.inverse;
  if (!o.clipped_by.empty()) {  // what is clipped stays open: the clips bound without surface
    Solid clipped;
    clipped.kind = SolidKind::kIntersection;
    clipped.name = s->name;
    clipped.children.push_back(std::move(*s));
    for (const Object& clip : o.clipped_by)
      if (std::optional<Solid> c = solid(clip)) {
        c->bounds_only = true;
        clipped.children.push_back(std::move(*c));
      }
    s = std::move(clipped);
  }
  return s;
}

// One mesh per material (mesh2 texture_list gives triangles their own), each with the vertices
// its triangles use, in POV-Ray's object space; the instance mirrors it into the world, and
// RenderGeometry and glTF both reverse the winding of a mirroring instance.
void Converter::mesh(const Object& o) {
  const Transform world_from_object = world_from_pov_space() * o.world_from_object;
  if (!invertible(world_from_object)) {
    warn(o, "has a singular transform: left out");
    return;
  }
  std::map<uint32_t, uint32_t> material_of_texture;     // texture index (or none) -> material
  std::map<uint32_t, std::vector<uint32_t>> triangles;  // material -> triangles
  const size_t count = o.indices.size() / 3;
  size_t bad = 0;
  for (size_t t = 0; t < count; ++t) {
    if (std::max({o.indices[3 * t], o.indices[3 * t + 1], o.indices[3 * t + 2]}) >=
        o.vertices.size()) {
      ++bad;
      continue;
    }
    const uint32_t texture = t < o.triangle_textures.size() ? o.triangle_textures[t] : UINT32_MAX;
    auto [it, added] = material_of_texture.try_emplace(texture, 0);
    if (added)
      it->second =
          material_for_(texture < o.textures.size() ? o.textures[texture] : o.texture, o.interior);
    triangles[it->second].push_back(uint32_t(t));
  }
  if (bad) warn(o, "has " + std::to_string(bad) + " triangles past its vertices: left out");
  const bool smooth = o.normals.size() == o.vertices.size();
  for (const auto& [material, list] : triangles) {
    TriangleMesh m;
    m.name = name(o);
    m.material = material;
    std::vector<uint32_t> remap(o.vertices.size(), UINT32_MAX);
    for (uint32_t t : list)
      for (int k = 0; k < 3; ++k) {
        const uint32_t i = o.indices[3 * t + k];
        if (remap[i] == UINT32_MAX) {
          remap[i] = uint32_t(m.positions.size());
          m.positions.emplace_back(o.vertices[i]);
          if (smooth) m.normals.emplace_back(o.normals[i]);
        }
        m.indices.push_back(remap[i]);
      }
    scene_.instances.push_back({uint32_t(scene_.meshes.size()), world_from_object, m.name});
    scene_.meshes.push_back(std::move(m));
  }
}

void Converter::emit(const Object& o) {
  if (o.no_image) {
    incomplete(o, o.keyword + " with no_image",
               "left out (POV-Ray would still let it cast shadows)");
    return;
  }
  if (o.no_shadow) warn(o, "has no_shadow, which is not rendered: it casts shadows");
  if (o.double_illuminate)
    warn(o, "has double_illuminate, which is not rendered: it is lit on the lights' side only");
  const bool plain = !o.inverse && o.clipped_by.empty();
  // A union's members keep all their surfaces in POV-Ray: each is an object of its own.
  if (plain && (o.shape == Shape::kUnion || (o.shape == Shape::kMerge && contains_mesh(o)))) {
    if (o.shape == Shape::kMerge)
      incomplete(o, "merge of triangles", "rendered as a union (inner surfaces stay)");
    for (const Object& child : o.children)
      emit(child);
    return;
  }
  if (o.shape == Shape::kMesh) {
    if (!plain)
      incomplete(o, o.keyword + " clipped or inverted",
                 "drawn whole (triangles have no inside here)");
    mesh(o);
    return;
  }
  if (std::optional<Solid> s = solid(o)) scene_.solids.push_back(std::move(*s));
}

}  // namespace

void convert_objects(const Scene& pov, const MaterialFor& material_for, fb::Scene& scene,
                     Diagnostics& diagnostics) {
  Converter converter(material_for, scene, diagnostics);
  for (const Object& o : pov.objects)
    converter.emit(o);
}

}  // namespace fb::pov
