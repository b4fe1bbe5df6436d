// Camera `fisheye_polynomial`: Cycles' fisheye lens polynomial (Blender 3.3+), a calibrated lens:
// theta(r) = -(k0 + k1 r + k2 r^2 + k3 r^3 + k4 r^4), r in mm on the imaged sensor, cut at
// |theta| > fov / 2 and, unlike Cycles, past the first radius where the mapping folds over (there
// two radii would image one direction): both black. filmback/panorama.h has the mapping.
#include <filmback/panorama.h>
#include <filmback/plugin_sdk.h>

#include <cmath>

namespace {

namespace pano = fb::panorama;

// Blender's fisheye_polynomial_k0..k4 (their defaults fit a real lens) and fisheye_fov.
constexpr fb_param_desc kOwnParams[] = {
    {"fisheye_fov_rad", FB_PARAM_FLOAT, "3.141592653589793", "rad", nullptr, 1e-3,
     2 * pano::kPi + 1e-6, "full angle imaged, at most 2 pi; beyond it, black"},
    {"k0", FB_PARAM_FLOAT, "-1.1735143712967577e-05", "rad", nullptr, -1e3, 1e3,
     "theta's constant term"},
    {"k1", FB_PARAM_FLOAT, "-0.019988736882805824", "rad/mm", nullptr, -1e3, 1e3,
     "theta's linear term"},
    {"k2", FB_PARAM_FLOAT, "-3.3525322965933866e-06", "rad/mm^2", nullptr, -1e3, 1e3,
     "theta's quadratic term"},
    {"k3", FB_PARAM_FLOAT, "3.099275275886036e-06", "rad/mm^3", nullptr, -1e3, 1e3,
     "theta's cubic term"},
    {"k4", FB_PARAM_FLOAT, "-2.6064646454854524e-08", "rad/mm^4", nullptr, -1e3, 1e3,
     "theta's quartic term"},
};
constexpr auto kSchema = pano::with_lens(kOwnParams);
constexpr auto kFov = fb::param<double>(kSchema.params, "fisheye_fov_rad");
constexpr fb::Param<double> kCoefficients[] = {
    fb::param<double>(kSchema.params, "k0"), fb::param<double>(kSchema.params, "k1"),
    fb::param<double>(kSchema.params, "k2"), fb::param<double>(kSchema.params, "k3"),
    fb::param<double>(kSchema.params, "k4")};

struct LensPolynomial {
  pano::Polynomial polynomial;
  double fov_rad;
  fb::Vec2d sensor_mm;
  double fold_mm;
  LensPolynomial(const fb_value* values, const fb_camera_setup& s)
      : polynomial{{kCoefficients[0](values), kCoefficients[1](values), kCoefficients[2](values),
                    kCoefficients[3](values), kCoefficients[4](values)}},
        fov_rad(kFov(values)),
        sensor_mm(pano::imaged_sensor_mm(s)),
        fold_mm(0) {
    if (const char* problem = pano::imaged_sensor_problem(s)) throw std::invalid_argument(problem);
    const auto& k = polynomial.k;
    if (k[1] == 0 && k[2] == 0 && k[3] == 0 && k[4] == 0)
      throw std::invalid_argument("k1..k4 are all 0: theta does not vary across the image");
    fold_mm = polynomial.fold_radius_mm(std::hypot(sensor_mm.x, sensor_mm.y) / 2);
  }
  fb::Vec3d direction(pano::Film f) const {
    return pano::polynomial_direction(f, polynomial, fov_rad, fold_mm, sensor_mm);
  }
  // The angles across the frame (cut by the fold and the field of view), the paraxial focal
  // length 1 / |k1| (dr/dtheta at the axis) and its 35 mm equivalent, and where it folds over.
  std::string describe() const {
    const double corner_mm = std::hypot(sensor_mm.x, sensor_mm.y) / 2;
    const auto theta_deg = [&](double r_mm) {
      return pano::degrees(
          std::min(std::abs(polynomial.theta(std::min(r_mm, fold_mm))), fov_rad / 2));
    };
    std::string lines = pano::fisheye_fov_text({sensor_mm.x / 2, sensor_mm.y / 2}, theta_deg);
    if (const double k1 = polynomial.k[1]; k1 != 0)
      lines += pano::text(
          "paraxial focal length: %.6g mm (1 / |k1|); 35 mm equivalent %.6g mm (diagonal-based)\n",
          1 / std::abs(k1), pano::equivalent_35mm_mm(1 / std::abs(k1), sensor_mm));
    if (fold_mm < corner_mm)
      lines += pano::text("the mapping folds over at r = %.6g mm: black beyond\n", fold_mm);
    return lines;
  }
};

constexpr fb_camera_api kApi = fb::camera_api<pano::Camera<LensPolynomial>>();
constexpr fb_plugin kPlugin = fb::describe(
    "fisheye_polynomial", "1.1.0",
    "Cycles' fisheye lens polynomial: theta(r) from Blender's k0..k4, cut at its field of view",
    kSchema.params, kApi);

}  // namespace

FB_PLUGIN_ENTRY(kPlugin)
