#include "core/math/blob.h"

#include <algorithm>
#include <cmath>

#include "core/math/polynomial.h"

namespace fb {

namespace {

// A squared distance along the line p(t) = po + t pd: q(t) = c[0] + c[1] t + c[2] t^2.
struct Quadratic {
  double c[3];
};

Quadratic to_point(Vec3d centre, Vec3d po, Vec3d pd) {
  const Vec3d w = po - centre;
  return {{dot(w, w), 2 * dot(w, pd), dot(pd, pd)}};
}

Quadratic to_axis_line(const BlobComponent& k, Vec3d po, Vec3d pd) {
  const Vec3d u = normalize(k.b - k.a), w = po - k.a;
  const double wu = dot(w, u), du = dot(pd, u);
  return {{dot(w, w) - wu * wu, 2 * (dot(w, pd) - wu * du), dot(pd, pd) - du * du}};
}

// The component's squared distance along the line in the regime (its centre; a cylinder's axis or
// one of its ends) that holds at parameter t_regime.
Quadratic squared_distance(const BlobComponent& k, Vec3d po, Vec3d pd, double t_regime) {
  if (!k.cylinder) return to_point(k.a, po, pd);
  const Vec3d axis = k.b - k.a;
  const double h = dot(po + pd * t_regime - k.a, axis);
  if (h < 0) return to_point(k.a, po, pd);
  if (h > dot(axis, axis)) return to_point(k.b, po, pd);
  return to_axis_line(k, po, pd);
}

double squared_distance_at(const BlobComponent& k, Vec3d p) {
  return squared_distance(k, p, {0, 0, 0}, 0).c[0];
}

// Where q(t) = r^2 (entering or leaving the region), appended to `out`.
void region_ends(const Quadratic& q, double r2, std::vector<double>& out) {
  const double a = q.c[2], b = q.c[1], c = q.c[0] - r2;
  if (!(a > 0)) return;
  const double disc = b * b - 4 * a * c;
  if (!(disc > 0)) return;
  const double s = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  out.push_back(s / a);
  if (s != 0) out.push_back(c / s);
}

}  // namespace

double blob_field(const Blob& blob, Vec3d p) {
  double field = 0;
  for (const BlobComponent& k : blob.components) {
    const double q = squared_distance_at(k, k.component_from_blob.point(p));
    const double r2 = k.radius * k.radius;
    if (q < r2) field += k.strength * (1 - q / r2) * (1 - q / r2);
  }
  return field;
}

Vec3d blob_gradient(const Blob& blob, Vec3d p) {
  Vec3d gradient{0, 0, 0};
  for (const BlobComponent& k : blob.components) {
    const Vec3d local = k.component_from_blob.point(p);
    const double r2 = k.radius * k.radius;
    const double q = squared_distance_at(k, local);
    if (!(q < r2)) continue;
    // grad q in the component's space: 2 (p - nearest point of the centre or axis)
    Vec3d nearest = k.a;
    if (k.cylinder) {
      const Vec3d axis = k.b - k.a;
      const double h = std::clamp(dot(local - k.a, axis) / dot(axis, axis), 0.0, 1.0);
      nearest = k.a + axis * h;
    }
    const Vec3d grad_q_local = (local - nearest) * 2.0;
    // back to the blob's space through the transpose of component_from_blob's linear part
    const Transform& m = k.component_from_blob;
    const Vec3d grad_q{
        m(0, 0) * grad_q_local.x + m(1, 0) * grad_q_local.y + m(2, 0) * grad_q_local.z,
        m(0, 1) * grad_q_local.x + m(1, 1) * grad_q_local.y + m(2, 1) * grad_q_local.z,
        m(0, 2) * grad_q_local.x + m(1, 2) * grad_q_local.y + m(2, 2) * grad_q_local.z};
    gradient = gradient + grad_q * (-2 * k.strength * (1 - q / r2) / r2);
  }
  return gradient;
}

Bounds3d blob_bounds(const Blob& blob) {
  Bounds3d bounds;
  for (const BlobComponent& k : blob.components) {
    if (!(k.strength > 0)) continue;
    const Vec3d r{k.radius, k.radius, k.radius};
    const Vec3d lo = min(k.a, k.cylinder ? k.b : k.a) - r,
                hi = max(k.a, k.cylinder ? k.b : k.a) + r;
    const Transform blob_from_component = k.component_from_blob.inverse();
    for (int i = 0; i < 8; ++i)
      bounds.extend(blob_from_component.point(
          {i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z}));
  }
  return bounds;
}

size_t blob_max_crossings(const Blob& blob) {
  // At most eight region ends and end-plane crossings a component (a cylinder: two with each end
  // sphere and with the infinite cylinder, two end planes): 8 n - 1 pieces of four roots each.
  return 4 * (8 * blob.components.size() + 1);
}

const std::vector<double>& blob_crossings(const Blob& blob, Vec3d o, Vec3d d) {
  struct Line {
    Vec3d o, d;  // the ray in the component's space
  };
  thread_local std::vector<double> ends, roots;
  thread_local std::vector<Line> lines;
  ends.clear(), roots.clear(), lines.clear();
  for (const BlobComponent& k : blob.components) {
    const Line line{k.component_from_blob.point(o), k.component_from_blob.vector(d)};
    lines.push_back(line);
    const double r2 = k.radius * k.radius;
    region_ends(to_point(k.a, line.o, line.d), r2, ends);
    if (!k.cylinder) continue;
    // a cylinder: the regions of its ends' spheres and of its infinite cylinder, and the end
    // planes, where the regime changes (each piece tests its own regime at its middle)
    region_ends(to_point(k.b, line.o, line.d), r2, ends);
    region_ends(to_axis_line(k, line.o, line.d), r2, ends);
    const Vec3d axis = k.b - k.a;
    const double rate = dot(line.d, axis), start = dot(line.o - k.a, axis);
    if (rate != 0) ends.insert(ends.end(), {-start / rate, (dot(axis, axis) - start) / rate});
  }
  std::sort(ends.begin(), ends.end());
  for (size_t i = 0; i + 1 < ends.size(); ++i) {
    const double lo = ends[i], hi = ends[i + 1];
    if (!(lo < hi)) continue;
    const double mid = 0.5 * (lo + hi);
    double c[5] = {-blob.threshold, 0, 0, 0, 0};
    bool any = false;
    for (size_t j = 0; j < blob.components.size(); ++j) {
      const BlobComponent& k = blob.components[j];
      const Quadratic q = squared_distance(k, lines[j].o, lines[j].d, mid);
      const double r2 = k.radius * k.radius;
      if (!(q.c[0] + mid * (q.c[1] + mid * q.c[2]) < r2)) continue;
      // s (1 - q / r^2)^2 with 1 - q / r^2 = e0 + e1 t + e2 t^2
      const double e0 = 1 - q.c[0] / r2, e1 = -q.c[1] / r2, e2 = -q.c[2] / r2, s = k.strength;
      c[0] += s * e0 * e0, c[1] += s * 2 * e0 * e1, c[2] += s * (e1 * e1 + 2 * e0 * e2);
      c[3] += s * 2 * e1 * e2, c[4] += s * e2 * e2;
      any = true;
    }
    if (!any) continue;  // the field is 0 there: outside
    double found[4];
    const int count = sign_changes(c, 4, lo, hi, found);
    roots.insert(roots.end(), found, found + count);
  }
  return roots;
}

}  // namespace fb
