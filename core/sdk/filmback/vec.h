// Small fixed-size vectors for plugins and the core. Header-only so that a plugin built with
// another compiler needs nothing from filmback but headers (docs/plugins.md).
#pragma once

#include <cmath>

namespace fb {

template <typename T>
struct Vec2 {
  T x{}, y{};
  constexpr Vec2() = default;
  constexpr Vec2(T x_, T y_) : x(x_), y(y_) {}
  constexpr Vec2 operator+(Vec2 o) const { return {x + o.x, y + o.y}; }
  constexpr Vec2 operator-(Vec2 o) const { return {x - o.x, y - o.y}; }
  constexpr Vec2 operator*(T s) const { return {x * s, y * s}; }
};

template <typename T>
struct Vec3 {
  T x{}, y{}, z{};
  constexpr Vec3() = default;
  constexpr Vec3(T x_, T y_, T z_) : x(x_), y(y_), z(z_) {}
  explicit constexpr Vec3(const T v[3]) : x(v[0]), y(v[1]), z(v[2]) {}
  template <typename U>
  explicit constexpr Vec3(Vec3<U> v) : x(T(v.x)), y(T(v.y)), z(T(v.z)) {}

  constexpr T operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr Vec3 operator+(Vec3 o) const { return {x + o.x, y + o.y, z + o.z}; }
  constexpr Vec3 operator-(Vec3 o) const { return {x - o.x, y - o.y, z - o.z}; }
  constexpr Vec3 operator-() const { return {-x, -y, -z}; }
  constexpr Vec3 operator*(Vec3 o) const { return {x * o.x, y * o.y, z * o.z}; }
  constexpr Vec3 operator*(T s) const { return {x * s, y * s, z * s}; }
  constexpr Vec3 operator/(T s) const { return {x / s, y / s, z / s}; }
  constexpr Vec3& operator+=(Vec3 o) { return *this = *this + o; }
  constexpr Vec3& operator*=(Vec3 o) { return *this = *this * o; }
  constexpr Vec3& operator*=(T s) { return *this = *this * s; }
  void store(T out[3]) const { out[0] = x, out[1] = y, out[2] = z; }
};

template <typename T>
constexpr Vec3<T> operator*(T s, Vec3<T> v) {
  return v * s;
}
template <typename T>
constexpr T dot(Vec3<T> a, Vec3<T> b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <typename T>
constexpr Vec3<T> cross(Vec3<T> a, Vec3<T> b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <typename T>
T length(Vec3<T> v) {
  return std::sqrt(dot(v, v));
}
template <typename T>
Vec3<T> normalize(Vec3<T> v) {
  return v / length(v);
}
template <typename T>
constexpr Vec3<T> abs(Vec3<T> v) {
  return {std::abs(v.x), std::abs(v.y), std::abs(v.z)};
}
template <typename T>
constexpr T max_component(Vec3<T> v) {
  return v.x > v.y ? (v.x > v.z ? v.x : v.z) : (v.y > v.z ? v.y : v.z);
}
template <typename T>
constexpr T min_component(Vec3<T> v) {
  return v.x < v.y ? (v.x < v.z ? v.x : v.z) : (v.y < v.z ? v.y : v.z);
}
template <typename T>
constexpr Vec3<T> min(Vec3<T> a, Vec3<T> b) {
  return {a.x < b.x ? a.x : b.x, a.y < b.y ? a.y : b.y, a.z < b.z ? a.z : b.z};
}
template <typename T>
constexpr Vec3<T> max(Vec3<T> a, Vec3<T> b) {
  return {a.x > b.x ? a.x : b.x, a.y > b.y ? a.y : b.y, a.z > b.z ? a.z : b.z};
}
template <typename T>
bool is_finite(Vec3<T> v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

using Vec2f = Vec2<float>;
using Vec2d = Vec2<double>;
using Vec3f = Vec3<float>;
using Vec3d = Vec3<double>;
using Rgb = Vec3<float>;  // linear Rec.709 radiance or reflectance

// Rec.709 luminance weights (ITU-R BT.709), for light power and Russian roulette.
constexpr float luminance(Rgb c) {
  return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}

}  // namespace fb
