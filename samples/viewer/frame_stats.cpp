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
