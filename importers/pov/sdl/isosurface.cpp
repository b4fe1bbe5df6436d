// isosurface { function { F } [contained_by { box { A, B } | sphere { C, R } }] [threshold T]
// [accuracy A] [max_gradient G] [evaluate P0, P1, P2] [open] [max_trace N | all_intersections] }
// (POV-Ray 3.7 reference, "Isosurface"): the function and its bounds, checked here; the
// intersector walks it (core/scene/isosurface.h). docs/pov.md, "Isosurface".
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "core/function/isosurface_function.h"
#include "importers/pov/sdl/parser.h"

namespace fb::pov::sdl {

namespace {

// The grid the function is probed on at load, per axis: 17^3 samples, a few milliseconds for any
// function the bounded program can be.
constexpr int kIsosurfaceProbeCells = 16;

// A float that must be positive and finite, read after its keyword.
double positive_float(Parser& p, const char* name) {
  const SourceLocation where = p.location_of(p.peek());
  const double v = p.parse_float();
  if (!(v > 0 && std::isfinite(v)))
    p.fail_at(where, std::string("isosurface ") + name + " " + number_string(v) +
                         ": it must be positive and finite");
  return v;
}

// The grid probe's findings, as POV-Ray reports them once it has rendered: a gradient above
// max_gradient ("The isosurface may contain holes!"), and a function with no number anywhere.
// With `evaluate`, POV-Ray adapts its estimate as it renders; here the estimate is fixed from
// the probe: P0 at least, P1 times the steepest gradient found.
void probe_function(Parser& p, const SourceLocation& where, Isosurface& iso,
                    const double* evaluate) {
  const IsosurfaceProbe probe = isosurface_probe(iso, kIsosurfaceProbeCells);
  if (probe.finite_samples == 0) {
    p.warn_at(where,
              "isosurface function is not a number anywhere it was sampled in its "
              "container: it will show no surface");
    return;
  }
  if (evaluate) {
    iso.max_gradient = std::max(evaluate[0], evaluate[1] * probe.steepest_gradient);
    return;
  }
  if (probe.steepest_gradient > iso.max_gradient) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "isosurface: the maximum gradient found was %.3f, but max_gradient is %.3f: the "
                  "isosurface may contain holes; adjust max_gradient",
                  probe.steepest_gradient, iso.max_gradient);
    p.warn_at(where, text);
  }
}

}  // namespace

void Parser::parse_contained_by(Isosurface& container) {
  expect("{");
  const Tok shape = next();
  const SourceLocation where = location_of(shape);
  if (!shape.word("box") && !shape.word("sphere"))
    fail_at(where, "contained_by expects a box or a sphere, found '" + shape.token.text + "'");
  expect("{");
  container.sphere_container = shape.word("sphere");
  if (container.sphere_container) {
    container.centre = parse_vector();
    accept(",");
    container.radius = parse_float();
    const double c = std::max(
        {std::abs(container.centre.x), std::abs(container.centre.y), std::abs(container.centre.z)});
    if (!(container.radius > 0 && std::isfinite(container.radius) && std::isfinite(c)))
      fail_at(where, "contained_by sphere: its radius must be positive and it must be finite");
  } else {
    container.box_lo = parse_vector();
    accept(",");
    container.box_hi = parse_vector();
    const Bounds3d box = isosurface_bounds(container);
    const Vec3d size = box.hi - box.lo;
    if (!(box.finite() && size.x > 0 && size.y > 0 && size.z > 0 &&
          std::isfinite(size.x + size.y + size.z)))
      fail_at(where, "contained_by box: its corners must be finite and span a volume");
  }
  expect("}");
  expect("}");
}

void Parser::parse_isosurface(Object& o) {
  o.shape = Shape::kIsosurface;
  Isosurface iso;
  const Tok first = next();  // directives run: an #if may choose the function
  const SourceLocation function_where = location_of(first);
  if (!first.word("function")) fail_at(function_where, "isosurface expects its function first");
  const FunctionValue f = parse_function_body({"x", "y", "z"}, true);
  if (!f.unsupported.empty()) unsupported("function " + f.unsupported, function_where);
  iso.function = f.program;
  double evaluate[3];
  bool evaluated = false;
  for (;;) {
    Tok tok = next();  // directives run
    if (tok.word("contained_by")) {
      parse_contained_by(iso);
    } else if (tok.word("threshold")) {
      const SourceLocation where = location_of(peek());
      iso.threshold = parse_float();
      if (!std::isfinite(iso.threshold))
        fail_at(where, "isosurface threshold " + number_string(iso.threshold) + ": not finite");
    } else if (tok.word("accuracy")) {
      iso.accuracy = positive_float(*this, "accuracy");
    } else if (tok.word("max_gradient")) {
      iso.max_gradient = positive_float(*this, "max_gradient");
    } else if (tok.word("evaluate")) {
      for (int i = 0; i < 3; ++i) {
        if (i) accept(",");
        evaluate[i] = positive_float(*this, "evaluate parameter");
      }
      evaluated = true;
    } else if (tok.word("open")) {
      o.open = true;
    } else if (tok.word("max_trace")) {
      parse_float();  // every crossing is found (up to kIsosurfaceMaxCrossings): as
                      // all_intersections
    } else if (tok.word("all_intersections")) {
    } else {
      unget(std::move(tok));
      break;
    }
  }
  probe_function(*this, o.where, iso, evaluated ? evaluate : nullptr);
  o.isosurface = std::make_shared<const Isosurface>(std::move(iso));
}

}  // namespace fb::pov::sdl
