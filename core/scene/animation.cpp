#include "core/scene/animation.h"

#include <algorithm>
#include <cmath>

namespace fb {
namespace {

double dot(const Quatd& a, const Quatd& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w;
}

Quatd normalized(const Quatd& q) {
  const double n = std::sqrt(dot(q, q));
  return {q.x / n, q.y / n, q.z / n, q.w / n};
}

Quatd to_quat(const double* v) {
  return {v[0], v[1], v[2], v[3]};
}

}  // namespace

Quatd slerp(Quatd a, Quatd b, double t) {
  // q and -q are the same rotation: take the shorter arc (glTF 2.0 Appendix C, s = sign(a·b)).
  if (dot(a, b) < 0) b = {-b.x, -b.y, -b.z, -b.w};
  // The angle between them, 2 atan2(|a - b|, |a + b|): accurate at every angle, unlike acos(a·b)
  // near 0, where the spec's implementation note falls back to linear interpolation.
  const Quatd d{a.x - b.x, a.y - b.y, a.z - b.z, a.w - b.w};
  const Quatd s{a.x + b.x, a.y + b.y, a.z + b.z, a.w + b.w};
  const double angle = 2 * std::atan2(std::sqrt(dot(d, d)), std::sqrt(dot(s, s)));
  double wa = 1 - t, wb = t;
  if (angle > 1e-9) {
    const double sin_angle = std::sin(angle);
    wa = std::sin((1 - t) * angle) / sin_angle;
    wb = std::sin(t * angle) / sin_angle;
  }
  return normalized(
      {wa * a.x + wb * b.x, wa * a.y + wb * b.y, wa * a.z + wb * b.z, wa * a.w + wb * b.w});
}

void AnimationCurve::evaluate(double t, double* out) const {
  const uint32_t w = width();
  const size_t n = times_s.size();
  const bool cubic = interpolation == Interpolation::kCubicSpline;
  // Key k's value, and for cubic splines its in- (-1) and out-tangent (+1).
  auto key = [&](size_t k, int part = 0) { return &values[((cubic ? 3 * k + 1 : k) + part) * w]; };
  if (!(t > times_s.front()) || t >= times_s.back() || n == 1) {
    std::copy_n(key(t >= times_s.back() ? n - 1 : 0), w, out);
    return;
  }
  const size_t k =
      size_t(std::upper_bound(times_s.begin(), times_s.end(), t) - times_s.begin()) - 1;
  const double td = times_s[k + 1] - times_s[k];
  const double s = (t - times_s[k]) / td;
  const double *v0 = key(k), *v1 = key(k + 1);
  switch (interpolation) {
    case Interpolation::kStep:
      std::copy_n(v0, w, out);
      return;
    case Interpolation::kLinear:
      if (path == TrsPath::kRotation) {
        const Quatd q = slerp(to_quat(v0), to_quat(v1), s);
        out[0] = q.x, out[1] = q.y, out[2] = q.z, out[3] = q.w;
      } else {
        for (uint32_t i = 0; i < w; ++i)
          out[i] = (1 - s) * v0[i] + s * v1[i];
      }
      return;
    case Interpolation::kCubicSpline: {
      // glTF 2.0 Appendix C: p(s) = (2s³ - 3s² + 1) v_k + td (s³ - 2s² + s) b_k
      //                            + (-2s³ + 3s²) v_k+1 + td (s³ - s²) a_k+1
      const double s2 = s * s, s3 = s2 * s;
      const double *b0 = key(k, +1), *a1 = key(k + 1, -1);
      for (uint32_t i = 0; i < w; ++i)
        out[i] = (2 * s3 - 3 * s2 + 1) * v0[i] + td * (s3 - 2 * s2 + s) * b0[i] +
                 (-2 * s3 + 3 * s2) * v1[i] + td * (s3 - s2) * a1[i];
      if (path == TrsPath::kRotation) {
        const Quatd q = normalized(to_quat(out));
        out[0] = q.x, out[1] = q.y, out[2] = q.z, out[3] = q.w;
      }
      return;
    }
  }
}

bool AnimationCurve::varies(double t0, double t1) const {
  if (!(t1 > t0) || times_s.size() < 2 || t1 <= times_s.front() || t0 >= times_s.back())
    return false;  // an instant, or clamped to the first or last key throughout
  const uint32_t w = width();
  const bool cubic = interpolation == Interpolation::kCubicSpline;
  // The keys whose values reach [t0, t1]: from the last at or before t0 to the first at or after
  // t1, whose segment ends inside; a step holds its value to the next key, so for STEP only up to
  // the last at or before t1.
  const auto first = std::upper_bound(times_s.begin(), times_s.end(), t0);
  const size_t lo = first == times_s.begin() ? 0 : size_t(first - times_s.begin()) - 1;
  const size_t hi =
      interpolation == Interpolation::kStep
          ? size_t(std::upper_bound(times_s.begin(), times_s.end(), t1) - times_s.begin()) - 1
          : std::min(size_t(std::lower_bound(times_s.begin(), times_s.end(), t1) - times_s.begin()),
                     times_s.size() - 1);
  // Between equal values every interpolation is constant, unless a cubic tangent bends it.
  const size_t stride = cubic ? 3 * w : w;
  const double* reference = &values[lo * stride + (cubic ? w : 0)];
  for (size_t k = lo; k <= hi; ++k) {
    const double* v = &values[k * stride];
    for (uint32_t i = 0; i < w; ++i) {
      if (!cubic && v[i] != reference[i]) return true;
      if (cubic && (v[i] != 0 || v[w + i] != reference[i] || v[2 * w + i] != 0)) return true;
    }
  }
  return false;
}

Transform Trs::matrix() const {
  return Transform::translate(translation) * Transform::rotate(rotation) * Transform::scale(scale);
}

uint32_t NodeHierarchy::add_node(uint32_t parent, const Transform& local, const Trs& rest) {
  SceneNode node;
  node.parent = parent;
  node.local = local;
  node.rest = rest;
  node.world = parent == kNoNode ? local : nodes[parent].world * local;
  nodes.push_back(node);
  return uint32_t(nodes.size() - 1);
}

void NodeHierarchy::finish() {
  for (uint32_t c = 0; c < curves.size(); ++c)
    nodes[curves[c].node].curves[size_t(curves[c].path)] = c;
  for (SceneNode& node : nodes) {
    node.animated = node.parent != kNoNode && nodes[node.parent].animated;
    for (uint32_t c : node.curves)
      node.animated |= c != kNoCurve;
  }
}

// Bottom-up, iteratively: a hierarchy as deep as a hostile file likes cannot exhaust the stack.
Transform NodeHierarchy::world_from_node(uint32_t index, double time_s) const {
  Transform node_from_leaf;
  for (uint32_t i = index; i != kNoNode; i = nodes[i].parent) {
    const SceneNode& node = nodes[i];
    if (!node.animated) return node.world * node_from_leaf;
    Transform local = node.local;
    if (node.curves != std::array{kNoCurve, kNoCurve, kNoCurve}) {
      Trs trs = node.rest;
      double v[4];
      if (node.curves[0] != kNoCurve)
        curves[node.curves[0]].evaluate(time_s, v), trs.translation = {v[0], v[1], v[2]};
      if (node.curves[1] != kNoCurve)
        curves[node.curves[1]].evaluate(time_s, v), trs.rotation = to_quat(v);
      if (node.curves[2] != kNoCurve)
        curves[node.curves[2]].evaluate(time_s, v), trs.scale = {v[0], v[1], v[2]};
      local = trs.matrix();
    }
    node_from_leaf = local * node_from_leaf;
  }
  return node_from_leaf;
}

bool NodeHierarchy::moves(uint32_t index, double t0, double t1) const {
  for (uint32_t i = index; i != kNoNode && nodes[i].animated; i = nodes[i].parent)
    for (uint32_t c : nodes[i].curves)
      if (c != kNoCurve && curves[c].varies(t0, t1)) return true;
  return false;
}

}  // namespace fb
