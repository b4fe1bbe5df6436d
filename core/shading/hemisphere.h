// Direction sampling and frames around a closure's normal, in render space (Cycles'
// kernel/sample/mapping.h and util/math.h make_orthonormals_tangent).
#pragma once

#include <cmath>
#include <numbers>

#include <filmback/geometry.h>
#include <filmback/sampling.h>
#include <filmback/vec.h>

namespace fb {

inline constexpr float kInvPi = std::numbers::inv_pi_v<float>;

// Cosine-weighted direction about N; pdf = cos / pi (sample_cos_hemisphere).
inline Vec3f sample_cos_hemisphere(Vec3f N, Vec2f u, float& pdf) {
  const Vec3f local = sample_cosine_hemisphere(u);
  pdf = local.z * kInvPi;
  return Frame(N).to_world(local);
}

// Uniform direction about N; pdf = 1 / (2 pi) (sample_uniform_hemisphere).
inline Vec3f sample_uniform_hemisphere(Vec3f N, Vec2f u, float& pdf) {
  const float z = u.x, r = std::sqrt(std::max(0.f, 1.f - z * z));
  const float phi = 2.f * std::numbers::pi_v<float> * u.y;
  pdf = 0.5f * kInvPi;
  return Frame(N).to_world({r * std::cos(phi), r * std::sin(phi), z});
}

// X along the tangent T made perpendicular to N, Y = N x X (make_orthonormals_tangent).
struct TangentFrame {
  Vec3f X, Y, Z;
  TangentFrame(Vec3f N, Vec3f T) : Z(N) {
    Y = normalize(cross(N, T));
    X = cross(Y, N);
  }
  Vec3f to_local(Vec3f v) const { return {dot(v, X), dot(v, Y), dot(v, Z)}; }
  Vec3f to_world(Vec3f v) const { return X * v.x + Y * v.y + Z * v.z; }
};

}  // namespace fb
