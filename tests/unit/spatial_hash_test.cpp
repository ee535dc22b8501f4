// The hash table that folds the uniform grid: the 27 cells around any cell must land in 27
// distinct buckets (the contact gather relies on it to visit each neighbour once).
#include <gtest/gtest.h>

#include <set>

#include "core/world_impl.h"

namespace sandphys::detail {
namespace {

std::uint32_t bucket(const HashTable& t, int x, int y, int z) {
  return (std::uint32_t(x) + std::uint32_t(y) * t.multiplierY + std::uint32_t(z) * t.multiplierZ) &
         (t.size - 1u);
}

TEST(SpatialHash, NeighbourhoodsNeverShareABucket) {
  for (std::uint32_t particles : {1u, 5000u, 65536u, 1000000u, 4000000u}) {
    HashTable t = HashTable::forParticles(particles);
    EXPECT_GE(t.size, particles);
    EXPECT_EQ(t.size & (t.size - 1u), 0u);
    for (int cz = -40; cz <= 40; cz += 7) {
      for (int cy = -40; cy <= 40; cy += 9) {
        for (int cx = -40; cx <= 40; cx += 11) {
          std::set<std::uint32_t> seen;
          for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
              for (int dx = -1; dx <= 1; ++dx) seen.insert(bucket(t, cx + dx, cy + dy, cz + dz));
          ASSERT_EQ(seen.size(), 27u)
              << "table " << t.size << " at cell " << cx << "," << cy << "," << cz;
        }
      }
    }
  }
}

}  // namespace
}  // namespace sandphys::detail
