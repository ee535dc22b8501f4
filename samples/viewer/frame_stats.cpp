#include "viewer/frame_stats.h"

#include <algorithm>

namespace sandphys::viewer {

void PlotHistory::push(float value) {
  if (m_values.size() == kLength) m_values.erase(m_values.begin());
  m_values.push_back(value);
}

void PlotHistory::clear() {
  m_values.clear();
}

float PlotHistory::max() const {
  return m_values.empty() ? 0.0f : *std::max_element(m_values.begin(), m_values.end());
}

void recordStep(FrameStats& stats, const World& world, const StepReport& report,
                double stepMilliseconds) {
  stats.stepped = true;
  stats.report = report;
  stats.stepMilliseconds = stepMilliseconds;
  stats.particles = world.particleCount();
  const double granules = report.hasStats ? report.stats.granulesAlive : world.granulesSpawned();
  stats.cundall = granules * report.substeps / std::max(stepMilliseconds * 1e-3, 1e-9);
  stats.maxOverlapOverD =
      report.hasStats ? report.stats.maxOverlap / world.settings().particleDiameter : 0.0;
  stats.kernels = world.kernelTimes();
}

void StatsHistory::clear() {
  kineticEnergy.clear();
  contacts.clear();
  frameMs.clear();
}

void StatsHistory::push(const FrameStats& stats) {
  frameMs.push(static_cast<float>(stats.frameMilliseconds));
  if (stats.stepped && stats.report.hasStats) {
    kineticEnergy.push(static_cast<float>(stats.report.stats.kineticEnergy));
    contacts.push(static_cast<float>(stats.report.stats.contacts));
  }
}

}  // namespace sandphys::viewer
