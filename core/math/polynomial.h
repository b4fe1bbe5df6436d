// Real roots of small polynomials along a ray, for the analytic solids
// (core/accel/solid_intersect).
#pragma once

#include <cstdint>
#include <vector>

#include <filmback/vec.h>

namespace fb {

// POV-Ray's poly and polynomial reach order 15; the lathe's cubic segments give degree 6.
constexpr int kMaxPolynomialDegree = 15;

// c[0] + c[1] t + ... + c[degree] t^degree, by Horner's rule.
double evaluate_polynomial(const double* c, int degree, double t);

// The points in (lo, hi) where the polynomial (degree <= kMaxPolynomialDegree) changes between
// > 0 and <= 0, ascending, written to `roots` (room for `degree`); returns how many. The interval
// is cut at the sign changes of the derivative (found the same way, down to a line), so each
// piece is monotone and holds at most one root, which safeguarded Newton iteration (bisection
// when a Newton step leaves the bracket) finds to the last bits of a double. This isolates every
// root that changes the sign whatever the degree, as a Sturm sequence would, without the
// sequence's loss of precision at high degree; the work is bounded: at most degree (degree + 1)
// / 2 bracketed searches of at most 200 steps. Roots of even multiplicity (tangent rays) are not
// sign changes and are not reported: a ray that grazes a surface does not enter it.
int sign_changes(const double* c, int degree, double lo, double hi, double* roots);

// One term c x^x y^y z^z of a polynomial in three variables.
struct Monomial {
  double c = 0;
  uint8_t x = 0, y = 0, z = 0;
};
using Polynomial3 = std::vector<Monomial>;

double evaluate_polynomial3(const Polynomial3& p, Vec3d point);
Vec3d polynomial3_gradient(const Polynomial3& p, Vec3d point);
int polynomial3_degree(const Polynomial3& p);
// c[0..kMaxPolynomialDegree] of p(o + t d) as a polynomial in t; p's degree must be at most
// kMaxPolynomialDegree.
void restrict_to_ray(const Polynomial3& p, Vec3d o, Vec3d d, double c[kMaxPolynomialDegree + 1]);

}  // namespace fb
