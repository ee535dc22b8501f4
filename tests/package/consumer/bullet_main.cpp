// An outside program that uses the installed Bullet bridge: a Bullet box coupled to a sandphys
// World falls onto a bed of granules and comes to rest on it, carried by the sand. Exits
// non-zero otherwise.
#include <btBulletDynamicsCommon.h>

#include <sandphys/bullet/bridge.h>
#include <sandphys/sandphys.h>

#include <cmath>
#include <cstdio>
#include <exception>

int main() {
  try {
    sandphys::GpuContext gpu = sandphys::GpuContext::headless();
    sandphys::WorldSettings settings{.maxBodies = 64};
    settings.maxParticles = 64 * 4 + 2000;
    sandphys::World sand(gpu, settings);
    sand.addCollider(sandphys::Plane{});  // the floor, y = 0
    sand.addGranules(sandphys::GranuleBlock{
        .center = {0.0f, 0.03f, 0.0f}, .countX = 4, .countY = 1, .countZ = 4});

    btDefaultCollisionConfiguration configuration;
    btCollisionDispatcher dispatcher(&configuration);
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld dynamics(&dispatcher, &broadphase, &solver, &configuration);
    dynamics.setGravity(btVector3(0, -9.81f, 0));
    btBoxShape shape(btVector3(0.05f, 0.02f, 0.05f));
    const btScalar mass = 1.0f;
    btVector3 inertia;
    shape.calculateLocalInertia(mass, inertia);
    btDefaultMotionState motion(btTransform(btQuaternion::getIdentity(), btVector3(0, 0.1f, 0)));
    btRigidBody box(btRigidBody::btRigidBodyConstructionInfo(mass, &motion, &shape, inertia));
    dynamics.addRigidBody(&box);

    sandphys::bullet::Bridge bridge(sand, dynamics);
    bridge.couple(&box);
    for (int frame = 0; frame < 30; ++frame) bridge.step(1.0f / 60.0f);
    const float y = float(box.getCenterOfMassPosition().y());
    dynamics.removeRigidBody(&box);

    // Without the sand the box would have fallen through y = 0 (Bullet has no floor here): the
    // granules, one layer 2 d high, hold it up.
    if (!std::isfinite(y) || y < 0.02f || y > 0.1f) {
      std::fprintf(stderr, "FAIL: the box ended at y = %g m; on the sand it rests near 0.06 m\n",
                   y);
      return 1;
    }
    std::printf("ok: a Bullet box came down onto the sand and stays at y = %.3f m\n", y);
    return 0;
  } catch (const sandphys::Error& error) {
    std::fprintf(stderr, "FAIL: sandphys::Error: %s\n", error.what());
    return 1;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "FAIL: %s\n", error.what());
    return 1;
  }
}
