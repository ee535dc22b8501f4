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
  EXPECT_TRUE(std::isinf(m.maxOverlap)) << "HertzMindlin has no overlap cap";
  WorldSettings paper = s;
  paper.contactLaw = ContactLaw::PaperViscous;
  EXPECT_NEAR(ContactModel::fromSettings(paper).maxOverlap, 0.1f * s.particleDiameter, 1e-9);
  EXPECT_NEAR(m.radius, 0.5f * s.particleDiameter, 1e-9);
  // Stiffer sand needs a shorter step: t_n ∝ E^(-2/5).
  WorldSettings stiff = s;
  stiff.material.youngsModulus *= 32.0f;
  EXPECT_NEAR(ContactModel::fromSettings(stiff).timeStep / m.timeStep, 0.25, 1e-3);
}

TEST(ContactModel, MindlinStiffnessFollowsTheShearModulus) {
  // k_t0 = 8 G* sqrt(R*) with G* = E / (4 (1 + ν)(2 - ν)) for two grains and twice that against
  // a rigid surface; against k_n = 4/3 E* sqrt(R*) that is the textbook ratio
  // k_t / (dF_n/dξ) = 2 (1 - ν) / (2 - ν) for both.
  WorldSettings s;
  const ContactModel m = ContactModel::fromSettings(s);
  const double nu = s.material.poissonRatio;
  const double ratio = 2.0 * (1.0 - nu) / (2.0 - nu);
  EXPECT_NEAR(m.shearStiffnessGrain / (1.5 * m.stiffnessGrain), ratio, 1e-6);
  EXPECT_NEAR(m.shearStiffnessWall / (1.5 * m.stiffnessWall), ratio, 1e-6);
}

TEST(ContactModel, PeakOverlapIsTheEnergyBalanceOfAnUndampedImpact) {
  // ½ m* v² = 2/5 k_n ξ^{5/2} at the deepest point.
  const double m = 0.02, k = 4.0e5, v = 3.0;
  const double xi = hertzPeakOverlap(m, k, v);
  EXPECT_NEAR(0.4 * k * std::pow(xi, 2.5), 0.5 * m * v * v, 1e-9 * m * v * v);
  WorldSettings s;
  const ContactModel c = ContactModel::fromSettings(s);
  EXPECT_FLOAT_EQ(c.peakOverlapGrain,
                  float(hertzPeakOverlap(0.5 * c.granuleMass, c.stiffnessGrain, s.maxSpeed)));
  EXPECT_FLOAT_EQ(c.peakOverlapWall, float(hertzPeakOverlap(c.granuleMass, c.stiffnessWall,
                                                            kGuardParticleSpeed * s.maxSpeed)));
  // Four floor particles around the hole: four times one contact's energy at the hole's overlap.
  const double hole = 1.0 - 1.0 / std::sqrt(2.0);
  EXPECT_NEAR(0.4 * std::pow(floorPassOverlap(1.0), 2.5), 4.0 * 0.4 * std::pow(hole, 2.5), 1e-12);
}

TEST(ContactModel, SandTooSoftForItsSpeedGuardIsRefusedWithTheStiffnessThatWouldDo) {
  WorldSettings s;
  s.material.youngsModulus = 5.0e6f;
  s.maxSpeed = 10.0f;  // the defaults before the cap went: grains would pass through
  try {
    (void)ContactModel::fromSettings(s);
    FAIL() << "accepted";
  } catch (const InvalidArgument& e) {
    const std::string message = e.what();
    for (const char* part : {"youngsModulus = 5000000", "maxSpeed = 10", "would overlap by",
                             "raise youngsModulus to at least", "lower maxSpeed to"}) {
      EXPECT_NE(message.find(part), std::string::npos) << part << " in: " << message;
    }
    // The E it names does pass.
    const std::size_t at = message.find("at least ") + 9;
    s.material.youngsModulus = std::stof(message.substr(at)) * 1.001f;
    EXPECT_NO_THROW((void)ContactModel::fromSettings(s));
  }
  // The paper's law caps the overlap instead and takes the same settings.
  s.material.youngsModulus = 5.0e6f;
  s.contactLaw = ContactLaw::PaperViscous;
  EXPECT_NO_THROW((void)ContactModel::fromSettings(s));
}

// The neighbour lists' skin: as given, or room for kListSkinSubsteps substeps at the speed guard
// on each side of a pair, within [kMinListSkin, kMaxListSkin] diameters.
TEST(ContactModel, ListSkinFollowsTheStatedRule) {
  WorldSettings s;
  const double d = s.particleDiameter;
  const ContactModel derived = ContactModel::fromSettings(s);
  const double travel = 2.0 * kListSkinSubsteps * s.maxSpeed * derived.timeStep;
  ASSERT_GT(travel, kMinListSkin * d);
  ASSERT_LT(travel, kMaxListSkin * d);
  EXPECT_NEAR(derived.listSkin, travel, 1e-6 * travel);
  s.maxSpeed = 0.01f;  // a crawl: the smallest skin
  const ContactModel slow = ContactModel::fromSettings(s);
  ASSERT_LT(2.0 * kListSkinSubsteps * s.maxSpeed * slow.timeStep, kMinListSkin * d);
  EXPECT_FLOAT_EQ(slow.listSkin, kMinListSkin * s.particleDiameter);
  s = WorldSettings{};
  s.stepsPerContact = 8.0f;  // the longest step
  s.maxSpeed = 40.0f;
  s.material.youngsModulus = 1e9f;
  const ContactModel fast = ContactModel::fromSettings(s);
  ASSERT_GT(2.0 * kListSkinSubsteps * s.maxSpeed * fast.timeStep, kMaxListSkin * d);
  EXPECT_FLOAT_EQ(fast.listSkin, kMaxListSkin * s.particleDiameter);
  s.listSkin = 0.3f * s.particleDiameter;
  EXPECT_FLOAT_EQ(ContactModel::fromSettings(s).listSkin, 0.3f * s.particleDiameter);
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
        BadSetting{"material.rollingFriction",
                   [](WorldSettings& s) { s.material.rollingFriction = std::nanf(""); }, "nan",
                   "finite and >= 0"},
        BadSetting{"material.rollingFriction",
                   [](WorldSettings& s) { s.material.rollingFriction = -0.05f; }, "-0.05",
                   "finite and >= 0"},
        BadSetting{"material.rollingFriction",
                   [](WorldSettings& s) {
                     s.contactLaw = ContactLaw::PaperViscous;
                     s.material.rollingFriction = 0.1f;
                   },
                   "0.1", "must be 0 with ContactLaw::PaperViscous"},
        BadSetting{"material.restitution", [](WorldSettings& s) { s.material.restitution = 0.0f; },
                   "0", "(0, 1]"},
        BadSetting{"material.restitution", [](WorldSettings& s) { s.material.restitution = 1.5f; },
                   "1.5", "(0, 1]"},
        BadSetting{"material.poissonRatio",
                   [](WorldSettings& s) { s.material.poissonRatio = 0.5f; }, "0.5", "[0, 0.5)"},
        BadSetting{"maxSpeed", [](WorldSettings& s) { s.maxSpeed = 0.0f; }, "0", "> 0"},
        BadSetting{"stepsPerContact", [](WorldSettings& s) { s.stepsPerContact = 4.0f; }, "4",
                   "[8, 10000]"},
        BadSetting{"stepsPerContact", [](WorldSettings& s) { s.stepsPerContact = 1e20f; }, "1e+20",
                   "[8, 10000]"},
        BadSetting{"timeStep", [](WorldSettings& s) { s.timeStep = 1e-3f; }, "0.001", "t_n / 8"},
        BadSetting{"timeStep", [](WorldSettings& s) { s.timeStep = 1e-22f; }, "1e-22",
                   "t_n / 10000"},
        BadSetting{"contactLaw", [](WorldSettings& s) { s.contactLaw = ContactLaw(7); }, "7",
                   "PaperViscous"},
        BadSetting{"listSkin", [](WorldSettings& s) { s.listSkin = std::nanf(""); }, "nan",
                   "finite and >= 0 (m)"},
        BadSetting{"listSkin", [](WorldSettings& s) { s.listSkin = -0.001f; }, "-0.001",
                   "finite and >= 0 (m)"},
        BadSetting{"listSkin", [](WorldSettings& s) { s.listSkin = 0.05f; }, "0.05",
                   "[0, particleDiameter = 0.02]"}));

}  // namespace
}  // namespace sandphys
