// The World's statistics (WorldStats): reduced over every particle on the GPU and read back, once
// a frame at most (WorldSettings::statsEachFrame) or when asked; kept while nothing changed them,
// so that a frame of sleeping sand does not pay for them again (docs/architecture.md, "Sleep").
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/world_impl.h"

namespace sandphys {

using namespace detail;

WorldStats World::readStats() {
  impl().gpu->makeCurrent();
  return impl().readStats();
}

void World::resetPeakOverlap() {
  impl().gpu->makeCurrent();
  impl().resetPeakOverlap();
}

void World::Impl::resetPeakOverlap() {
  if (paramsDirty) uploadParams();
  // What a reduce would now find, whatever else it reads.
  reducedStats.maxOverlap = 0.0;
  if (particleCount == 0 || peaksClear) return;
  buffers.bindAll();
  // Unnamed: a per-frame pass, kept out of the per-substep kernel times.
  dispatch(kernels.resetPeakOverlap, nullptr, particleCount, kWorkgroupSize);
  peaksClear = true;
}

WorldStats World::Impl::readStats() {
  if (!statsCurrent || paramsDirty) return reduceStats();
  WorldStats s = reducedStats;
  fillKeptFields(s);
  return s;
}

WorldStats World::Impl::reduceStats() {
  if (paramsDirty) uploadParams();
  buffers.bindAll();
  glUseProgram(kernels.statsReduce);
  glDispatchCompute(kStatsWorkgroups, 1, 1);
  ++statsReductions;
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<GpuStatsPartial> partials(kStatsWorkgroups);
  buffers[kStatsPartials].download(0, partials.size() * sizeof(GpuStatsPartial), partials.data());
  buffers[kCounters].download(0, sizeof counters, counters.data());

  WorldStats s;
  std::uint64_t pairEnds = 0;
  std::uint64_t wallContacts = 0;
  double alive = 0.0;
  for (const auto& p : partials) {
    pairEnds += p.counts.x;
    wallContacts += p.counts.y;
    (keepsHistory() ? s.contactSlotOverflows : s.penetrationClamps) += p.counts.z;
    s.velocityClamps += p.counts.w;
    s.kineticEnergy += double(p.sums.x) + double(p.sums.y);
    s.maxOverlap = std::max(s.maxOverlap, double(p.sums.z));
    alive += p.sums.w;
    s.granulesAsleep += p.sleep.x;
  }
  s.granulesAlive = std::uint32_t(std::llround(alive));
  s.contacts = std::uint32_t(pairEnds / 2 + wallContacts);
  fillKeptFields(s);
  sandLooksIdle = computedNothing(counters);
  reducedStats = s;
  statsCurrent = true;
  return s;
}

void World::Impl::fillKeptFields(WorldStats& s) const {
  s.bodies = bodyCount;
  s.particles = particleCount;
  s.granulesSpawned = granulesSpawned;
  s.granulesKilled = counters[kCounterKilled];
  s.granulesNotBorn = counters[kCounterSpawnTaken];
  s.gridBuckets = table.size;
  s.listBuilds = counters[kCounterListBuilds];
  s.listNearMarkings = counters[kCounterNearMarkings];
  s.neighbourListOverflows = counters[kCounterListOverflows];
  // A substep sorts when the count of the substeps before it is a multiple of the interval.
  s.granuleSorts = sortsGranules() && steps > 0 ? (steps - 1) / sortInterval() : 0;
  if (sleep.enabled) {
    s.stillGridBuilds = counters[kCounterStillBuilds];
    s.movingGridParticles = counters[kCounterGridActive] + counters[kCounterGridRecent];
  }
  s.steps = steps;
  s.simulatedTime = simTime;
}

}  // namespace sandphys
