// Quaternion algebra against independent truth: rotation matrices built from Euler's formula
// (Rodrigues), and the group laws on random rotations.
#include "swath/vehicle/vec3.hpp"

#include <gtest/gtest.h>

#include "swath/vehicle/random.hpp"

namespace swath::vehicle {
namespace {

Vec3 random_unit(SplitMix64& r) {
  const Vec3 v{r.normal(), r.normal(), r.normal()};
  return v / norm(v);
}

// Rodrigues: R v = v cos θ + (k × v) sin θ + k (k · v)(1 − cos θ).
Vec3 rodrigues(const Vec3& k, double theta, const Vec3& v) {
  return v * std::cos(theta) + cross(k, v) * std::sin(theta) +
         k * (dot(k, v) * (1 - std::cos(theta)));
}

void expect_near(const Vec3& a, const Vec3& b, double tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

TEST(Quat, RotatesAsRodriguesAndComposesInOrder) {
  SplitMix64 r(7);
  for (int i = 0; i < 200; ++i) {
    const Vec3 k1 = random_unit(r), k2 = random_unit(r), v{r.normal(), r.normal(), r.normal()};
    const double a1 = r.uniform(-3.1, 3.1), a2 = r.uniform(-3.1, 3.1);
    const Quat q1 = axis_angle(k1, a1), q2 = axis_angle(k2, a2);
    expect_near(rotate(q1, v), rodrigues(k1, a1, v), 1e-12);
    // q2 ⊗ q1: first q1, then q2.
    expect_near(rotate(q2 * q1, v), rodrigues(k2, a2, rodrigues(k1, a1, v)), 1e-12);
    expect_near(rotate_inverse(q1, rotate(q1, v)), v, 1e-12);
    EXPECT_NEAR(norm(rotate(q1, v)), norm(v), 1e-12);
  }
}

TEST(Quat, RotationVectorIsTheInverseOfTheExponential) {
  SplitMix64 r(11);
  for (int i = 0; i < 200; ++i) {
    const Vec3 theta = random_unit(r) * r.uniform(0, 3.14);
    expect_near(rotation_vector(from_rotation_vector(theta)), theta, 1e-11);
  }
  // Tiny angles keep their precision; the shorter way round past π.
  expect_near(rotation_vector(from_rotation_vector({1e-9, -2e-9, 0})), {1e-9, -2e-9, 0}, 1e-20);
  const Vec3 back = rotation_vector(axis_angle({0, 0, 1}, 1.5 * M_PI));
  expect_near(back, {0, 0, -0.5 * M_PI}, 1e-12);
}

TEST(Vec3, CrossIsPerpendicularAndHadamardComponentWise) {
  const Vec3 a{1, 2, 3}, b{-4, 0.5, 2};
  EXPECT_DOUBLE_EQ(dot(cross(a, b), a), 0);
  EXPECT_DOUBLE_EQ(dot(cross(a, b), b), 0);
  EXPECT_EQ(cross(Vec3{1, 0, 0}, Vec3{0, 1, 0}), (Vec3{0, 0, 1}));  // right-handed
  EXPECT_EQ(hadamard(a, b), (Vec3{-4, 1, 6}));
}

}  // namespace
}  // namespace swath::vehicle
