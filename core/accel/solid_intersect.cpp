#include "core/accel/solid_intersect.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <string>
#include <utility>

#include "core/function/isosurface_function.h"
#include "core/math/julia_fractal.h"
#include "core/math/lemon.h"
#include "core/math/polynomial.h"
#include "core/math/sor.h"
#include "core/math/sphere_sweep.h"
#include "core/math/superellipsoid.h"
#include "core/scene/lathe.h"
#include "core/util/error.h"

namespace fb {

struct RenderSolid::Node {
  SolidKind kind = SolidKind::kSphere;
  bool inverse = false, open = false;
  bool surface = true;  // false below a `bounds_only` solid: its boundaries are no surface
  double radius0 = 1, radius1 = 1;
  uint32_t material = 0;
  Transform object_from_render;
  Transform normal_from_object;  // inverse transpose of render_from_object
  Bounds3d bounds;               // render space, of the set before `inverse`; may be infinite
  Polynomial3 polynomial;        // kPolynomial, in object space
  std::shared_ptr<const Outline> outline;  // kOutline
  bool conic = false;                      // kOutline: conic sweep
  double z0 = 0, z1 = 1;                   // kOutline: the slab it is swept through
  Bounds3d window;       // kPolynomial: render-space box its roots are searched in
  double magnitude = 0;  // farthest corner of a bounded primitive from the render origin
  Blob blob;             // kBlob, in object space
  Sor sor;               // kSor, in object space
  Lemon lemon;           // kLemon
  std::shared_ptr<const SphereSweep> sweep;      // kSphereSweep
  std::shared_ptr<const Isosurface> isosurface;  // kIsosurface, in object space
  std::shared_ptr<const JuliaFractal> julia;     // kJuliaFractal, in object space
  // What the tree can give one ray, known at build time so that no ray allocates (issue 17):
  size_t max_spans = 0;        // spans of this node's set along a ray, at most
  size_t max_child_spans = 0;  // of any child's (set operations)
  size_t workspace = 0;        // scratch spans node_spans needs beside its output
  std::vector<Node> children;
};

namespace {

using Node = RenderSolid::Node;
constexpr double kInf = HUGE_VAL;

struct Ray {
  Vec3d o, d;
};

// Where the ray crosses into or out of a set: on a primitive's surface part, or at the edge of
// the window the spans are computed in (leaf == nullptr).
struct Boundary {
  double t = 0;
  const Node* leaf = nullptr;
  // Which face: box 2 axis + (max side); cone 0 side, 1 base, 2 cap; outline 1 base, 2 cap, and
  // its wall 0 where the ray enters the primitive, 3 where it leaves.
  uint8_t part = 0;
  bool surface = false;  // false: bounds the set but is no surface (open caps, outside a disc)
  bool flipped = false;  // the set's outside is the primitive's inside (an odd complement)
  uint32_t segment = 0;  // kOutline's wall: which segment (in the padding: a span stays 48 bytes)
};

struct Span {
  Boundary in, out;
};

// The spans a ray's intersection works in live in one buffer sized from the tree (Node::
// max_spans, ::workspace): on the stack up to this many, which covers every tree a scene writes
// by hand (48 bytes a span: 12 KiB), else in a per-thread buffer grown once to the largest tree.
constexpr size_t kStackSpans = 256;
// A tree needing more than this is refused at load (48 MiB a thread): only a hostile or
// generated scene nests CSG that deep.
constexpr size_t kMaxSpans = size_t(1) << 20;

Boundary on(const Node& leaf, double t, uint8_t part = 0, bool surface = true) {
  return {t, &leaf, part, surface && leaf.surface, false};
}

// Appends [in, out] clipped to the window [lo, hi] to spans[0, count); what the window cuts is
// no surface.
void push(Span* spans, int& count, Boundary in, Boundary out, double lo, double hi) {
  if (!(in.t >= lo)) in = {lo};
  if (!(out.t <= hi)) out = {hi};
  if (in.t < out.t) spans[count++] = {in, out};
}

// The ray's parameter range inside an axis-aligned box, within [lo, hi]; false if it misses.
bool clip_to_box(const Bounds3d& box, const Ray& r, double& lo, double& hi) {
  if (box.empty()) return false;
  for (int a = 0; a < 3; ++a) {
    if (r.d[a] == 0) {
      if (r.o[a] < box.lo[a] || r.o[a] > box.hi[a]) return false;
      continue;
    }
    double t1 = (box.lo[a] - r.o[a]) / r.d[a], t2 = (box.hi[a] - r.o[a]) / r.d[a];
    if (t1 > t2) std::swap(t1, t2);
    lo = std::max(lo, t1), hi = std::min(hi, t2);
  }
  return lo <= hi;
}

// ---- Set operations on sorted, disjoint spans ------------------------------------------------
// Each writes at most the count its bound in build() allows: n spans have n + 1 gaps, a union
// at most n + m spans, an intersection n + m - 1 (each step of the sweep ends one input span).

// The gaps of spans[0, n) within [lo, hi], written back over them (through `scratch`).
int complement(Span* spans, int n, double lo, double hi, Span* scratch) {
  int gaps = 0;
  Boundary from{lo};
  for (int i = 0; i < n; ++i) {
    Span s = spans[i];
    s.in.flipped = !s.in.flipped, s.out.flipped = !s.out.flipped;
    if (from.t < s.in.t) scratch[gaps++] = {from, s.in};
    from = s.out;
  }
  if (from.t < hi) scratch[gaps++] = {from, Boundary{hi}};
  std::copy_n(scratch, gaps, spans);
  return gaps;
}

int intersection(const Span* a, int na, const Span* b, int nb, Span* out) {
  int n = 0;
  for (int i = 0, j = 0; i < na && j < nb;) {
    const Boundary& in = a[i].in.t >= b[j].in.t ? a[i].in : b[j].in;
    const bool a_ends_first = a[i].out.t <= b[j].out.t;
    const Boundary& end = a_ends_first ? a[i].out : b[j].out;
    if (in.t < end.t) out[n++] = {in, end};
    a_ends_first ? ++i : ++j;
  }
  return n;
}

// Merges by entry (the first list's span first on a tie, as std::merge) and joins spans that
// overlap or touch.
int united(const Span* a, int na, const Span* b, int nb, Span* out) {
  int n = 0;
  for (int i = 0, j = 0; i < na || j < nb;) {
    const Span& s = j == nb || (i < na && !(b[j].in.t < a[i].in.t)) ? a[i++] : b[j++];
    if (n > 0 && s.in.t <= out[n - 1].out.t) {
      if (s.out.t > out[n - 1].out.t) out[n - 1].out = s.out;
    } else {
      out[n++] = s;
    }
  }
  return n;
}

// ---- Primitives, in object space -------------------------------------------------------------

// Re-centring on the point of the ray nearest the object's origin keeps the quadratic and quartic
// coefficients small when the ray starts far away (Haines et al., "Precision Improvements for
// Ray/Sphere Intersection", Ray Tracing Gems ch. 7): s = t - t0.
double nearest_to_origin(const Ray& r) {
  return -dot(r.o, r.d) / dot(r.d, r.d);
}

void sphere_spans(const Node& leaf, const Ray& r, double lo, double hi, Span* out, int& n) {
  const double a = dot(r.d, r.d);
  if (!(a > 0)) return;
  const double t0 = nearest_to_origin(r);
  const Vec3d c = r.o + r.d * t0;
  const double h2 = (1 - dot(c, c)) / a;
  if (!(h2 > 0)) return;
  const double h = std::sqrt(h2);
  push(out, n, on(leaf, t0 - h), on(leaf, t0 + h), lo, hi);
}

void box_spans(const Node& leaf, const Ray& r, double lo, double hi, Span* out, int& n) {
  Boundary in{-kInf}, exit{kInf};
  for (int a = 0; a < 3; ++a) {
    if (r.d[a] == 0) {
      if (std::abs(r.o[a]) > 1) return;
      continue;
    }
    const double t_low = (-1 - r.o[a]) / r.d[a], t_high = (1 - r.o[a]) / r.d[a];
    const bool up = r.d[a] > 0;
    const double t_in = up ? t_low : t_high, t_out = up ? t_high : t_low;
    if (t_in > in.t) in = on(leaf, t_in, uint8_t(2 * a + (up ? 0 : 1)));
    if (t_out < exit.t) exit = on(leaf, t_out, uint8_t(2 * a + (up ? 1 : 0)));
  }
  if (in.t < exit.t) push(out, n, in, exit, lo, hi);
}

// z <= 0; a disc's surface is only the annulus of its plane.
void half_space_spans(const Node& leaf, const Ray& r, double lo, double hi, Span* out, int& n) {
  if (r.d.z == 0) {
    if (r.o.z <= 0) push(out, n, {lo}, {hi}, lo, hi);
    return;
  }
  const double t = -r.o.z / r.d.z;
  bool surface = true;
  if (leaf.kind == SolidKind::kDisc) {
    const double x = r.o.x + t * r.d.x, y = r.o.y + t * r.d.y, r2 = x * x + y * y;
    surface = r2 <= 1 && r2 >= leaf.radius1 * leaf.radius1;
  }
  if (r.d.z > 0)
    push(out, n, {-kInf}, on(leaf, t, 0, surface), lo, hi);
  else
    push(out, n, on(leaf, t, 0, surface), {kInf}, lo, hi);
}

// x^2 + y^2 <= r(z)^2 between the planes z = 0 and z = 1: the quadric's spans (A s^2 + 2 B s +
// C <= 0, one span, two rays, all or nothing) intersected with the slab's.
void cone_spans(const Node& leaf, const Ray& r, double lo, double hi, Span* out, int& n) {
  const bool cylinder = leaf.kind == SolidKind::kCylinder;
  const double r0 = cylinder ? 1 : leaf.radius0, k = cylinder ? 0 : leaf.radius1 - leaf.radius0;
  if (!(dot(r.d, r.d) > 0)) return;
  const double t0 = nearest_to_origin(r);
  const Vec3d c = r.o + r.d * t0, d = r.d;
  const double rz = r0 + k * c.z;
  const double A = d.x * d.x + d.y * d.y - k * k * d.z * d.z;
  const double B = c.x * d.x + c.y * d.y - rz * k * d.z;
  const double C = c.x * c.x + c.y * c.y - rz * rz;
  Span quadric[2];
  int quadric_count = 0;
  const auto side = [&](double s) { return on(leaf, t0 + s, 0); };
  if (A == 0) {
    if (B == 0) {
      if (C <= 0) quadric[quadric_count++] = {{-kInf}, {kInf}};
    } else {
      const double s = -C / (2 * B);
      quadric[quadric_count++] = B > 0 ? Span{{-kInf}, side(s)} : Span{side(s), {kInf}};
    }
  } else {
    const double disc = B * B - A * C;
    if (disc > 0) {
      const double q = -(B + std::copysign(std::sqrt(disc), B));
      const double s1 = std::min(q / A, C / q), s2 = std::max(q / A, C / q);
      if (A > 0) {
        quadric[quadric_count++] = {side(s1), side(s2)};
      } else {
        quadric[quadric_count++] = {{-kInf}, side(s1)};
        quadric[quadric_count++] = {side(s2), {kInf}};
      }
    } else if (A < 0) {
      quadric[quadric_count++] = {{-kInf}, {kInf}};
    }
  }
  Span slab[1];
  int slab_count = 0;
  const bool caps = !leaf.open;
  if (d.z == 0) {
    if (c.z >= 0 && c.z <= 1) slab[slab_count++] = {{-kInf}, {kInf}};
  } else {
    const double s_base = -c.z / d.z, s_cap = (1 - c.z) / d.z;
    const Boundary base = on(leaf, t0 + s_base, 1, caps), cap = on(leaf, t0 + s_cap, 2, caps);
    slab[slab_count++] = d.z > 0 ? Span{base, cap} : Span{cap, base};
  }
  Span both[2];
  const int count = intersection(quadric, quadric_count, slab, slab_count, both);
  for (int i = 0; i < count; ++i)
    push(out, n, both[i].in, both[i].out, lo, hi);
}

// (|p|^2 + 1 - r^2)^2 - 4 (x^2 + y^2) <= 0, a quartic in s along the re-centred ray, solved
// within the torus's box. The roots are searched from lo on whatever `hi` is, so that a ray cut
// short at Embree's tfar finds the very roots the renderer's second, uncut intersection finds.
void torus_spans(const Node& leaf, const Ray& r, double lo, double hi, Span* out, int& n) {
  const double minor = leaf.radius1;
  if (!(dot(r.d, r.d) > 0)) return;
  const double t0 = nearest_to_origin(r);
  const Ray c{r.o + r.d * t0, r.d};
  double s_lo = lo - t0, s_hi = kInf;
  // The box a little wider than the torus, so that no root sits on the ends of the search.
  const double R = 1.001 * (1 + minor), Z = 1.001 * minor;
  if (!clip_to_box({{-R, -R, -Z}, {R, R, Z}}, c, s_lo, s_hi)) return;
  const Vec3d o = c.o, d = c.d;
  const double dd = dot(d, d), od = dot(o, d), k = dot(o, o) + 1 - minor * minor;
  const double coefficients[5] = {
      k * k - 4 * (o.x * o.x + o.y * o.y), 4 * od * k - 8 * (o.x * d.x + o.y * d.y),
      4 * od * od + 2 * dd * k - 4 * (d.x * d.x + d.y * d.y), 4 * od * dd, dd * dd};
  double roots[4];
  const int count = sign_changes(coefficients, 4, s_lo, s_hi, roots);
  Boundary from{t0 + s_lo};
  for (int i = 0; i <= count; ++i) {
    const double s_end = i < count ? roots[i] : s_hi;
    const Boundary end = i < count ? on(leaf, t0 + s_end) : Boundary{t0 + s_hi};
    const double mid = 0.5 * ((from.t - t0) + s_end);
    if (evaluate_polynomial(coefficients, 4, mid) <= 0) push(out, n, from, end, lo, hi);
    from = end;
  }
}

// p(s) <= 0 along the re-centred ray, roots searched where the ray crosses the window (the
// scene's reach): past it the set goes on, bounded by no surface. As for the torus, the search
// does not depend on `hi`.
void polynomial_spans(const Node& leaf, const Ray& render_ray, const Ray& r, double lo, double hi,
                      Span* out, int& n) {
  if (!(dot(r.d, r.d) > 0)) return;
  double w_lo = lo, w_hi = kInf;
  if (!clip_to_box(leaf.window, render_ray, w_lo, w_hi)) return;
  const double t0 = nearest_to_origin(r);
  double c[kMaxPolynomialDegree + 1];
  restrict_to_ray(leaf.polynomial, r.o + r.d * t0, r.d, c);
  int degree = kMaxPolynomialDegree;
  while (degree > 0 && c[degree] == 0)
    --degree;
  const double s_lo = w_lo - t0, s_hi = w_hi - t0;
  double roots[kMaxPolynomialDegree];
  const int count = sign_changes(c, degree, s_lo, s_hi, roots);
  Boundary from{w_lo};
  for (int i = 0; i <= count; ++i) {
    const double s_end = i < count ? roots[i] : s_hi;
    const Boundary end = i < count ? on(leaf, t0 + s_end) : Boundary{w_hi};
    const double mid = 0.5 * ((from.t - t0) + s_end);
    if (evaluate_polynomial(c, degree, mid) <= 0) push(out, n, from, end, lo, hi);
    from = end;
  }
}

// Segment ends are searched a little past [0, 1], so that a ray through the point two segments
// share meets at least one of them: found by both, the crossing only splits a piece in two.
constexpr double kOutlineJointSlack = 1e-9;

// The polynomial in u whose sign changes are where the ray o + t d crosses the segment's wall.
// Linear sweep: the ray's shadow on the xy plane crosses the curve. Conic: the plane through the
// apex (the origin) and the ray holds the ruling through (point(u), 1): n . (point(u), 1) = 0
// with n = o x d, again of the segment's degree.
void outline_wall_polynomial(const Node& leaf, const OutlineSegment& s, Vec3d o, Vec3d d,
                             double c[4]) {
  if (!leaf.conic) return segment_line_polynomial(s, {o.x, o.y}, {d.x, d.y}, c);
  const Vec3d n = cross(o, d);
  for (int i = 0; i < 4; ++i)
    c[i] = n.x * s.c[i].x + n.y * s.c[i].y + (i == 0 ? n.z : 0);
}

// The ray's parameter where it meets the wall at the segment's u: along the shadow, or where
// o + t d = z (point(u), 1), that is (o x w) + t (d x w) = 0 for w = (point(u), 1).
double outline_wall_t(const Node& leaf, const OutlineSegment& s, double u, Vec3d o, Vec3d d) {
  const Vec2d b = segment_point(s, u);
  if (!leaf.conic) {
    const double dx = b.x - o.x, dy = b.y - o.y;
    return (dx * d.x + dy * d.y) / (d.x * d.x + d.y * d.y);
  }
  const Vec3d w{b.x, b.y, 1}, dw = cross(d, w);
  return -dot(cross(o, w), dw) / dot(dw, dw);
}

// Whether a point within the slab is inside: its cross-section, scaled back by z when conic.
bool outline_section_holds(const Node& leaf, Vec3d p) {
  if (!leaf.conic) return outline_contains(*leaf.outline, {p.x, p.y});
  return p.z != 0 && outline_contains(*leaf.outline, {p.x / p.z, p.y / p.z});
}

// The outline swept through the slab z0 <= z <= z1: the ray's piece within it cut at the walls'
// crossings (each segment's wall polynomial's sign changes), each piece then inside or not by
// the section's even-odd test at its middle. Deciding each piece on its own, rather than
// flipping at every crossing, keeps a crossing found twice or a tangent ray from turning inside
// out. `crossings` holds outline.degrees spans (only their `in` is used).
void outline_spans(const Node& leaf, const Ray& r, double lo, double hi, Span* out, int& n,
                   Span* crossings) {
  const Outline& outline = *leaf.outline;
  if (!(dot(r.d, r.d) > 0)) return;
  Boundary slab_in{-kInf}, slab_out{kInf};
  if (r.d.z == 0) {
    if (!(r.o.z >= leaf.z0 && r.o.z <= leaf.z1)) return;
  } else {
    const Boundary base = on(leaf, (leaf.z0 - r.o.z) / r.d.z, 1, !leaf.open);
    const Boundary cap = on(leaf, (leaf.z1 - r.o.z) / r.d.z, 2, !leaf.open);
    slab_in = r.d.z > 0 ? base : cap, slab_out = r.d.z > 0 ? cap : base;
  }
  // A ray along the linear sweep's walls crosses none (its shadow is a point).
  const bool crosses = leaf.conic || r.d.x != 0 || r.d.y != 0;
  int count = 0;
  for (uint32_t i = 0; crosses && i < outline.segments.size(); ++i) {
    const OutlineSegment& s = outline.segments[i];
    double c[4], u[3];
    outline_wall_polynomial(leaf, s, r.o, r.d, c);
    const int roots = sign_changes(c, s.degree, -kOutlineJointSlack, 1 + kOutlineJointSlack, u);
    for (int k = 0; k < roots; ++k) {
      const double t = outline_wall_t(leaf, s, u[k], r.o, r.d);
      if (!(t > slab_in.t && t < slab_out.t)) continue;
      crossings[count].in = on(leaf, t, 0);
      crossings[count++].in.segment = i;
    }
  }
  std::sort(crossings, crossings + count,
            [](const Span& a, const Span& b) { return a.in.t < b.in.t; });
  bool inside = false;
  Boundary entry, from = slab_in;
  for (int k = 0; k <= count; ++k) {
    Boundary end = k < count ? crossings[k].in : slab_out;
    if (!(end.t > from.t)) continue;  // an empty piece: it leaves the state as it was
    // Past the outermost crossing of an unbounded piece, the line is outside the outline.
    const bool piece_inside = std::isfinite(from.t) && std::isfinite(end.t) &&
                              outline_section_holds(leaf, r.o + r.d * (0.5 * (from.t + end.t)));
    if (piece_inside && !inside) entry = from;
    if (!piece_inside && inside) {
      from.part = from.part == 0 ? 3 : from.part;  // the wall where the ray leaves
      push(out, n, entry, from, lo, hi);
    }
    inside = piece_inside;
    from = end;
  }
  if (inside) push(out, n, entry, slab_out, lo, hi);
}

// f <= 0 (core/math/superellipsoid.h) between pairs of crossings, searched along the ray's
// whole chord of a box a little wider than the unit box whatever lo and hi are: the same ray
// finds the same roots, and f > 0 at both ends of the chord pairs them.
void superellipsoid_spans(const Node& leaf, const Ray& r, double lo, double hi, Span* out, int& n) {
  if (!(dot(r.d, r.d) > 0)) return;
  const double t0 = nearest_to_origin(r);
  const Ray c{r.o + r.d * t0, r.d};
  constexpr double kChordBox = 1 + 1e-6;
  double s_lo = -kInf, s_hi = kInf;
  if (!clip_to_box({{-kChordBox, -kChordBox, -kChordBox}, {kChordBox, kChordBox, kChordBox}}, c,
                   s_lo, s_hi))
    return;
  double roots[kSuperellipsoidMaxCrossings];
  const int count =
      superellipsoid_crossings({leaf.radius0, leaf.radius1}, c.o, c.d, s_lo, s_hi, roots);
  for (int i = 0; i + 1 < count; i += 2)
    push(out, n, on(leaf, t0 + roots[i]), on(leaf, t0 + roots[i + 1]), lo, hi);
}

// F >= threshold (core/math/blob.h): each gap between two crossings is inside or outside as the
// field at its middle says, neighbouring inside gaps joining (where two of the field's quartic
// pieces meet, a crossing may be found twice). Before the first crossing and after the last the
// ray is outside every component.
void blob_spans(const Node& leaf, const Ray& r, double lo, double hi, Span* out, int& n) {
  if (!(dot(r.d, r.d) > 0)) return;
  const double t0 = nearest_to_origin(r);
  const Vec3d o = r.o + r.d * t0;
  const std::vector<double>& roots = blob_crossings(leaf.blob, o, r.d);
  bool inside = false;
  double from = 0;
  for (size_t i = 0; i < roots.size(); ++i) {
    const bool gap_inside =
        i + 1 < roots.size() &&
        blob_field(leaf.blob, o + r.d * (0.5 * (roots[i] + roots[i + 1]))) >= leaf.blob.threshold;
    if (gap_inside && !inside) from = roots[i];
    if (!gap_inside && inside) push(out, n, on(leaf, t0 + from), on(leaf, t0 + roots[i]), lo, hi);
    inside = gap_inside;
  }
}

// x^2 + z^2 <= r(y)^2 (core/math/sor.h), segment by segment in the ray's order: within a segment's
// slab a cubic in t, searched within the sor's box. Slab ends between segments are no surface
// (the spans join there); the lowest and highest are the caps (parts 1 and 2), surface unless
// open.
void sor_spans(const Node& leaf, const Ray& r, double lo, double hi, Span* out, int& n) {
  if (!(dot(r.d, r.d) > 0) || leaf.sor.empty()) return;
  const double t0 = nearest_to_origin(r);
  const Vec3d o = r.o + r.d * t0, d = r.d;
  // The sor's box, a little wider than its widest circle so that no root sits on the ends of
  // the search; its height is the slabs'.
  Bounds3d box = sor_bounds(leaf.sor);
  box.lo.x *= 1.001, box.lo.z *= 1.001, box.hi.x *= 1.001, box.hi.z *= 1.001;
  double box_lo = -kInf, box_hi = kInf;
  if (!clip_to_box(box, {o, d}, box_lo, box_hi)) return;
  const size_t count = leaf.sor.size();
  const int first = n;
  for (size_t k = 0; k < count; ++k) {
    const size_t i = d.y >= 0 ? k : count - 1 - k;
    const SorSegment& seg = leaf.sor[i];
    double s_in = box_lo, s_out = box_hi;
    Boundary in{t0 + s_in}, exit{t0 + s_out};
    if (d.y != 0) {
      const double s_bottom = (seg.y0 - o.y) / d.y, s_top = (seg.y1 - o.y) / d.y;
      const Boundary bottom =
          i == 0 ? on(leaf, t0 + s_bottom, 1, !leaf.open) : Boundary{t0 + s_bottom};
      const Boundary top =
          i + 1 == count ? on(leaf, t0 + s_top, 2, !leaf.open) : Boundary{t0 + s_top};
      const bool up = d.y > 0;
      // Ties go to the slab: the box's ends are the caps' planes.
      if ((up ? s_bottom : s_top) >= s_in) s_in = up ? s_bottom : s_top, in = up ? bottom : top;
      if ((up ? s_top : s_bottom) <= s_out) s_out = up ? s_top : s_bottom, exit = up ? top : bottom;
    } else if (o.y < seg.y0 || o.y > seg.y1) {
      continue;
    }
    if (!(s_in < s_out)) continue;
    // g(s) = (o.x + s d.x)^2 + (o.z + s d.z)^2 - r^2(u), u = (o.y + s d.y - y0) / height
    const double u0 = (o.y - seg.y0) / (seg.y1 - seg.y0), u1 = d.y / (seg.y1 - seg.y0);
    const double* c = seg.c;
    double g[4] = {o.x * o.x + o.z * o.z - (c[0] + u0 * (c[1] + u0 * (c[2] + u0 * c[3]))),
                   2 * (o.x * d.x + o.z * d.z) - (c[1] + 2 * c[2] * u0 + 3 * c[3] * u0 * u0) * u1,
                   d.x * d.x + d.z * d.z - (c[2] + 3 * c[3] * u0) * u1 * u1, -c[3] * u1 * u1 * u1};
    int degree = 3;
    while (degree > 0 && g[degree] == 0)
      --degree;
    double roots[3];
    const int found = sign_changes(g, degree, s_in, s_out, roots);
    Boundary from = in;
    for (int j = 0; j <= found; ++j) {
      const Boundary end = j < found ? on(leaf, t0 + roots[j]) : exit;
      const double mid = 0.5 * ((from.t - t0) + (end.t - t0));
      if (evaluate_polynomial(g, degree, mid) <= 0) {
        if (n > first && out[n - 1].out.t >= from.t && !out[n - 1].out.surface) {
          out[n - 1].out = end;  // continues across a slab end between segments
          if (!(end.t <= hi)) out[n - 1].out = {hi};
        } else {
          push(out, n, from, end, lo, hi);
        }
      }
      from = end;
    }
  }
}

// (rho + major)^2 + z^2 <= 1 between the planes z_low and z_high (core/math/lemon.h; caps parts 1
// and 2, surface unless open): the ray's piece within the slab, searched within the lemon's box
// a little widened, is cut at the spindle torus's crossings (its quartic, or the unit sphere's
// quadratic below kLemonLeastMajor), and each piece is inside or not by the lemon's own test at
// its middle, so the crossings of the rest of the torus (the "apple") only split a piece. The
// lemon is convex, but rounding at its cusps may split its span: up to three are kept.
void lemon_spans(const Node& leaf, const Ray& r, double lo, double hi, Span* out, int& n) {
  if (!(dot(r.d, r.d) > 0)) return;
  const Lemon& lemon = leaf.lemon;
  const double t0 = nearest_to_origin(r);
  const Vec3d o = r.o + r.d * t0, d = r.d;
  const double m = 1.001 * lemon_widest(lemon);
  double s_lo = -kInf, s_hi = kInf;
  if (!clip_to_box({{-m, -m, -kInf}, {m, m, kInf}}, {o, d}, s_lo, s_hi)) return;
  Boundary from{t0 + s_lo}, exit{t0 + s_hi};
  if (d.z != 0) {
    const double s_low = (lemon.z_low - o.z) / d.z, s_high = (lemon.z_high - o.z) / d.z;
    const Boundary low = on(leaf, t0 + s_low, 1, !leaf.open);
    const Boundary high = on(leaf, t0 + s_high, 2, !leaf.open);
    const bool up = d.z > 0;
    if ((up ? s_low : s_high) >= s_lo) s_lo = up ? s_low : s_high, from = up ? low : high;
    if ((up ? s_high : s_low) <= s_hi) s_hi = up ? s_high : s_low, exit = up ? high : low;
  } else if (o.z < lemon.z_low || o.z > lemon.z_high) {
    return;
  }
  if (!(s_lo < s_hi)) return;
  double c[5];
  int degree = 4;
  if (lemon.major < kLemonLeastMajor) {
    c[0] = dot(o, o) - 1, c[1] = 2 * dot(o, d), c[2] = dot(d, d), degree = 2;
  } else {
    lemon_quartic(lemon, o, d, c);
  }
  double roots[4];
  const int count = sign_changes(c, degree, s_lo, s_hi, roots);
  bool inside = false;
  Boundary entry;
  for (int i = 0; i <= count; ++i) {
    const Boundary end = i < count ? on(leaf, t0 + roots[i]) : exit;
    if (!(end.t > from.t)) continue;  // an empty piece: it leaves the state as it was
    const double mid = 0.5 * ((from.t - t0) + (end.t - t0));
    const bool piece_inside = lemon_value(lemon, o + d * mid) <= 0;
    if (piece_inside && !inside) entry = from;
    if (!piece_inside && inside) push(out, n, entry, from, lo, hi);
    inside = piece_inside;
    from = end;
  }
  if (inside) push(out, n, entry, exit, lo, hi);
}

// The sphere sweep (core/math/sphere_sweep.h) along the ray: cut at every segment's possible
// crossings (its end spheres' and its envelope's) among the segments whose box the ray meets,
// each piece then inside or not by the sweep's own test at its middle, so a crossing hidden
// inside another segment's spheres only splits a piece. `crossings` holds
// sweep_boundaries spans (only their `in` is used).
size_t sweep_boundaries(const SphereSweep& sweep) {
  return sweep.segments.size() * kSweepSegmentCrossings;
}

void sweep_spans(const Node& leaf, const Ray& r, double lo, double hi, Span* out, int& n,
                 Span* crossings) {
  if (!(dot(r.d, r.d) > 0)) return;
  const SphereSweep& sweep = *leaf.sweep;
  const double t0 = nearest_to_origin(r);
  const Vec3d o = r.o + r.d * t0, d = r.d;
  int count = 0;
  for (uint32_t i = 0; i < sweep.segments.size(); ++i) {
    const SweepSegment& segment = sweep.segments[i];
    double s_lo = -kInf, s_hi = kInf;
    if (!clip_to_box(segment.bounds, {o, d}, s_lo, s_hi)) continue;
    double s[kSweepSegmentCrossings];
    const int found = sweep_segment_crossings(segment, o, d, s);
    for (int k = 0; k < found; ++k) {
      if (!std::isfinite(s[k])) continue;
      crossings[count].in = on(leaf, t0 + s[k], 0);
      crossings[count++].in.segment = i;
    }
  }
  std::sort(crossings, crossings + count,
            [](const Span& a, const Span& b) { return a.in.t < b.in.t; });
  bool inside = false;
  Boundary entry;
  for (int k = 0; k + 1 < count; ++k) {
    const Boundary &from = crossings[k].in, &end = crossings[k + 1].in;
    if (!(end.t > from.t)) continue;  // an empty piece: it leaves the state as it was
    const bool piece_inside = sphere_sweep_value(sweep, r.o + r.d * (0.5 * (from.t + end.t))) <= 0;
    if (piece_inside && !inside) entry = from;
    if (!piece_inside && inside) push(out, n, entry, from, lo, hi);
    inside = piece_inside;
  }
  if (inside) push(out, n, entry, crossings[count - 1].in, lo, hi);
}

// The boundaries lathe_spans may cut a ray at: each segment's crossings and its two ends.
size_t lathe_boundaries(const Outline& profile) {
  return profile.segments.size() * (kLatheSegmentCrossings + 2);
}

// The lathe (core/scene/lathe.h) along the ray, within its box: the ray cut at the surface's
// crossings, each piece then inside or not by POV-Ray's inside test at its middle, as for the
// outline. An unclosed curve's inside test jumps at the heights of its loose ends, which bound
// the set but are no surface: the ray is cut there too. `cuts` holds lathe_boundaries spans.
void lathe_spans(const Node& leaf, const Ray& r, double lo, double hi, Span* out, int& n,
                 Span* cuts) {
  const Outline& profile = *leaf.outline;
  if (!(dot(r.d, r.d) > 0)) return;
  const double t0 = nearest_to_origin(r);
  const Vec3d o = r.o + r.d * t0, d = r.d;
  // The box a little wider than the lathe's, so that no crossing sits on its ends.
  Bounds3d box = lathe_bounds(profile);
  const Vec3d pad = (box.hi - box.lo) * 1e-3 + Vec3d{1e-9, 1e-9, 1e-9};
  box.lo = box.lo - pad, box.hi = box.hi + pad;
  double s_in = -kInf, s_out = kInf;
  if (!clip_to_box(box, {o, d}, s_in, s_out)) return;
  const bool level = !(std::abs(d.y) > kLatheLevelRay * length(d));
  const std::vector<OutlineSegment>& segments = profile.segments;
  const auto same = [](Vec2d a, Vec2d b) { return a.x == b.x && a.y == b.y; };
  int count = 0;
  for (uint32_t i = 0; i < segments.size(); ++i) {
    const OutlineSegment& s = segments[i];
    double u[kLatheSegmentCrossings], t[kLatheSegmentCrossings];
    const int found = lathe_crossings(s, o, d, u, t);
    for (int k = 0; k < found; ++k) {
      if (!(t[k] > s_in && t[k] < s_out)) continue;
      cuts[count].in = on(leaf, t0 + t[k], 0);
      cuts[count++].in.segment = i;
    }
    // The curve's neighbours, the first's being the last (a closed curve has no loose end).
    const size_t last = segments.size() - 1;
    const bool loose_start = !same(segments[i == 0 ? last : i - 1].end, s.start);
    const bool loose_end = !same(segments[i == last ? 0 : i + 1].start, s.end);
    for (const auto& [loose, end] : {std::pair{loose_start, s.start}, {loose_end, s.end}}) {
      const double t_end = level ? kInf : (end.y - o.y) / d.y;
      if (loose && t_end > s_in && t_end < s_out) cuts[count++].in = Boundary{t0 + t_end};
    }
  }
  // At equal t a crossing goes first: the piece that starts there starts on the surface.
  std::sort(cuts, cuts + count, [](const Span& a, const Span& b) {
    return a.in.t < b.in.t || (a.in.t == b.in.t && a.in.leaf && !b.in.leaf);
  });
  const Boundary box_in{t0 + s_in}, box_out{t0 + s_out};
  bool inside = false;
  Boundary entry, from = box_in;
  for (int k = 0; k <= count; ++k) {
    Boundary end = k < count ? cuts[k].in : box_out;
    if (!(end.t > from.t)) continue;  // an empty piece: it leaves the state as it was
    const bool piece_inside = lathe_contains(profile, o + d * (0.5 * (from.t + end.t) - t0));
    if (piece_inside && !inside) entry = from;
    if (!piece_inside && inside) {
      from.part = 3;  // where the ray leaves
      push(out, n, entry, from, lo, hi);
    }
    inside = piece_inside;
    from = end;
  }
  if (inside) push(out, n, entry, box_out, lo, hi);
}

// f < threshold within the container (core/scene/isosurface.h): the walk's crossings pair up from
// its inside state at the container's entry. The container's boundary is part 1, surface unless
// `open`. Where a cap stopped the walk, the ray leaves the set through no surface. The walk
// starts at the container's entry whatever lo is, and stops only past hi: the same ray meets the
// same crossings before hi.
void isosurface_spans(const Node& leaf, const Ray& r, double lo, double hi, Span* out, int& n) {
  const Isosurface& iso = *leaf.isosurface;
  double t_in = 0, t_out = 0;
  if (!isosurface_container_chord(iso, r.o, r.d, t_in, t_out)) return;
  const IsosurfaceWalk walk = isosurface_walk(iso, r.o, r.d, t_in, t_out, hi);
  const bool caps = !leaf.open;
  bool inside = walk.inside_at_entry;
  Boundary from = on(leaf, t_in, 1, caps);
  for (int i = 0; i < walk.count; ++i) {
    const Boundary crossing = on(leaf, walk.crossings[i]);
    if (inside) push(out, n, from, crossing, lo, hi);
    from = crossing, inside = !inside;
  }
  if (inside)
    push(out, n, from, walk.complete ? on(leaf, t_out, 1, caps) : Boundary{walk.t_end}, lo, hi);
}

// The julia fractal's set (core/math/julia_fractal.h): the march's crossings pair up from its
// inside state where the ray enters the bounding sphere, which holds the whole set. Where a cap
// stopped the march, the ray leaves the set through no surface.
void julia_spans(const Node& leaf, const Ray& r, double lo, double hi, Span* out, int& n) {
  const JuliaFractal& julia = *leaf.julia;
  double t_in = 0, t_out = 0;
  if (!julia_fractal_chord(julia, r.o, r.d, t_in, t_out)) return;
  const JuliaWalk walk = julia_fractal_walk(julia, r.o, r.d, t_in, t_out, hi);
  bool inside = walk.inside_at_entry;
  Boundary from{t_in};
  for (int i = 0; i < walk.count; ++i) {
    const Boundary crossing = on(leaf, walk.crossings[i]);
    if (inside) push(out, n, from, crossing, lo, hi);
    from = crossing, inside = !inside;
  }
  if (inside) push(out, n, from, Boundary{walk.complete ? t_out : walk.t_end}, lo, hi);
}

// The primitive's spans (at most primitive_max_spans) into out, using primitive_workspace spans
// of scratch; returns their count.
int primitive_spans(const Node& leaf, const Ray& render_ray, double lo, double hi, Span* out,
                    Span* scratch) {
  const Ray r{leaf.object_from_render.point(render_ray.o),
              leaf.object_from_render.vector(render_ray.d)};
  int n = 0;
  switch (leaf.kind) {
    case SolidKind::kSphere:
      sphere_spans(leaf, r, lo, hi, out, n);
      break;
    case SolidKind::kBox:
      box_spans(leaf, r, lo, hi, out, n);
      break;
    case SolidKind::kHalfSpace:
    case SolidKind::kDisc:
      half_space_spans(leaf, r, lo, hi, out, n);
      break;
    case SolidKind::kCylinder:
    case SolidKind::kCone:
      cone_spans(leaf, r, lo, hi, out, n);
      break;
    case SolidKind::kTorus:
      torus_spans(leaf, r, lo, hi, out, n);
      break;
    case SolidKind::kPolynomial:
      polynomial_spans(leaf, render_ray, r, lo, hi, out, n);
      break;
    case SolidKind::kOutline:
      outline_spans(leaf, r, lo, hi, out, n, scratch);
      break;
    case SolidKind::kSuperellipsoid:
      superellipsoid_spans(leaf, r, lo, hi, out, n);
      break;
    case SolidKind::kBlob:
      blob_spans(leaf, r, lo, hi, out, n);
      break;
    case SolidKind::kSor:
      sor_spans(leaf, r, lo, hi, out, n);
      break;
    case SolidKind::kLathe:
      lathe_spans(leaf, r, lo, hi, out, n, scratch);
      break;
    case SolidKind::kLemon:
      lemon_spans(leaf, r, lo, hi, out, n);
      break;
    case SolidKind::kSphereSweep:
      sweep_spans(leaf, r, lo, hi, out, n, scratch);
      break;
    case SolidKind::kIsosurface:
      isosurface_spans(leaf, r, lo, hi, out, n);
      break;
    case SolidKind::kJuliaFractal:
      julia_spans(leaf, r, lo, hi, out, n);
      break;
    default:
      break;
  }
  return n;
}

// The most spans primitive_spans gives: a quadric's two spans within the cone's slab; one per
// interval between the roots of a torus (4) or polynomial (its degree, up to 15); an outline's
// walls, crossed at most `degrees` times, leave at most half as many pieces inside, and one more;
// one per pair of a superellipsoid's or a blob's crossings.
size_t primitive_max_spans(const Node& leaf) {
  switch (leaf.kind) {
    case SolidKind::kCylinder:
    case SolidKind::kCone:
      return 2;
    case SolidKind::kTorus:
    case SolidKind::kPolynomial:
      return kMaxPolynomialDegree + 1;
    case SolidKind::kOutline:
      return leaf.outline->degrees / 2 + 1;
    case SolidKind::kSuperellipsoid:
      return kSuperellipsoidMaxCrossings / 2;
    case SolidKind::kBlob:
      return blob_max_crossings(leaf.blob) / 2 + 1;
    case SolidKind::kSor:  // a cubic's two spans a segment
      return 2 * leaf.sor.size() + 1;
    case SolidKind::kLathe:  // pieces between its cuts, every other one inside
      return lathe_boundaries(*leaf.outline) / 2 + 1;
    case SolidKind::kLemon:  // five pieces between four crossings, every other one inside
      return 3;
    case SolidKind::kSphereSweep:  // pieces between its crossings, every other one inside
      return sweep_boundaries(*leaf.sweep) / 2 + 1;
    case SolidKind::kIsosurface:  // every other piece between its crossings
      return kIsosurfaceMaxCrossings / 2 + 1;
    case SolidKind::kJuliaFractal:
      return kJuliaMaxCrossings / 2 + 1;
    default:
      return 1;
  }
}

// The scratch primitive_spans needs: an outline's wall crossings, a lathe's cuts, a sweep's
// crossings.
size_t primitive_workspace(const Node& leaf) {
  if (leaf.kind == SolidKind::kOutline) return leaf.outline->degrees;
  if (leaf.kind == SolidKind::kSphereSweep) return sweep_boundaries(*leaf.sweep);
  return leaf.kind == SolidKind::kLathe ? lathe_boundaries(*leaf.outline) : 0;
}

int node_spans(const Node& node, const Ray& r, double lo, double hi, Span* out, Span* scratch);

// A set operation's spans into out. Its scratch holds a child's spans, the combination being
// built, and below them the children's own scratch.
int children_spans(const Node& node, const Ray& r, double lo, double hi, Span* out, Span* scratch) {
  Span* const child = scratch;
  Span* const combined = child + node.max_child_spans;
  Span* const below = combined + node.max_spans;
  int n = 0;
  if (node.kind == SolidKind::kUnion) {
    for (const Node& c : node.children) {
      const int m = node_spans(c, r, lo, hi, child, below);
      if (m == 0) continue;  // the union so far is already joined
      n = united(out, n, child, m, combined);
      std::copy_n(combined, n, out);
    }
    return n;
  }
  for (size_t i = 0; i < node.children.size(); ++i) {
    if (i == 0) {
      n = node_spans(node.children[0], r, lo, hi, out, below);
    } else {
      const int m = node_spans(node.children[i], r, lo, hi, child, below);
      n = intersection(out, n, child, m, combined);
      std::copy_n(combined, n, out);
    }
    if (n == 0) break;
  }
  return n;
}

// The node's set along the ray within [lo, hi]: at most node.max_spans spans into out, using
// node.workspace spans of scratch. Returns their count. A node whose box the ray misses within
// the window is empty there; its box is tested on a window a little past `hi`, so that rounding
// never culls a surface just short of it.
int node_spans(const Node& node, const Ray& r, double lo, double hi, Span* out, Span* scratch) {
  int n = 0;
  double box_lo = lo, box_hi = hi + std::abs(hi) * 1e-9;
  if (clip_to_box(node.bounds, r, box_lo, box_hi)) {
    n = node.kind < SolidKind::kUnion ? primitive_spans(node, r, lo, hi, out, scratch)
                                      : children_spans(node, r, lo, hi, out, scratch);
  }
  if (node.inverse) n = complement(out, n, lo, hi, scratch);
  return n;
}

// The outward normal of an outline's wall at object-space point p, which the ray along d (object
// space) enters (part 0) or leaves (part 3) there. Even-odd contours have no orientation of
// their own: the side the ray comes from tells outside from inside. The segment's parameter at
// p is the root of the same wall polynomial (the ray through p) whose point is nearest to p.
// Linear: the tangent turned; conic: the tangent (t, 0) crossed with the ruling (point(u), 1).
Vec3d outline_wall_normal(const Node& leaf, const Boundary& b, Vec3d p, Vec3d d) {
  const OutlineSegment& s = leaf.outline->segments[b.segment];
  double c[4], u[3];
  outline_wall_polynomial(leaf, s, p, d, c);
  const int roots = sign_changes(c, s.degree, -kOutlineJointSlack, 1 + kOutlineJointSlack, u);
  const double scale = leaf.conic ? p.z : 1;
  double best = HUGE_VAL, u_best = 0;
  for (int k = 0; k < roots; ++k) {
    const Vec2d miss = segment_point(s, u[k]) * scale - Vec2d{p.x, p.y};
    const double distance = miss.x * miss.x + miss.y * miss.y;
    if (distance < best) best = distance, u_best = u[k];
  }
  const Vec2d t = segment_tangent(s, u_best), q = segment_point(s, u_best);
  Vec3d normal{t.y, -t.x, leaf.conic ? t.x * q.y - t.y * q.x : 0};
  if ((dot(normal, d) > 0) != (b.part == 3)) normal = -normal;
  return normal;
}

// The primitive's outward gradient at object-space point p on the boundary b, which the ray
// along object-space direction d crosses there.
Vec3d gradient(const Node& leaf, const Boundary& b, Vec3d p, Vec3d d) {
  const uint8_t part = b.part;
  switch (leaf.kind) {
    case SolidKind::kSphere:
      return p;
    case SolidKind::kBox: {
      Vec3d n{0, 0, 0};
      (part / 2 == 0 ? n.x : part / 2 == 1 ? n.y : n.z) = part % 2 ? 1 : -1;
      return n;
    }
    case SolidKind::kCylinder:
    case SolidKind::kCone: {
      if (part != 0) return {0, 0, part == 1 ? -1.0 : 1.0};
      const bool cylinder = leaf.kind == SolidKind::kCylinder;
      const double r0 = cylinder ? 1 : leaf.radius0, k = cylinder ? 0 : leaf.radius1 - r0;
      return {p.x, p.y, -(r0 + k * p.z) * k};
    }
    case SolidKind::kTorus: {
      const double g = dot(p, p) + 1 - leaf.radius1 * leaf.radius1;
      return {g * p.x - 2 * p.x, g * p.y - 2 * p.y, g * p.z};
    }
    case SolidKind::kPolynomial:
      return polynomial3_gradient(leaf.polynomial, p);
    case SolidKind::kOutline:
      if (part == 1 || part == 2) return {0, 0, part == 1 ? -1.0 : 1.0};
      return outline_wall_normal(leaf, b, p, d);
    case SolidKind::kSuperellipsoid:
      return superellipsoid_gradient({leaf.radius0, leaf.radius1}, p);
    case SolidKind::kBlob:  // the field grows inwards
      return -blob_gradient(leaf.blob, p);
    case SolidKind::kSor:
      return part == 0 ? sor_side_gradient(leaf.sor, p) : Vec3d{0, part == 1 ? -1.0 : 1.0, 0};
    case SolidKind::kLathe:
      return lathe_normal(leaf.outline->segments[b.segment], p, d, part == 3);
    case SolidKind::kLemon:
      return part == 0 ? lemon_gradient(leaf.lemon, p) : Vec3d{0, 0, part == 1 ? -1.0 : 1.0};
    case SolidKind::kSphereSweep:
      return sweep_segment_normal(leaf.sweep->segments[b.segment], p);
    case SolidKind::kIsosurface:
      return part == 1 ? isosurface_container_normal(*leaf.isosurface, p)
                       : isosurface_gradient(*leaf.isosurface, p);
    case SolidKind::kJuliaFractal:
      return julia_fractal_gradient(*leaf.julia, p);
    default:
      return {0, 0, 1};  // kHalfSpace, kDisc
  }
}

// What node_spans can need for the node, from its children's needs (counts saturate at
// kMaxSpans + 1: a hostile tree must not wrap them around).
void budget_spans(Node& node) {
  const auto capped = [](size_t v) { return std::min(v, kMaxSpans + 1); };
  size_t spans = 0, child_workspace = 0;
  if (node.kind < SolidKind::kUnion) {
    spans = primitive_max_spans(node);
  } else {
    for (size_t i = 0; i < node.children.size(); ++i) {
      const Node& c = node.children[i];
      node.max_child_spans = std::max(node.max_child_spans, c.max_spans);
      child_workspace = std::max(child_workspace, c.workspace);
      if (node.kind == SolidKind::kUnion)
        spans = capped(spans + c.max_spans);
      else
        spans = i == 0 ? c.max_spans : spans + std::max(c.max_spans, size_t(1)) - 1;
    }
  }
  // The combination is built to the size before the complement, whose gap more fits in the
  // workspace it then reuses.
  node.max_spans = capped(spans + (node.inverse ? 1 : 0));
  const size_t children =
      node.children.empty() ? 0 : capped(node.max_child_spans + node.max_spans + child_workspace);
  node.workspace =
      std::max({children, node.inverse ? node.max_spans : 0, capped(primitive_workspace(node))});
}

Node build(const Solid& solid, const Transform& render_from_world, const Bounds3d& reach,
           bool surface) {
  Node node;
  node.kind = solid.kind;
  node.surface = surface && !solid.bounds_only;
  node.inverse = solid.inverse;
  node.open = solid.open;
  node.radius0 = std::abs(solid.radius0);
  node.radius1 = std::abs(solid.radius1);
  node.material = solid.material;
  node.bounds = uncomplemented_bounds(solid, render_from_world);
  node.polynomial = solid.polynomial;
  node.outline = solid.outline;
  node.conic = solid.conic;
  if (solid.kind == SolidKind::kOutline && solid.conic)
    node.z0 = std::min(solid.radius0, solid.radius1),
    node.z1 = std::max(solid.radius0, solid.radius1);
  node.blob = solid.blob;
  node.sor = solid.sor;
  node.lemon = solid.lemon;
  node.sweep = solid.sweep;
  node.isosurface = solid.isosurface;
  node.julia = solid.julia;
  node.window = reach;
  if (solid.is_primitive()) {
    const Transform render_from_object = render_from_world * solid.world_from_object;
    node.object_from_render = render_from_object.inverse();
    node.normal_from_object = render_from_object.normal_transform();
    if (!node.object_from_render.is_finite() || !node.normal_from_object.is_finite())
      throw InputError("solid '" + solid.name + "': its placement cannot be inverted");
    if (node.bounds.finite())
      node.magnitude = length(max(abs(node.bounds.lo), abs(node.bounds.hi)));
  }
  for (const Solid& child : solid.children)
    node.children.push_back(build(child, render_from_world, reach, node.surface));
  budget_spans(node);
  return node;
}

// Calls f with a buffer of `spans` spans: on the stack when they fit, else a per-thread buffer
// that grows to the largest tree met and then stays (no allocation per ray after the first).
template <class F>
auto with_spans(size_t spans, F f) {
  if (spans <= kStackSpans) {
    // Raw bytes, not Span[]: constructing 256 spans per ray would cost more than using them. A
    // Span is an aggregate, whose objects the storage holds implicitly (C++20, P0593).
    alignas(Span) std::byte stack[kStackSpans * sizeof(Span)];
    return f(reinterpret_cast<Span*>(stack));
  }
  thread_local std::vector<Span> heap;
  if (heap.size() < spans) heap.resize(spans);
  return f(heap.data());
}

}  // namespace

RenderSolid::RenderSolid(const Solid& solid, const Transform& render_from_world,
                         const Bounds3d& reach) {
  root_.push_back(build(solid, render_from_world, reach, true));
  const Node& root = root_.front();
  spans_ = root.max_spans + root.workspace;
  if (spans_ > kMaxSpans)
    throw InputError("solid '" + solid.name + "': its CSG tree can give a ray " +
                     (spans_ > kMaxSpans + 1 ? "more than " : "") + std::to_string(spans_) +
                     " spans to combine, more than the " + std::to_string(kMaxSpans) +
                     " the intersector holds; split its unions into separate objects");
  const Bounds3d set = solid_bounds(solid, render_from_world);
  bounded_ = set.finite();
  bounds_ = {max(set.lo, reach.lo), min(set.hi, reach.hi)};
}

RenderSolid::~RenderSolid() = default;
RenderSolid::RenderSolid(RenderSolid&&) noexcept = default;

std::optional<SolidHit> RenderSolid::first_hit(Vec3d origin, Vec3d direction, double t_min,
                                               double t_max) const {
  const Ray r{origin, direction};
  double lo = t_min, hi = t_max + std::abs(t_max) * 1e-9;
  if (!clip_to_box(bounds_, r, lo, hi)) return std::nullopt;
  // The window is [t_min, t_max): cutting it at the bounds' exit would cut the surfaces that
  // touch the bounds there. Every boundary before t_max is the one an uncut window gives.
  const std::optional<Boundary> hit = with_spans(spans_, [&](Span* spans) {
    const int n =
        node_spans(root_.front(), r, t_min, t_max, spans, spans + root_.front().max_spans);
    for (int i = 0; i < n; ++i)
      for (const Boundary* b : {&spans[i].in, &spans[i].out})
        if (b->surface && b->t > t_min && b->t < t_max) return std::optional<Boundary>(*b);
    return std::optional<Boundary>();
  });
  if (!hit) return std::nullopt;
  const Node& leaf = *hit->leaf;
  SolidHit result;
  result.t = hit->t;
  result.material = leaf.material;
  result.position = r.o + r.d * hit->t;
  const Vec3d object_direction = leaf.object_from_render.vector(r.d);
  const Vec3d p = leaf.object_from_render.point(r.o) + object_direction * hit->t;
  const Vec3d n = leaf.normal_from_object.vector(gradient(leaf, *hit, p, object_direction));
  const double len = length(n);
  result.normal = len > 0 ? n / len : -normalize(r.d);  // a cone's apex, a torus's centre
  if (hit->flipped) result.normal = -result.normal;
  // Rounding to float (half an ulp, bounded by epsilon |p|), plus the double-precision solve:
  // roots and transforms are good to ~1e-15 of the magnitudes involved; 1e-9 of them is ample.
  constexpr double kFloatRounding = std::numeric_limits<float>::epsilon();
  const double solve = 1e-9 * (length(result.position) + leaf.magnitude);
  result.position_error = abs(result.position) * kFloatRounding + Vec3d{solve, solve, solve};
  return result;
}

bool RenderSolid::contains(Vec3d point) const {
  // The spans of a line through the point, unbounded both ways: the point is in the set when one
  // of them holds t = 0. The direction is irrational to the axes, so the line does not run along
  // a box's face or a plane.
  const Ray r{point, {0.5477225575051661, 0.7745966692414834, 0.3162277660168379}};
  return with_spans(spans_, [&](Span* spans) {
    const int n = node_spans(root_.front(), r, -kInf, kInf, spans, spans + root_.front().max_spans);
    for (int i = 0; i < n; ++i)
      if (spans[i].in.t <= 0 && spans[i].out.t >= 0) return true;
    return false;
  });
}

}  // namespace fb
