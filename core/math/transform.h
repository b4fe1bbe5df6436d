// Affine transforms in double precision. Camera and scene placement live here so that a shot far
// from the origin keeps sub-millimetre precision; only render-space data (camera at the origin)
// is narrowed to float. Names read right to left: render_from_world * world_from_object.
#pragma once

#include <array>

#include <filmback/vec.h>

namespace fb {

struct Quatd {
  double x = 0, y = 0, z = 0, w = 1;  // glTF order: (x, y, z, w)
};

class Transform {
 public:
  Transform();  // identity
  static Transform from_rows(const std::array<double, 16>& row_major);
  static Transform from_columns(const std::array<double, 16>& column_major);  // glTF "matrix"
  static Transform translate(Vec3d t);
  static Transform scale(Vec3d s);
  static Transform rotate(Quatd q);                             // q normalised here
  static Transform look_at(Vec3d eye, Vec3d target, Vec3d up);  // world_from_camera, looks down -Z

  Transform operator*(const Transform& rhs) const;
  Transform inverse() const;  // general 4x4 inverse; singular matrices give non-finite entries
  // The inverse transpose of the linear part: apply it to normals with vector().
  Transform normal_transform() const;

  Vec3d point(Vec3d p) const;
  Vec3d vector(Vec3d v) const;
  Vec3d translation() const { return {m_[0][3], m_[1][3], m_[2][3]}; }
  // The rotation part with per-axis scale removed (Blender ignores camera scale when projecting).
  Transform without_scale_and_translation() const;
  Transform without_scale() const;  // rotation and translation: how cameras and lights are placed
  double determinant3x3() const;
  bool is_finite() const;

  double operator()(int row, int col) const { return m_[row][col]; }

 private:
  double m_[4][4];
};

}  // namespace fb
