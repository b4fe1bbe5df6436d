#include "core/render/zoom_in_shutter.h"

#include <cmath>

#include <filmback/camera_projection.h>

namespace fb {

void ZoomInShutter::apply(double s, float& x_px, float& y_px) const {
  const double k = s < 0.5 ? std::lerp(k_open, 1.0, 2 * s) : std::lerp(1.0, k_close, 2 * s - 1);
  x_px = float(cx_px + (x_px - cx_px) * k);
  y_px = float(cy_px + (y_px - cy_px) * k);
}

std::optional<ZoomInShutter> zoom_in_shutter(const fb_camera_setup& open,
                                             const fb_camera_setup& centre,
                                             const fb_camera_setup& close) {
  const ViewPlane c = view_plane(centre);
  const double k_open = c.fx / view_plane(open).fx, k_close = c.fx / view_plane(close).fx;
  if (k_open == 1 && k_close == 1) return std::nullopt;
  return ZoomInShutter{k_open, k_close, c.cx, c.cy};
}

}  // namespace fb
