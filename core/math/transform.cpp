#include "core/math/transform.h"

#include <cmath>

namespace fb {

Transform::Transform() {
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      m_[r][c] = r == c ? 1.0 : 0.0;
}

Transform Transform::from_rows(const std::array<double, 16>& row_major) {
  Transform t;
  for (int i = 0; i < 16; ++i)
    t.m_[i / 4][i % 4] = row_major[i];
  return t;
}

Transform Transform::from_columns(const std::array<double, 16>& column_major) {
  Transform t;
  for (int i = 0; i < 16; ++i)
    t.m_[i % 4][i / 4] = column_major[i];
  return t;
}

Transform Transform::translate(Vec3d v) {
  Transform t;
  t.m_[0][3] = v.x, t.m_[1][3] = v.y, t.m_[2][3] = v.z;
  return t;
}

Transform Transform::scale(Vec3d s) {
  Transform t;
  t.m_[0][0] = s.x, t.m_[1][1] = s.y, t.m_[2][2] = s.z;
  return t;
}

Transform Transform::rotate(Quatd q) {
  const double n = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
  const double x = q.x / n, y = q.y / n, z = q.z / n, w = q.w / n;
  return from_rows({1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w), 0,  //
                    2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w), 0,  //
                    2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y), 0,  //
                    0, 0, 0, 1});
}

Transform Transform::look_at(Vec3d eye, Vec3d target, Vec3d up) {
  const Vec3d back = normalize(eye - target);  // camera +Z points away from what it sees
  const Vec3d right = normalize(cross(up, back));
  const Vec3d true_up = cross(back, right);
  return from_rows({right.x, true_up.x, back.x, eye.x,  //
                    right.y, true_up.y, back.y, eye.y,  //
                    right.z, true_up.z, back.z, eye.z,  //
                    0, 0, 0, 1});
}

Transform Transform::operator*(const Transform& rhs) const {
  Transform t;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      double sum = 0;
      for (int k = 0; k < 4; ++k)
        sum += m_[r][k] * rhs.m_[k][c];
      t.m_[r][c] = sum;
    }
  return t;
}

// Gauss-Jordan elimination with partial pivoting.
Transform Transform::inverse() const {
  double a[4][8];
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      a[r][c] = m_[r][c];
      a[r][c + 4] = r == c ? 1.0 : 0.0;
    }
  for (int col = 0; col < 4; ++col) {
    int pivot = col;
    for (int r = col + 1; r < 4; ++r)
      if (std::abs(a[r][col]) > std::abs(a[pivot][col])) pivot = r;
    for (int c = 0; c < 8; ++c)
      std::swap(a[col][c], a[pivot][c]);
    const double inv_pivot = 1.0 / a[col][col];  // inf for a singular matrix, by design
    for (int c = 0; c < 8; ++c)
      a[col][c] *= inv_pivot;
    for (int r = 0; r < 4; ++r) {
      if (r == col) continue;
      const double f = a[r][col];
      for (int c = 0; c < 8; ++c)
        a[r][c] -= f * a[col][c];
    }
  }
  Transform t;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      t.m_[r][c] = a[r][c + 4];
  return t;
}

Vec3d Transform::point(Vec3d p) const {
  const double x = m_[0][0] * p.x + m_[0][1] * p.y + m_[0][2] * p.z + m_[0][3];
  const double y = m_[1][0] * p.x + m_[1][1] * p.y + m_[1][2] * p.z + m_[1][3];
  const double z = m_[2][0] * p.x + m_[2][1] * p.y + m_[2][2] * p.z + m_[2][3];
  const double w = m_[3][0] * p.x + m_[3][1] * p.y + m_[3][2] * p.z + m_[3][3];
  return w == 1.0 ? Vec3d{x, y, z} : Vec3d{x / w, y / w, z / w};
}

Vec3d Transform::vector(Vec3d v) const {
  return {m_[0][0] * v.x + m_[0][1] * v.y + m_[0][2] * v.z,
          m_[1][0] * v.x + m_[1][1] * v.y + m_[1][2] * v.z,
          m_[2][0] * v.x + m_[2][1] * v.y + m_[2][2] * v.z};
}

Transform Transform::normal_transform() const {
  const Transform inv = inverse();
  Transform t;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      t.m_[r][c] = inv.m_[c][r];
  return t;
}

Transform Transform::without_scale_and_translation() const {
  Transform t;
  for (int c = 0; c < 3; ++c) {
    const Vec3d axis = normalize(Vec3d{m_[0][c], m_[1][c], m_[2][c]});
    t.m_[0][c] = axis.x, t.m_[1][c] = axis.y, t.m_[2][c] = axis.z;
  }
  return t;
}

Transform Transform::without_scale() const {
  return translate(translation()) * without_scale_and_translation();
}

double Transform::determinant3x3() const {
  return m_[0][0] * (m_[1][1] * m_[2][2] - m_[1][2] * m_[2][1]) -
         m_[0][1] * (m_[1][0] * m_[2][2] - m_[1][2] * m_[2][0]) +
         m_[0][2] * (m_[1][0] * m_[2][1] - m_[1][1] * m_[2][0]);
}

bool Transform::is_finite() const {
  for (const auto& row : m_)
    for (double v : row)
      if (!std::isfinite(v)) return false;
  return true;
}

}  // namespace fb
