#pragma once

#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h>
#include <BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolver.h>
#include <BulletDynamics/Dynamics/btDiscreteDynamicsWorld.h>

#include <memory>
#include <vector>

#include <sandphys/sandphys.h>

class btCollisionShape;
class btRigidBody;

namespace sandphys::bullet {

/// A Bullet dynamics world with Bullet's default parts (collision configuration, dispatcher,
/// DBVT broadphase, sequential-impulse solver), which keeps the rigid bodies added through it:
/// for a program, sample or test that has no Bullet world of its own to couple to the sand. An
/// engine that has one hands that to Bridge instead.
class OwnedWorld {
 public:
  /// `gravity`, m/s²: the sand's (Bridge refuses two different gravities).
  explicit OwnedWorld(const Vec3& gravity = WorldSettings{}.gravity);
  /// Takes its bodies out of the world before they go.
  ~OwnedWorld();
  OwnedWorld(const OwnedWorld&) = delete;
  OwnedWorld& operator=(const OwnedWorld&) = delete;

  btDiscreteDynamicsWorld& dynamics() { return m_dynamics; }

  /// Adds a rigid body of `shape` (which must outlive this world), `mass` kg (0: static) and its
  /// inertia from the shape, at `pose`, with Bullet's `friction` coefficient; no motion state, so
  /// the body's own transform is its pose.
  btRigidBody* add(btCollisionShape& shape, btScalar mass, const btTransform& pose,
                   btScalar friction = 0.5f);
  /// The same for a shape the world keeps.
  btRigidBody* add(std::unique_ptr<btCollisionShape> shape, btScalar mass, const btTransform& pose,
                   btScalar friction = 0.5f);

 private:
  btDefaultCollisionConfiguration m_configuration;
  btCollisionDispatcher m_dispatcher{&m_configuration};
  btDbvtBroadphase m_broadphase;
  btSequentialImpulseConstraintSolver m_solver;
  btDiscreteDynamicsWorld m_dynamics{&m_dispatcher, &m_broadphase, &m_solver, &m_configuration};
  std::vector<std::unique_ptr<btCollisionShape>> m_shapes;
  std::vector<std::unique_ptr<btRigidBody>> m_bodies;
};

}  // namespace sandphys::bullet
