// Three-vectors for the soil model: plain arrays, world frame unless a name says otherwise.
#pragma once

#include <array>
#include <cmath>

namespace marsokhod::sim::soil {

using Vec3 = std::array<double, 3>;

inline Vec3 operator+(const Vec3& u, const Vec3& v) {
  return {u[0] + v[0], u[1] + v[1], u[2] + v[2]};
}
inline Vec3 operator-(const Vec3& u, const Vec3& v) {
  return {u[0] - v[0], u[1] - v[1], u[2] - v[2]};
}
inline Vec3 operator*(double s, const Vec3& v) { return {s * v[0], s * v[1], s * v[2]}; }
inline double dot(const Vec3& u, const Vec3& v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; }
inline Vec3 cross(const Vec3& u, const Vec3& v) {
  return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}
inline double norm(const Vec3& v) { return std::sqrt(dot(v, v)); }
inline Vec3& operator+=(Vec3& u, const Vec3& v) {
  u = u + v;
  return u;
}

}  // namespace marsokhod::sim::soil
