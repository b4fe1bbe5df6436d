// prism { [linear_sweep | conic_sweep] [linear_spline | quadratic_spline | cubic_spline |
// bezier_spline] Height1, Height2, Count, <Point 1>, ... } (POV-Ray 3.7 reference, "Prism"): its
// points become an outline (importers/pov/sdl/prism_outline.h) swept in y between the heights.
#include "importers/pov/sdl/parser.h"
#include "importers/pov/sdl/prism_outline.h"

#include "core/util/error.h"

namespace fb::pov::sdl {

namespace {

struct PrismKeyword {
  std::string_view name;
  PrismSpline spline;
};

constexpr PrismKeyword kPrismSplines[] = {{"linear_spline", PrismSpline::kLinear},
                                          {"quadratic_spline", PrismSpline::kQuadratic},
                                          {"cubic_spline", PrismSpline::kCubic},
                                          {"bezier_spline", PrismSpline::kBezier}};

}  // namespace

void Parser::parse_prism(Object& o) {
  o.shape = Shape::kPrism;
  PrismSpline spline = PrismSpline::kLinear;
  for (bool more = true; more;) {
    const Tok& t = peek();
    more = false;
    if (t.word("linear_sweep") || t.word("conic_sweep")) {
      o.conic = t.word("conic_sweep");
      next();
      more = true;
    }
    for (const PrismKeyword& k : kPrismSplines)
      if (peek().word(k.name)) {
        spline = k.spline;
        next();
        more = true;
      }
  }
  o.r0 = parse_float();
  accept(",");
  o.r1 = parse_float();
  accept(",");
  const double n = parse_count();
  const SourceLocation count_at = here();
  if (!(n >= 0 && n <= double(kMaxPrismPoints)))
    fail_at(count_at, "prism point count " + number_text(n) + " is not 0 to " +
                          std::to_string(kMaxPrismPoints));
  count_objects(static_cast<uint64_t>(n));
  std::vector<Vec2d> points;
  for (size_t i = 0; i < static_cast<size_t>(n); ++i) {
    accept(",");
    const Value v = parse_numeric(2);
    points.push_back({v.v[0], v.v[1]});
  }
  std::vector<std::string> warnings;
  std::optional<Outline> outline;
  try {
    outline = prism_outline(spline, points, warnings);
  } catch (const std::invalid_argument& e) {
    fail_at(o.where, e.what());
  }
  for (const std::string& w : warnings)
    warn_at(o.where, w);
  if (outline) o.outline = std::make_shared<const Outline>(std::move(*outline));
}

}  // namespace fb::pov::sdl
