// The hash grid fitted to the sand (shaders/sim/common/grid_fit.glsl): the buckets a list build
// gives the particles, read back from the GPU, against the cells they stand in.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <vector>

#include "core/world_access.h"
#include "core/world_impl.h"
#include "support/test_world.h"

namespace sandphys::detail {
namespace {

struct Cell {
  int x, y, z;
};

// Single-particle bodies at the centres of the cells `cells` (cells of d + skin), weightless and
// apart, after the substep whose list build sorted them: each one's bucket, in order.
std::vector<std::uint32_t> bucketsOfSpheresAt(const std::vector<Cell>& cells,
                                              HashTable* cpuTable = nullptr) {
  WorldSettings settings = testing::smallSettings(std::uint32_t(cells.size()));
  settings.gravity = {0.0f, 0.0f, 0.0f};
  testing::TestWorld world(settings);
  const World::Impl& w = WorldAccess::impl(*world);
  const float reach = settings.particleDiameter + w.model.listSkin;
  for (const Cell& c : cells) {
    world.addSphere(
        {(float(c.x) + 0.5f) * reach, (float(c.y) + 0.5f) * reach, (float(c.z) + 0.5f) * reach});
  }
  world->substep(1);
  std::vector<std::uint32_t> buckets(cells.size());
  testing::gpu().makeCurrent();
  w.buffers[kParticleCell].download(0, buckets.size() * sizeof(std::uint32_t), buckets.data());
  if (cpuTable) *cpuTable = w.table;
  return buckets;
}

// A slab of 24 x 2 x 36 cells, wider than the cube of 16 cells a side that the CPU's multipliers
// fold the 4096 buckets into (HashTable::forParticles), so with them cells 17 apart in x and
// one apart in y share a bucket. Fitted, its rows of 26 buckets and planes of 4 rows fit the
// table 39 deep: every cell a bucket of its own.
TEST(FittedGrid, ASlabWiderThanTheTablesCubeGetsABucketPerCell) {
  std::vector<Cell> cells;
  for (int z = 0; z < 36; ++z)
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 24; ++x) cells.push_back({x - 5, y + 3, z - 20});
  HashTable table;
  const std::vector<std::uint32_t> buckets = bucketsOfSpheresAt(cells, &table);
  ASSERT_EQ(table.size, 4096u);
  std::map<std::uint32_t, std::size_t> holder;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    ASSERT_LT(buckets[i], table.size) << "particle " << i;
    const auto [at, fresh] = holder.emplace(buckets[i], i);
    EXPECT_TRUE(fresh) << "cells " << cells[i].x << "," << cells[i].y << "," << cells[i].z
                       << " and " << cells[at->second].x << "," << cells[at->second].y << ","
                       << cells[at->second].z << " share bucket " << buckets[i];
  }
}

std::uint32_t cpuBucket(const HashTable& t, const Cell& c) {
  return (std::uint32_t(c.x) + std::uint32_t(c.y) * t.multiplierY +
          std::uint32_t(c.z) * t.multiplierZ) &
         (t.size - 1u);
}

// Sand spread wider than any fit the table holds (a sphere 5000 cells off) keeps the CPU's
// multipliers, whose 27 neighbours of a cell are distinct for any extent.
TEST(FittedGrid, SandTooWideForTheTableKeepsTheCpusMultipliers) {
  std::vector<Cell> cells;
  for (int x = 0; x < 20; ++x) cells.push_back({x, 0, 0});
  cells.push_back({5000, 1, 2});
  HashTable table;
  const std::vector<std::uint32_t> buckets = bucketsOfSpheresAt(cells, &table);
  for (std::size_t i = 0; i < cells.size(); ++i) {
    EXPECT_EQ(buckets[i], cpuBucket(table, cells[i])) << "particle " << i;
  }
}

}  // namespace
}  // namespace sandphys::detail
