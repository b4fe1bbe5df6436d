#include "checkerboard.h"

#include <cmath>

#include "support/gltf_builder.h"

namespace fb::filters {

Checkerboard make_checkerboard(uint32_t width_px, uint32_t height_px, double margin_px) {
  Checkerboard board{width_px, height_px, double(height_px), 0.0};
  board.pitch_rad = std::atan(0.25 * height_px / board.focal_px);  // horizon at a quarter height
  board.margin_px = margin_px;
  return board;
}

double Checkerboard::yfov_rad() const {
  return 2 * std::atan(0.5 * height_px / focal_px);
}

int32_t Checkerboard::half_columns(int32_t row) const {
  // A ray at raster x has |x_world| <= depth * (|x - W/2| / f) / cos(pitch + vertical angle):
  // bounded generously by twice the lateral slope at the frame's (and margin's) edge.
  const double slope = 2 * (0.5 * width_px + margin_px) / focal_px;
  return int32_t(std::ceil((row + 1) * slope)) + 2;
}

bool Checkerboard::emits(int32_t column, int32_t row) const {
  if (row < 0 || row >= int32_t(far_m)) return false;
  const int32_t half = half_columns(row);
  return column >= -half && column < half && (column + row) % 2 == 0;
}

double Checkerboard::radiance(double x_px, double y_px) const {
  // Camera space (glTF): x right, y up, looking down -z; then the pitch about x.
  const double xc = (x_px - 0.5 * width_px) / focal_px, yc = -(y_px - 0.5 * height_px) / focal_px;
  const double c = std::cos(pitch_rad), s = std::sin(pitch_rad);
  const double dy = c * yc - s, dz = -s * yc - c;  // R_x(-pitch) (xc, yc, -1)
  if (dy >= 0) return 0.0;                         // the sky
  const double t = height_m / -dy;
  const double x = t * xc, depth = -t * dz;
  return emits(int32_t(std::floor(x)), int32_t(std::floor(depth))) ? 1.0 : 0.0;
}

void Checkerboard::write_gltf(const std::filesystem::path& file) const {
  test::GltfBuilder gltf;
  std::vector<Vec3f> positions;
  std::vector<uint32_t> indices;
  for (int32_t row = 0; row < int32_t(far_m); ++row)
    for (int32_t column = -half_columns(row); column < half_columns(row); ++column) {
      if (!emits(column, row)) continue;
      const auto base = uint32_t(positions.size());
      const float x0 = float(column), x1 = float(column + 1);
      const float z0 = -float(row), z1 = -float(row + 1);  // depth is -z
      positions.insert(positions.end(), {{x0, 0, z0}, {x1, 0, z0}, {x1, 0, z1}, {x0, 0, z1}});
      indices.insert(indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
  test::GltfBuilder::Node board;
  board.mesh = gltf.mesh(positions, indices, gltf.material({0, 0, 0}, {1, 1, 1}));
  gltf.node(board);
  test::GltfBuilder::Node camera;
  camera.camera = gltf.perspective_camera(yfov_rad(), double(width_px) / height_px, 0.01, 1e4);
  camera.translation = {0, height_m, 0};
  camera.rotation = {-std::sin(pitch_rad / 2), 0, 0, std::cos(pitch_rad / 2)};
  gltf.node(camera);
  gltf.write(file);
}

}  // namespace fb::filters
