// The antialiasing target of docs/filters.md: an emissive checkerboard on the ground, receding to
// the horizon, as a glTF scene for filmback and as a closed form for the reference. Cells of
// 1 m with radiance 1 where (i + k) is even alternate with black ones (the sky is black too); a
// pinhole camera 1 m above the ground looks down by the angle that puts the horizon a quarter of
// the way down the frame, so the pattern's frequency grows without bound towards the horizon.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

namespace fb::filters {

struct Checkerboard {
  uint32_t width_px, height_px;
  double focal_px;       // pinhole focal length in pixels (square pixels)
  double pitch_rad;      // the camera looks down by this angle
  double height_m = 1;   // of the camera above the ground
  double far_m = 300;    // the board ends here; beyond it is black
  double margin_px = 0;  // the reference may be asked for this far outside the frame

  // Cells in row k (0 <= k < far_m, at depth [k, k + 1) m) span columns [-half(k), half(k)):
  // wide enough to fill the frame and its margin, and no wider.
  int32_t half_columns(int32_t row) const;
  bool emits(int32_t column, int32_t row) const;
  // The radiance seen through raster position (x, y) px.
  double radiance(double x_px, double y_px) const;
  // The scene as glTF (camera and board), written to `file`.
  void write_gltf(const std::filesystem::path& file) const;
  double yfov_rad() const;
};

// The default shot of docs/filters.md at `width` x `height`: the focal length is the height.
Checkerboard make_checkerboard(uint32_t width_px, uint32_t height_px, double margin_px);

}  // namespace fb::filters
