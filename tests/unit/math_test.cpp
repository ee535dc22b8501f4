// The Vec3 and Quat operations of sandphys/math.h against their definitions: the rotation by a
// quaternion is the sandwich q v q*, turns the right way and keeps lengths.
#include <gtest/gtest.h>
#include <sandphys/math.h>

#include <numbers>

namespace sandphys {
namespace {

constexpr float kHalfPi = 0.5f * std::numbers::pi_v<float>;

void expectNear(Vec3 a, Vec3 b, float tolerance = 1e-6f) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(Math, RotationTurnsRightHandedAboutItsAxis) {
  const Quat quarterAboutY = fromAxisAngle({0, 1, 0}, kHalfPi);
  expectNear(rotate(quarterAboutY, {1, 0, 0}), {0, 0, -1});
  expectNear(rotate(quarterAboutY, {0, 0, 1}), {1, 0, 0});
  expectNear(rotate(quarterAboutY, {0, 1, 0}), {0, 1, 0});
  const Quat quarterAboutZ = fromAxisAngle({0, 0, 1}, kHalfPi);
  expectNear(rotate(quarterAboutZ, {1, 0, 0}), {0, 1, 0});
}

TEST(Math, RotationIsTheQuaternionSandwichAndComposesLikeTheProduct) {
  const Quat a = fromAxisAngle(normalized({1, 2, 3}), 0.7f);
  const Quat b = fromAxisAngle(normalized({-2, 0.5f, 1}), -1.9f);
  const Vec3 v{0.3f, -1.2f, 2.5f};
  const Quat sandwich = a * Quat{0, v.x, v.y, v.z} * conjugate(a);
  EXPECT_NEAR(sandwich.w, 0.0f, 1e-6f);
  expectNear(rotate(a, v), {sandwich.x, sandwich.y, sandwich.z}, 1e-5f);
  expectNear(rotate(a * b, v), rotate(a, rotate(b, v)), 1e-5f);
  expectNear(rotate(conjugate(a), rotate(a, v)), v, 1e-5f);
  EXPECT_NEAR(length(rotate(a, v)), length(v), 1e-5f);
}

TEST(Math, VectorProductsFollowTheirDefinitions) {
  const Vec3 a{1, 2, 3}, b{-4, 0.5f, 2};
  EXPECT_EQ(dot(a, b), -4.0f + 1.0f + 6.0f);
  EXPECT_EQ(cross(a, b), (Vec3{2 * 2 - 3 * 0.5f, 3 * -4 - 1 * 2, 1 * 0.5f - 2 * -4}));
  EXPECT_EQ(dot(cross(a, b), a), 0.0f);
  EXPECT_EQ(a + b - b, a);
  EXPECT_EQ(2.0f * a, a * 2.0f);
  EXPECT_EQ((a * 2.0f) / 2.0f, a);
  EXPECT_EQ(-a + a, Vec3{});
  EXPECT_NEAR(length(normalized(b)), 1.0f, 1e-6f);
  EXPECT_EQ(normalized(Vec3{}), Vec3{});
}

}  // namespace
}  // namespace sandphys
