// The order of the bodies in their slots: the sort of the granules by place
// (WorldSettings::sortInterval; docs/architecture.md, "Granule order") and the ids that stay the
// bodies' own while their states move.
#include <numeric>
#include <string>
#include <utility>

#include "core/assert.h"
#include "core/world_impl.h"

namespace sandphys {

using namespace detail;

std::span<const std::uint32_t> World::Impl::slotIds() const {
  if (orderStale) {
    gpu->makeCurrent();
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    idsOfSlots = buffers[kBodyIds].downloadArray<std::uint32_t>(bodyCount);
    slotsOfIds.assign(bodyCount, 0);
    for (std::uint32_t slot = 0; slot < bodyCount; ++slot) slotsOfIds[idsOfSlots[slot]] = slot;
    orderStale = false;
  }
  return idsOfSlots;
}

std::uint32_t World::Impl::slotOf(std::uint32_t id) const {
  // Only dynamic granules trade slots, so a slot added with another motion still holds the body of
  // its index: a kinematic body that an engine sets every frame costs no read-back after a sort.
  if (bodyMotions[id] != Motion::Dynamic) return id;
  return slotIds().empty() ? id : slotsOfIds[id];
}

std::uint32_t World::Impl::idOf(std::uint32_t slot) const {
  const std::span<const std::uint32_t> ids = slotIds();
  return ids.empty() ? slot : ids[slot];
}

void World::Impl::addIds(std::uint32_t first, std::uint32_t end) {
  std::vector<std::uint32_t> own(end - first);
  std::iota(own.begin(), own.end(), first);
  buffers[kBodyIds].upload(first * 4ull, own.size() * 4, own.data());
  // Tables that are stale are read whole when next needed; empty ones mean each its own.
  if (orderStale || idsOfSlots.empty()) return;
  idsOfSlots.insert(idsOfSlots.end(), own.begin(), own.end());
  slotsOfIds.insert(slotsOfIds.end(), own.begin(), own.end());
}

void World::Impl::setIds(std::span<const std::uint32_t> ids) {
  SANDPHYS_ASSERT(ids.empty() || ids.size() == bodyCount,
                  std::to_string(ids.size()) + " ids for " + std::to_string(bodyCount) + " bodies");
  std::vector<std::uint32_t> all(ids.begin(), ids.end());
  if (all.empty()) {
    all.resize(bodyCount);
    std::iota(all.begin(), all.end(), 0u);
  }
  buffers[kBodyIds].upload(0, all.size() * 4, all.data());
  idsOfSlots.clear();
  slotsOfIds.clear();
  orderStale = !ids.empty();
}

bool World::Impl::granuleSortDue() const {
  // No body, nothing to sort (and with sleep no collect_active to write the sort's commands).
  return sortsGranules() && bodyCount > 0 && steps > 0 && steps % sortInterval() == 0;
}

void World::Impl::prepareContactsAndSort() {
  // The order comes from a grid built for it from this substep's positions, not from whichever
  // build came last (builds follow the motion since the last one, and restores and read-backs
  // ask for their own): so it follows from the state alone, and a World restored from a snapshot
  // sorts as the original did.
  listsStale = true;
  prepareContacts();
  sortGranules();
  // The lists and the pair counts of the sorted slots, before this substep's contacts.
  listsStale = true;
  prepareContacts();
}

void World::Impl::prepareActiveAndSort() {
  // As prepareContactsAndSort, from a build of every list that collect_active asks for when it
  // sorts: its moving grid holds the computed bodies alone, so the order follows from the state.
  // The computed granules trade slots among themselves, so the active lists still hold, and the
  // build's commands are still in place to build again for the new slots. When the substep
  // computes nothing, every command is of zero groups: sleeping sand is not sorted, as a frame
  // that skips the substep would not sort it.
  buffers[kCounters].upload(4 * kCounterGranuleSort, 4, &kSortRequested);
  prepareActive();
  sortGranules();
  buildLists();
}

void World::Impl::dispatchSortPass(GLuint program, const char* name, SortPass over,
                                   std::uint32_t threads, std::uint32_t groupSize) {
  if (sleep.enabled) {
    dispatchIndirect(program, name, sortDispatchOffset(over));
  } else {
    dispatch(program, name, threads, groupSize);
  }
}

void World::Impl::moveWords(Binding buffer, bool particles, std::uint32_t stride,
                            std::uint32_t first, std::uint32_t words) {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kOrderTarget, buffers[buffer].id());
  const std::uint32_t items = particles ? particleCount : bodyCount;
  const SortPass over = particles ? kSortOverParticles : kSortOverBodies;
  const std::pair<GLuint, const char*> passes[] = {{kernels.orderPack, "order_pack"},
                                                   {kernels.orderGather, "order_gather"}};
  for (const auto& [program, name] : passes) {
    glUseProgram(program);
    glUniform4ui(0, particles ? 1u : 0u, stride, first, words);
    dispatchSortPass(program, name, over, items, kWorkgroupSize);
  }
}

void World::Impl::sortGranules() {
  stateChanged();
  // The list build's prefix sum of cellCount into cellStart over the table in use: a workgroup of
  // kScanBlock / 4 threads per block of kScanBlock entries, then one of 1024 over the blocks.
  const auto scan = [&] {
    const std::uint32_t threads = kScanBlock / 4;
    const std::uint32_t blocks = table.size / kScanBlock;
    dispatchSortPass(kernels.scanBlocks, "order_scan", kSortOverScanBlocks, blocks * threads,
                     threads);
    dispatchSortPass(kernels.scanBlockSums, "order_scan", kSortOverBlockSums, 1024, 1024);
    dispatchSortPass(kernels.scanAdd, "order_scan", kSortOverScanBlocks, blocks * threads, threads);
  };
  // The granules in the order of the last build's grid, numbered; their slots, numbered; each
  // slot's source and each granule's destination (granule_order.glsl).
  dispatchSortPass(kernels.orderSequence, "order_sequence", kSortOverParticles, particleCount,
                   kWorkgroupSize);
  scan();
  dispatchSortPass(kernels.orderSources, "order_sources", kSortOverParticles, particleCount,
                   kWorkgroupSize);
  dispatchSortPass(kernels.orderSlots, "order_slots", kSortOverBodies, bodyCount, kWorkgroupSize);
  scan();
  dispatchSortPass(kernels.orderMoves, "order_moves", kSortOverBodies, bodyCount, kWorkgroupSize);
  // The states that differ from granule to granule move as they are, bit for bit; what all of
  // them share (mass, inertia, particle offsets, flags, each particle's body and inverse mass)
  // stays. The lists and the grid are built again.
  for (Binding b : {kBodyPosition, kBodyOrientation, kBodyVelocity, kBodyAngularVelocity}) {
    moveWords(b, false, 4, 0, 4);
  }
  moveWords(kBodyInfo, false, 4, 3, 1);  // the speed-guard count
  moveWords(kBodyIds, false, 1, 0, 1);
  for (Binding b : {kParticlePosition, kParticleVelocity}) moveWords(b, true, 4, 0, 3);
  for (Binding b : {kParticleForce, kParticleStats}) moveWords(b, true, 4, 0, 4);
  if (sleep.enabled && keepsHistory()) moveWords(kParticleSpin, true, 4, 0, 4);
  if (keepsHistory()) {
    moveWords(kParticleTorque, true, 4, 0, 4);
    moveWords(kContactPairs, true, 4, 0, 4);
    for (std::uint32_t group = 0; group < kContactSlotGroups; ++group) {
      moveWords(Binding(kContactSlots0 + group), true, 16, 0, 16);
    }
    dispatchSortPass(kernels.orderKeys, "order_keys", kSortOverParticles, particleCount,
                     kWorkgroupSize);
  }
  if (keepsRollingHistory()) {
    // Twelve slots of four words per particle, in the neighbour lists' room of sixteen words.
    for (std::uint32_t part = 0; part < 3; ++part)
      moveWords(kRollingSlots, true, 48, 16 * part, 16);
  }
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kOrderTarget, 0);
  gridValid = false;
  orderStale = true;
}

}  // namespace sandphys
