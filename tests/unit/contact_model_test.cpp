// The contact law's CPU side: damping factor, contact time, time step and settings validation.
#include <gtest/gtest.h>
#include <sandphys/sandphys.h>

#include <cmath>
#include <limits>

namespace sandphys {
namespace {

TEST(ContactModel, ElasticImpactTakesTheClosedFormHertzTime) {
  // Undamped Hertz impact: t = 2 ξmax/v ∫0^1 dx / sqrt(1 - x^{5/2}) = 2.9432 ξmax / v with
  // ξmax = (5 m* v² / (4 k_n))^{2/5} (energy balance). Independent of our ODE integration.
  const double m = 0.01, k = 2.5e5, v = 1.7;
  const double xiMax = std::pow(1.25 * m * v * v / k, 0.4);
  EXPECT_NEAR(hertzContactTime(m, k, 0.0, v), 2.9432 * xiMax / v, 1e-3 * 2.9432 * xiMax / v);
}

TEST(ContactModel, DampingFactorIsZeroForElasticAndGrowsAsRestitutionFalls) {
  EXPECT_EQ(hertzDampingFactor(1.0), 0.0);
  double previous = 0.0;
  for (double e : {0.9, 0.7, 0.5, 0.3, 0.1}) {
    double c = hertzDampingFactor(e);
    EXPECT_GT(c, previous) << "e = " << e;
    previous = c;
  }
}

TEST(ContactModel, ContactTimeScalesWithSpeedToTheMinusOneFifth) {
  const double c = hertzDampingFactor(0.5);
  const double t1 = hertzContactTime(0.01, 2.5e5, c, 1.0);
  const double t32 = hertzContactTime(0.01, 2.5e5, c, 32.0);
  EXPECT_NEAR(t1 / t32, 2.0, 1e-3);  // 32^(1/5) = 2
}

TEST(ContactModel, DerivedTimeStepResolvesTheContact) {
  WorldSettings s;
  ContactModel m = ContactModel::fromSettings(s);
  EXPECT_NEAR(m.timeStep, m.contactTime / s.stepsPerContact, 1e-9);
  EXPECT_NEAR(m.maxOverlap, 0.1f * s.particleDiameter, 1e-9);
  EXPECT_NEAR(m.radius, 0.5f * s.particleDiameter, 1e-9);
  // Stiffer sand needs a shorter step: t_n ∝ E^(-2/5).
  WorldSettings stiff = s;
  stiff.material.youngsModulus *= 32.0f;
  EXPECT_NEAR(ContactModel::fromSettings(stiff).timeStep / m.timeStep, 0.25, 1e-3);
}

// Each bad setting throws InvalidArgument whose message names the field, the value and a limit.
struct BadSetting {
  const char* field;
  void (*apply)(WorldSettings&);
  const char* value;
  const char* limit;
};

class BadSettings : public ::testing::TestWithParam<BadSetting> {};

TEST_P(BadSettings, AreRefusedWithFieldValueAndLimit) {
  const BadSetting& bad = GetParam();
  WorldSettings s;
  bad.apply(s);
  try {
    ContactModel::fromSettings(s);
    FAIL() << bad.field << " was accepted";
  } catch (const InvalidArgument& e) {
    std::string message = e.what();
    EXPECT_NE(message.find(bad.field), std::string::npos) << message;
    EXPECT_NE(message.find(bad.value), std::string::npos) << message;
    EXPECT_NE(message.find(bad.limit), std::string::npos) << message;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Settings, BadSettings,
    ::testing::Values(
        BadSetting{"particleDiameter", [](WorldSettings& s) { s.particleDiameter = std::nanf(""); },
                   "nan", "> 0"},
        BadSetting{"particleDiameter", [](WorldSettings& s) { s.particleDiameter = -0.01f; },
                   "-0.01", "> 0"},
        BadSetting{"material.density", [](WorldSettings& s) { s.material.density = 0.0f; }, "0",
                   "> 0"},
        BadSetting{"material.youngsModulus",
                   [](WorldSettings& s) { s.material.youngsModulus = -5.0f; }, "-5", "> 0"},
        BadSetting{"material.youngsModulus",
                   [](WorldSettings& s) {
                     s.material.youngsModulus = std::numeric_limits<float>::infinity();
                   },
                   "inf", "> 0"},
        BadSetting{"material.friction", [](WorldSettings& s) { s.material.friction = -0.1f; },
                   "-0.1", ">= 0"},
        BadSetting{"material.restitution", [](WorldSettings& s) { s.material.restitution = 0.0f; },
                   "0", "(0, 1]"},
        BadSetting{"material.restitution", [](WorldSettings& s) { s.material.restitution = 1.5f; },
                   "1.5", "(0, 1]"},
        BadSetting{"material.poissonRatio",
                   [](WorldSettings& s) { s.material.poissonRatio = 0.5f; }, "0.5", "[0, 0.5)"},
        BadSetting{"maxSpeed", [](WorldSettings& s) { s.maxSpeed = 0.0f; }, "0", "> 0"},
        BadSetting{"stepsPerContact", [](WorldSettings& s) { s.stepsPerContact = 4.0f; }, "4",
                   ">= 8"},
        BadSetting{"timeStep", [](WorldSettings& s) { s.timeStep = 1e-3f; }, "0.001", "t_n / 8"}));

}  // namespace
}  // namespace sandphys
