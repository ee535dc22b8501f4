#include "export/lammps_deck.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <variant>

#include "core/world_access.h"
#include "export/lammps_text.h"
#include "export/lammps_walls.h"

namespace sandphys::detail {

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
  const double g = length(settings.gravity);
  // Rolling friction's spring and damping, constant in LAMMPS, at the overlap one granule's
  // weight makes (without gravity, a granule's at maxSpeed).
  const double rollingFriction = settings.material.rollingFriction;
  const double weight = double(model.granuleMass) * g;
  auto restingOverlap = [&](double kn, double peak) {
    return weight > 0.0 ? hertzRestingOverlap(weight, kn) : peak;
  };
  const double grainOverlap = restingOverlap(model.stiffnessGrain, model.peakOverlapGrain);
  const double wallOverlap = restingOverlap(model.stiffnessWall, model.peakOverlapWall);
  const std::string grain = lammpsContact(
      model.stiffnessGrain / std::sqrt(0.5 * model.radius),
      model.shearStiffnessGrain / std::sqrt(0.5 * model.radius), settings.material.restitution,
      settings.material.friction,
      lammpsRolling(model.stiffnessGrain, model.shearStiffnessGrain, model.dampingFactorGrain,
                    0.5 * model.granuleMass, grainOverlap, rollingFriction));
  if (rollingFriction > 0.0) {
    notes.push_back(
        "rolling friction: rolling sds with sandphys's k_t and damping at the overlap of one "
        "granule's weight (" +
        lammpsNumber(grainOverlap) + " m between grains, " + lammpsNumber(wallOverlap) +
        " m on a wall), where sandphys scales both with the overlap as its tangential spring");
  }
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
  notes.push_back("speed guard: sandphys clamps bodies at maxSpeed " +
                  lammpsNumber(settings.maxSpeed) + " m/s; LAMMPS does not clamp");
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
    notes.push_back("emitter " + std::to_string(k) + " (centre " + lammpsVector(e.center) + " m, " +
                    lammpsNumber(e.rate) + " granules/s, " +
                    std::to_string(w.emitters[k]->emitted()) + " of " +
                    std::to_string(e.maxGranules) +
                    " emitted) is not run: fix pour with a molecule template would be the nearest");
  }
  notes.insert(notes.end(), options.notes.begin(), options.notes.end());

  const std::vector<ColliderShape>& colliders = w.colliderShapes;
  const LammpsWalls walls =
      lammpsWalls(colliders, model, scene, rollingFriction, wallOverlap, notes);
  deck.walls = static_cast<std::uint32_t>(colliders.size());

  std::ostringstream out;
  out << "\nvariable seconds index " << lammpsNumber(options.runSeconds) << '\n'
      << "variable dt equal " << lammpsNumber(dt) << '\n'
      << "variable steps equal round(v_seconds/v_dt)\n"
      << "variable every equal " << std::max<long long>(1, std::llround(options.outputSeconds / dt))
      << "\n\n"
      << "units si\natom_style hybrid sphere molecular\natom_modify map array\n"
      << "boundary m m m\nnewton on\ncomm_modify vel yes cutoff " << lammpsNumber(ghostCutoff)
      << '\n'
      << (verticalY ? "# Ranks split the scene across gravity, not along it.\nprocessors * 1 *\n"
                    : "")
      << "read_data sandphys.data\n"
      << "group clumps type 1\ngroup frozen type 2\n"
      << "timestep ${dt}\n"
      << "neighbor " << lammpsNumber(skin) << " bin\n"
      << "neigh_modify delay 0 every 1 check yes exclude molecule/intra clumps exclude type 2 2\n"
      << "\n# Grains: sandphys ContactLaw::HertzMindlin, E = "
      << lammpsNumber(settings.material.youngsModulus)
      << " Pa, nu = " << lammpsNumber(settings.material.poissonRatio)
      << ", e = " << lammpsNumber(settings.material.restitution)
      << ", mu = " << lammpsNumber(settings.material.friction) << ", d = " << lammpsNumber(d)
      << " m.\npair_style granular\npair_coeff * * " << grain << '\n'
      << "fix freeze frozen freeze\n";
  if (!scene.clumps.empty()) {
    // Gravity on each clump's own mass at its centre of mass (the infile's), not on its
    // particles, whose masses and centre only approximate a sampled body's.
    out << "fix gravity clumps gravity " << lammpsNumber(g) << " vector "
        << lammpsVector(g > 0.0 ? settings.gravity / float(g) : Vec3{0.0f, -1.0f, 0.0f})
        << " disable\n"
        << "fix rigid clumps rigid/small molecule infile bodies.rigid gravity gravity\n";
  }
  out << walls.variables
      << "\n# Colliders: granular region walls on the clumps (sandphys treats them as rigid).\n"
      << walls.walls;
  if (!w.sinks.empty() && !scene.clumps.empty()) {
    out << "\n# Sinks: whole clumps with a particle in the box are deleted, every 10 substeps.\n";
    for (std::size_t k = 0; k < w.sinks.size(); ++k) {
      const GpuSink& sink = w.sinks[k];
      const std::string name = "sink" + std::to_string(k);
      out << "region " << name << " block " << lammpsNumber(sink.lo.x) << ' '
          << lammpsNumber(sink.hi.x) << ' ' << lammpsNumber(sink.lo.y) << ' '
          << lammpsNumber(sink.hi.y) << ' ' << lammpsNumber(sink.lo.z) << ' '
          << lammpsNumber(sink.hi.z) << '\n'
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
         << lammpsNumber(options.runSeconds) << " s\n"
         << "# Exported at substep " << w.steps << " (t = " << lammpsNumber(w.simTime)
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
