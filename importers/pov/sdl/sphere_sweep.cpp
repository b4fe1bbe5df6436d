// sphere_sweep { linear_spline | b_spline | cubic_spline N, <c1>, r1, ..., <cN>, rN
// [tolerance T] } (POV-Ray 3.7 reference, "Sphere Sweep"; Parse_Sphere_Sweep): the spheres'
// segments (core/math/sphere_sweep.h), built here once.
#include <cmath>

#include "core/math/sphere_sweep.h"
#include "importers/pov/sdl/parser.h"

namespace fb::pov::sdl {

namespace {

struct SweepKeyword {
  std::string_view name;
  SweepSpline spline;
};

constexpr SweepKeyword kSweepSplines[] = {{"linear_spline", SweepSpline::kLinear},
                                          {"b_spline", SweepSpline::kBSpline},
                                          {"cubic_spline", SweepSpline::kCatmullRom}};

}  // namespace

void Parser::parse_sphere_sweep(Object& o) {
  o.shape = Shape::kSphereSweep;
  const Tok kind = next();
  const SweepKeyword* spline = nullptr;
  for (const SweepKeyword& k : kSweepSplines)
    if (kind.word(k.name)) spline = &k;
  if (!spline)
    fail_at(location_of(kind), "sphere_sweep needs linear_spline, b_spline or cubic_spline, got '" +
                                   kind.token.text + "'");
  const SourceLocation count_at = location_of(peek());
  const double n = parse_count();
  const size_t least = sweep_least_spheres(spline->spline);
  if (!(n >= double(least) && n <= double(options().limits.objects)))
    fail_at(count_at, std::string(spline->name) + " sphere_sweep needs at least " +
                          std::to_string(least) + " spheres, got " + number_string(n));
  count_objects(uint64_t(n));
  std::vector<Vec3d> centres;
  std::vector<double> radii;
  for (size_t i = 0; i < size_t(n); ++i) {
    accept(",");
    const SourceLocation centre_at = location_of(peek());
    const Vec3d c = parse_vector();
    if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z))
      fail_at(centre_at, "sphere_sweep centre is not finite");
    accept(",");
    const SourceLocation radius_at = location_of(peek());
    const double r = parse_count();  // no comparison: a '<' opens the next centre
    if (!(r >= 0 && std::isfinite(r)))
      fail_at(radius_at,
              "sphere_sweep radius " + number_string(r) + ": it must be finite and not negative");
    centres.push_back(c);
    radii.push_back(r);
  }
  // POV-Ray's depth tolerance keeps its own rays from meeting the surface they leave; the
  // crossings here are exact, so it is read and has nothing to do.
  if (peek().word("tolerance")) {
    next();
    parse_float();
  }
  o.sweep =
      std::make_shared<SphereSweep>(sphere_sweep_from_spheres(spline->spline, centres, radii));
}

}  // namespace fb::pov::sdl
