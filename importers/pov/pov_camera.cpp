#include "importers/pov/pov_camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "core/util/error.h"
#include "importers/pov/pov_space.h"

namespace fb::pov {
namespace {

constexpr double kEpsilon = 1e-10;  // POV-Ray's EPSILON (frame.h), as Parse_Camera uses it
// Below this the camera model's approximation of a skewed camera is not worth a warning.
constexpr double kNegligiblePx = 0.01;
// Nor a projection type's vectors off perpendicular by less than this.
constexpr double kNegligibleDeg = 1e-6;
// The converted camera's sensor width: the focal length follows from it and the field of view.
constexpr double kSensorMm = 36;

// "file:line:column", as the SDL evaluator's messages; nothing for POV-Ray's default camera.
std::string place(const CameraStatement& s) {
  return s.where.file.empty() ? "" : s.where.text();
}

[[noreturn]] void fail(const CameraStatement& s, const std::string& what) {
  throw_input(place(s), "", what);
}

// Where the angle is written (the statement, for one built without that place).
std::string angle_place(const CameraStatement& s) {
  return s.angle_where.file.empty() ? place(s) : s.angle_where.text();
}

[[noreturn]] void fail_angle(const CameraStatement& s, const std::string& what) {
  throw_input(angle_place(s), "camera angle", what);
}

void warn(Diagnostics& diagnostics, const CameraStatement& s, const std::string& what) {
  diagnostics.warn(located(place(s), "", what));
}

// An orthonormal frame built from three vectors in the order given (Gram-Schmidt): the first keeps
// its direction, the second its component perpendicular to the first, the third its component
// perpendicular to both. Not finite when they do not span space.
struct Frame {
  Vec3d axis[3];
};

Frame gram_schmidt(Vec3d a, Vec3d b, Vec3d c) {
  Frame f{};
  const Vec3d in[3] = {a, b, c};
  for (int i = 0; i < 3; ++i) {
    Vec3d v = in[i];
    for (int j = 0; j < i; ++j)
      v = v - dot(v, f.axis[j]) * f.axis[j];
    f.axis[i] = v * (1 / length(v));
  }
  return f;
}

}  // namespace

const char* keyword_of(CameraType type) {
  switch (type) {
    case CameraType::kPerspective:
      return "perspective";
    case CameraType::kOrthographic:
      return "orthographic";
    case CameraType::kFisheye:
      return "fisheye";
    case CameraType::kUltraWideAngle:
      return "ultra_wide_angle";
    case CameraType::kOmnimax:
      return "omnimax";
    case CameraType::kPanoramic:
      return "panoramic";
    case CameraType::kCylinder:
      return "cylinder";
    case CameraType::kSpherical:
      return "spherical";
    case CameraType::kMeshCamera:
      return "mesh_camera";
  }
  return "unknown";
}

PovCameraVectors evaluate_camera(const CameraStatement& s, Diagnostics& diagnostics) {
  PovCameraVectors v;
  v.type = s.type;
  v.location = s.location;
  v.direction = s.direction;
  v.right = s.right;
  v.up = s.up;
  // Parse_Camera's Direction_Length starts at 1 and follows angle and look_at; it becomes the
  // focal distance when no focal_point is given (so `direction 3*z` alone focuses at 1).
  double direction_length = 1;

  const bool projective = s.type == CameraType::kPerspective || s.type == CameraType::kOrthographic;
  if (s.type == CameraType::kCylinder && (s.cylinder_type < 1 || s.cylinder_type > 4))
    fail(s, "invalid cylinder camera type " + std::to_string(s.cylinder_type) +
                ": valid are types 1 to 4");
  v.cylinder_type = s.cylinder_type;
  if (s.angle_deg) {
    const double angle = *s.angle_deg;
    const bool spherical = s.type == CameraType::kSpherical;
    if (!(angle >= 0))
      fail_angle(s, spherical ? "negative horizontal angle" : "negative viewing angle");
    if (s.angle_v_deg && !spherical)
      fail_angle(s, "a second angle: only a spherical camera takes one (angle H, V)");
    if (s.angle_v_deg && !(*s.angle_v_deg >= 0)) fail_angle(s, "negative vertical angle");
    if (spherical) {
      v.angle_h_deg = angle;
      v.angle_v_deg = s.angle_v_deg.value_or(angle / 2);
    } else {
      v.angle_deg = angle;
    }
    if (projective) {
      if (angle >= 180) fail_angle(s, "viewing angle has to be smaller than 180 degrees");
      // The horizontal field of view across |right|: |direction| = |right| / (2 tan(angle / 2)).
      if (angle > 0) {
        direction_length = length(v.right) / (2 * std::tan(angle * std::numbers::pi / 360));
        v.direction = normalize(v.direction) * direction_length;
      }
    }
  }

  if (s.look_at) {
    // look_at keeps the lengths of direction, right and up (field of view, aspect) and the
    // handedness of the three, and rebuilds their directions from location, look_at and sky.
    direction_length = length(v.direction);
    const double up_length = length(v.up), right_length = length(v.right);
    const double handedness = dot(cross(v.up, v.direction), v.right);
    const Vec3d towards = *s.look_at - v.location;
    if (dot(towards, towards) < kEpsilon)
      fail(s, "camera location and look_at point must be different");
    const Vec3d d = normalize(towards);
    Vec3d r = cross(s.sky, d);
    if (std::abs(r.x) < kEpsilon && std::abs(r.y) < kEpsilon && std::abs(r.z) < kEpsilon) {
      warn(diagnostics, s,
           "the camera looks along sky: the given right vector is kept, as POV-Ray does");
      r = v.right;
    }
    r = normalize(r);
    v.up = cross(d, r) * up_length;
    v.direction = d * direction_length;
    v.right = r * (handedness > 0 ? right_length : -right_length);
  }

  // An orthographic camera without right and up, or with an angle, sees the area a perspective
  // one would see in the plane through look_at (POV-Ray's internal default <0, 0, 1> without it).
  if (s.type == CameraType::kOrthographic && ((!s.right_given && !s.up_given) || s.angle_deg)) {
    const double k1 = length(s.look_at.value_or(Vec3d{0, 0, 1}) - v.location);
    const double k2 = length(v.direction);
    if (k1 > kEpsilon && k2 > kEpsilon) {
      v.right = v.right * (k1 / k2);
      v.up = v.up * (k1 / k2);
    }
  }

  v.focal_distance = s.focal_point ? length(*s.focal_point - v.location) : direction_length;
  if (v.focal_distance == 0) v.focal_distance = 1;
  v.aperture = s.aperture;
  v.focal_blur = s.aperture != 0 && s.blur_samples > 0;

  // Transforms last, whatever their place in the statement. The focal distance and the aperture
  // stay in world units: POV-Ray scales the focal plane by F / |direction| after the transform.
  v.location = s.transform.point(v.location);
  v.direction = s.transform.vector(v.direction);
  v.right = s.transform.vector(v.right);
  v.up = s.transform.vector(v.up);
  return v;
}

namespace {

[[noreturn]] void fail_degenerate(const CameraStatement& s) {
  fail(s,
       "the camera's direction, right and up vectors do not span space (one is zero or they are "
       "parallel)");
}

// POV-Ray's camera types beyond perspective and orthographic, each rendered by its camera plugin
// (plugins/cameras/pov_*: kind "pov_<type>", the parameters below).
bool is_projection_type(CameraType type) {
  return type != CameraType::kPerspective && type != CameraType::kOrthographic &&
         type != CameraType::kMeshCamera;
}

// The values a projection's plugin takes (its schema), each with the place in the .pov it comes
// from: the angle where it is written, the lengths of the vectors from the whole statement.
std::vector<NamedNumber> projection_numbers(const CameraStatement& s, const PovCameraVectors& v) {
  std::vector<NamedNumber> numbers;
  const auto add = [&](const char* key, double value, ValueOrigin origin) {
    numbers.push_back({key, value, std::move(origin)});
  };
  const auto length_of = [&](const char* key, const char* vector, Vec3d value) {
    add(key, length(value),
        ValueOrigin::from_file(place(s), "camera",
                               std::string("|") + vector + "| after POV-Ray's camera rules"));
  };
  const ValueOrigin angle_origin =
      s.angle_deg ? ValueOrigin::from_file(angle_place(s), "camera angle")
                  : ValueOrigin::from_file(place(s), "camera", "POV-Ray's default angle");
  switch (v.type) {
    case CameraType::kSpherical:
      add("angle_h_deg", v.angle_h_deg, angle_origin);
      add("angle_v_deg", v.angle_v_deg,
          s.angle_v_deg || !s.angle_deg
              ? angle_origin
              : ValueOrigin::from_file(angle_origin.file, angle_origin.path,
                                       "half the horizontal angle, as POV-Ray"));
      return numbers;
    case CameraType::kCylinder:
      add("variant", v.cylinder_type, ValueOrigin::from_file(place(s), "camera type cylinder"));
      [[fallthrough]];
    case CameraType::kFisheye:
    case CameraType::kUltraWideAngle:
      add("angle_deg", v.angle_deg, angle_origin);
      break;
    default:  // omnimax and panoramic have no angle
      break;
  }
  length_of("right_length_m", "right", v.right);
  length_of("up_length_m", "up", v.up);
  if (v.type == CameraType::kPanoramic) length_of("direction_length_m", "direction", v.direction);
  return numbers;
}

// A projection type: the camera posed with POV-Ray's normalised right, up and direction as its x,
// y and -z axes (the frame the plugins build rays in), its values as the plugin's parameters.
PovCamera convert_projection(const CameraStatement& s, const PovCameraVectors& v,
                             Diagnostics& diagnostics) {
  const Vec3d location = world_from_pov(v.location), direction = world_from_pov(v.direction),
              right = world_from_pov(v.right), up = world_from_pov(v.up);
  const double span = std::abs(dot(cross(right, up), direction));
  if (!(is_finite(location) && is_finite(right) && is_finite(up) && is_finite(direction) &&
        span > 1e-12 * length(right) * length(up) * length(direction)))
    fail_degenerate(s);
  // POV-Ray combines the vectors as they are; the camera needs them perpendicular. Direction is
  // kept, up made perpendicular to it, right to both (keeping its side: a mirror stays one).
  const Frame f = gram_schmidt(direction, up, right);
  double off_deg = 0;
  for (const auto& [a, b] : {std::pair{right, up}, {right, direction}, {up, direction}})
    off_deg =
        std::max(off_deg, std::asin(std::min(1.0, std::abs(dot(normalize(a), normalize(b))))) *
                              180 / std::numbers::pi);
  if (off_deg > kNegligibleDeg)
    warn(diagnostics, s,
         std::string("the camera's direction, right and up vectors are not perpendicular (up to ") +
             number_text(off_deg) + " degrees off): POV-Ray's " + keyword_of(s.type) +
             " camera uses them as given, filmback with up and right made perpendicular to "
             "direction");
  if (v.focal_blur)
    warn(diagnostics, s,
         std::string("unsupported feature 'focal_blur' with a ") + keyword_of(s.type) +
             " camera: rendered in focus");

  // The spherical camera turns about right and up by the right-hand rule in POV-Ray's space, so a
  // frame of negative handedness turns both ways round: negating right and up (a half turn about
  // direction) gives the pov_spherical plugin a frame its one formula fits.
  const double handedness = dot(cross(v.up, v.direction), v.right);
  const double turn = v.type == CameraType::kSpherical && handedness < 0 ? -1 : 1;
  const Vec3d x = f.axis[2] * turn, y = f.axis[1] * turn, z = f.axis[0] * -1.0;

  PovCamera out;
  SceneCamera& c = out.camera;
  c.name = "camera";
  c.source = "camera statement at " + place(s);
  c.world_from_camera = Transform::from_rows({x.x, y.x, z.x, location.x,  //
                                              x.y, y.y, z.y, location.y,  //
                                              x.z, y.z, z.z, location.z,  //
                                              0, 0, 0, 1});
  PhysicalCamera& p = c.physical;
  p.projection = FB_PROJECTION_PANORAMIC;
  p.sensor_fit = FB_SENSOR_FIT_HORIZONTAL;
  p.clip_near_m = 0;  // POV-Ray's rays start at the location
  // The plugin maps raster points itself. The view plane, which only estimates on-screen sizes
  // for a panorama (subdivision), is the perspective camera of the same vectors.
  p.sensor_width_mm = kSensorMm;
  p.sensor_height_mm = kSensorMm * length(v.up) / length(v.right);
  p.focal_length_mm = kSensorMm * length(v.direction) / length(v.right);
  c.model = CameraModel{std::string("pov_") + keyword_of(s.type), projection_numbers(s, v),
                        ValueOrigin::from_file(place(s), "camera type")};
  return out;  // pixel aspect 1: the plugin spreads the image over the raster as POV-Ray does
}

}  // namespace

PovCamera convert_camera(const std::optional<CameraStatement>& statement, uint32_t width_px,
                         uint32_t height_px, Diagnostics& diagnostics) {
  CameraStatement s;  // no statement: POV-Ray's defaults
  if (statement) s = *statement;
  const PovCameraVectors v = evaluate_camera(s, diagnostics);
  if (is_projection_type(v.type)) return convert_projection(s, v, diagnostics);
  const bool orthographic = v.type == CameraType::kOrthographic;

  const Vec3d location = world_from_pov(v.location), direction = world_from_pov(v.direction),
              right = world_from_pov(v.right), up = world_from_pov(v.up);
  // A frame (q1, q2, q3) with q3 the depth axis; in it right = (rx, 0, 0) + (0, 0, *),
  // up = (ux, uy, *), direction = (dx, dy, dz). Perspective rays direction + x0 right + y0 up
  // are then the pinhole's rays through ((x0 rx + y0 ux + dx) / dz, (y0 uy + dy) / dz): the
  // view plane |right| / dz wide, with dx and dy a lens shift, exact but for the skew ux of a
  // right not perpendicular to up. Orthographic rays run along direction from
  // location + x0 right + y0 up: with q3 along direction, right and up count only by their
  // components across it.
  const Frame f =
      orthographic ? gram_schmidt(direction, right, up) : gram_schmidt(right, up, direction);
  const Vec3d q1 = orthographic ? f.axis[1] : f.axis[0];
  const Vec3d q2 = orthographic ? f.axis[2] : f.axis[1];
  const Vec3d q3 = orthographic ? f.axis[0] : f.axis[2];
  const double rx = dot(right, q1), ux = dot(up, q1), uy = dot(up, q2);
  const double dx = dot(direction, q1), dy = dot(direction, q2), dz = dot(direction, q3);
  const double span = std::abs(dot(cross(right, up), direction));
  if (!(is_finite(location) && std::isfinite(rx) && std::isfinite(uy) && std::isfinite(dz) &&
        rx > 0 && uy > 0 && dz > 0 &&
        span > 1e-12 * length(right) * length(up) * length(direction)))
    fail_degenerate(s);

  PovCamera out;
  SceneCamera& c = out.camera;
  c.name = "camera";
  c.source = statement ? "camera statement at " + place(s)
                       : "POV-Ray's default camera (the scene has none)";
  // Columns q1, q2, -q3: the camera looks down -Z. A mirrored POV-Ray camera (negative
  // handedness) gives a reflection here, which the renderer applies as it is (render_loop.cpp).
  c.world_from_camera = Transform::from_rows({q1.x, q2.x, -q3.x, location.x,  //
                                              q1.y, q2.y, -q3.y, location.y,  //
                                              q1.z, q2.z, -q3.z, location.z,  //
                                              0, 0, 0, 1});
  PhysicalCamera& p = c.physical;
  p.sensor_fit = FB_SENSOR_FIT_HORIZONTAL;
  p.clip_near_m = 0;  // POV-Ray's rays start at the location (orthographic: its plane)
  // The image spans rx x uy whatever its size: pixels are rx / uy * H / W wide per unit height.
  out.pixel_aspect = rx / uy * double(height_px) / double(width_px);
  // 1 POV-Ray unit is 1 m; a kSensorMm sensor with the focal length that gives this field of view.
  p.sensor_width_mm = kSensorMm;
  p.sensor_height_mm = kSensorMm * uy / rx;
  if (orthographic) {
    p.projection = FB_PROJECTION_ORTHOGRAPHIC;
    p.ortho_scale_m = rx;
  } else {
    p.focal_length_mm = kSensorMm * dz / rx;
    p.shift_x = dx / rx;  // fractions of the fitted (horizontal) view-plane extent
    p.shift_y = dy / rx;
  }

  const double skew_px = 0.5 * std::abs(ux) * double(width_px) / rx;
  if (skew_px > kNegligiblePx)
    warn(diagnostics, s,
         std::string("the camera's right and up vectors are not perpendicular") +
             (orthographic ? " (seen along direction)" : "") +
             ": POV-Ray renders the skew, filmback cannot; objects at the top and bottom edges "
             "are up to " +
             number_text(skew_px) + " px off horizontally");

  if (v.focal_blur) {
    if (orthographic) {
      warn(diagnostics, s, "unsupported feature 'focal_blur' with an orthographic camera");
    } else {
      // POV-Ray's lens samples lie in a disc of radius 0.5 scaled by aperture / 2 (tracepixel.cpp
      // JitterCameraRay): lens radius aperture / 4. Its focal plane is where the rays
      // (F / |direction|) (direction + x0 right + y0 up) end, at depth F dz / |direction|.
      const double lens_radius_m = std::abs(v.aperture) / 4;
      p.fstop = p.focal_length_mm * 1e-3 / (2 * lens_radius_m);
      p.focus_distance_m = v.focal_distance * dz / length(direction);
      if (std::hypot(dx, dy) > 1e-9 * dz)
        warn(diagnostics, s,
             "focal_blur with direction not perpendicular to right and up: the lens lies across "
             "the image plane's normal, POV-Ray's across direction");
    }
  }
  return out;
}

}  // namespace fb::pov
