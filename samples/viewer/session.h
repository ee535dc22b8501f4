#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include <sandphys/sandphys.h>

#include "app/recording.h"
#include "app/sand_tools.h"
#include "scenes/registry.h"
#include "scenes/scene.h"
#include "viewer/frame_pacer.h"
#include "viewer/frame_stats.h"

namespace sandphys::viewer {

using samples::Ray;
using samples::SandTools;

/// Material and time-step values the panel edits. They apply at the next restart, because they
/// set the World's contact law and time step, which are fixed at creation; kernel profiling and
/// the drawing switches apply at the next frame.
struct SimulationControls {
  float youngsModulus = 5.0e6f;   ///< Pa
  float friction = 0.5f;          ///< Coulomb μ between grains
  float restitution = 0.5f;       ///< grain-grain
  float stepsPerContact = 20.0f;  ///< substeps per Hertz contact duration t_n
  double frameDt = 1.0 / 60.0;    ///< simulated seconds per viewer frame
  /// GL timer queries around every kernel (World::kernelTimes), switched at the next frame
  /// (World::setProfileKernels). Off by default: on llvmpipe the queries about double the cost of
  /// a substep.
  bool profileKernels = false;
  /// Sleeping sand (WorldSettings::sleep).
  bool sleep = false;
  /// Draw sleeping granules tinted (takes effect at once, not at a restart).
  bool tintSleeping = true;
  /// Draw the bodies that have a surface (Scene::surfaces) as their particles, as the sand sees
  /// them (takes effect at once).
  bool bodyParticles = false;

  /// The values `settings` (a scene's) and `frameDt` give.
  static SimulationControls from(const WorldSettings& settings, double frameDt);
  /// `settings` with these values in place.
  WorldSettings applyTo(WorldSettings settings) const;
};

/// One scene running in a World on the viewer's context, with the sand tools attached, paced
/// by a FramePacer. A restart builds the scene again on a fresh World.
class Session {
 public:
  /// Starts `scene` (already configured, e.g. by the command line) at `frameDt` s per frame,
  /// stepped as `pacer` decides.
  Session(const GpuContext& gpu, std::unique_ptr<scenes::Scene> scene, double frameDt,
          FramePacer pacer = {});
  /// Finishes a recording that is still running.
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  /// Records the run (--record) from its start, which must be now: right after construction or
  /// a restart, before any frame. Every frame's duration (the pacer's, in slow motion) and the
  /// sand tools' input go into `file` (docs/recording.md), which a headless --replay checks. The
  /// recording ends at the next restart or scene switch, or with the session. Throws
  /// sandphys::Error naming the file when it cannot be written.
  void startRecording(const std::filesystem::path& file, std::uint64_t snapshotEvery);
  /// Whether a recording is running, and its frames so far.
  bool recording() const { return m_recorder != nullptr; }
  std::uint64_t recordedFrames() const { return m_recordedFrames; }

  /// Rebuilds the scene on a fresh World with the controls applied. When the controls make an
  /// invalid World, the error is kept for the panel (lastError) and the scene's own settings are
  /// used instead.
  void restart();
  /// Replaces the scene by a new one of `entry` with its default parameters, resets the controls
  /// to that scene's values and restarts.
  void switchScene(const scenes::SceneEntry& entry);

  /// Runs one frame: the tools, World::step, the scene's update; fills `stats`. Steps the whole
  /// frame dt, or, when the pacer says fewer substeps fit in the frame budget, only those (slow
  /// motion); the World's accumulator carries what a float duration rounds off.
  void stepFrame(bool pour, bool push, const Ray& cursorRay, FrameStats& stats);
  /// Substeps one whole frame dt takes with the running World, in 1..maxSubstepsPerFrame.
  std::uint32_t fullSubsteps() const;

  World& world() { return *m_world; }
  const World& world() const { return *m_world; }
  scenes::Scene& scene() { return *m_scene; }
  const scenes::Scene& scene() const { return *m_scene; }
  /// Frame budget and render quality; edits apply from the next frame.
  FramePacer& pacer() { return m_pacer; }
  const FramePacer& pacer() const { return m_pacer; }
  SimulationControls& controls() { return m_controls; }
  /// The controls the running World was built with.
  const SimulationControls& applied() const { return m_applied; }
  const SandTools& tools() const { return m_tools; }
  const std::string& lastError() const { return m_lastError; }
  /// Frame time dropped by the substep cap since the restart, s.
  double droppedSeconds() const { return m_droppedSeconds; }

 private:
  const GpuContext& m_gpu;
  std::unique_ptr<scenes::Scene> m_scene;
  std::unique_ptr<World> m_world;
  SandTools m_tools;
  FramePacer m_pacer;
  SimulationControls m_controls;
  SimulationControls m_applied;
  std::string m_lastError;
  double m_droppedSeconds = 0.0;
  std::unique_ptr<samples::SceneRecorder> m_recorder;
  std::filesystem::path m_recordPath;
  std::uint64_t m_recordedFrames = 0;

  void finishRecording();
};

}  // namespace sandphys::viewer
