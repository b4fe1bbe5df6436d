// julia_fractal { <c> [quaternion | hypercomplex] [sqr | cube | exp | ... | pwr(X, Y)]
// [max_iteration N] [precision P] [slice <S>, D] } (POV-Ray 3.7 reference, "Julia Fractal";
// Parse_Julia_Fractal): the set's parameters, checked here; the intersector marches it
// (core/math/julia_fractal.h). docs/pov.md, "Julia fractal".
#include <cmath>
#include <memory>

#include "core/math/julia_fractal.h"
#include "importers/pov/sdl/parser.h"

namespace fb::pov::sdl {

namespace {

// The hypercomplex functions POV-Ray applies to each duplex half: read, not rendered.
constexpr std::string_view kJuliaComplexFunctions[] = {
    "exp",  "ln",    "sin",  "asin",  "cos",  "acos",  "tan",       "atan",
    "sinh", "asinh", "cosh", "acosh", "tanh", "atanh", "reciprocal"};

bool is_complex_function(const Tok& tok) {
  for (std::string_view name : kJuliaComplexFunctions)
    if (tok.word(name)) return true;
  return false;
}

bool finite4(const Value& v) {
  return std::isfinite(v.v[0]) && std::isfinite(v.v[1]) && std::isfinite(v.v[2]) &&
         std::isfinite(v.v[3]);
}

}  // namespace

std::string Parser::parse_julia_fractal(Object& o) {
  o.shape = Shape::kJuliaFractal;
  JuliaFractal julia;
  const SourceLocation c_at = location_of(peek());
  const Value c = parse_numeric(4);
  if (!finite4(c)) fail_at(c_at, "julia_fractal parameter is not finite");
  for (int i = 0; i < 4; ++i)
    julia.c[i] = c.v[i];
  std::string function = "sqr";
  SourceLocation function_at = o.where;
  for (;;) {
    Tok tok = next();  // directives run
    if (tok.word("quaternion")) {
      julia.algebra = JuliaAlgebra::kQuaternion;
    } else if (tok.word("hypercomplex")) {
      julia.algebra = JuliaAlgebra::kHypercomplex;
    } else if (tok.word("sqr") || tok.word("cube")) {
      function = tok.token.text, function_at = location_of(tok);
    } else if (tok.word("pwr")) {
      function = "pwr", function_at = location_of(tok);
      expect("(");
      parse_float();
      accept(",");
      parse_float();
      expect(")");
    } else if (is_complex_function(tok)) {
      function = tok.token.text, function_at = location_of(tok);
    } else if (tok.word("max_iteration")) {
      const SourceLocation where = location_of(peek());
      const double n = parse_float();
      if (!(n >= 1 && n <= kJuliaMaxIterations))
        fail_at(where, "julia_fractal max_iteration " + number_string(n) + ": it must be 1 to " +
                           std::to_string(kJuliaMaxIterations));
      julia.max_iteration = int(n);
    } else if (tok.word("precision")) {
      const SourceLocation where = location_of(peek());
      const double p = parse_float();
      if (!(p > 0 && std::isfinite(p)))
        fail_at(where,
                "julia_fractal precision " + number_string(p) + ": it must be positive and finite");
      julia.least_step = 1 / p;
    } else if (tok.word("slice")) {
      const SourceLocation where = location_of(peek());
      const Value s = parse_numeric(4);
      accept(",");
      const double distance = parse_float();
      // Parse_Julia_Fractal: the normal is made unit; its t part must not vanish, since the
      // slice gives w = (distance - s.xyz . p) / s.w.
      const double len =
          std::sqrt(s.v[0] * s.v[0] + s.v[1] * s.v[1] + s.v[2] * s.v[2] + s.v[3] * s.v[3]);
      if (!finite4(s) || !std::isfinite(distance) || !(len > 0) ||
          !(std::abs(s.v[3]) / len > 1e-10))
        fail_at(where,
                "julia_fractal slice: its normal must be finite with a non-zero 4th "
                "component, and its distance finite");
      for (int i = 0; i < 4; ++i)
        julia.slice[i] = s.v[i] / len;
      julia.slice_distance = distance / len;
    } else {
      unget(std::move(tok));
      break;
    }
  }
  const bool quaternion = julia.algebra == JuliaAlgebra::kQuaternion;
  if (quaternion && function != "sqr" && function != "cube")
    fail_at(function_at,
            "julia_fractal: quaternion supports only sqr and cube, got '" + function + "'");
  if (!quaternion && function != "sqr")
    return "julia_fractal hypercomplex " + function;  // reported, left out
  julia.power = function == "cube" ? 3 : 2;
  julia_fractal_set_bounds(julia);
  // The march would take more than its cap of samples across the bounding sphere: the steps are
  // made long enough to cross it, and the user told what changed.
  const double finest = 2 * julia.radius / kJuliaMaxSamples;
  if (julia.least_step < finest) {
    warn_at(o.where, "julia_fractal precision " + number_string(1 / julia.least_step) +
                         " takes more than " + std::to_string(kJuliaMaxSamples) +
                         " steps across the set: rendered with precision " +
                         number_string(1 / finest));
    julia.least_step = finest;
  }
  o.julia = std::make_shared<const JuliaFractal>(julia);
  return {};
}

}  // namespace fb::pov::sdl
