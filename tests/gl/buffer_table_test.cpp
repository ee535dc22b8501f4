// gpu_buffers.def against the driver: every buffer's generated declaration, compiled, is a block
// at the entry's binding whose array has the stride the C++ side sizes it by, and every view is a
// sampler of the entry's unit whose texels are the array's elements.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "core/gpu_buffers.h"
#include "core/world_access.h"
#include "gl/shader_library.h"
#include "support/test_world.h"

namespace sandphys::detail {
namespace {

// A kernel may declare only 16 storage blocks, fewer than the table holds: each probe declares
// kProbeBuffers of them and their views, and makes them active.
constexpr unsigned kProbeBuffers = 12;

std::string probeSource(unsigned first, unsigned end) {
  std::string declarations;
  std::string sum = "0u";
  for (unsigned b = first; b < end; ++b) {
    const GpuBufferSpec& spec = kGpuBuffers[b];
    const std::string array = spec.array;
    declarations += std::string(spec.macro) + "(coherent)\n";
    sum += " + uint(" + array + ".length())";
    if (spec.textureUnit == kNoTextureUnit) continue;
    declarations += std::string(spec.macro) + "_TEXTURE\n";
    sum += " + uint(texelFetch(" + array + "Texture, 0).x)";
  }
  return "#version 450\n#include \"common/layout.glsl\"\nlayout(local_size_x = 1) in;\n" +
         declarations +
         "layout(std430, binding = 50) writeonly buffer ProbeOut { uint probeOut; };\n"
         "void main() { probeOut = " +
         sum + "; }\n";
}

GLint resourceProperty(GLuint program, GLenum interface, GLuint index, GLenum property) {
  GLint value = -1;
  glGetProgramResourceiv(program, interface, index, 1, &property, 1, nullptr, &value);
  return value;
}

struct ArrayLayout {
  GLint stride = -1;  // of the block's runtime-sized array
  GLint offset = -1;  // of its first element
};

GLint variableProperty(GLuint program, GLuint variable, GLenum property) {
  return resourceProperty(program, GL_BUFFER_VARIABLE, variable, property);
}

// The runtime-sized array among the block's variables (the others form a header): an array of
// vectors is one variable of array size 0; an array of structs is one variable per member, each
// of top-level array size 0, the first at the array's offset.
ArrayLayout arrayLayout(GLuint program, GLuint block) {
  const GLint count =
      resourceProperty(program, GL_SHADER_STORAGE_BLOCK, block, GL_NUM_ACTIVE_VARIABLES);
  std::vector<GLint> variables(std::size_t(std::max(count, 0)));
  const GLenum property = GL_ACTIVE_VARIABLES;
  glGetProgramResourceiv(program, GL_SHADER_STORAGE_BLOCK, block, 1, &property, count, nullptr,
                         variables.data());
  ArrayLayout layout;
  for (GLint v : variables) {
    const GLuint index = GLuint(v);
    if (variableProperty(program, index, GL_ARRAY_SIZE) == 0) {
      layout.stride = variableProperty(program, index, GL_ARRAY_STRIDE);
    } else if (variableProperty(program, index, GL_TOP_LEVEL_ARRAY_SIZE) == 0) {
      layout.stride = variableProperty(program, index, GL_TOP_LEVEL_ARRAY_STRIDE);
    } else {
      continue;
    }
    const GLint offset = variableProperty(program, index, GL_OFFSET);
    if (layout.offset < 0 || offset < layout.offset) layout.offset = offset;
  }
  return layout;
}

void expectBlock(GLuint program, unsigned binding) {
  const GpuBufferSpec& spec = kGpuBuffers[binding];
  const std::string name = std::string(spec.name) + "Buffer";
  const GLuint block = glGetProgramResourceIndex(program, GL_SHADER_STORAGE_BLOCK, name.c_str());
  ASSERT_NE(block, GL_INVALID_INDEX) << name << " is not active";
  EXPECT_EQ(resourceProperty(program, GL_SHADER_STORAGE_BLOCK, block, GL_BUFFER_BINDING),
            GLint(binding));
  const ArrayLayout layout = arrayLayout(program, block);
  EXPECT_EQ(layout.stride, GLint(spec.elementBytes));
  EXPECT_EQ(layout.offset, GLint(binding == kContactList ? kContactListHeaderBytes : 0));
}

void expectView(GLuint program, const GpuBufferSpec& spec) {
  const std::string name = std::string(spec.array) + "Texture";
  const GLuint sampler = glGetProgramResourceIndex(program, GL_UNIFORM, name.c_str());
  ASSERT_NE(sampler, GL_INVALID_INDEX) << name << " is not active";
  const GLenum format = viewFormat(spec.element);
  EXPECT_EQ(resourceProperty(program, GL_UNIFORM, sampler, GL_TYPE),
            GLint(format == GL_RGBA32F ? GL_SAMPLER_BUFFER : GL_UNSIGNED_INT_SAMPLER_BUFFER));
  GLint unit = -1;
  glGetUniformiv(program, resourceProperty(program, GL_UNIFORM, sampler, GL_LOCATION), &unit);
  EXPECT_EQ(unit, GLint(spec.textureUnit));
  // One texel per element, so that texel i is element i.
  EXPECT_EQ(format == GL_R32UI ? 4u : 16u, spec.elementBytes);
}

TEST(BufferTable, EveryBufferIsDeclaredAtItsBindingWithItsStrideAndView) {
  testing::gpu().makeCurrent();
  for (unsigned first = 0; first < kBindingCount; first += kProbeBuffers) {
    const unsigned end = std::min<unsigned>(first + kProbeBuffers, kBindingCount);
    gl::ShaderLibrary library(gl::embeddedShaders(),
                              {{kBufferDeclarationsFile, generatedBufferDeclarations()},
                               {"sim/buffers_probe.comp", probeSource(first, end)}});
    const GLuint program = library.compileCompute("sim/buffers_probe.comp");
    for (unsigned b = first; b < end; ++b) {
      SCOPED_TRACE(kGpuBuffers[b].array);
      expectBlock(program, b);
      if (kGpuBuffers[b].textureUnit != kNoTextureUnit) expectView(program, kGpuBuffers[b]);
    }
    glDeleteProgram(program);
  }
}

// What only sleeping sand uses (its lists of what a substep computes, the builds of each list and
// body, the quiet chunks, the spin and calm count beside each particle) takes the smallest buffer
// in a World without sleep, and the capacity in one with it: six buffers. The lists' near marks,
// which only a World without sleep uses, the other way round.
TEST(BufferTable, SleepBuffersTakeMemoryOnlyInASleepingWorldAndNearMarksOnlyInAnAwakeOne) {
  unsigned checked = 0;
  for (const bool sleep : {false, true}) {
    WorldSettings settings = testing::smallSettings(128);
    settings.sleep.enabled = sleep;
    testing::TestWorld world(settings);
    const World::Impl& w = WorldAccess::impl(*world);
    for (unsigned b = 0; b < kBindingCount; ++b) {
      const GpuBufferSpec& spec = kGpuBuffers[b];
      std::size_t units = 0;
      if (spec.sizedBy == SizedBy::SleepBodies) units = w.bodyCapacity;
      if (spec.sizedBy == SizedBy::SleepParticles) units = w.particleCapacity;
      if (spec.sizedBy == SizedBy::SleepChunks) {
        units = (w.bodyCapacity + kCollectChunk - 1) / kCollectChunk;
      }
      const bool awakeOnly = spec.sizedBy == SizedBy::AwakeLists;
      if (awakeOnly) units = w.particleCapacity;
      if (units == 0) continue;
      SCOPED_TRACE(std::string(spec.array) + (sleep ? ", sleep" : ", no sleep"));
      if (sleep != awakeOnly) {
        EXPECT_EQ(w.buffers[Binding(b)].size(), units * spec.unitBytes());
      } else {
        EXPECT_LE(w.buffers[Binding(b)].size(), 16u);  // gl::Buffer's smallest
      }
      ++checked;
    }
  }
  EXPECT_EQ(checked, 14u);
}

// World::gpuMemoryByBuffer names every buffer of the table, in its order, then the uniform block;
// each entry is that buffer's size, the sizes add up to gpuMemoryBytes, and the buffers sized by
// the particles hold the capacity's elements (the contact slots: four of 16 B per particle in each
// group).
TEST(BufferTable, MemoryByBufferIsEachBufferAndAddsUpToTheWorldsMemory) {
  testing::TestWorld world(testing::smallSettings(128));
  const World::Impl& w = WorldAccess::impl(*world);
  const std::vector<BufferMemory> memory = world->gpuMemoryByBuffer();
  ASSERT_EQ(memory.size(), kBindingCount + 1u);
  std::uint64_t sum = 0;
  for (unsigned b = 0; b < kBindingCount; ++b) {
    SCOPED_TRACE(kGpuBuffers[b].array);
    EXPECT_EQ(memory[b].name, kGpuBuffers[b].array);
    EXPECT_EQ(memory[b].bytes, w.buffers[Binding(b)].size());
    sum += memory[b].bytes;
  }
  EXPECT_EQ(memory.back().name, "params");
  EXPECT_EQ(memory.back().bytes, w.buffers.params.size());
  EXPECT_EQ(sum + memory.back().bytes, world->gpuMemoryBytes());
  const std::uint64_t particles = world->particleCapacity();
  EXPECT_EQ(memory[kParticlePosition].bytes, particles * 16u);
  for (const Binding slots : {kContactSlots0, kContactSlots1, kContactSlots2}) {
    EXPECT_EQ(memory[slots].bytes, particles * 4u * 16u) << memory[slots].name;
  }
}

}  // namespace
}  // namespace sandphys::detail
