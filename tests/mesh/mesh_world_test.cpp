// Sampled meshes in a World (headless GL): the particles stand where the mesh says, and a body
// too large for the capacity left is refused without changing the world.
#include <gtest/gtest.h>
#include <sandphys/sandphys.h>

#include <Eigen/Geometry>

#include <cstdio>

#include "mesh/mesh_shapes.h"
#include "support/test_world.h"

namespace sandphys {
namespace {

using mesh_testing::namedIcosphere;
using mesh_testing::toEigen;

TEST(MeshBody, ParticlesStandWhereTheMeshPutsThem) {
  // A box with three different moments, so that its principal frame is a real rotation, posed
  // with a rotation of its own: particle = position + R(q) (mesh point - centre of mass).
  const Eigen::Matrix3d tilt =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  const TriangleMesh box = mesh_testing::transformed(
      boxMesh({-0.06f, -0.03f, -0.02f}, {0.06f, 0.03f, 0.02f}), tilt, {0.3, 0.1, -0.2});
  WorldSettings settings = testing::smallSettings(8);
  settings.gravity = {0, 0, 0};
  settings.maxParticles = 1024;
  World world(testing::gpu(), settings);
  const SampledMesh sampled = sampleMesh(box, settings.particleDiameter);
  ASSERT_NE(sampled.shape.principalRotation.w, 1.0f);

  const Eigen::Quaterniond pose(Eigen::AngleAxisd(1.1, Eigen::Vector3d(0, 1, 0.5).normalized()));
  const Eigen::Vector3d position(1.0, 2.0, 3.0);
  world.addBody(
      sampled.shape,
      {.position = {float(position.x()), float(position.y()), float(position.z())},
       .orientation = {float(pose.w()), float(pose.x()), float(pose.y()), float(pose.z())},
       .motion = Motion::Kinematic});
  ASSERT_EQ(world.particleCount(), sampled.centres.size());
  world.substep(1);  // places the particles from the body's pose

  const std::vector<ParticleState> particles = world.readParticles();
  const Eigen::Vector3d com(sampled.massProperties.centreOfMass[0],
                            sampled.massProperties.centreOfMass[1],
                            sampled.massProperties.centreOfMass[2]);
  double worst = 0.0;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const Eigen::Vector3d expected =
        position + pose.toRotationMatrix() * (toEigen(sampled.centres[i]) - com);
    worst = std::max(worst, (toEigen(particles[i].position) - expected).norm());
  }
  std::printf("%zu particles, largest misplacement %.3g m\n", particles.size(), worst);
  EXPECT_LT(worst, 1e-5) << "largest particle misplacement, m";
}

TEST(MeshBody, BodyBeyondTheParticleCapacityIsRefusedAndNothingChanges) {
  WorldSettings settings = testing::smallSettings(16);  // 64 particles
  testing::TestWorld world(settings);
  world.addGranule({0, 0.1f, 0});
  const std::uint32_t bodies = world->bodyCount(), particles = world->particleCount();
  ASSERT_EQ(particles, 4u);

  const SampledMesh rock =
      sampleMesh(namedIcosphere(0.05, 2, {}, "rock"), world->settings().particleDiameter);
  ASSERT_GT(rock.centres.size(), world->particleCapacity() - particles);
  try {
    world->addBody(rock.shape, {.position = {0, 0.5f, 0}});
    FAIL() << "a body of " << rock.centres.size() << " particles fit in "
           << world->particleCapacity();
  } catch (const CapacityExceeded& e) {
    EXPECT_NE(std::string(e.what()).find("WorldSettings.maxParticles = 64"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(world->bodyCount(), bodies);
  EXPECT_EQ(world->particleCount(), particles);
  // Room made with reserve: now it fits.
  world->reserve(16, std::uint32_t(particles + rock.centres.size()));
  world->addBody(rock.shape, {.position = {0, 0.5f, 0}});
  EXPECT_EQ(world->particleCount(), particles + rock.centres.size());
}

}  // namespace
}  // namespace sandphys

namespace sandphys {
namespace {

// A sampled surface holds a granule meeting it at maxSpeed out while the impact's overlap stays
// under surfacePassOverlap(h / d): at the default spacing (0.8 d) with a wide margin; at 1.6 d a
// granule slips into a hole at 0.08 d of overlap with each of three samples, and the body is
// refused. A cluster of particles that is not a sampled surface is not checked.
TEST(MeshBody, ASurfaceWhoseHolesAGranuleAtTheGuardGetsThroughIsRefused) {
  testing::TestWorld w;
  const float d = w->settings().particleDiameter;
  const TriangleMesh box = boxMesh({-0.05f, -0.05f, -0.05f}, {0.05f, 0.05f, 0.05f});
  const SampledMesh fine = sampleMesh(box, d);
  EXPECT_FLOAT_EQ(fine.shape.surfaceSpacing, kDefaultMeshSpacing * d);
  EXPECT_TRUE(w->addBody(fine.shape, BodyDesc{.position = {0, 0.5f, 0}}).isValid());
  const SampledMesh coarse = sampleMesh(box, d, {.spacing = 1.6f * d});
  try {
    w->addBody(coarse.shape, BodyDesc{.position = {1, 0.5f, 0}});
    FAIL() << "a surface sampled at 1.6 d was accepted";
  } catch (const InvalidArgument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("sampled at a spacing of 1.6 d"), std::string::npos) << message;
    EXPECT_NE(message.find("raise youngsModulus to at least"), std::string::npos) << message;
  }
  EXPECT_EQ(w->bodyCount(), 1u);
  EXPECT_GT(surfacePassOverlap(0.8), 2.0 * w->contactModel().peakOverlapFixedParticle / d);
}

}  // namespace
}  // namespace sandphys
