#include "export/lammps_walls.h"

#include <algorithm>
#include <cmath>
#include <variant>

#include "export/lammps_text.h"

namespace sandphys::detail {

namespace {

bool moves(const ColliderMotion& m) {
  return !(m.velocity == Vec3{}) || !(m.angularVelocity == Vec3{});
}

// Writes collider k as a region and a granular wall on the clumps; says in `notes` what differs.
class WallWriter {
 public:
  WallWriter(std::ostringstream& out, std::vector<std::string>& notes, const ContactModel& model,
             const LammpsScene& scene, double rollingFriction, double rollingOverlap)
      : m_out(out),
        m_notes(notes),
        m_scene(scene),
        m_model(model),
        m_rollingFriction(rollingFriction),
        m_rollingOverlap(rollingOverlap) {
    const double wallRadius = std::sqrt(double(model.radius));
    m_kn = model.stiffnessWall / wallRadius;
    m_kt = model.shearStiffnessWall / wallRadius;
  }

  // A granule on a rigid wall: m* = the granule's mass, the damping for the wall's restitution.
  std::string rolling(double restitution) const {
    return lammpsRolling(m_model.stiffnessWall, m_model.shearStiffnessWall,
                         hertzDampingFactor(restitution), m_model.granuleMass, m_rollingOverlap,
                         m_rollingFriction);
  }

  void write(std::uint32_t k, const ColliderShape& shape) {
    const std::string region = "wall" + std::to_string(k);
    std::visit([&](const auto& s) { writeRegion(region, k, s); }, shape);
    std::visit(
        [&](const auto& s) {
          m_out << "fix " << region << " clumps wall/gran/region granular "
                << lammpsContact(m_kn, m_kt, s.material.restitution, s.material.friction,
                                 rolling(s.material.restitution))
                << " region " << region << '\n';
          if (moves(s.motion)) {
            m_notes.push_back("collider " + std::to_string(k) +
                              ": its surface moves in sandphys (ColliderMotion velocity " +
                              lammpsVector(s.motion.velocity) + " m/s, spin " +
                              lammpsVector(s.motion.angularVelocity) +
                              " rad/s); here it stands still");
          }
        },
        shape);
  }

 private:
  void writeRegion(const std::string& region, std::uint32_t, const Plane& p) {
    const Vec3 n = normalized(p.normal);
    const float offset = p.offset / length(p.normal);
    m_out << "region " << region << " plane " << lammpsVector(offset * n) << ' ' << lammpsVector(n)
          << " side in\n";
  }

  void writeRegion(const std::string& region, std::uint32_t, const Box& b) {
    const Vec3 lo = b.center - b.halfExtents;
    const Vec3 hi = b.center + b.halfExtents;
    m_out << "region " << region << " block " << lammpsNumber(lo.x) << ' ' << lammpsNumber(hi.x)
          << ' ' << lammpsNumber(lo.y) << ' ' << lammpsNumber(hi.y) << ' ' << lammpsNumber(lo.z)
          << ' ' << lammpsNumber(hi.z) << " side " << (b.inside ? "in" : "out");
    const Quat q = b.orientation;
    const double sine = std::sqrt(double(q.x) * q.x + double(q.y) * q.y + double(q.z) * q.z);
    if (sine > 0.0) {
      // A turned box: the block turned about its centre by a constant angle.
      const double angle = 2.0 * std::atan2(sine, double(q.w));
      m_out << " rotate v_" << region << "_angle " << lammpsVector(b.center) << ' '
            << lammpsNumber(q.x / sine) << ' ' << lammpsNumber(q.y / sine) << ' '
            << lammpsNumber(q.z / sine);
      m_preamble << "variable " << region << "_angle equal " << lammpsNumber(angle) << '\n';
    }
    m_out << '\n';
  }

  void writeRegion(const std::string& region, std::uint32_t k, const Cylinder& c) {
    m_out << "region " << region << " cylinder y " << lammpsNumber(c.base.x) << ' '
          << lammpsNumber(c.base.z) << ' ' << lammpsNumber(c.radius) << ' '
          << lammpsNumber(c.base.y) << ' ' << lammpsNumber(c.base.y + c.height)
          << " side in open 1 open 2\n";
    noteOutside(k, "cylinder", [&](const Vec3d& x) {
      return std::hypot(x[0] - c.base.x, x[2] - c.base.z) > c.radius;
    });
  }

  void writeRegion(const std::string& region, std::uint32_t k, const Funnel& f) {
    const double top = f.outletRadius + f.height * std::tan(double(f.halfAngle));
    m_out << "region " << region << " cone y " << lammpsNumber(f.outletCenter.x) << ' '
          << lammpsNumber(f.outletCenter.z) << ' ' << lammpsNumber(f.outletRadius) << ' '
          << lammpsNumber(top) << ' ' << lammpsNumber(f.outletCenter.y) << ' '
          << lammpsNumber(f.outletCenter.y + f.height) << " side in open 1 open 2\n";
    noteOutside(k, "funnel", [&](const Vec3d& x) {
      const double h = std::clamp((x[1] - f.outletCenter.y) / f.height, 0.0, 1.0);
      const double radius = f.outletRadius + h * (top - f.outletRadius);
      return std::hypot(x[0] - f.outletCenter.x, x[2] - f.outletCenter.z) > radius &&
             x[1] > f.outletCenter.y && x[1] < f.outletCenter.y + f.height;
    });
  }

  // sandphys's cylinder and funnel walls are thin and hold grains on both sides; a LAMMPS region
  // wall has one side, the inside.
  template <typename Outside>
  void noteOutside(std::uint32_t k, const char* kind, Outside outside) {
    std::uint32_t count = 0;
    for (std::uint32_t i = 0; i < m_scene.clumpAtoms; ++i)
      count += outside(m_scene.atoms[i].position);
    if (count > 0) {
      m_notes.push_back("collider " + std::to_string(k) + " (" + kind +
                        "): " + std::to_string(count) +
                        " clump particles lie outside it; the region wall holds grains inside "
                        "only, so from outside they pass through it");
    }
  }

 public:
  std::ostringstream m_preamble;  // variables the regions name, written before them

 private:
  std::ostringstream& m_out;
  std::vector<std::string>& m_notes;
  const LammpsScene& m_scene;
  const ContactModel& m_model;
  double m_rollingFriction;
  double m_rollingOverlap;
  double m_kn = 0.0;
  double m_kt = 0.0;
};

}  // namespace

LammpsWalls lammpsWalls(const std::vector<ColliderShape>& colliders, const ContactModel& model,
                        const LammpsScene& scene, double rollingFriction, double rollingOverlap,
                        std::vector<std::string>& notes) {
  std::ostringstream out;
  WallWriter writer(out, notes, model, scene, rollingFriction, rollingOverlap);
  for (std::uint32_t k = 0; k < colliders.size(); ++k) writer.write(k, colliders[k]);
  return {writer.m_preamble.str(), out.str()};
}

}  // namespace sandphys::detail
