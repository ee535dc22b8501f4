// layout.glsl and its C++ twin gpu_layout.h must agree: the driver's offsets of every member of
// the uniform block and the structs must match offsetof on the C++ side.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <iterator>
#include <string>

#include "core/gpu_layout.h"
#include "gl/shader_library.h"
#include "support/test_world.h"

namespace sandphys::detail {
namespace {

GLint resourceOffset(GLuint program, GLenum interface, const char* name) {
  GLuint index = glGetProgramResourceIndex(program, interface, name);
  EXPECT_NE(index, GL_INVALID_INDEX) << name << " is not active in the probe shader";
  if (index == GL_INVALID_INDEX) return -1;
  GLenum property = GL_OFFSET;
  GLint offset = -1;
  glGetProgramResourceiv(program, interface, index, 1, &property, 1, nullptr, &offset);
  return offset;
}

// Stride of the top-level array of a buffer block: "colliders[0].a" for arrays of structs,
// "bodyPosition[0]" for arrays of vectors.
GLint stride(GLuint program, const char* name) {
  GLuint index = glGetProgramResourceIndex(program, GL_BUFFER_VARIABLE, name);
  EXPECT_NE(index, GL_INVALID_INDEX) << name;
  // GL reports a plain array's stride as ARRAY_STRIDE, an array of structs' as
  // TOP_LEVEL_ARRAY_STRIDE.
  const GLenum properties[2] = {GL_ARRAY_STRIDE, GL_TOP_LEVEL_ARRAY_STRIDE};
  GLint values[2] = {0, 0};
  glGetProgramResourceiv(program, GL_BUFFER_VARIABLE, index, 2, properties, 2, nullptr, values);
  return std::max(values[0], values[1]);
}

// One property of a uniform or storage block (GL_BUFFER_DATA_SIZE, GL_NUM_ACTIVE_VARIABLES).
GLint blockProperty(GLuint program, GLenum interface, const char* name, GLenum property) {
  GLuint block = glGetProgramResourceIndex(program, interface, name);
  EXPECT_NE(block, GL_INVALID_INDEX) << name;
  GLint value = 0;
  glGetProgramResourceiv(program, interface, block, 1, &property, 1, nullptr, &value);
  return value;
}
GLint blockSize(GLuint program, GLenum interface, const char* name) {
  return blockProperty(program, interface, name, GL_BUFFER_DATA_SIZE);
}

TEST(LayoutTwin, UniformBlockAndStructsMatchTheCppDeclarations) {
  testing::gpu().makeCurrent();
  gl::ShaderLibrary library;
  GLuint program = library.compileCompute("sim/layout_probe.comp");

  // Each member at the offset of its C++ twin, and no member that the C++ side lacks.
  struct Member {
    const char* name;
    std::size_t offset;
  };
  const Member members[] = {
      {"gravity", offsetof(SimParams, gravity)},
      {"dt", offsetof(SimParams, dt)},
      {"particleRadius", offsetof(SimParams, particleRadius)},
      {"particleDiameter", offsetof(SimParams, particleDiameter)},
      {"inverseCellSize", offsetof(SimParams, inverseCellSize)},
      {"maxOverlap", offsetof(SimParams, maxOverlap)},
      {"grainStiffness", offsetof(SimParams, grainStiffness)},
      {"grainDamping", offsetof(SimParams, grainDamping)},
      {"friction", offsetof(SimParams, friction)},
      {"tangentialDamping", offsetof(SimParams, tangentialDamping)},
      {"wallStiffness", offsetof(SimParams, wallStiffness)},
      {"maxSpeed", offsetof(SimParams, maxSpeed)},
      {"particleCount", offsetof(SimParams, particleCount)},
      {"bodyCount", offsetof(SimParams, bodyCount)},
      {"hashMask", offsetof(SimParams, hashMask)},
      {"sinkCount", offsetof(SimParams, sinkCount)},
      {"hashSize", offsetof(SimParams, hashSize)},
      {"hashMultiplierY", offsetof(SimParams, hashMultiplierY)},
      {"hashMultiplierZ", offsetof(SimParams, hashMultiplierZ)},
      {"planesEnd", offsetof(SimParams, planesEnd)},
      {"boxesEnd", offsetof(SimParams, boxesEnd)},
      {"revolutionsEnd", offsetof(SimParams, revolutionsEnd)},
      {"grainShearStiffness", offsetof(SimParams, grainShearStiffness)},
      {"wallShearStiffness", offsetof(SimParams, wallShearStiffness)},
      {"listReachSquared", offsetof(SimParams, listReachSquared)},
      {"listMoveSquared", offsetof(SimParams, listMoveSquared)},
      {"nearReachSquared", offsetof(SimParams, nearReachSquared)},
      {"nearMoveSquared", offsetof(SimParams, nearMoveSquared)},
      {"listStride", offsetof(SimParams, listStride)},
      {"sleepLinearSpeed", offsetof(SimParams, sleepLinearSpeed)},
      {"sleepAngularSpeed", offsetof(SimParams, sleepAngularSpeed)},
      {"wakeAcceleration", offsetof(SimParams, wakeAcceleration)},
      {"sleepSubsteps", offsetof(SimParams, sleepSubsteps)},
      {"sleepNeighbourLead", offsetof(SimParams, sleepNeighbourLead)},
      {"oneGrid", offsetof(SimParams, oneGrid)},
      {"rollingFriction", offsetof(SimParams, rollingFriction)},
  };
  for (const Member& m : members) {
    const std::string name = std::string("SimParams.") + m.name;
    EXPECT_EQ(resourceOffset(program, GL_UNIFORM, name.c_str()), GLint(m.offset)) << name;
  }
  EXPECT_EQ(blockProperty(program, GL_UNIFORM_BLOCK, "SimParams", GL_NUM_ACTIVE_VARIABLES),
            GLint(std::size(members)));
  EXPECT_EQ(blockSize(program, GL_UNIFORM_BLOCK, "SimParams"), GLint(sizeof(SimParams)));

  EXPECT_EQ(stride(program, "colliders[0].a"), GLint(sizeof(GpuCollider)));
  EXPECT_EQ(resourceOffset(program, GL_BUFFER_VARIABLE, "colliders[0].material"),
            GLint(offsetof(GpuCollider, material)));
  EXPECT_EQ(resourceOffset(program, GL_BUFFER_VARIABLE, "colliders[0].velocity"),
            GLint(offsetof(GpuCollider, velocity)));
  EXPECT_EQ(resourceOffset(program, GL_BUFFER_VARIABLE, "colliders[0].spin"),
            GLint(offsetof(GpuCollider, spin)));
  EXPECT_EQ(stride(program, "sinks[0].lo"), GLint(sizeof(GpuSink)));
  EXPECT_EQ(resourceOffset(program, GL_BUFFER_VARIABLE, "sinks[0].hi"),
            GLint(offsetof(GpuSink, hi)));
  EXPECT_EQ(stride(program, "statsPartials[0].counts"), GLint(sizeof(GpuStatsPartial)));
  EXPECT_EQ(resourceOffset(program, GL_BUFFER_VARIABLE, "statsPartials[0].sums"),
            GLint(offsetof(GpuStatsPartial, sums)));
  EXPECT_EQ(resourceOffset(program, GL_BUFFER_VARIABLE, "statsPartials[0].sleep"),
            GLint(offsetof(GpuStatsPartial, sleep)));
  EXPECT_EQ(resourceOffset(program, GL_BUFFER_VARIABLE, "contactList[0]"), 16);
  EXPECT_EQ(stride(program, "contactList[0]"), 16);
  EXPECT_EQ(stride(program, "bodyPosition[0]"), 16);
  EXPECT_EQ(stride(program, "particleBody[0]"), 4);
  // The slot counts of layout.glsl.
  EXPECT_EQ(blockSize(program, GL_SHADER_STORAGE_BLOCK, "SlotsProbe"), GLint(16 * kContactSlots));
  EXPECT_EQ(blockSize(program, GL_SHADER_STORAGE_BLOCK, "SlotGroupProbe"),
            GLint(16 * kContactSlotsPerGroup));
  EXPECT_EQ(blockSize(program, GL_SHADER_STORAGE_BLOCK, "SlotGroupsProbe"),
            GLint(16 * kContactSlotGroups));
  EXPECT_EQ(blockSize(program, GL_UNIFORM_BLOCK, "ContactRecordProbe"),
            GLint(sizeof(GpuContactRecord)));
  // The neighbour lists' constants.
  EXPECT_EQ(blockSize(program, GL_SHADER_STORAGE_BLOCK, "ListCapacityProbe"),
            GLint(4 * kNeighbourListCapacity));
  EXPECT_EQ(blockSize(program, GL_SHADER_STORAGE_BLOCK, "ListDispatchProbe"),
            GLint(4 * kCounterListDispatch));
  // The counters of sleep's two grids that the CPU reads, the one it writes to have every pair
  // counted, the near markings it reads, the sort's request and commands (sleep), and the end,
  // each member of the probe at its word.
  const Member gridCounters[] = {{"stillBuildsProbe[0]", 4 * kCounterStillBuilds},
                                 {"gridActiveProbe[0]", 4 * kCounterGridActive},
                                 {"gridRecentProbe", 4 * kCounterGridRecent},
                                 {"recountPairsProbe", 4 * kCounterRecountPairs},
                                 {"nearMarkingsProbe", 4 * kCounterNearMarkings},
                                 {"granuleSortProbe", 4 * kCounterGranuleSort},
                                 {"sortDispatchProbe[0]", 4 * kCounterSortDispatch},
                                 {"countersEndProbe", 4 * kCounterCount}};
  for (const Member& m : gridCounters) {
    EXPECT_EQ(resourceOffset(program, GL_BUFFER_VARIABLE, m.name), GLint(m.offset)) << m.name;
  }
  EXPECT_EQ(blockSize(program, GL_SHADER_STORAGE_BLOCK, "ListPassesProbe"),
            GLint(16 * kListBuildPasses));
  EXPECT_EQ(blockSize(program, GL_SHADER_STORAGE_BLOCK, "ListPassProbe"),
            GLint(16 * (kPassListBuild + 1)));
  EXPECT_EQ(resourceOffset(program, GL_BUFFER_VARIABLE, "collectChunkProbe[0]"),
            GLint(4 * kCounterActiveDispatch));
  EXPECT_EQ(resourceOffset(program, GL_BUFFER_VARIABLE, "sleepProbeEnd"),
            GLint(4 * (kCounterActiveDispatch + kCollectChunk)));
  EXPECT_EQ(blockSize(program, GL_SHADER_STORAGE_BLOCK, "ActivePassesProbe"),
            GLint(16 * kActivePasses));
  glDeleteProgram(program);
}

}  // namespace
}  // namespace sandphys::detail
