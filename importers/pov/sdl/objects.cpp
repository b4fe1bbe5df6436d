// Objects: the finite and infinite primitives, triangle meshes, polygon, object references, CSG,
// and the modifiers every object takes (transforms, texture, flags, clipped_by).
#include <algorithm>
#include <array>
#include <cmath>

#include "importers/pov/sdl/keyword_table.h"
#include "importers/pov/sdl/parser.h"

namespace fb::pov::sdl {
namespace {

constexpr std::string_view kSupported[] = {"sphere",       "box",           "plane",
                                           "cylinder",     "cone",          "torus",
                                           "disc",         "triangle",      "smooth_triangle",
                                           "mesh",         "mesh2",         "polygon",
                                           "object",       "union",         "merge",
                                           "difference",   "intersection",  "light_source",
                                           "light_group",  "quadric",       "cubic",
                                           "quartic",      "poly",          "polynomial",
                                           "prism",        "text",          "superellipsoid",
                                           "height_field", "blob",          "sor",
                                           "lathe",        "ovus",          "lemon",
                                           "sphere_sweep", "bicubic_patch", "isosurface",
                                           "parametric",   "julia_fractal"};
// parsed and reported: their geometry needs code the renderer does not have yet
constexpr std::string_view kUnsupported[] = {"fractal"};

bool is_csg(Shape s) {
  return s == Shape::kUnion || s == Shape::kMerge || s == Shape::kIntersection ||
         s == Shape::kDifference;
}

void transform_object(Object& o, const Matrix& m, const Matrix& inverse) {
  if (is_csg(o.shape)) {
    for (Object& child : o.children)
      transform_object(child, m, inverse);
  } else {
    o.world_from_object = m * o.world_from_object;
  }
  if (o.texture_given) transform_texture(o.texture, inverse);
  for (Texture& t : o.textures)
    transform_texture(t, inverse);
  for (Object& clip : o.clipped_by)
    transform_object(clip, m, inverse);
}

void transform_node(Node& node, const Matrix& m) {
  Matrix inverse = m.inverse();
  if (node.object) transform_object(*node.object, m, inverse);
  for (LightSource& light : node.lights) {
    light.location = m.point(light.location);
    light.point_at = m.point(light.point_at);
    light.axis1 = m.vector(light.axis1);
    light.axis2 = m.vector(light.axis2);
  }
}

// A CSG's texture and interior go to the children that have none (POV-Ray manual 3.4.6).
void inherit(Object& o, const Texture* texture, const std::optional<Interior>& interior) {
  for (Object& child : o.children) {
    if (texture && !child.texture_given) {
      if (is_csg(child.shape)) {
        inherit(child, texture, std::nullopt);
      } else {
        child.texture = *texture;
      }
      child.texture_given = true;
    }
    if (interior && !child.interior) {
      if (is_csg(child.shape)) inherit(child, nullptr, interior);
      child.interior = interior;
    }
  }
}

Vec3d sub(Vec3d a, Vec3d b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
Vec3d cross(Vec3d a, Vec3d b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// Ear clipping of one closed loop of `count` points starting at `first`, in the plane of its
// Newell normal. Long loops (> 2000 points) and degenerate ones fall back to a fan.
void triangulate_loop(const std::vector<Vec3d>& points, uint32_t first, uint32_t count,
                      std::vector<uint32_t>& indices) {
  if (count < 3) return;
  Vec3d n{0, 0, 0};
  for (uint32_t i = 0; i < count; ++i) {
    Vec3d a = points[first + i], b = points[first + (i + 1) % count];
    n.x += (a.y - b.y) * (a.z + b.z);
    n.y += (a.z - b.z) * (a.x + b.x);
    n.z += (a.x - b.x) * (a.y + b.y);
  }
  int drop = std::abs(n.x) > std::abs(n.y) ? (std::abs(n.x) > std::abs(n.z) ? 0 : 2)
                                           : (std::abs(n.y) > std::abs(n.z) ? 1 : 2);
  auto p2 = [&](uint32_t i) -> std::pair<double, double> {
    Vec3d p = points[first + i];
    if (drop == 0) return {p.y, p.z};
    if (drop == 1) return {p.z, p.x};
    return {p.x, p.y};
  };
  std::vector<uint32_t> ring(count);
  for (uint32_t i = 0; i < count; ++i)
    ring[i] = i;
  double area = 0;
  for (uint32_t i = 0; i < count; ++i) {
    auto [ax, ay] = p2(i);
    auto [bx, by] = p2((i + 1) % count);
    area += ax * by - bx * ay;
  }
  if (area < 0) std::reverse(ring.begin(), ring.end());
  auto cross2 = [&](uint32_t a, uint32_t b, uint32_t c) {
    auto [ax, ay] = p2(a);
    auto [bx, by] = p2(b);
    auto [cx, cy] = p2(c);
    return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
  };
  auto emit = [&](uint32_t a, uint32_t b, uint32_t c) {
    indices.insert(indices.end(), {first + a, first + b, first + c});
  };
  while (ring.size() > 3 && count <= 2000) {
    bool clipped = false;
    for (size_t i = 0; i < ring.size(); ++i) {
      uint32_t a = ring[(i + ring.size() - 1) % ring.size()], b = ring[i],
               c = ring[(i + 1) % ring.size()];
      if (cross2(a, b, c) <= 0) continue;  // reflex corner
      bool empty = true;
      for (uint32_t q : ring) {
        if (q == a || q == b || q == c) continue;
        if (cross2(a, b, q) >= 0 && cross2(b, c, q) >= 0 && cross2(c, a, q) >= 0) {
          empty = false;
          break;
        }
      }
      if (!empty) continue;
      emit(a, b, c);
      ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(i));
      clipped = true;
      break;
    }
    if (!clipped) break;
  }
  for (size_t i = 1; i + 1 < ring.size(); ++i)
    emit(ring[0], ring[i], ring[i + 1]);
}

Node missing_node(const std::string& keyword, const SourceLocation& where) {
  Node node;
  node.missing.push_back({keyword, where, std::nullopt});
  return node;
}

// ---- the primitives' own arguments (POV-Ray 3.7 reference, "Finite Solid Primitives",
// "Infinite Solid Primitives", "Finite Patch Primitives") ----

// Where a primitive's argument goes: the points or vectors `a` and `b`, the radii (or distance)
// `r0` and `r1`.
enum class Arg { kA, kB, kR0, kR1 };

// A primitive whose arguments are a fixed list of vectors and floats, separated by optional
// commas.
struct Primitive {
  std::string_view name;
  Shape shape;
  std::array<Arg, 4> args;
  int count;
  bool optional_r1 = false;  // disc's hole radius
};

constexpr Primitive kPrimitives[] = {
    {"sphere", Shape::kSphere, {Arg::kA, Arg::kR0}, 2},                 // Center, Radius
    {"box", Shape::kBox, {Arg::kA, Arg::kB}, 2},                        // Corner1, Corner2
    {"plane", Shape::kPlane, {Arg::kA, Arg::kR0}, 2},                   // Normal, Distance
    {"cylinder", Shape::kCylinder, {Arg::kA, Arg::kB, Arg::kR0}, 3},    // Base, Cap, Radius
    {"cone", Shape::kCone, {Arg::kA, Arg::kR0, Arg::kB, Arg::kR1}, 4},  // Base, r, Cap, r
    {"torus", Shape::kTorus, {Arg::kR0, Arg::kR1}, 2},                  // Major, Minor
    {"disc", Shape::kDisc, {Arg::kA, Arg::kB, Arg::kR0}, 3, true},      // Center, Normal, r
};

void parse_primitive(Parser& p, Object& o, const Primitive& primitive) {
  o.shape = primitive.shape;
  for (int i = 0; i < primitive.count; ++i) {
    if (i) p.accept(",");
    switch (primitive.args[static_cast<size_t>(i)]) {
      case Arg::kA:
        o.a = p.parse_vector();
        break;
      case Arg::kB:
        o.b = p.parse_vector();
        break;
      case Arg::kR0:
        o.r0 = p.parse_float();
        break;
      case Arg::kR1:
        o.r1 = p.parse_float();
        break;
    }
  }
  if (primitive.optional_r1 && p.accept(",")) o.r1 = p.parse_float();
}

// triangle { C1, C2, C3 } / smooth_triangle { C1, N1, C2, N2, C3, N3 }: a one-triangle mesh.
void parse_triangle(Parser& p, Object& o, bool smooth) {
  o.shape = Shape::kMesh;
  for (int i = 0; i < 3; ++i) {
    if (i) p.accept(",");
    o.vertices.push_back(p.parse_vector());
    if (smooth) {
      p.accept(",");
      o.normals.push_back(p.parse_vector());
    }
  }
  o.indices = {0, 1, 2};
}

// polygon { Count, P1, ... }: sub-polygons close where a point repeats the first of its loop
// (POV-Ray manual 3.4.2.4); each loop is triangulated on its own (holes are not cut).
void parse_polygon(Parser& p, Object& o) {
  o.shape = Shape::kMesh;
  double n = p.parse_count();
  if (!(n >= 3 && n <= static_cast<double>(p.options().limits.objects)))
    p.fail("polygon needs at least 3 points");
  p.count_objects(static_cast<uint64_t>(n));
  std::vector<Vec3d> points;
  for (size_t i = 0; i < static_cast<size_t>(n); ++i) {
    p.accept(",");
    Value v = p.parse_numeric(3);
    points.push_back({v.v[0], v.v[1], v.v[2]});
  }
  size_t start = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    bool closes = i > start + 1 && points[i].x == points[start].x &&
                  points[i].y == points[start].y && points[i].z == points[start].z;
    if (closes || i + 1 == points.size()) {
      size_t end = closes ? i : i + 1;
      uint32_t first = static_cast<uint32_t>(o.vertices.size());
      o.vertices.insert(o.vertices.end(), points.begin() + static_cast<std::ptrdiff_t>(start),
                        points.begin() + static_cast<std::ptrdiff_t>(end));
      triangulate_loop(o.vertices, first, static_cast<uint32_t>(end - start), o.indices);
      start = i + 1;
    }
  }
}

// superellipsoid { <e, n> }: both exponents positive and finite. Outside [1e-3, 1e3] they are
// bounded (with a warning): a thousandth is already a box to a few parts in a thousand, and past
// it the powers 2/e leave the range of a double.
void parse_superellipsoid(Parser& p, Object& o) {
  constexpr double kSuperellipsoidLeast = 1e-3, kSuperellipsoidMost = 1e3;
  o.shape = Shape::kSuperellipsoid;
  const SourceLocation where = p.location_of(p.peek());
  const Value v = p.parse_numeric(2);
  const double e = v.v[0], n = v.v[1];
  if (!(e > 0 && n > 0 && std::isfinite(e) && std::isfinite(n)))
    p.fail_at(where, "superellipsoid exponents <" + number_string(e) + ", " + number_string(n) +
                         ">: both must be positive and finite");
  o.r0 = std::clamp(e, kSuperellipsoidLeast, kSuperellipsoidMost);
  o.r1 = std::clamp(n, kSuperellipsoidLeast, kSuperellipsoidMost);
  if (o.r0 != e || o.r1 != n)
    p.warn("superellipsoid exponents <" + number_string(e) + ", " + number_string(n) +
           "> bounded to <" + number_string(o.r0) + ", " + number_string(o.r1) + ">");
}

// sor { N, <r1, y1>, ..., <rN, yN> }: at least 4 points, heights increasing (POV-Ray's
// "Incorrect point in surface of revolution"), a point out of order refused at its place.
void parse_sor(Parser& p, Object& o) {
  o.shape = Shape::kSor;
  const double n = p.parse_count();
  if (!(n >= 4 && n <= double(p.options().limits.objects)))
    p.fail("sor needs at least 4 points, got " + number_string(n));
  p.count_objects(uint64_t(n));
  for (size_t i = 0; i < size_t(n); ++i) {
    p.accept(",");
    const SourceLocation where = p.location_of(p.peek());
    const Value v = p.parse_numeric(2);
    if (!std::isfinite(v.v[0]) || !std::isfinite(v.v[1]))
      p.fail_at(where, "sor point is not finite");
    // The curve's points rise strictly; the first and last, which only steer its end slopes, may
    // share their neighbour's height (objects/sor1.pov starts so).
    const bool end_point = i == 1 || i + 1 == size_t(n);
    if (!o.profile.empty() &&
        (end_point ? v.v[1] < o.profile.back().second : !(v.v[1] > o.profile.back().second)))
      p.fail_at(where, "sor point's height " + number_string(v.v[1]) + " is " +
                           (end_point ? "below" : "not above") + " the previous point's " +
                           number_string(o.profile.back().second));
    o.profile.emplace_back(v.v[0], v.v[1]);
  }
}

// A radius that must be finite and not negative, refused at its place otherwise.
double parse_radius(Parser& p, const std::string& what) {
  const SourceLocation where = p.location_of(p.peek());
  const double r = p.parse_float();
  if (!(r >= 0 && std::isfinite(r)))
    p.fail_at(where, what + " " + number_string(r) + ": it must be finite and not negative");
  return r;
}

// ovus { bottom_radius, top_radius } (POV-Ray 3.7's Parse_Ovus): "Both Ovus radii must be
// positive"; the shape itself is worked out where it is converted (importers/pov/pov_geometry).
void parse_ovus(Parser& p, Object& o) {
  o.shape = Shape::kOvus;
  o.r0 = parse_radius(p, "ovus bottom radius");
  p.accept(",");
  o.r1 = parse_radius(p, "ovus top radius");
}

// lemon { apex, apex_radius, base, base_radius, inner_radius [open] } (POV-Ray 3.8's
// Parse_Lemon and Compute_Lemon_Data): radii not negative, the two points apart; an inner radius
// too small for the torus's circle to reach both end circles is raised to the least that does,
// with a warning, as POV-Ray does.
void parse_lemon(Parser& p, Object& o) {
  o.shape = Shape::kLemon;
  const SourceLocation where = p.location_of(p.peek());
  o.a = p.parse_vector();
  p.accept(",");
  o.r0 = parse_radius(p, "lemon apex radius");
  p.accept(",");
  o.b = p.parse_vector();
  p.accept(",");
  o.r1 = parse_radius(p, "lemon base radius");
  p.accept(",");
  const SourceLocation inner_where = p.location_of(p.peek());
  o.r2 = parse_radius(p, "lemon inner radius");
  const double len = length(o.a - o.b);
  if (!(len > 0 && std::isfinite(len)))
    p.fail_at(where, "lemon's apex and base coincide (or are not finite): degenerate lemon");
  // In units of the axis's length, base at height 0 with radius a, apex at 1 with radius b: the
  // circle through both end circles' rims reaches the axis (the torus's major radius 0) at r =
  // sqrt((a^2 - b^2)^2 + 2 a^2 + 2 b^2 + 1) / 2; below it the circle would pass the axis.
  const double a = o.r1 / len, b = o.r0 / len;
  const double least =
      0.5 * len * std::sqrt((a * a - b * b) * (a * a - b * b) + 2 * a * a + 2 * b * b + 1);
  if (o.r2 < least) {
    p.warn_at(inner_where, "lemon inner radius " + number_string(o.r2) +
                               " is too small: the least is " + number_string(least) +
                               ", which is used");
    o.r2 = least;
  }
}

// The other shapes, whose arguments need their own parser.
struct ShapeParser {
  std::string_view name;
  void (*parse)(Parser&, Object&);
};

constexpr ShapeParser kShapes[] = {
    {"triangle", [](Parser& p, Object& o) { parse_triangle(p, o, false); }},
    {"smooth_triangle", [](Parser& p, Object& o) { parse_triangle(p, o, true); }},
    {"mesh", [](Parser& p, Object& o) { p.parse_mesh(o); }},
    {"mesh2", [](Parser& p, Object& o) { p.parse_mesh2(o); }},
    {"polygon", parse_polygon},
    {"prism", [](Parser& p, Object& o) { p.parse_prism(o); }},
    {"superellipsoid", parse_superellipsoid},
    {"height_field", [](Parser& p, Object& o) { p.parse_height_field(o); }},
    {"blob", [](Parser& p, Object& o) { p.parse_blob(o); }},
    {"sor", parse_sor},
    {"lathe", [](Parser& p, Object& o) { p.parse_lathe(o); }},
    {"ovus", parse_ovus},
    {"lemon", parse_lemon},
    {"sphere_sweep", [](Parser& p, Object& o) { p.parse_sphere_sweep(o); }},
    {"bicubic_patch", [](Parser& p, Object& o) { p.parse_bicubic_patch(o); }},
    {"isosurface", [](Parser& p, Object& o) { p.parse_isosurface(o); }},
    {"parametric", [](Parser& p, Object& o) { p.parse_parametric(o); }},
};

// gif and pot keep their heights in palette indices (pot: two 8-bit halves of one 16-bit height),
// which OpenImageIO's GIF reader turns into colours; iff and sys it does not read.
bool is_unread_height_field(const Tok& first) {
  for (std::string_view w : {"gif", "pot", "iff", "sys"})
    if (first.word(w)) return true;
  return false;
}

bool is_polynomial(std::string_view w) {
  return w == "quadric" || w == "cubic" || w == "quartic" || w == "poly" || w == "polynomial";
}

// ---- mesh2 (POV-Ray 3.7 reference, "Mesh2"): its blocks, read in any order ----

// The `{ Count,` that opens a mesh2 block, bounded by the object limit.
size_t mesh2_count(Parser& p) {
  p.expect("{");
  double n = p.parse_count();
  if (!(n >= 0 && n <= static_cast<double>(p.options().limits.objects))) p.fail("bad mesh2 count");
  p.count_objects(static_cast<uint64_t>(n));
  return static_cast<size_t>(n);
}

// The `, }` that closes a mesh2 block (a trailing comma is allowed).
void mesh2_close(Parser& p) {
  p.accept(",");
  p.expect("}");
}

void parse_mesh2_vectors(Parser& p, std::vector<Vec3d>& target) {
  size_t n = mesh2_count(p);
  for (size_t i = 0; i < n; ++i) {
    p.accept(",");
    target.push_back(p.parse_vector());
  }
  mesh2_close(p);
}

void skip_mesh2_uv_vectors(Parser& p) {
  size_t n = mesh2_count(p);
  for (size_t i = 0; i < n; ++i) {
    p.accept(",");
    p.parse_numeric(2);
  }
  mesh2_close(p);
}

void parse_mesh2_texture_list(Parser& p, Object& o) {
  size_t n = mesh2_count(p);
  for (size_t i = 0; i < n; ++i) {
    p.accept(",");
    Tok t = p.next();
    if (!t.word("texture")) p.fail("expected texture in texture_list");
    o.textures.push_back(p.parse_texture());
  }
  mesh2_close(p);
}

// The optional texture indices after a face: one, or one per corner (only the first is kept).
void parse_face_texture_index(Parser& p, Object& o) {
  p.accept(",");
  // (a float; the next face is a vector, perhaps a vector identifier: `F1+A, F2+A` in
  // shapes.inc's HFCreate_)
  const Tok& after = p.peek();
  const bool texture_index = after.token.kind == TokenKind::kNumber || after.symbol("(") ||
                             (after.identifier && after.value.kind == ValueKind::kFloat);
  if (!texture_index) return;
  double t = p.parse_float();
  if (!(t >= 0 && t < 4294967295.0)) p.fail("bad mesh2 texture index");
  o.triangle_textures.resize(o.indices.size() / 3 - 1, 0);
  o.triangle_textures.push_back(static_cast<uint32_t>(t));
  for (int k = 0; k < 2; ++k) {
    if (!p.peek().symbol(",")) break;
    p.next();
    const Tok& more = p.peek();
    if (more.symbol("<") || more.symbol("}")) break;
    p.parse_float();
  }
}

// face_indices, normal_indices or uv_indices (`block`): three indices per triangle.
void parse_mesh2_indices(Parser& p, const std::string& block, Object& o,
                         std::vector<uint32_t>& normal_indices) {
  size_t n = mesh2_count(p);
  for (size_t i = 0; i < n; ++i) {
    p.accept(",");
    Value v = p.parse_numeric(3);
    for (int k = 0; k < 3; ++k) {
      if (!(v.v[k] >= 0 && v.v[k] < 4294967295.0)) p.fail("negative or huge mesh2 index");
      uint32_t index = static_cast<uint32_t>(v.v[k]);
      if (block == "face_indices") o.indices.push_back(index);
      if (block == "normal_indices") normal_indices.push_back(index);
    }
    if (block == "face_indices") parse_face_texture_index(p, o);
  }
  mesh2_close(p);
}

// Checks every index against its list, and gives the mesh its normals: per vertex, or, with
// normal_indices, per corner.
void finish_mesh2(Parser& p, Object& o, std::vector<Vec3d>& normals,
                  const std::vector<uint32_t>& normal_indices) {
  if (!o.triangle_textures.empty()) o.triangle_textures.resize(o.indices.size() / 3, 0);
  for (uint32_t t : o.triangle_textures) {
    if (t >= o.textures.size()) p.fail("mesh2 texture index past the texture_list");
  }
  for (uint32_t i : o.indices) {
    if (i >= o.vertices.size())
      p.fail("mesh2 face index " + std::to_string(i) + " past the vertex_vectors");
  }
  if (!normals.empty() && !normal_indices.empty()) {
    if (normal_indices.size() != o.indices.size())
      p.fail("mesh2 normal_indices and face_indices differ in count");
    // one normal per corner: corners become vertices of their own
    std::vector<Vec3d> vertices, corner_normals;
    for (size_t i = 0; i < o.indices.size(); ++i) {
      if (normal_indices[i] >= normals.size()) p.fail("mesh2 normal index past the normal_vectors");
      vertices.push_back(o.vertices[o.indices[i]]);
      corner_normals.push_back(normals[normal_indices[i]]);
      o.indices[i] = static_cast<uint32_t>(i);
    }
    o.vertices = std::move(vertices);
    o.normals = std::move(corner_normals);
  } else if (normals.size() == o.vertices.size()) {
    o.normals = std::move(normals);
  }
}

// ---- object modifiers (POV-Ray 3.7 reference, "Object Modifiers") ----

void take_material(const MaterialValue& m, Object& o) {
  if (m.texture) {
    o.texture = *m.texture;
    o.texture_given = true;
  }
  if (m.interior) o.interior = m.interior;
}

// texture, pigment, finish, normal, interior, material: false if `tok` is none of them.
bool parse_appearance_mod(Parser& p, const Tok& tok, Object& o) {
  const std::string& w = tok.token.text;
  if (w == "texture") {
    Texture t = p.parse_texture();
    if (o.texture_given && o.shape != Shape::kMesh) {
      p.add_texture_layer(o.texture, std::move(t));
      return true;
    }
    o.texture = std::move(t);
    o.texture_given = true;
  } else if (w == "pigment") {
    Pigment pigment = p.parse_pigment();
    p.ensure_texture(o);
    o.texture.top().pigment = std::move(pigment);
  } else if (w == "finish") {
    p.ensure_texture(o);
    o.texture.top().finish = p.parse_finish(o.texture.top().finish);
  } else if (w == "normal") {
    Normal normal = p.parse_normal();
    p.ensure_texture(o);
    o.texture.top().normal = std::move(normal);
  } else if (w == "interior") {
    o.interior = p.parse_interior();
  } else if (w == "material") {
    take_material(p.parse_material(), o);
  } else {
    return false;
  }
  return true;
}

// The flags, each with an optional boolean (`hollow off`); those with no field are parsed and
// have no effect here.
struct Flag {
  std::string_view name;
  bool Object::*field;
};

constexpr Flag kFlags[] = {
    {"hollow", &Object::hollow},
    {"no_shadow", &Object::no_shadow},
    {"no_image", &Object::no_image},
    {"no_reflection", &Object::no_reflection},
    {"double_illuminate", &Object::double_illuminate},
    {"open", &Object::open},
    {"no_radiosity", nullptr},
    {"sturm", nullptr},
    {"global_lights", nullptr},
    {"split_union", nullptr},
    {"cutaway_textures", nullptr},
    {"hierarchy", nullptr},
    {"smooth", nullptr},
    {"uv_mapping", nullptr},
};

bool parse_flag(Parser& p, std::string_view w, Object& o) {
  for (const Flag& flag : kFlags) {
    if (flag.name != w) continue;
    bool value = p.parse_bool_option();
    if (flag.field) o.*flag.field = value;
    return true;
  }
  return false;
}

// A declared texture or material used as a modifier.
bool take_declared_appearance(Parser& p, const Tok& tok, Object& o) {
  if (!tok.identifier) return false;
  if (const Texture* texture = tok.value.get<Texture>()) {
    // a texture identifier after a texture is a layer; as the first one it is the texture
    if (!o.texture_given) {
      o.texture = *texture;
      o.texture_given = true;
    } else {
      p.add_texture_layer(o.texture, *texture);
    }
    return true;
  }
  if (const MaterialValue* material = tok.value.get<MaterialValue>()) {
    take_material(*material, o);
    return true;
  }
  return false;
}

}  // namespace

bool Parser::is_object_keyword(const Tok& tok) const {
  if (!tok.keyword()) return false;
  for (std::string_view w : kSupported) {
    if (tok.token.text == w) return true;
  }
  for (std::string_view w : kUnsupported) {
    if (tok.token.text == w) return true;
  }
  return false;
}

// One object statement, its keyword read: an unsupported kind is skipped and reported, the others
// read their arguments (a shape, a polynomial, a reference or a CSG's children) then the
// modifiers.
Node Parser::parse_object(const Tok& keyword) {
  Nesting guard(*this);
  const std::string& w = keyword.token.text;
  SourceLocation where = location_of(keyword);
  for (std::string_view u : kUnsupported) {
    if (w == u) {
      skip_block();
      return missing_node(w, where);
    }
  }
  count_objects(1);
  if (w == "light_source") {
    Node node;
    node.lights.push_back(parse_light(keyword));
    return node;
  }
  Node node;
  Object o;
  o.keyword = w;
  o.where = where;
  expect("{");
  if (w == "object") return parse_object_reference();
  bool dropped = false;  // an unsupported object left out of this CSG
  if (w == "height_field" && is_unread_height_field(peek())) {
    skip_rest_of_block();
    return missing_node(w, where);
  }
  if (const Primitive* primitive = find_keyword(kPrimitives, w)) {
    parse_primitive(*this, o, *primitive);
  } else if (const ShapeParser* shape = find_keyword(kShapes, w)) {
    shape->parse(*this, o);
  } else if (is_polynomial(w)) {
    parse_polynomial(w, o);
  } else if (w == "julia_fractal") {
    if (const std::string missing = parse_julia_fractal(o); !missing.empty()) {
      skip_rest_of_block();
      return missing_node(missing, where);
    }
  } else if (w == "text") {
    if (!parse_text(o)) {
      skip_rest_of_block();
      return missing_node(w, where);  // a font that is not here
    }
  } else {
    dropped = parse_csg_children(w, where, o, node);
  }
  node.object = std::move(o);
  parse_object_mods(node);
  if (dropped) node.object.reset();  // a difference whose base is unsupported
  return node;
}

// object { Identifier | Object ... }: a copy of a declared or inline object, then modifiers (an
// unsupported or light-only object's transforms still move its lights).
Node Parser::parse_object_reference() {
  Node node;
  Tok first = next();
  if (first.identifier && first.value.get<Node>()) {
    node = *first.value.get<Node>();
  } else if (is_object_keyword(first)) {
    node = parse_object(first);
  } else {
    fail("expected an object identifier in object { }");
  }
  parse_object_mods(node);
  return node;
}

// union, merge, intersection, difference, light_group: the children, their lights and missing
// objects gathered into `node`. True if the difference's base was unsupported (the whole
// difference is then left out).
bool Parser::parse_csg_children(const std::string& w, const SourceLocation& where, Object& o,
                                Node& node) {
  if (w == "light_group") unsupported("light_group (its lights light the whole scene)", where);
  o.shape = w == "union"          ? Shape::kUnion
            : w == "merge"        ? Shape::kMerge
            : w == "intersection" ? Shape::kIntersection
                                  : Shape::kDifference;
  bool dropped = false;
  for (;;) {
    Tok tok = next();
    if (!is_object_keyword(tok)) {
      unget(std::move(tok));
      break;
    }
    Node child = parse_object(tok);
    node.lights.insert(node.lights.end(), child.lights.begin(), child.lights.end());
    node.missing.insert(node.missing.end(), child.missing.begin(), child.missing.end());
    if (child.object) {
      o.children.push_back(std::move(*child.object));
    } else if (child.lights.empty()) {
      if (o.shape == Shape::kDifference && o.children.empty()) dropped = true;
    }
  }
  return dropped;
}

void Parser::parse_mesh(Object& o) {
  o.shape = Shape::kMesh;
  bool smooth = false;
  for (;;) {
    Tok tok = next();
    if (tok.identifier && tok.value.get<Node>() && tok.value.get<Node>()->object &&
        tok.value.get<Node>()->object->shape == Shape::kMesh) {
      // mesh { Declared_Mesh ... }
      std::string keyword = o.keyword;
      SourceLocation where = o.where;
      o = *tok.value.get<Node>()->object;
      o.keyword = keyword;
      o.where = where;
      smooth = !o.normals.empty();
      continue;
    }
    bool tri = tok.word("triangle"), smooth_tri = tok.word("smooth_triangle");
    if (!tri && !smooth_tri) {
      if (tok.word("inside_vector")) {
        parse_vector();
        continue;
      }
      unget(std::move(tok));
      break;
    }
    count_objects(1);
    expect("{");
    uint32_t base = static_cast<uint32_t>(o.vertices.size());
    for (int i = 0; i < 3; ++i) {
      if (i) accept(",");
      o.vertices.push_back(parse_vector());
      if (smooth_tri) {
        accept(",");
        Vec3d n = parse_vector();
        if (!smooth) o.normals.resize(base, Vec3d{0, 0, 0});
        smooth = true;
        o.normals.push_back(n);
      } else if (smooth) {
        o.normals.push_back({0, 0, 0});  // filled with the face normal below
      }
    }
    o.indices.insert(o.indices.end(), {base, base + 1, base + 2});
    std::optional<uint32_t> texture;
    for (;;) {
      Tok item = next();
      if (item.symbol("}")) break;
      if (item.word("texture")) {
        // `texture { T }` per triangle
        o.textures.push_back(parse_texture());
        texture = static_cast<uint32_t>(o.textures.size() - 1);
      } else if (item.word("uv_vectors")) {
        parse_numeric(2);
        accept(",");
        parse_numeric(2);
        accept(",");
        parse_numeric(2);
      } else {
        fail("unexpected '" + item.token.text + "' in a mesh triangle");
      }
    }
    o.triangle_textures.push_back(texture.value_or(UINT32_MAX));
  }
  // flat triangles among smooth ones get their face normal at every corner
  for (size_t t = 0; smooth && t < o.indices.size() / 3; ++t) {
    Vec3d a = o.vertices[3 * t], b = o.vertices[3 * t + 1], c = o.vertices[3 * t + 2];
    Vec3d n = cross(sub(b, a), sub(c, a));
    for (int k = 0; k < 3; ++k) {
      Vec3d& m = o.normals[3 * t + k];
      if (m.x == 0 && m.y == 0 && m.z == 0) m = n;
    }
  }
  bool any_texture = std::any_of(o.triangle_textures.begin(), o.triangle_textures.end(),
                                 [](uint32_t t) { return t != UINT32_MAX; });
  if (!any_texture) o.triangle_textures.clear();
}

void Parser::parse_mesh2(Object& o) {
  o.shape = Shape::kMesh;
  std::vector<Vec3d> normals;
  std::vector<uint32_t> normal_indices;
  for (;;) {
    Tok tok = next();
    const std::string& w = tok.token.text;
    if (w == "vertex_vectors") {
      parse_mesh2_vectors(*this, o.vertices);
    } else if (w == "normal_vectors") {
      parse_mesh2_vectors(*this, normals);
    } else if (w == "uv_vectors") {
      skip_mesh2_uv_vectors(*this);
    } else if (w == "texture_list") {
      parse_mesh2_texture_list(*this, o);
    } else if (w == "face_indices" || w == "normal_indices" || w == "uv_indices") {
      parse_mesh2_indices(*this, w, o, normal_indices);
    } else if (w == "inside_vector") {
      parse_vector();
    } else {
      unget(std::move(tok));
      break;
    }
  }
  finish_mesh2(*this, o, normals, normal_indices);
}

namespace {

// Where x^i y^j z^k sits among an order-n polynomial's coefficients in POV-Ray's poly order (x
// powers from n down, then y, then z).
size_t poly_term_index(int order, int i, int j, int k) {
  size_t index = 0;
  for (int a = order; a >= 0; --a)
    for (int b = order - a; b >= 0; --b)
      for (int c = order - a - b; c >= 0; --c, ++index)
        if (a == i && b == j && c == k) return index;
  return index;
}

}  // namespace

// quadric { <A,B,C>, <D,E,F>, <G,H,I>, J }: A x^2 + B y^2 + C z^2 + D xy + E xz + F yz + G x +
// H y + I z + J; cubic { <20 terms> }, quartic { <35> }, poly { N, <(N+1)(N+2)(N+3)/6> } in
// POV-Ray's order; polynomial { N, xyz(i, j, k): c, ... } (POV-Ray 3.7), the terms it names, the
// others 0. Orders 2 to 15, as POV-Ray.
void Parser::parse_polynomial(const std::string& keyword, Object& o) {
  o.shape = Shape::kPolynomial;
  if (keyword == "quadric") {
    o.order = 2;
    Vec3d squares = parse_vector();
    accept(",");
    Vec3d mixed = parse_vector();
    accept(",");
    Vec3d linear = parse_vector();
    accept(",");
    const double constant = parse_float();
    // in poly order: x2, xy, xz, x, y2, yz, y, z2, z, 1
    o.coefficients = {squares.x, mixed.x,  mixed.y,   linear.x, squares.y,
                      mixed.z,   linear.y, squares.z, linear.z, constant};
    return;
  }
  o.order = keyword == "cubic" ? 3 : keyword == "quartic" ? 4 : 0;
  if (keyword == "poly" || keyword == "polynomial") {
    const double order = parse_count();  // `poly { 4 <...` has no comma: no comparison here
    if (!(order >= 2 && order <= 15)) fail(keyword + " order must be 2 to 15");
    o.order = static_cast<int>(order);
    accept(",");
  }
  const size_t terms = static_cast<size_t>((o.order + 1) * (o.order + 2) * (o.order + 3) / 6);
  if (keyword == "polynomial") {
    o.coefficients.assign(terms, 0);
    while (peek().word("xyz")) {
      next();
      expect("(");
      const SourceLocation where = location_of(peek());
      int powers[3];
      for (int a = 0; a < 3; ++a) {
        if (a > 0) expect(",");
        const double v = parse_float();
        if (!(v >= 0 && v <= o.order && v == std::floor(v)))
          fail_at(where, "polynomial term xyz(...): each power must be a whole number from 0 to " +
                             std::to_string(o.order) + ", got " + number_string(v));
        powers[a] = static_cast<int>(v);
      }
      if (powers[0] + powers[1] + powers[2] > o.order)
        fail_at(where, "polynomial term xyz(" + std::to_string(powers[0]) + ", " +
                           std::to_string(powers[1]) + ", " + std::to_string(powers[2]) +
                           ") is above the order " + std::to_string(o.order));
      expect(")");
      expect(":");
      o.coefficients[poly_term_index(o.order, powers[0], powers[1], powers[2])] = parse_float();
      accept(",");
    }
    return;
  }
  expect("<");
  int saved = vector_level_;
  vector_level_ = nesting + 1;
  for (size_t i = 0; i < terms; ++i) {
    if (i > 0) accept(",");  // POV-Ray also takes coefficients separated by blanks
    o.coefficients.push_back(parse_float());
  }
  vector_level_ = saved;
  expect(">");
}

void Parser::ensure_texture(Object& o) {
  if (o.texture_given) return;
  o.texture = default_texture_;
  o.texture.where = here();
  o.texture_given = true;
}

void Parser::parse_object_mods(Node& node) {
  for (;;) {
    Tok tok = next();
    if (tok.symbol("}")) break;
    if (tok.token.kind == TokenKind::kEnd) fail("missing '}' at the end of an object");
    const std::string& w = tok.token.text;
    if (auto m = parse_transform_item(tok)) {
      transform_node(node, *m);
      continue;
    }
    // modifiers of a light-only or unsupported object: parsed, nothing to change
    Object scratch;
    Object& o = node.object ? *node.object : scratch;
    if (parse_appearance_mod(*this, tok, o) || parse_flag(*this, w, o)) continue;
    if (w == "inverse") {
      o.inverse = !o.inverse;
    } else if (w == "inside_vector") {
      parse_vector();
    } else if (w == "clipped_by") {
      parse_clipped_by(node, o);
    } else if (w == "bounded_by") {
      skip_block();  // only a speed hint
    } else if (w == "photons" || w == "radiosity" || w == "interior_texture") {
      unsupported(w, location_of(tok));
      skip_block();
    } else if (!take_declared_appearance(*this, tok, o)) {
      fail("unexpected '" + w + "' in " + (node.object ? node.object->keyword : "object"));
    }
  }
  if (node.object) complete_appearance(*node.object);
}

// clipped_by { Object ... }: the clipping objects; the unsupported ones are reported with `node`.
void Parser::parse_clipped_by(Node& node, Object& o) {
  expect("{");
  for (;;) {
    Tok item = next();
    if (item.symbol("}")) break;
    if (item.word("bounded_by")) continue;  // clipped_by { bounded_by }: nothing to clip
    if (!is_object_keyword(item)) fail("expected an object in clipped_by");
    Node clip = parse_object(item);
    node.missing.insert(node.missing.end(), clip.missing.begin(), clip.missing.end());
    if (clip.object) o.clipped_by.push_back(std::move(*clip.object));
  }
}

// After the modifiers: a CSG's children inherit its texture and interior, and mesh triangles
// without their own texture take the mesh's.
void Parser::complete_appearance(Object& o) {
  if (is_csg(o.shape)) inherit(o, o.texture_given ? &o.texture : nullptr, o.interior);
  if (o.triangle_textures.empty()) return;
  uint32_t own = static_cast<uint32_t>(o.textures.size());
  bool used = false;
  for (uint32_t& t : o.triangle_textures) {
    if (t == UINT32_MAX) {
      t = own;
      used = true;
    }
  }
  if (used) {
    ensure_texture(o);
    o.textures.push_back(o.texture);
  }
}

// A top-level object joins the scene: leaves without a texture take the #default one.
void Parser::emit(Node node, const SourceLocation& where) {
  for (Unsupported& missing : node.missing) {
    if (missing.where.text() != where.text()) missing.placed = where;
    scene_.unsupported.push_back(std::move(missing));
  }
  std::function<void(Object&)> fill = [&](Object& o) {
    if (!o.texture_given) {
      o.texture = default_texture_;
      o.texture.where = o.where;
      o.texture_given = true;
    }
    for (Object& child : o.children)
      fill(child);
  };
  scene_.lights.insert(scene_.lights.end(), node.lights.begin(), node.lights.end());
  if (node.object) {
    fill(*node.object);
    scene_.objects.push_back(std::move(*node.object));
  }
}

}  // namespace fb::pov::sdl
