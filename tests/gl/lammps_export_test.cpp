// What exportLammps writes, read back without LAMMPS: every particle where the World has it, each
// clump's mass, inertia, velocity and angular momentum, every collider, sink and unmapped part
// named, and the law's coefficients (the LAMMPS run itself: tests/lammps).
#include <gtest/gtest.h>
#include <sandphys/sandphys.h>

#include <unistd.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/impact.h"
#include "support/test_world.h"

namespace sandphys {
namespace {

std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<std::vector<double>> rows(const std::string& text, std::size_t first) {
  std::vector<std::vector<double>> out;
  std::istringstream lines(text);
  std::string line;
  for (std::size_t i = 0; std::getline(lines, line); ++i) {
    if (i < first || line.empty()) continue;
    std::istringstream fields(line);
    std::vector<double> row;
    for (double v; fields >> v;) row.push_back(v);
    out.push_back(row);
  }
  return out;
}

struct ExportedWorld : ::testing::Test {
  std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("sandphys-export-" + std::to_string(::getpid()));
  void TearDown() override { std::filesystem::remove_all(dir); }
};

TEST_F(ExportedWorld, CarriesEveryParticleBodyColliderAndWhatDoesNotMap) {
  WorldSettings s = testing::smallSettings();
  World world(testing::gpu(), s);
  const float d = s.particleDiameter;
  world.addCollider(Plane{.normal = {0.1f, 1.0f, 0.0f}, .offset = -0.05f});
  world.addCollider(Box{.center = {0.0f, 0.2f, 0.0f},
                        .halfExtents = {0.3f, 0.3f, 0.3f},
                        .orientation = fromAxisAngle({0.0f, 1.0f, 0.0f}, 0.3f),
                        .inside = true,
                        .material = {.friction = 0.3f, .restitution = 0.7f}});
  world.addCollider(Cylinder{.base = {0.0f, 0.0f, 0.0f}, .radius = 0.25f, .height = 0.4f});
  world.addCollider(Funnel{.outletCenter = {0.0f, 0.3f, 0.0f}, .outletRadius = 0.05f});
  world.addSink(Sink{.min = {-1.0f, -1.0f, -1.0f}, .max = {1.0f, -0.5f, 1.0f}});
  world.addRoughFloor(RoughFloor{.center = {0.0f, 0.0f, 0.0f}, .radius = 4.0f * d});
  // An L of three particles: a body whose inertia is not isotropic, turned and spinning.
  const ParticleTemplate ell = makeParticleTemplate(
      {{0.0f, 0.0f, 0.0f}, {d, 0.0f, 0.0f}, {0.0f, 2.0f * d, 0.0f}}, d, 1000.0f);
  const Vec3 spin{1.0f, -2.0f, 0.5f};
  world.addBody(ell, {.position = {0.1f, 0.2f, 0.0f},
                      .orientation = fromAxisAngle(normalized(Vec3{1.0f, 1.0f, 0.0f}), 0.7f),
                      .velocity = {0.3f, 0.0f, -0.1f},
                      .angularVelocity = spin});
  world.addBody(ell, {.position = {-0.1f, 0.2f, 0.0f}, .motion = Motion::Kinematic});
  world.addGranules(GranuleBlock{
      .center = {0.0f, 0.3f, 0.0f}, .countX = 2, .countY = 2, .countZ = 2, .spacing = 3.0f * d});
  // One substep writes the particles from their bodies, as readParticles then shows them.
  world.substep(1);
  world.addEmitter(
      EmitterSettings{.center = {0.0f, 0.5f, 0.0f}, .rate = 100.0f, .maxGranules = 10});

  const LammpsExportSummary summary =
      exportLammps(world, dir, {.runSeconds = 0.5, .notes = {"a note of the caller's"}});
  EXPECT_EQ(summary.clumps, 9u);
  EXPECT_EQ(summary.clumpAtoms, 3u + 8u * 4u);
  const std::uint32_t floorParticles =
      static_cast<std::uint32_t>(roughFloorParticles(RoughFloor{.radius = 4.0f * d}, d));
  EXPECT_EQ(summary.frozenAtoms, floorParticles + 3u);
  EXPECT_EQ(summary.walls, 4u);
  EXPECT_EQ(summary.sinks, 1u);

  // Atoms: id type x y z diameter density molecule, clumps first in body order, then the frozen.
  const std::string data = readText(dir / "sandphys.data");
  const std::size_t atomsAt = data.find("Atoms # hybrid");
  ASSERT_NE(atomsAt, std::string::npos);
  const auto atoms = rows(data.substr(atomsAt), 2);
  ASSERT_EQ(atoms.size(), summary.clumpAtoms + summary.frozenAtoms);
  const std::vector<ParticleState> particles = world.readParticles();
  const std::vector<BodyState> bodies = world.readBodies();
  std::vector<std::size_t> order;  // the World's particle index of each atom
  for (int frozen = 0; frozen < 2; ++frozen) {
    for (std::size_t i = 0; i < particles.size(); ++i) {
      const bool dynamic = particles[i].body.index != 0 && particles[i].body.index != 2;
      if (dynamic == (frozen == 0)) order.push_back(i);
    }
  }
  for (std::size_t a = 0; a < atoms.size(); ++a) {
    const ParticleState& p = particles[order[a]];
    ASSERT_EQ(atoms[a].size(), 8u);
    EXPECT_EQ(atoms[a][1], a < summary.clumpAtoms ? 1.0 : 2.0) << "atom " << a;
    EXPECT_NEAR(atoms[a][2], p.position.x, 1e-6) << "atom " << a;
    EXPECT_NEAR(atoms[a][3], p.position.y, 1e-6) << "atom " << a;
    EXPECT_NEAR(atoms[a][4], p.position.z, 1e-6) << "atom " << a;
    EXPECT_FLOAT_EQ(float(atoms[a][5]), d);
  }

  // bodies.rigid: molecule mass xcm ycm zcm ixx iyy izz ixy ixz iyz vx vy vz lx ly lz 0 0 0.
  const auto clumps = rows(readText(dir / "bodies.rigid"), 2);
  ASSERT_EQ(clumps.size(), 9u);
  const std::vector<double>& l = clumps[0];
  ASSERT_EQ(l.size(), 20u);
  EXPECT_NEAR(l[1], ell.mass, 1e-6 * ell.mass);
  EXPECT_NEAR(l[2], bodies[1].position.x, 1e-7);
  Eigen::Matrix3d inertia;
  inertia << l[5], l[8], l[9], l[8], l[6], l[10], l[9], l[10], l[7];
  // The world-frame tensor has the template's principal moments, and L = I ω.
  const Eigen::Vector3d moments =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia).eigenvalues();
  Eigen::Vector3d expected(ell.principalInertia.x, ell.principalInertia.y, ell.principalInertia.z);
  std::sort(expected.data(), expected.data() + 3);
  EXPECT_NEAR((moments - expected).norm(), 0.0, 1e-5 * expected.norm());
  const Vec3 w = bodies[1].angularVelocity;  // after the substep
  const Eigen::Vector3d omega(w.x, w.y, w.z);
  EXPECT_NEAR((inertia * omega - Eigen::Vector3d(l[14], l[15], l[16])).norm(), 0.0,
              1e-5 * (inertia * omega).norm());
  // Velocity, with gravity's half kick of the first step (lammps_export.cpp).
  const double kick = 0.5 * world.timeStep() * s.gravity.y;
  EXPECT_NEAR(l[11], bodies[1].velocity.x, 1e-7);
  EXPECT_NEAR(l[12], bodies[1].velocity.y + kick, 1e-7);
  const ParticleTemplate granule = tetrahedronTemplate(d, s.material.density);
  EXPECT_NEAR(clumps[1][1], granule.mass, 1e-6 * granule.mass);

  // The deck: each collider, the sink, the law and every part that does not map.
  const std::string deck = readText(summary.deck);
  for (const char* line :
       {"region wall0 plane ", "region wall1 block ", " side in rotate v_wall1_angle ",
        "region wall2 cylinder y ", "region wall3 cone y ", "fix sink0 clumps evaporate ",
        "fix rigid clumps rigid/small molecule infile bodies.rigid gravity gravity",
        "variable seconds index 0.5", "a note of the caller's", "1 kinematic bodies", "emitter 0 ",
        "fix freeze frozen freeze"}) {
    EXPECT_NE(deck.find(line), std::string::npos) << "no '" << line << "' in\n" << deck;
  }
  // pair_coeff * * hertz kn e' tangential mindlin kt 1.0 mu damping tsuji: the Hertz and Mindlin
  // coefficients over sqrt(R*) = sqrt(d/4), and the e' whose Tsuji damping rebounds at e.
  std::istringstream pair(deck.substr(deck.find("pair_coeff * * hertz ") + 21));
  double kn, tsuji, kt, ratio, mu;
  std::string tangential, mindlin;
  pair >> kn >> tsuji >> tangential >> mindlin >> kt >> ratio >> mu;
  const double e = s.material.youngsModulus;
  const double nu = s.material.poissonRatio;
  EXPECT_NEAR(kn, 4.0 / 3.0 * e / (2.0 * (1.0 - nu * nu)), 1e-5 * kn);
  EXPECT_NEAR(kt, 8.0 * e / (2.0 * (1.0 + nu)) / (2.0 * (2.0 - nu)), 1e-5 * kt);
  EXPECT_FLOAT_EQ(float(mu), s.material.friction);
  const double alpha = 1.2728 - 4.2783 * tsuji + 11.087 * std::pow(tsuji, 2) -
                       22.348 * std::pow(tsuji, 3) + 27.467 * std::pow(tsuji, 4) -
                       18.022 * std::pow(tsuji, 5) + 4.8218 * std::pow(tsuji, 6);
  EXPECT_NEAR(detail::adhesiveHertzRestitution(alpha), s.material.restitution, 1e-4);
}

// Rolling friction maps onto LAMMPS's rolling sds, whose spring and damping are constants: the
// deck gives sandphys's k_t = k_t0 sqrt(ξ) and η = c(e) sqrt(m* k_n) ξ^{1/4} at the overlap ξ of
// one granule's weight, k_n and k_t0 from E and ν, between grains (m* half a granule) and on each
// wall (m* a granule, c for the wall's restitution). Without rolling friction there is none.
TEST_F(ExportedWorld, CarriesRollingFrictionAsRollingSds) {
  WorldSettings s = testing::smallSettings();
  s.material.rollingFriction = 0.1f;
  World world(testing::gpu(), s);
  world.addCollider(Plane{.material = {.friction = 0.4f, .restitution = 0.7f}});
  world.addGranules(GranuleBlock{.center = {0.0f, 0.1f, 0.0f}, .countX = 2, .countY = 1});
  world.substep(1);
  const std::string deck = readText(exportLammps(world, dir, {.runSeconds = 0.5}).deck);

  const double d = s.particleDiameter;
  const double e = s.material.youngsModulus;
  const double nu = s.material.poissonRatio;
  const double g = -s.gravity.y;
  const double granule = tetrahedronTemplate(float(d), s.material.density).mass;
  // k_n, k_t0 of a grain pair (R* = d/4) and of a grain on a rigid wall (R* = d/2).
  const double g0 = e / (2.0 * (1.0 + nu));
  const double knGrain = 4.0 / 3.0 * e / (2.0 * (1.0 - nu * nu)) * std::sqrt(0.25 * d);
  const double ktGrain = 8.0 * g0 / (2.0 * (2.0 - nu)) * std::sqrt(0.25 * d);
  const double knWall = 4.0 / 3.0 * e / (1.0 - nu * nu) * std::sqrt(0.5 * d);
  const double ktWall = 8.0 * g0 / (2.0 - nu) * std::sqrt(0.5 * d);
  auto expectRolling = [&](const std::string& from, double kn, double kt, double restitution,
                           double effectiveMass) {
    const std::size_t at = deck.find(" rolling sds ", deck.find(from));
    ASSERT_NE(at, std::string::npos) << "no rolling sds after '" << from << "' in\n" << deck;
    std::istringstream words(deck.substr(at + 13));
    double stiffness, damping, mu;
    words >> stiffness >> damping >> mu;
    const double xi = std::pow(granule * g / kn, 2.0 / 3.0);
    EXPECT_NEAR(stiffness, kt * std::sqrt(xi), 1e-4 * stiffness) << from;
    EXPECT_NEAR(
        damping,
        hertzDampingFactor(restitution) * std::sqrt(effectiveMass * kn) * std::pow(xi, 0.25),
        1e-4 * damping)
        << from;
    EXPECT_FLOAT_EQ(float(mu), s.material.rollingFriction) << from;
  };
  expectRolling("pair_coeff * * ", knGrain, ktGrain, s.material.restitution, 0.5 * granule);
  expectRolling("fix wall0 ", knWall, ktWall, 0.7, granule);
  EXPECT_NE(deck.find("rolling friction: rolling sds"), std::string::npos) << deck;

  s.material.rollingFriction = 0.0f;
  World without(testing::gpu(), s);
  without.addCollider(Plane{});
  const std::string plain = readText(exportLammps(without, dir, {.runSeconds = 0.5}).deck);
  EXPECT_EQ(plain.find("rolling"), std::string::npos) << plain;
}

TEST_F(ExportedWorld, RefusesABadSpanAndAFolderItCannotWrite) {
  World world(testing::gpu(), testing::smallSettings());
  EXPECT_NE(testing::errorMessageOf([&] {
              exportLammps(world, dir, {.runSeconds = 0.0});
            }).find("LammpsExportOptions.runSeconds"),
            std::string::npos);
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "file") << "x";
  const std::string message =
      testing::errorMessageOf([&] { exportLammps(world, dir / "file" / "deck"); });
  EXPECT_NE(message.find((dir / "file" / "deck").string()), std::string::npos) << message;
}

}  // namespace
}  // namespace sandphys
