#include "sandphys/bullet/owned_world.h"

#include <BulletCollision/CollisionShapes/btCollisionShape.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <sandphys/bullet/conversions.h>

namespace sandphys::bullet {

OwnedWorld::OwnedWorld(const Vec3& gravity) {
  m_dynamics.setGravity(toBullet(gravity));
}

OwnedWorld::~OwnedWorld() {
  for (const std::unique_ptr<btRigidBody>& body : m_bodies) m_dynamics.removeRigidBody(body.get());
}

btRigidBody* OwnedWorld::add(btCollisionShape& shape, btScalar mass, const btTransform& pose,
                             btScalar friction) {
  btVector3 inertia(0, 0, 0);
  if (mass > 0) shape.calculateLocalInertia(mass, inertia);
  btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, &shape, inertia);
  info.m_startWorldTransform = pose;
  info.m_friction = friction;
  m_bodies.push_back(std::make_unique<btRigidBody>(info));
  m_dynamics.addRigidBody(m_bodies.back().get());
  return m_bodies.back().get();
}

btRigidBody* OwnedWorld::add(std::unique_ptr<btCollisionShape> shape, btScalar mass,
                             const btTransform& pose, btScalar friction) {
  m_shapes.push_back(std::move(shape));
  return add(*m_shapes.back(), mass, pose, friction);
}

}  // namespace sandphys::bullet
