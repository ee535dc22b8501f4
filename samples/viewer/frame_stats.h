#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <sandphys/sandphys.h>

#include "render/renderer.h"

namespace sandphys::viewer {

/// The last kLength values of one number per frame, oldest first, contiguous as
/// ImGui::PlotLines wants them (shifting 240 floats per frame costs less than drawing the plot).
class PlotHistory {
 public:
  static constexpr std::size_t kLength = 240;  // four seconds at 60 frames per second

  void push(float value);
  void clear();
  const float* data() const { return m_values.data(); }
  int size() const { return static_cast<int>(m_values.size()); }
  float latest() const { return m_values.empty() ? 0.0f : m_values.back(); }
  float max() const;

 private:
  std::vector<float> m_values;
};

/// What the panel shows about the last frame.
struct FrameStats {
  bool stepped = false;  ///< the world stepped this frame (not paused)
  StepReport report{};
  std::uint32_t particles = 0;
  /// Substeps a whole frame dt takes (frameDt / timeStep, at most maxSubstepsPerFrame); the frame
  /// pacer may run fewer (report.substeps).
  std::uint32_t fullSubsteps = 0;
  /// The frame ran fewer substeps than a whole frame dt to stay within the frame budget.
  bool slowMotion = false;
  /// Simulated seconds of this frame / frame dt: about 1 in real time, below in slow motion.
  double timeScale = 0.0;
  double stepMilliseconds = 0.0;   ///< wall time of World::step and the scene's update
  double frameMilliseconds = 0.0;  ///< wall time of the whole previous frame
  /// The renderer's newest per-pass GPU times and the size it lit the scene at.
  render::RenderStats render{};
  double cundall = 0.0;          ///< granule updates per wall second of stepping
  double simPerWall = 0.0;       ///< simulated seconds per wall second of the whole frame
  double maxOverlapOverD = 0.0;  ///< largest overlap of the frame / particle diameter
  double droppedSeconds = 0.0;   ///< frame time dropped by the substep cap since the restart
  std::vector<KernelTime> kernels;
};

/// Fills what `stats` tells about a finished step from its `report`, its wall time
/// `stepMilliseconds` and the World it ran in: the report, particles, granule updates per second,
/// the largest overlap and the kernel times. Marks the frame stepped.
void recordStep(FrameStats& stats, const World& world, const StepReport& report,
                double stepMilliseconds);

/// The live plots of the panel.
struct StatsHistory {
  PlotHistory kineticEnergy;  ///< J
  PlotHistory contacts;
  PlotHistory frameMs;

  void clear();
  void push(const FrameStats& stats);
};

}  // namespace sandphys::viewer
