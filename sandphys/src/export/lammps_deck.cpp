#include "export/lammps_deck.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <variant>

#include "core/impact.h"
#include "core/world_access.h"

namespace sandphys::detail {

namespace {

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", v);
  return text;
}

std::string vec(Vec3 v) {
  return number(v.x) + ' ' + number(v.y) + ' ' + number(v.z);
}

// The restitution to give LAMMPS's `damping tsuji` so that its impact rebounds with `e`. LAMMPS
// turns it into the damping factor with Tsuji's fit alpha(e) and lets the damping pull at the
// end of a contact (core/impact.h), so the e it is given is not the e it produces: the factor
// that produces e in that impact, then the e whose alpha is that factor (alpha falls from 1.27
// at 0 to 0.0003 at 1).
double tsujiRestitution(double e) {
  const double factor = adhesiveHertzDampingFactor(e);
  auto alpha = [](double x) {
    return 1.2728 - 4.2783 * x + 11.087 * x * x - 22.348 * std::pow(x, 3) +
           27.467 * std::pow(x, 4) - 18.022 * std::pow(x, 5) + 4.8218 * std::pow(x, 6);
  };
  if (factor >= alpha(0.0)) return 0.0;
  if (factor <= alpha(1.0)) return 1.0;
  double lo = 0.0;
  double hi = 1.0;
  for (int i = 0; i < 48; ++i) {
    const double mid = 0.5 * (lo + hi);
    (alpha(mid) > factor ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

bool moves(const ColliderMotion& m) {
  return !(m.velocity == Vec3{}) || !(m.angularVelocity == Vec3{});
}

// The stiffness coefficients of pair granular's `hertz` and `tangential mindlin`, which LAMMPS
// multiplies by the contact radius a = sqrt(R* ξ): sandphys's k_n and k_t0 (which include
// sqrt(R*)) over sqrt(R*). Given explicitly, not as hertz/material, because fix wall/gran of
// LAMMPS 7 Jan 2022 derives a wall's moduli from E and ν with other formulas than its pairs
// (docs/lammps.md).
struct Contact {
  double kn = 0.0;
  double kt = 0.0;
  double restitution = 0.0;
  double friction = 0.0;
  std::string text() const {
    return "hertz " + number(kn) + ' ' + number(tsujiRestitution(restitution)) +
           " tangential mindlin " + number(kt) + " 1.0 " + number(friction) + " damping tsuji";
  }
};

// Writes collider k as a region and a granular wall on the clumps; says in `notes` what differs.
class WallWriter {
 public:
  WallWriter(std::ostringstream& out, std::vector<std::string>& notes, const ContactModel& model,
             const LammpsScene& scene)
      : m_out(out), m_notes(notes), m_scene(scene) {
    const double wallRadius = std::sqrt(double(model.radius));
    m_kn = model.stiffnessWall / wallRadius;
    m_kt = model.shearStiffnessWall / wallRadius;
  }

  void write(std::uint32_t k, const ColliderShape& shape) {
    const std::string region = "wall" + std::to_string(k);
    std::visit([&](const auto& s) { writeRegion(region, k, s); }, shape);
    std::visit(
        [&](const auto& s) {
          const Contact contact{m_kn, m_kt, s.material.restitution, s.material.friction};
          m_out << "fix " << region << " clumps wall/gran/region granular " << contact.text()
                << " region " << region << '\n';
          if (moves(s.motion)) {
            m_notes.push_back("collider " + std::to_string(k) +
                              ": its surface moves in sandphys (ColliderMotion velocity " +
                              vec(s.motion.velocity) + " m/s, spin " +
                              vec(s.motion.angularVelocity) + " rad/s); here it stands still");
          }
        },
        shape);
  }

 private:
  void writeRegion(const std::string& region, std::uint32_t, const Plane& p) {
    const Vec3 n = normalized(p.normal);
    const float offset = p.offset / length(p.normal);
    m_out << "region " << region << " plane " << vec(offset * n) << ' ' << vec(n) << " side in\n";
  }

  void writeRegion(const std::string& region, std::uint32_t, const Box& b) {
    const Vec3 lo = b.center - b.halfExtents;
    const Vec3 hi = b.center + b.halfExtents;
    m_out << "region " << region << " block " << number(lo.x) << ' ' << number(hi.x) << ' '
          << number(lo.y) << ' ' << number(hi.y) << ' ' << number(lo.z) << ' ' << number(hi.z)
          << " side " << (b.inside ? "in" : "out");
    const Quat q = b.orientation;
    const double sine = std::sqrt(double(q.x) * q.x + double(q.y) * q.y + double(q.z) * q.z);
    if (sine > 0.0) {
      // A turned box: the block turned about its centre by a constant angle.
      const double angle = 2.0 * std::atan2(sine, double(q.w));
      m_out << " rotate v_" << region << "_angle " << vec(b.center) << ' ' << number(q.x / sine)
            << ' ' << number(q.y / sine) << ' ' << number(q.z / sine);
      m_preamble << "variable " << region << "_angle equal " << number(angle) << '\n';
    }
    m_out << '\n';
  }

  void writeRegion(const std::string& region, std::uint32_t k, const Cylinder& c) {
    m_out << "region " << region << " cylinder y " << number(c.base.x) << ' ' << number(c.base.z)
          << ' ' << number(c.radius) << ' ' << number(c.base.y) << ' '
          << number(c.base.y + c.height) << " side in open 1 open 2\n";
    noteOutside(k, "cylinder", [&](const Vec3d& x) {
      return std::hypot(x[0] - c.base.x, x[2] - c.base.z) > c.radius;
    });
  }

  void writeRegion(const std::string& region, std::uint32_t k, const Funnel& f) {
    const double top = f.outletRadius + f.height * std::tan(double(f.halfAngle));
    m_out << "region " << region << " cone y " << number(f.outletCenter.x) << ' '
          << number(f.outletCenter.z) << ' ' << number(f.outletRadius) << ' ' << number(top) << ' '
          << number(f.outletCenter.y) << ' ' << number(f.outletCenter.y + f.height)
          << " side in open 1 open 2\n";
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
  double m_kn = 0.0;
  double m_kt = 0.0;
};

}  // namespace

LammpsDeck composeLammpsDeck(const World& world, const LammpsScene& scene,
                             const LammpsExportOptions& options) {
  const World::Impl& w = WorldAccess::impl(world);
  const WorldSettings& settings = w.settings;
  const ContactModel& model = w.model;
  const double d = settings.particleDiameter;
  const double dt = model.timeStep;
  LammpsDeck deck;
  std::vector<std::string>& notes = deck.notMapped;

  // The box of the data file: every particle with room around it; the deck shrink-wraps it
  // (boundary m), so that nothing is lost when grains leave it.
  for (int k = 0; k < 3; ++k) {
    const bool empty = scene.atoms.empty();
    deck.box[0][k] = (empty ? 0.0 : scene.lo[k]) - 2.0 * d;
    deck.box[1][k] = (empty ? 0.0 : scene.hi[k]) + 2.0 * d;
  }
  const double skin = std::max(double(model.listSkin), 0.1 * d);
  // fix rigid/small needs every particle of a clump within the ghost cutoff of its owner.
  const double ghostCutoff = std::max(2.0 * scene.largestClumpRadius + d + skin, 2.0 * d);
  const Contact grain{model.stiffnessGrain / std::sqrt(0.5 * model.radius),
                      model.shearStiffnessGrain / std::sqrt(0.5 * model.radius),
                      settings.material.restitution, settings.material.friction};
  const double g = length(settings.gravity);
  const bool verticalY = g > 0.0 && std::abs(settings.gravity.y) > 0.99 * g;

  if (settings.contactLaw == ContactLaw::PaperViscous) {
    notes.push_back(
        "ContactLaw::PaperViscous (the paper's law) has no LAMMPS counterpart; the deck uses "
        "Hertz-Mindlin with the same E, nu, e and mu");
  }
  notes.push_back(
      "contact history: tangential springs start from zero (sandphys keeps them per contact; "
      "LAMMPS builds its own from the first step)");
  notes.push_back(
      "damping: LAMMPS lets the damping pull at the end of a contact (sandphys does not), so "
      "damping tsuji is given the e that rebounds a lone particle at sandphys's restitution "
      "(docs/lammps.md); and sandphys shares two bodies' masses among the n contacts that join "
      "them, m* = 1 / (n (1/M_A + 1/M_B)), where LAMMPS takes M_A M_B / (M_A + M_B) for each, so "
      "a clump touching a body at n points is damped sqrt(n) times harder here");
  notes.push_back("speed guard: sandphys clamps bodies at maxSpeed " + number(settings.maxSpeed) +
                  " m/s; LAMMPS does not clamp");
  if (scene.kinematicBodies > 0) {
    notes.push_back(std::to_string(scene.kinematicBodies) +
                    " kinematic bodies (moved by a script or another engine, e.g. the Bullet "
                    "bridge's) are frozen particles where they stand");
  }
  if (scene.sleepingGranules > 0) {
    notes.push_back(std::to_string(scene.sleepingGranules) +
                    " sleeping granules are awake here: LAMMPS has no sleep");
  }
  for (const detail::KinematicPath& path : w.moves) {
    if (path.plan.endStep > w.steps) {
      notes.push_back("kinematic move of body slot " + std::to_string(path.body) + " (to substep " +
                      std::to_string(path.plan.endStep) + ") is not run");
    }
  }
  for (std::size_t k = 0; k < w.emitters.size(); ++k) {
    if (!w.emitters[k] || w.emitters[k]->finished()) continue;
    const EmitterSettings& e = w.emitters[k]->settings();
    notes.push_back("emitter " + std::to_string(k) + " (centre " + vec(e.center) + " m, " +
                    number(e.rate) + " granules/s, " + std::to_string(w.emitters[k]->emitted()) +
                    " of " + std::to_string(e.maxGranules) +
                    " emitted) is not run: fix pour with a molecule template would be the nearest");
  }
  notes.insert(notes.end(), options.notes.begin(), options.notes.end());

  std::ostringstream body;
  WallWriter walls(body, notes, model, scene);
  const std::vector<ColliderShape>& colliders = w.colliderShapes;
  body << "\n# Colliders: granular region walls on the clumps (sandphys treats them as rigid).\n";
  for (std::uint32_t k = 0; k < colliders.size(); ++k) walls.write(k, colliders[k]);
  deck.walls = static_cast<std::uint32_t>(colliders.size());

  std::ostringstream out;
  out << "\nvariable seconds index " << number(options.runSeconds) << '\n'
      << "variable dt equal " << number(dt) << '\n'
      << "variable steps equal round(v_seconds/v_dt)\n"
      << "variable every equal " << std::max<long long>(1, std::llround(options.outputSeconds / dt))
      << "\n\n"
      << "units si\natom_style hybrid sphere molecular\natom_modify map array\n"
      << "boundary m m m\nnewton on\ncomm_modify vel yes cutoff " << number(ghostCutoff) << '\n'
      << (verticalY ? "# Ranks split the scene across gravity, not along it.\nprocessors * 1 *\n"
                    : "")
      << "read_data sandphys.data\n"
      << "group clumps type 1\ngroup frozen type 2\n"
      << "timestep ${dt}\n"
      << "neighbor " << number(skin) << " bin\n"
      << "neigh_modify delay 0 every 1 check yes exclude molecule/intra clumps exclude type 2 2\n"
      << "\n# Grains: sandphys ContactLaw::HertzMindlin, E = "
      << number(settings.material.youngsModulus)
      << " Pa, nu = " << number(settings.material.poissonRatio)
      << ", e = " << number(settings.material.restitution)
      << ", mu = " << number(settings.material.friction) << ", d = " << number(d)
      << " m.\npair_style granular\npair_coeff * * " << grain.text() << '\n'
      << "fix freeze frozen freeze\n";
  if (!scene.clumps.empty()) {
    // Gravity on each clump's own mass at its centre of mass (the infile's), not on its
    // particles, whose masses and centre only approximate a sampled body's.
    out << "fix gravity clumps gravity " << number(g) << " vector "
        << vec(g > 0.0 ? settings.gravity / float(g) : Vec3{0.0f, -1.0f, 0.0f}) << " disable\n"
        << "fix rigid clumps rigid/small molecule infile bodies.rigid gravity gravity\n";
  }
  out << walls.m_preamble.str() << body.str();
  if (!w.sinks.empty() && !scene.clumps.empty()) {
    out << "\n# Sinks: whole clumps with a particle in the box are deleted, every 10 substeps.\n";
    for (std::size_t k = 0; k < w.sinks.size(); ++k) {
      const GpuSink& sink = w.sinks[k];
      const std::string name = "sink" + std::to_string(k);
      out << "region " << name << " block " << number(sink.lo.x) << ' ' << number(sink.hi.x) << ' '
          << number(sink.lo.y) << ' ' << number(sink.hi.y) << ' ' << number(sink.lo.z) << ' '
          << number(sink.hi.z) << '\n'
          << "fix " << name << " clumps evaporate 10 " << scene.clumpAtoms << ' ' << name << ' '
          << 1 + k << " molecule yes\n";
    }
    notes.push_back(
        "sinks: sandphys removes a granule when its centre of mass enters a sink; fix evaporate "
        "removes a clump with any particle in it, checked every 10 substeps");
  }
  deck.sinks = static_cast<std::uint32_t>(w.sinks.size());
  out << "\n# Output: thermo every ${every} substeps (the clumps' kinetic energy, J; particle\n"
      << "# pairs in contact; their mean normal force, N), the particles every 10 thermo lines,\n"
      << "# and the particles at the end (final.dump).\n"
      << "compute contacts all contact/atom\n"
      << "compute contactsum all reduce sum c_contacts\n"
      << "variable contacts equal c_contactsum/2\n"
      << "compute pairs all pair/local force\n"
      << "compute meanforce all reduce ave c_pairs\n";
  if (!scene.clumps.empty()) {
    out << "compute translation clumps ke/rigid rigid\n"
        << "compute rotation clumps erotate/rigid rigid\n"
        << "variable energy equal c_translation+c_rotation\n";
  } else {
    out << "variable energy equal 0\n";
  }
  out << "thermo_style custom step time atoms v_energy v_contacts c_meanforce\n"
      << "thermo_modify norm no format float %.9g\n"
      << "thermo ${every}\n"
      << "dump trajectory all custom $(10*v_every) traj.dump id mol type x y z\n"
      << "run ${steps}\n"
      << "write_dump all custom final.dump id mol type x y z vx vy vz modify sort id\n";

  std::ostringstream header;
  header << "# sandphys World exported for LAMMPS (docs/lammps.md in the sandphys sources).\n"
         << "# Needs the GRANULAR, RIGID and MOLECULE packages (Debian's lammps has them).\n"
         << "#   lmp -in in.sandphys                  on one process\n"
         << "#   mpirun -np N lmp -in in.sandphys     on N ranks\n"
         << "#   lmp -in in.sandphys -var seconds S   for another simulated span than "
         << number(options.runSeconds) << " s\n"
         << "# Exported at substep " << w.steps << " (t = " << number(w.simTime)
         << " s): " << scene.clumps.size() << " rigid clumps of " << scene.clumpAtoms
         << " particles (molecule k is the k-th alive dynamic body in sandphys's body slots), "
         << scene.atoms.size() - scene.clumpAtoms << " frozen particles (" << scene.staticBodies
         << " static, " << scene.kinematicBodies << " kinematic bodies), " << colliders.size()
         << " walls, " << w.sinks.size() << " sinks.\n#\n# Not mapped, and what it became:\n";
  for (const std::string& note : notes) header << "#   - " << note << '\n';
  deck.text = header.str() + out.str();
  return deck;
}

}  // namespace sandphys::detail
