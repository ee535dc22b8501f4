#include "scenes/block_avalanche.h"

#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btStaticPlaneShape.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include <sandphys/bullet/bridge.h>
#include <sandphys/bullet/conversions.h>
#include <sandphys/bullet/owned_world.h>
#include <sandphys/bullet/shape_mesh.h>

#include "scenes/kit/parameters.h"

namespace sandphys::scenes {

namespace {

using C = BlockAvalancheConfig;
const auto kTable = std::to_array<kit::Param<C>>({
    {"block-distance", &C::blockDistance, "d", 0.0, 1e4,
     "gap between the slope's foot and the low block"},
    {"block-density", &C::density, "kg/m^3", 1.0, 1e5, "density of the two wooden blocks"},
    {"block-friction", &C::blockFriction, "", 0.0, 10.0,
     "friction between the blocks and with the floor (Bullet)"},
});

btVector3 halfExtents(const Vec3& size, float d) {
  return bullet::toBullet(0.5f * d * size);
}

// Particles the bridge samples from a box of `size` (d), counted by sampling it the same way.
std::uint32_t sampledParticles(const Vec3& size, float d) {
  const btBoxShape shape(halfExtents(size, d));
  const TriangleMesh mesh = bullet::shapeMesh(shape, bullet::CouplingOptions{}.maxChordError * d);
  return static_cast<std::uint32_t>(sampleMesh(mesh, d).centres.size());
}

}  // namespace

// Bullet's world with its floor and blocks, and the bridge to the sand.
struct BlockAvalanche::Blocks {
  struct Block {
    std::string name;
    btRigidBody* body;
    Vec3 start;
  };

  bullet::OwnedWorld physics;
  std::vector<Block> blocks;
  std::unique_ptr<bullet::Bridge> bridge;
  BlockAvalancheConfig config;  // as at build()

  Blocks(float floorY, const BlockAvalancheConfig& blockConfig, const Vec3& gravity)
      : physics(gravity), config(blockConfig) {
    physics.add(std::make_unique<btStaticPlaneShape>(btVector3(0, 1, 0), floorY), 0.0f,
                btTransform::getIdentity(), config.blockFriction);
  }

  void addBlock(std::string name, const btVector3& half, const btVector3& centre) {
    const float mass = config.density * 8.0f * float(half.x() * half.y() * half.z());
    btRigidBody* body =
        physics.add(std::make_unique<btBoxShape>(half), mass,
                    btTransform(btQuaternion::getIdentity(), centre), config.blockFriction);
    blocks.push_back({std::move(name), body, bullet::toSand(centre)});
  }
};

BlockAvalanche::BlockAvalanche() = default;
BlockAvalanche::~BlockAvalanche() = default;

std::vector<SceneParameter> BlockAvalanche::parameters() {
  std::vector<SceneParameter> out = SlopeAvalanche::parameters();
  for (SceneParameter& own : kit::bind<C>(kTable, m_blocksConfig)) out.push_back(std::move(own));
  return out;
}

WorldSettings BlockAvalanche::worldSettings() const {
  WorldSettings settings = SlopeAvalanche::worldSettings();
  settings.maxBodies += 2;
  settings.maxParticles +=
      sampledParticles(m_blocksConfig.lowBlock, d()) + sampledParticles(m_blocksConfig.plank, d());
  return settings;
}

void BlockAvalanche::build(World& world) {
  SlopeAvalanche::build(world);
  const float d = this->d();
  const float floorY = bounds().min.y;
  m_blocks.reset();  // the old bridge refers to the old World
  m_blocks = std::make_unique<Blocks>(floorY, m_blocksConfig, world.settings().gravity);
  const btVector3 low = halfExtents(m_blocksConfig.lowBlock, d);
  const btVector3 plank = halfExtents(m_blocksConfig.plank, d);
  const float foot = m_config.slopeLength * d;
  const float lowX = foot + m_blocksConfig.blockDistance * d + low.x();
  m_blocks->addBlock("low-block", low, btVector3(lowX, floorY + low.y(), 0.0f));
  m_blocks->addBlock("plank", plank, btVector3(lowX, floorY + 2.0f * low.y() + plank.y(), 0.0f));
  m_blocks->bridge = std::make_unique<bullet::Bridge>(world, m_blocks->physics.dynamics());
  m_surfaces.clear();
  for (Blocks::Block& block : m_blocks->blocks) m_blocks->bridge->couple(block.body);
  for (const bullet::Bridge::Coupled& c : m_blocks->bridge->coupled()) {
    m_surfaces.push_back({c.sandBody, c.surface, c.principalRotation, BodyMaterial::Wood});
  }
}

StepReport BlockAvalanche::step(World& world, float frameDt) {
  return m_blocks ? m_blocks->bridge->step(frameDt) : world.step(frameDt);
}

std::vector<RecordedInput> BlockAvalanche::externalInputs() const {
  return m_blocks ? m_blocks->bridge->pushes() : std::vector<RecordedInput>{};
}

std::vector<SceneBody> BlockAvalanche::blockBodies() const {
  std::vector<SceneBody> out;
  if (!m_blocks) return out;
  for (const Blocks::Block& block : m_blocks->blocks) {
    const btTransform& pose = block.body->getCenterOfMassTransform();
    // The blocks start upright: the tilt is the angle of the body's y axis from the world's.
    const btScalar up = std::clamp(pose.getBasis().getColumn(1).y(), btScalar(-1), btScalar(1));
    out.push_back({.name = block.name,
                   .position = bullet::toSand(pose.getOrigin()),
                   .orientation = bullet::toSand(pose.getRotation()),
                   .speed = float(block.body->getLinearVelocity().length()),
                   .tiltDegrees = float(std::acos(up) * 180.0 / std::numbers::pi)});
  }
  return out;
}

std::string BlockAvalanche::status() const {
  const std::vector<SceneBody> blocks = blockBodies();
  if (blocks.empty()) return SlopeAvalanche::status();
  const std::string degrees = std::to_string(int(blocks[1].tiltDegrees)) + " deg";
  if (!finished()) return SlopeAvalanche::status() + ", plank tilt " + degrees;
  // A plank leaning past 45 degrees has fallen: it cannot stand on its end again.
  return "came to rest; the plank " +
         std::string(blocks[1].tiltDegrees > 45.0f ? "toppled" : "still stands") + " (tilt " +
         degrees + ")";
}

std::vector<SceneMetric> BlockAvalanche::metrics(std::span<const BodyState> bodies) const {
  std::vector<SceneMetric> out = SlopeAvalanche::metrics(bodies);
  const std::vector<SceneBody> now = blockBodies();
  for (std::size_t i = 0; i < now.size(); ++i) {
    const Vec3 moved = now[i].position - m_blocks->blocks[i].start;
    std::string key = now[i].name;
    std::replace(key.begin(), key.end(), '-', '_');
    out.push_back({key + "_tilt_deg", now[i].tiltDegrees});
    out.push_back({key + "_displacement_m", std::hypot(moved.x, moved.y, moved.z)});
  }
  return out;
}

}  // namespace sandphys::scenes
