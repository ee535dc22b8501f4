#include "viewer/session.h"

#include <algorithm>
#include <chrono>

namespace sandphys::viewer {

namespace {

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace

SimulationControls SimulationControls::from(const WorldSettings& settings, double frameDt) {
  return {.youngsModulus = settings.material.youngsModulus,
          .friction = settings.material.friction,
          .restitution = settings.material.restitution,
          .stepsPerContact = settings.stepsPerContact,
          .frameDt = frameDt,
          .profileKernels = settings.profileKernels};
}

WorldSettings SimulationControls::applyTo(WorldSettings settings) const {
  settings.material.youngsModulus = youngsModulus;
  settings.material.friction = friction;
  settings.material.restitution = restitution;
  settings.stepsPerContact = stepsPerContact;
  settings.profileKernels = profileKernels;
  return settings;
}

Session::Session(const GpuContext& gpu, std::unique_ptr<scenes::Scene> scene, double frameDt)
    : m_gpu(gpu), m_scene(std::move(scene)) {
  m_controls = SimulationControls::from(m_scene->settings(), frameDt);
  restart();
}

void Session::restart() {
  // The old World goes first: two full-size worlds need not fit in memory at once.
  m_world.reset();
  m_lastError.clear();
  m_droppedSeconds = 0.0;
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

void Session::stepFrame(bool pour, bool push, const Ray& cursorRay, FrameStats& stats) {
  const float frameDt = static_cast<float>(m_applied.frameDt);
  const Clock::time_point start = Clock::now();
  m_tools.update(*m_world, pour, push, cursorRay, frameDt);
  stats.report = m_world->step(frameDt);
  m_tools.countEmitted(stats.report.granulesEmitted);
  m_scene->update(*m_world, stats.report, m_world->simulatedTime());
  stats.stepMilliseconds = millisecondsSince(start);
  stats.stepped = true;

  m_droppedSeconds += stats.report.droppedTime;
  stats.droppedSeconds = m_droppedSeconds;
  stats.particles = m_world->particleCount();
  const double granules =
      stats.report.hasStats ? stats.report.stats.granulesAlive : m_world->granulesSpawned();
  stats.cundall = granules * stats.report.substeps / std::max(stats.stepMilliseconds * 1e-3, 1e-9);
  stats.maxOverlapOverD = stats.report.hasStats
                              ? stats.report.stats.maxOverlap / m_world->settings().particleDiameter
                              : 0.0;
  stats.kernels = m_world->kernelTimes();
}

}  // namespace sandphys::viewer
