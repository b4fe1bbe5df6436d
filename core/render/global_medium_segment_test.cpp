#include "core/render/global_medium_segment.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fb {
namespace {

constexpr float kMediumClosedFormTolerance = 1e-6f;

GlobalMedium constant_fog(Rgb colour, double distance_m) {
  GlobalMedium m;
  m.colour = colour;
  m.distance_m = distance_m;
  return m;
}

void expect_rgb_near(Rgb a, Rgb b, float tolerance, const char* what) {
  EXPECT_NEAR(a.x, b.x, tolerance) << what;
  EXPECT_NEAR(a.y, b.y, tolerance) << what;
  EXPECT_NEAR(a.z, b.z, tolerance) << what;
}

// POV-Ray's constant fog is the blend lerp(surface, fog colour, 1 - exp(-d / distance)), which
// is also the exact solution of a medium that absorbs with sigma = 1 / distance and emits
// sigma * colour: two segments compose into one, as a medium's must.
TEST(GlobalMedium, ConstantFogIsPovRaysBlendAndComposesAlongTheRay) {
  const Rgb fog{0.3f, 0.5f, 0.7f}, surface{0.9f, 0.2f, 0.4f};
  const std::vector<GlobalMedium> media{constant_fog(fog, 4)};
  for (double d : {0.5, 3.0, 10.0}) {
    const MediumSegment s =
        medium_segment(media, MediumModel::kPovRayBlend, {1, 2, 3}, {0, 0, -1}, d);
    const float k = float(1 - std::exp(-d / 4));
    expect_rgb_near(surface * s.transmittance + s.emitted, surface * (1 - k) + fog * k,
                    kMediumClosedFormTolerance, "blend");
    const MediumSegment near =
        medium_segment(media, MediumModel::kPovRayBlend, {1, 2, 3}, {0, 0, -1}, 0.4 * d);
    const MediumSegment far =
        medium_segment(media, MediumModel::kPovRayBlend, {1, 2, 3 - 0.4 * d}, {0, 0, -1}, 0.6 * d);
    expect_rgb_near(near.transmittance * far.transmittance, s.transmittance,
                    kMediumClosedFormTolerance, "transmittance composes");
    expect_rgb_near(near.emitted + near.transmittance * far.emitted, s.emitted,
                    kMediumClosedFormTolerance, "emission composes");
  }
  // A ray that escapes sees the fog alone.
  const MediumSegment escaping =
      medium_segment(media, MediumModel::kPovRayBlend, {0, 0, 0}, {0, 1, 0}, HUGE_VAL);
  expect_rgb_near(escaping.transmittance, {}, 0.f, "escaping");
  expect_rgb_near(escaping.emitted, fog, 0.f, "escaping");
  // No medium: nothing changes, exactly.
  const MediumSegment none = medium_segment({}, MediumModel::kPovRayBlend, {0, 0, 0}, {0, 1, 0}, 5);
  expect_rgb_near(none.transmittance, {1.f, 1.f, 1.f}, 0.f, "none");
  expect_rgb_near(none.emitted, {}, 0.f, "none");
}

// filter tints the light from behind by the fog's colour; transmit is the least of it that
// comes through (POV-Ray's do_fog).
TEST(GlobalMedium, FogFilterTintsAndTransmitBoundsWhatComesThrough) {
  GlobalMedium m = constant_fog({0.2f, 0.6f, 1.0f}, 2);
  m.filter = 0.5f;
  m.transmit = 0.3f;
  const MediumSegment near =
      medium_segment({m}, MediumModel::kPovRayBlend, {0, 0, 0}, {1, 0, 0}, 0.5);
  const float k = float(std::exp(-0.25));  // above transmit
  expect_rgb_near(near.transmittance, Rgb{0.6f, 0.8f, 1.0f} * k, kMediumClosedFormTolerance,
                  "tinted");
  expect_rgb_near(near.emitted, m.colour * (1 - k), kMediumClosedFormTolerance, "near");
  const MediumSegment far =
      medium_segment({m}, MediumModel::kPovRayBlend, {0, 0, 0}, {1, 0, 0}, 20);
  expect_rgb_near(far.transmittance, Rgb{0.6f, 0.8f, 1.0f} * 0.3f, kMediumClosedFormTolerance,
                  "at least transmit");
  expect_rgb_near(far.emitted, m.colour * 0.7f, kMediumClosedFormTolerance, "far");
}

// Ground fog's closed-form optical depth against the density 1 (h <= 0), 1 / (1 + h^2) (h > 0)
// integrated numerically along segments that cross the offset, stay above or below it, and
// run level; rays escaping downwards are hidden, upwards they see a finite depth.
TEST(GlobalMedium, GroundFogDepthIsTheIntegralOfItsDensity) {
  GlobalMedium m;
  m.profile = MediumProfile::kGround;
  m.distance_m = 3;
  m.offset_m = 0.5;
  m.altitude_m = 0.8;
  m.up = {0, 1, 0};
  const auto numeric = [&](Vec3d o, Vec3d d, double length) {
    constexpr int kSteps = 200000;
    double sum = 0;
    for (int i = 0; i < kSteps; ++i) {
      const double h = (o.y + d.y * (i + 0.5) * length / kSteps - m.offset_m) / m.altitude_m;
      sum += (h <= 0 ? 1 : 1 / (1 + h * h)) * length / kSteps;
    }
    return sum / m.distance_m;
  };
  struct Segment {
    Vec3d origin, direction;
    double length;
  };
  const double s = std::sqrt(0.5);
  const Segment segments[] = {{{0, -1, 0}, {s, s, 0}, 6},
                              {{0, 3, 0}, {0, -1, 0}, 5},
                              {{0, 1, 0}, {s, s, 0}, 4},
                              {{2, 0, 1}, {0, -s, s}, 3},
                              {{0, 2, 0}, {1, 0, 0}, 7}};
  for (const Segment& g : segments)
    EXPECT_NEAR(optical_depth(m, g.origin, g.direction, g.length),
                numeric(g.origin, g.direction, g.length), 1e-7)
        << g.origin.y << " " << g.direction.y;
  EXPECT_TRUE(std::isinf(optical_depth(m, {0, 2, 0}, {0, -1, 0}, HUGE_VAL)));
  const double up = optical_depth(m, {0, 2, 0}, {0, 1, 0}, HUGE_VAL);
  const double h0 = (2 - 0.5) / 0.8;
  EXPECT_NEAR(up, 0.8 * (std::atan(1e300) - std::atan(h0)) / 3, 1e-12);
}

// The physical medium (docs/pov.md "Fog"): one fog is POV-Ray's blend without filter and
// transmit; two constant fogs are one medium of the summed extinction emitting their
// extinction-weighted mean colour, whose segments compose as any medium's do.
TEST(GlobalMedium, PhysicalMediumSumsExtinctionAndComposes) {
  GlobalMedium one = constant_fog({0.2f, 0.6f, 1.0f}, 2);
  one.filter = 0.5f, one.transmit = 0.3f;  // POV-Ray's only: the physical medium has neither
  const MediumSegment s = medium_segment({one}, MediumModel::kPhysical, {0, 0, 0}, {1, 0, 0}, 20);
  const float k = float(std::exp(-10.0));
  expect_rgb_near(s.transmittance, {k, k, k}, kMediumClosedFormTolerance, "one fog");
  expect_rgb_near(s.emitted, one.colour * (1 - k), kMediumClosedFormTolerance, "one fog");

  const std::vector<GlobalMedium> two{constant_fog({1.f, 0.f, 0.f}, 2),
                                      constant_fog({0.f, 0.f, 1.f}, 6)};
  const double sigma = 1.0 / 2 + 1.0 / 6;
  const Rgb mean =
      Rgb{1.f, 0.f, 0.f} * float(0.5 / sigma) + Rgb{0.f, 0.f, 1.f} * float(1 / 6.0 / sigma);
  for (double d : {0.3, 2.0, 9.0}) {
    const MediumSegment both = medium_segment(two, MediumModel::kPhysical, {0, 1, 0}, {0, 0, 1}, d);
    const float through = float(std::exp(-sigma * d));
    expect_rgb_near(both.transmittance, {through, through, through}, kMediumClosedFormTolerance,
                    "summed extinction");
    expect_rgb_near(both.emitted, mean * (1 - through), kMediumClosedFormTolerance, "mean colour");
    const MediumSegment near =
        medium_segment(two, MediumModel::kPhysical, {0, 1, 0}, {0, 0, 1}, 0.3 * d);
    const MediumSegment far =
        medium_segment(two, MediumModel::kPhysical, {0, 1, 0.3 * d}, {0, 0, 1}, 0.7 * d);
    expect_rgb_near(near.emitted + near.transmittance * far.emitted, both.emitted,
                    kMediumClosedFormTolerance, "emission composes");
  }
  const MediumSegment escaping =
      medium_segment(two, MediumModel::kPhysical, {0, 0, 0}, {0, 1, 0}, HUGE_VAL);
  expect_rgb_near(escaping.transmittance, {}, 0.f, "escaping");
  expect_rgb_near(escaping.emitted, mean, kMediumClosedFormTolerance, "escaping");
}

}  // namespace
}  // namespace fb
