#version 450
// Not a simulation pass: touches every declaration of layout.glsl whose offsets the C++ twin
// (gpu_layout.h) relies on, so that tests/gl/layout_twin_test.cpp can ask the driver for them.
#include "common/layout.glsl"

layout(local_size_x = 1) in;

BODY_POSITION(coherent)
PARTICLE_BODY(readonly)
COLLIDERS(readonly)
SINKS(readonly)
STATS_PARTIALS(readonly)
CONTACT_LIST_BUFFER(readonly)
// Blocks whose sizes carry the slot counts, for the test to compare with kContactSlots and
// kContactSlotsPerGroup.
layout(std430, binding = 40) readonly buffer SlotsProbe { vec4 slotsProbe[CONTACT_SLOTS]; };
layout(std430, binding = 41) readonly buffer SlotGroupProbe { vec4 slotGroupProbe[CONTACT_SLOTS_PER_GROUP]; };
layout(std430, binding = 42) readonly buffer SlotGroupsProbe { vec4 slotGroupsProbe[CONTACT_SLOT_GROUPS]; };
// And a contact list record's, for GpuContactRecord (a uniform block: the storage blocks are at
// the driver's limit).
layout(std140, binding = 1) uniform ContactRecordProbe { vec4 contactRecordProbe[CONTACT_RECORD]; };
// And the neighbour lists' constants: capacity, the counters' layout and the build's passes.
layout(std430, binding = 43) readonly buffer ListCapacityProbe { uint listCapacityProbe[NEIGHBOUR_LIST_CAPACITY]; };
layout(std430, binding = 44) readonly buffer ListDispatchProbe { uint listDispatchProbe[COUNTER_LIST_DISPATCH]; };
layout(std430, binding = 45) readonly buffer ListPassesProbe { uvec4 listPassesProbe[LIST_BUILD_PASSES]; };
layout(std430, binding = 46) readonly buffer ListPassProbe { uvec4 listPassProbe[PASS_LIST_BUILD + 1u]; };
// The counters of sleep's two grids that the CPU reads, the one it writes for the pair counts
// and the lists' near markings it reads: each member starts at its counter.
layout(std430, binding = 49) readonly buffer GridCountersProbe {
  uint beforeStillBuildsProbe[COUNTER_STILL_BUILDS];
  uint stillBuildsProbe[COUNTER_GRID_ACTIVE - COUNTER_STILL_BUILDS];
  uint gridActiveProbe[COUNTER_GRID_RECENT - COUNTER_GRID_ACTIVE];
  uint gridRecentProbe;
  uint beforeRecountPairsProbe[COUNTER_RECOUNT_PAIRS - COUNTER_GRID_RECENT - 1];
  uint recountPairsProbe;
  uint beforeNearMarkingsProbe[COUNTER_NEAR_MARKINGS - COUNTER_RECOUNT_PAIRS - 1];
  uint nearMarkingsProbe;
  uint beforeGranuleSortProbe[COUNTER_GRANULE_SORT - COUNTER_NEAR_MARKINGS - 1];
  uint granuleSortProbe;
  uint beforeSortDispatchProbe[COUNTER_SORT_DISPATCH - COUNTER_GRANULE_SORT - 1];
  uint sortDispatchProbe[4 * SORT_PASSES];
  uint countersEndProbe;
};
// The active passes' commands and collect_active.comp's chunk (sleep): each member starts at
// its count.
layout(std430, binding = 47) readonly buffer ActiveDispatchProbe {
  uint activeDispatchProbe[COUNTER_ACTIVE_DISPATCH];
  uint collectChunkProbe[COLLECT_CHUNK];
  uint sleepProbeEnd;
};
layout(std430, binding = 48) readonly buffer ActivePassesProbe { uvec4 activePassesProbe[ACTIVE_PASS_LARGE + 1u]; };

void main() {
  // Every member of a std140 block is active once the block is used.
  vec4 sum = vec4(params.gravity, params.dt) + vec4(float(params.oneGrid));
  sum += colliders[0].a + colliders[0].b + colliders[0].c + colliders[0].material;
  sum += colliders[0].velocity + colliders[0].spin;
  sum += slotsProbe[0] + slotGroupProbe[0] + slotGroupsProbe[0] + contactRecordProbe[0];
  sum += vec4(listPassesProbe[0]);
  sum.y += float(listCapacityProbe[0] + listDispatchProbe[0] + listPassProbe[0].x);
  sum.z += float(activeDispatchProbe[0] + activePassesProbe[0].x + collectChunkProbe[0] +
                 sleepProbeEnd);
  sum.w += float(beforeStillBuildsProbe[0] + stillBuildsProbe[0] + gridActiveProbe[0] + gridRecentProbe + recountPairsProbe);
  sum.w += float(beforeNearMarkingsProbe[0] + nearMarkingsProbe);
  sum.w += float(beforeGranuleSortProbe[0] + granuleSortProbe + beforeSortDispatchProbe[0] +
                 sortDispatchProbe[0] + countersEndProbe);
  sum += sinks[0].lo + sinks[0].hi;
  sum += vec4(statsPartials[0].counts) + statsPartials[0].sums + vec4(statsPartials[0].sleep);
  sum += contactList[0] + vec4(float(contactListCount + contactListCapacity + pad0 + pad1));
  sum.x += float(particleBody[0]);
  bodyPosition[0] = sum;
}
