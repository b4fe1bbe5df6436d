// A zoom while the shutter is open, as Cycles 3.4 renders it (docs/camera-model.md, "Animated
// lenses"). Cycles syncs the field of view at shutter open, centre and close (blender/camera.cpp,
// sync_camera_motion: only the field of view, from the focal length and sensor; focus, f-stop and
// shift stay the frame's) and interpolates the camera-space point of the raster position on the
// view plane linearly, from open to centre and from centre to close (kernel/camera/camera.h,
// camera_sample_perspective with have_perspective_motion; scene/camera.cpp, perspective_pre/post).
// The host does the same before any projective camera plugin maps the raster position with the
// centre's projection: it scales the position about the principal point c, where the view axis
// meets the image,
//   x' = c + (x - c) k(s),  k(s) = lerp(k_open, 1, 2s) for s < 1/2, else lerp(1, k_close, 2s - 1),
// with s the ray's fraction of the open shutter and k_open = fx_centre / fx_open the ratio of the
// view plane's extents, tan(fov_open / 2) / tan(fov_centre / 2).
#pragma once

#include <optional>

#include <filmback/plugin_abi.h>

namespace fb {

struct ZoomInShutter {
  double k_open = 1, k_close = 1;
  double cx_px = 0, cy_px = 0;  // the principal point, raster pixels (y down)

  // The raster position the centre's projection maps to where the camera at shutter fraction s
  // looks through (x, y).
  void apply(double s, float& x_px, float& y_px) const;
};

// The zoom between perspective setups at shutter open, centre and close, or nothing when their
// fields of view are the same (Cycles' use_perspective_motion).
std::optional<ZoomInShutter> zoom_in_shutter(const fb_camera_setup& open,
                                             const fb_camera_setup& centre,
                                             const fb_camera_setup& close);

}  // namespace fb
