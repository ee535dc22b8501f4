#pragma once

#include <cstdint>
#include <vector>

#include <sandphys/sandphys.h>

class btDiscreteDynamicsWorld;
class btRigidBody;

namespace sandphys::bullet {

/// How the bridge exchanges state between the two worlds.
struct BridgeSettings {
  /// Simulated time between two exchanges of poses and forces, s; 0 = automatic, chosen at the
  /// start of every frame: the time in which the fastest point of any coupled body moves a tenth
  /// of a particle diameter, at most maxCouplingStep. See Bridge for why.
  float couplingStep = 0.0f;
  /// Upper end of the automatic coupling step, s (the stability bound in Bridge).
  float maxCouplingStep = 0.002f;
};

/// How a Bullet body is turned into sand-side particles.
struct CouplingOptions {
  /// Largest distance between neighbouring surface samples, m; 0 = kDefaultMeshSpacing particle
  /// diameters (see MeshSampling::spacing).
  float spacing = 0.0f;
  /// How closely a curved shape's facets follow it, in particle diameters.
  float maxChordError = 0.02f;
};

/// Two-way coupling of a sandphys World with a Bullet btDiscreteDynamicsWorld. Bullet owns every
/// coupled body and every contact between them; the sand sees each coupled body as a kinematic
/// (or, for Bullet's static bodies, static) body of particles sampled from its collision shape.
///
/// One exchange ("coupling step" of length h):
///  1. each coupled body's pose and velocities go from Bullet to the sand (World::setBodyState);
///  2. the sand runs its substeps for h, moving the body along with those velocities, and sums
///     the contact force and torque on it on the GPU;
///  3. the sums are read back (World::takeBodyForces, 32 bytes per body) and their means over
///     the substeps applied in Bullet (applyCentralForce, applyTorque); a body the sand computed
///     in none of them (it slept there with the sand around it, or the exchange ran no substep)
///     gets the force of the last exchange that computed it;
///  4. Bullet steps h (one fixed step), with its own gravity and contacts.
/// The scheme is explicit: during an exchange the body moves through the sand as if the sand did
/// not push it, and the push acts in Bullet one exchange late. Two things bound h:
///  - penetration: a body entering sand at speed v sinks v·h unopposed; the automatic h keeps
///    that to d/10 for the fastest point of any coupled body (|v| + |ω| r), the depth at which
///    the sand's own penetration guard starts to clamp;
///  - stability: the sand acts like a spring of stiffness K on a body of mass m, and the lagged
///    force stays stable while h < 2 / sqrt(K / m). Resting on sand, K ≈ 1.5 m g / δ (Hertz, δ
///    the bed's compression), so h < 2 sqrt(δ / 1.5 g): 0.5 ms needs δ > 0.1 µm, always true; a
///    very light body (a few granules' mass) hit hard, or a long h chosen by hand, breaks it.
///    couple() refuses bodies lighter than kMinMassInGranules granules, and the automatic h
///    never exceeds BridgeSettings::maxCouplingStep (2 ms: stable down to δ = 1.5 g (h/2)² =
///    15 µm of bed compression).
/// A frame therefore runs ceil(frameDt / h) exchanges, each with one small read-back.
class Bridge {
 public:
  /// Bodies lighter than this many sand granules are refused (see the stability bound above).
  static constexpr float kMinMassInGranules = 10.0f;

  /// Both worlds must outlive the bridge. Their gravities must agree (InvalidArgument names
  /// both): Bullet moves the coupled bodies under its own, the sand its granules under its own.
  Bridge(World& sand, btDiscreteDynamicsWorld& dynamics, const BridgeSettings& settings = {});

  /// Couples a body of the Bullet world by sampling its own collision shape. Dynamic Bullet
  /// bodies become kinematic sand bodies; static ones (mass 0) static sand bodies. Throws
  /// sandphys::Error: a shape that cannot be sampled, a body lighter than kMinMassInGranules
  /// granules, a body already coupled, no room in the World (nothing is added then).
  BodyId couple(btRigidBody* body, const CouplingOptions& options = {});
  /// The same with a given surface (in the body's centre-of-mass frame) instead of the shape's.
  BodyId couple(btRigidBody* body, const TriangleMesh& surface,
                const CouplingOptions& options = {});

  /// Advances both worlds by `frameDt` s in coupling steps (see above); does not call Bullet's
  /// stepSimulation otherwise, so the application must not step Bullet itself. Returns the sand's
  /// report of the whole frame (substeps and times summed, statistics of the last exchange).
  StepReport step(float frameDt);

  /// The coupling step of the last step() (or, before any, of a body at rest), s, and how many
  /// exchanges that step() ran.
  float couplingStep() const { return m_lastStep; }
  int exchanges() const { return m_lastExchanges; }

  /// Every pose and velocity the last step() pushed to the sand, in order (each exchange pushes
  /// every coupled body that moves, and not one that Bullet has put to sleep: see Coupled::asleep):
  /// the inputs a recording keeps from Bullet.
  const std::vector<RecordedInput>& pushes() const { return m_pushes; }

  /// What the sand did to one coupled body over the last frame.
  struct Coupled {
    btRigidBody* body = nullptr;
    BodyId sandBody;
    std::uint32_t particles = 0;
    Vec3 force{};        ///< mean sand force over the last step(), N
    Vec3 torque{};       ///< mean sand torque about the centre of mass over the last step(), N m
    float reach = 0.0f;  ///< farthest particle surface from the centre of mass, m
    /// Bullet has deactivated the body: the bridge pushed it once at rest and pushes it no more,
    /// so sand that sleeps around it stays asleep, and so does the sand body. The sand wakes it
    /// (btRigidBody::activate) when its force or torque on it departs from what it was when the
    /// body fell asleep by more than the sand's wake acceleration (SleepModel::wakeAcceleration, or
    /// the default kSleepWakeAcceleration g without sleep) times its mass (and reach, for the
    /// torque).
    bool asleep = false;
    Vec3 restForce{};   ///< the sand force when it fell asleep, N
    Vec3 restTorque{};  ///< the sand torque then, N m
    /// The surface the particles were sampled from, about the sand body's centre of mass in the
    /// frame BodyDesc::orientation turns (Bullet's centre-of-mass frame), m: what to draw.
    TriangleMesh surface;
    /// The sand body's ParticleTemplate::principalRotation.
    Quat principalRotation{};
  };
  const std::vector<Coupled>& coupled() const { return m_coupled; }
  /// The entry of `body`, or nullptr when it is not coupled.
  const Coupled* find(const btRigidBody* body) const;

 private:
  float automaticStep() const;
  void pushPoses();
  void applySandForces(double weight);

  World& m_sand;
  btDiscreteDynamicsWorld& m_dynamics;
  BridgeSettings m_settings;
  float m_wakeAcceleration = 0.0f;  // m/s^2 (Coupled::asleep)
  std::vector<Vec3> m_lastForce;    // each body's mean sand force, the last one computed, N
  std::vector<Vec3> m_lastTorque;   // and torque, N m
  float m_lastStep = 0.0f;
  int m_lastExchanges = 0;
  std::vector<Coupled> m_coupled;
  std::vector<Vec3> m_frameForce;
  std::vector<Vec3> m_frameTorque;
  std::vector<RecordedInput> m_pushes;
};

}  // namespace sandphys::bullet
