#include "core/math/polynomial.h"

#include <algorithm>
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

namespace {

double power(double v, int n) {
  double r = 1;
  for (int i = 0; i < n; ++i)
    r *= v;
  return r;
}

// (o + t d)^n as coefficients out[0..n] of t (binomial expansion), n <= kMaxPolynomialDegree:
// C(n, k) = C(n, k - 1) (n - k + 1) / k, exact in doubles at these sizes.
void binomial_power(double o, double d, int n, double* out) {
  double choose = 1;
  for (int k = 0; k <= n; ++k) {
    if (k > 0) choose = choose * (n - k + 1) / k;
    out[k] = choose * power(o, n - k) * power(d, k);
  }
}

}  // namespace

double evaluate_polynomial3(const Polynomial3& p, Vec3d point) {
  double v = 0;
  for (const Monomial& m : p)
    v += m.c * power(point.x, m.x) * power(point.y, m.y) * power(point.z, m.z);
  return v;
}

Vec3d polynomial3_gradient(const Polynomial3& p, Vec3d q) {
  Vec3d g{0, 0, 0};
  for (const Monomial& m : p) {
    const double px = power(q.x, m.x), py = power(q.y, m.y), pz = power(q.z, m.z);
    if (m.x) g.x += m.c * m.x * power(q.x, m.x - 1) * py * pz;
    if (m.y) g.y += m.c * m.y * px * power(q.y, m.y - 1) * pz;
    if (m.z) g.z += m.c * m.z * px * py * power(q.z, m.z - 1);
  }
  return g;
}

int polynomial3_degree(const Polynomial3& p) {
  int degree = 0;
  for (const Monomial& m : p)
    if (m.c != 0) degree = std::max(degree, m.x + m.y + m.z);
  return degree;
}

void restrict_to_ray(const Polynomial3& p, Vec3d o, Vec3d d, double c[kMaxPolynomialDegree + 1]) {
  constexpr int n = kMaxPolynomialDegree + 1;
  for (int k = 0; k < n; ++k)
    c[k] = 0;
  for (const Monomial& m : p) {
    double x[n], y[n], z[n];
    binomial_power(o.x, d.x, m.x, x);
    binomial_power(o.y, d.y, m.y, y);
    binomial_power(o.z, d.z, m.z, z);
    for (int i = 0; i <= m.x; ++i)
      for (int j = 0; j <= m.y; ++j)
        for (int k = 0; i + j + k < n && k <= m.z; ++k)
          c[i + j + k] += m.c * x[i] * y[j] * z[k];
  }
}

}  // namespace fb
