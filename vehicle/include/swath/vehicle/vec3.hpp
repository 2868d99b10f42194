#pragma once
// Small value types of 3-D flight: vectors and unit quaternions. Plain, header-only, no Eigen: they
// cross every interface of vehicle/, control/ and fleet/ (Eigen stays inside the .cpp files that
// solve with it). Frames are named where the values are used: world ENU (x east, y north, z up),
// body FLU (x forward, y left, z up) (docs/swath-control.md).

#include <cmath>

namespace swath::vehicle {

struct Vec3 {
  double x = 0, y = 0, z = 0;

  constexpr Vec3& operator+=(const Vec3& o) {
    x += o.x, y += o.y, z += o.z;
    return *this;
  }
  constexpr Vec3& operator-=(const Vec3& o) {
    x -= o.x, y -= o.y, z -= o.z;
    return *this;
  }
  constexpr Vec3& operator*=(double s) {
    x *= s, y *= s, z *= s;
    return *this;
  }
  friend constexpr Vec3 operator+(Vec3 a, const Vec3& b) { return a += b; }
  friend constexpr Vec3 operator-(Vec3 a, const Vec3& b) { return a -= b; }
  friend constexpr Vec3 operator-(const Vec3& a) { return {-a.x, -a.y, -a.z}; }
  friend constexpr Vec3 operator*(Vec3 a, double s) { return a *= s; }
  friend constexpr Vec3 operator*(double s, Vec3 a) { return a *= s; }
  friend constexpr Vec3 operator/(const Vec3& a, double s) { return {a.x / s, a.y / s, a.z / s}; }
  friend constexpr bool operator==(const Vec3&, const Vec3&) = default;
};

constexpr double dot(const Vec3& a, const Vec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
/// Component-wise product (diagonal matrices: inertia, drag coefficients).
constexpr Vec3 hadamard(const Vec3& a, const Vec3& b) {
  return {a.x * b.x, a.y * b.y, a.z * b.z};
}
inline double norm(const Vec3& a) {
  return std::sqrt(dot(a, a));
}
/// The distance between a and b in the x-y plane (altitudes ignored).
inline double horizontal_distance(const Vec3& a, const Vec3& b) {
  return std::hypot(b.x - a.x, b.y - a.y);
}
/// horizontal_distance(a, b) ≤ radius, without the square root (hot loops: clustering).
inline bool horizontally_within(const Vec3& a, const Vec3& b, double radius) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  return dx * dx + dy * dy <= radius * radius;
}

/// A rotation as a unit quaternion w + xi + yj + zk (Hamilton convention). As an attitude it maps
/// body FLU vectors to world ENU: v_world = q ⊗ (0, v_body) ⊗ q*.
struct Quat {
  double w = 1, x = 0, y = 0, z = 0;
  friend constexpr bool operator==(const Quat&, const Quat&) = default;
};

/// Hamilton product a ⊗ b: first b, then a.
constexpr Quat operator*(const Quat& a, const Quat& b) {
  return {
      a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z, a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
      a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x, a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}
constexpr Quat conjugate(const Quat& q) {
  return {q.w, -q.x, -q.y, -q.z};
}
/// q scaled to unit length (the identity for a zero quaternion).
inline Quat normalized(const Quat& q) {
  const double n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  if (!(n > 0)) return {};
  return {q.w / n, q.x / n, q.y / n, q.z / n};
}
/// v rotated by unit quaternion q (body to world for an attitude).
constexpr Vec3 rotate(const Quat& q, const Vec3& v) {
  // v + 2 w (u × v) + 2 u × (u × v), u the vector part: 15 multiplications fewer than q v q*.
  const Vec3 u{q.x, q.y, q.z};
  const Vec3 t = 2.0 * cross(u, v);
  return v + q.w * t + cross(u, t);
}
/// v rotated by q's inverse (world to body for an attitude).
constexpr Vec3 rotate_inverse(const Quat& q, const Vec3& v) {
  return rotate(conjugate(q), v);
}
/// The rotation of `angle_rad` (right-handed) about the unit axis `axis`.
inline Quat axis_angle(const Vec3& axis, double angle_rad) {
  const double s = std::sin(angle_rad / 2);
  return {std::cos(angle_rad / 2), axis.x * s, axis.y * s, axis.z * s};
}
/// The rotation vector θ·axis as a quaternion (exponential map; exact for any |θ|).
inline Quat from_rotation_vector(const Vec3& theta_rad) {
  const double angle = norm(theta_rad);
  if (angle < 1e-12) return normalized({1, theta_rad.x / 2, theta_rad.y / 2, theta_rad.z / 2});
  return axis_angle(theta_rad / angle, angle);
}
/// The rotation vector of unit q (logarithm map), the shorter way round: |result| <= π.
inline Vec3 rotation_vector(const Quat& q) {
  const Quat p = q.w < 0 ? Quat{-q.w, -q.x, -q.y, -q.z} : q;
  const double s = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
  if (s < 1e-12) return {2 * p.x, 2 * p.y, 2 * p.z};
  const double angle = 2 * std::atan2(s, p.w);
  return Vec3{p.x, p.y, p.z} * (angle / s);
}

}  // namespace swath::vehicle
