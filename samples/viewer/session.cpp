#include "viewer/session.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

namespace sandphys::viewer {

namespace {

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The duration of `substeps` substeps as World::step takes it. A float product may fall a hair
// short of the double one the World divides by, and would then run one substep less; rounding
// up makes the World run exactly `substeps` from an empty accumulator.
float substepsDuration(std::uint32_t substeps, float timeStep) {
  const double exact = static_cast<double>(substeps) * static_cast<double>(timeStep);
  float duration = static_cast<float>(exact);
  if (static_cast<double>(duration) < exact) {
    duration = std::nextafter(duration, std::numeric_limits<float>::max());
  }
  return duration;
}

}  // namespace

SimulationControls SimulationControls::from(const WorldSettings& settings, double frameDt) {
  return {.youngsModulus = settings.material.youngsModulus,
          .friction = settings.material.friction,
          .restitution = settings.material.restitution,
          .stepsPerContact = settings.stepsPerContact,
          .frameDt = frameDt,
          .profileKernels = settings.profileKernels,
          .sleep = settings.sleep.enabled};
}

WorldSettings SimulationControls::applyTo(WorldSettings settings) const {
  settings.material.youngsModulus = youngsModulus;
  settings.material.friction = friction;
  settings.material.restitution = restitution;
  settings.stepsPerContact = stepsPerContact;
  settings.profileKernels = profileKernels;
  settings.sleep.enabled = sleep;
  return settings;
}

Session::Session(const GpuContext& gpu, std::unique_ptr<scenes::Scene> scene, double frameDt,
                 FramePacer pacer)
    : m_gpu(gpu), m_scene(std::move(scene)), m_pacer(pacer) {
  m_controls = SimulationControls::from(m_scene->settings(), frameDt);
  restart();
}

Session::~Session() {
  try {
    finishRecording();
  } catch (const std::exception& error) {
    std::fprintf(stderr, "sandphys-samples: %s\n", error.what());
  }
}

void Session::startRecording(const std::filesystem::path& file, std::uint64_t snapshotEvery) {
  finishRecording();
  m_recorder = std::make_unique<samples::SceneRecorder>(file, *m_scene, m_world->settings(),
                                                        m_applied.frameDt, snapshotEvery,
                                                        m_gpu.description(), true);
  m_recorder->begin(*m_world);
  m_recordPath = file;
  m_recordedFrames = 0;
}

void Session::finishRecording() {
  if (!m_recorder) return;
  std::unique_ptr<samples::SceneRecorder> recorder = std::move(m_recorder);
  const std::uint64_t bytes = recorder->finish(*m_world);
  std::fprintf(stderr, "sandphys-samples: recorded %llu frames to %s (%llu bytes)\n",
               static_cast<unsigned long long>(m_recordedFrames), m_recordPath.string().c_str(),
               static_cast<unsigned long long>(bytes));
}

void Session::restart() {
  // A recording covers one run from its start: a restart ends it.
  finishRecording();
  // The old World goes first: two full-size worlds need not fit in memory at once.
  m_world.reset();
  m_lastError.clear();
  m_droppedSeconds = 0.0;
  m_pacer.forgetStepCost();
  WorldSettings settings = SandTools::withToolCapacity(m_scene->settings());
  settings.profileKernels = m_controls.profileKernels;
  try {
    m_world = std::make_unique<World>(m_gpu, m_controls.applyTo(settings));
    m_applied = m_controls;
  } catch (const Error& error) {
    m_lastError = error.what();
    m_world = std::make_unique<World>(m_gpu, settings);
    m_applied = SimulationControls::from(settings, m_controls.frameDt);
  }
  m_scene->build(*m_world);
  m_tools.attach(*m_world, *m_scene);
}

void Session::switchScene(const scenes::SceneEntry& entry) {
  m_scene = entry.create();
  m_controls = SimulationControls::from(m_scene->settings(), m_controls.frameDt);
  restart();
}

std::uint32_t Session::fullSubsteps() const {
  const double substeps = std::round(m_applied.frameDt / static_cast<double>(m_world->timeStep()));
  return static_cast<std::uint32_t>(
      std::clamp(substeps, 1.0, static_cast<double>(m_world->settings().maxSubstepsPerFrame)));
}

void Session::stepFrame(bool pour, bool push, const Ray& cursorRay, FrameStats& stats) {
  const std::uint32_t full = fullSubsteps();
  const std::uint32_t substeps = m_pacer.substepsFor(full);
  stats.fullSubsteps = full;
  stats.slowMotion = substeps < full;
  // The whole frame dt, not full · timeStep, when it fits: then the frame ticks in real time
  // whatever remainder frameDt / timeStep leaves.
  const float frameDt = stats.slowMotion ? substepsDuration(substeps, m_world->timeStep())
                                         : static_cast<float>(m_applied.frameDt);
  // Kernel profiling changes no bit of the result: it follows the panel at once.
  if (m_controls.profileKernels != m_applied.profileKernels) {
    m_world->setProfileKernels(m_controls.profileKernels);
    m_applied.profileKernels = m_controls.profileKernels;
  }
  const Clock::time_point start = Clock::now();
  m_tools.update(*m_world, pour, push, cursorRay, frameDt);
  const StepReport report = m_scene->step(*m_world, frameDt);
  m_tools.countEmitted(report.granulesEmitted);
  m_scene->update(*m_world, report, m_world->simulatedTime());
  recordStep(stats, *m_world, report, millisecondsSince(start));
  if (m_recorder) {
    m_recorder->recordFrame(*m_world, *m_scene, frameDt, ++m_recordedFrames,
                            samples::toolEvents(pour, push, cursorRay));
  }
  stats.timeScale = report.simulatedTime / m_applied.frameDt;
  m_pacer.recordStep(stats.stepMilliseconds, report.substeps);
  m_droppedSeconds += report.droppedTime;
  stats.droppedSeconds = m_droppedSeconds;
}

}  // namespace sandphys::viewer
