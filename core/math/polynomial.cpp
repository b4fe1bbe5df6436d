#include "core/math/polynomial.h"

#include <cmath>

namespace fb {

double evaluate_polynomial(const double* c, int degree, double t) {
  double v = c[degree];
  for (int i = degree - 1; i >= 0; --i)
    v = v * t + c[i];
  return v;
}

namespace {

// The sign change of a monotone piece within (a, b), where (p(a) > 0) != (p(b) > 0).
double bracketed_root(const double* c, const double* dc, int degree, double a, double b) {
  const bool a_positive = evaluate_polynomial(c, degree, a) > 0;
  double x = 0.5 * (a + b);
  // Each step at least halves the bracket or is a Newton step inside it; 200 steps are far more
  // than the 2 x 1077 binary exponents a double bracket can span before it is two ulps wide.
  for (int step = 0; step < 200; ++step) {
    const double fx = evaluate_polynomial(c, degree, x);
    if ((fx > 0) == a_positive)
      a = x;
    else
      b = x;
    const double mid = 0.5 * (a + b);
    if (mid <= a || mid >= b) break;  // a and b are neighbouring doubles
    const double newton = x - fx / evaluate_polynomial(dc, degree - 1, x);
    if (newton == x) break;
    x = newton > a && newton < b ? newton : mid;
  }
  return x;
}

}  // namespace

int sign_changes(const double* c, int degree, double lo, double hi, double* roots) {
  if (!(lo < hi) || degree < 1) return 0;
  double dc[kMaxPolynomialDegree];
  for (int i = 1; i <= degree; ++i)
    dc[i - 1] = i * c[i];
  // The pieces' ends: lo, the derivative's sign changes (the extrema), hi.
  double ends[kMaxPolynomialDegree + 1];
  ends[0] = lo;
  const int extrema = degree > 1 ? sign_changes(dc, degree - 1, lo, hi, ends + 1) : 0;
  ends[extrema + 1] = hi;
  int count = 0;
  for (int i = 0; i <= extrema; ++i) {
    const double a = ends[i], b = ends[i + 1];
    const double pa = evaluate_polynomial(c, degree, a), pb = evaluate_polynomial(c, degree, b);
    // The polynomial keeps its sign across an extremum: a zero there only touches the axis.
    const bool touch = (i > 0 && pa == 0) || (i < extrema && pb == 0);
    if (!touch && (pa > 0) != (pb > 0)) roots[count++] = bracketed_root(c, dc, degree, a, b);
  }
  return count;
}

}  // namespace fb
