#pragma once

// The storage buffers of a World, made from the one list in core/gpu_buffers.def: their binding
// points, texture units, sizes and GLSL declarations.

#include <GL/glew.h>

#include <cstddef>
#include <string>
#include <string_view>

#include "core/gpu_layout.h"

namespace sandphys::detail {

/// What a buffer's element count follows. Lists and the grid's buffers (Table, TablePlusOne,
/// ScanBlocks, GridParticles: one of each per grid, two under sleep) are rebuilt from the
/// particles, so nothing is kept when they grow.
/// History: the particles when the contact law keeps contact state (HertzMindlin), else one unit;
/// RollingHistory: the particles when it also keeps rolling springs (rolling friction), else one;
/// SleepBodies, SleepParticles: the bodies, the particles with sleep, else one unit; SleepChunks:
/// collect_active.comp's chunks of kCollectChunk bodies with sleep, else one unit.
/// OrderBodies: the bodies when the granules are sorted by place (WorldSettings::sortInterval),
/// else one unit.
/// AwakeLists: the particles without sleep, else one unit, rebuilt from the lists.
enum class SizedBy {
  Bodies,
  Particles,
  SleepBodies,
  SleepParticles,
  SleepChunks,
  OrderBodies,
  Lists,
  AwakeLists,
  History,
  RollingHistory,
  Table,
  TablePlusOne,
  ScanBlocks,
  GridParticles,
  Colliders,
  Fixed
};

/// SSBO binding points, one per buffer, in the order of gpu_buffers.def.
enum Binding : unsigned {
#define SANDPHYS_GPU_BUFFER(Name, ...) k##Name,
#include "core/gpu_buffers.def"
  kBindingCount
};
/// The storage binding past the table's: whichever buffer the sort of the granules by place moves
/// (World::Impl::sortGranules).
inline constexpr unsigned kOrderTarget = kBindingCount;

/// Texture units of the read-only buffer-texture views (View in gpu_buffers.def). On llvmpipe an
/// SSBO load at a per-invocation offset runs lane by lane, while a texel fetch is one vector
/// gather; on GPUs it is the cached read path. A kernel reads through a view only what earlier
/// dispatches wrote.
enum TextureUnit : unsigned {
#define SANDPHYS_TEXTURE_UNIT_View(Name) k##Name##Texture,
#define SANDPHYS_TEXTURE_UNIT_ViewAndImage(Name) k##Name##Texture,
#define SANDPHYS_TEXTURE_UNIT_NoView(Name)
#define SANDPHYS_GPU_BUFFER(Name, array, macro, element, bytes, sizedBy, perUnit, view, ...) \
  SANDPHYS_TEXTURE_UNIT_##view(Name)
#include "core/gpu_buffers.def"
#undef SANDPHYS_TEXTURE_UNIT_View
#undef SANDPHYS_TEXTURE_UNIT_ViewAndImage
#undef SANDPHYS_TEXTURE_UNIT_NoView
  kTextureCount
};
inline constexpr unsigned kNoTextureUnit = ~0u;

/// Image units of the buffers written through an image of their view (ViewAndImage in
/// gpu_buffers.def): a kernel that already binds as many storage blocks as the driver allows
/// (contacts.comp) writes them with imageStore, which also has no storage block's size limit.
enum ImageUnit : unsigned {
#define SANDPHYS_IMAGE_UNIT_View(Name)
#define SANDPHYS_IMAGE_UNIT_ViewAndImage(Name) k##Name##Image,
#define SANDPHYS_IMAGE_UNIT_NoView(Name)
#define SANDPHYS_GPU_BUFFER(Name, array, macro, element, bytes, sizedBy, perUnit, view, ...) \
  SANDPHYS_IMAGE_UNIT_##view(Name)
#include "core/gpu_buffers.def"
#undef SANDPHYS_IMAGE_UNIT_View
#undef SANDPHYS_IMAGE_UNIT_ViewAndImage
#undef SANDPHYS_IMAGE_UNIT_NoView
  kImageCount
};
inline constexpr unsigned kNoImageUnit = ~0u;

/// One entry of gpu_buffers.def, whose header explains the fields.
struct GpuBufferSpec {
  const char* name;  ///< NameBuffer is the GLSL block
  const char* array;
  const char* macro;
  const char* element;
  std::size_t elementBytes;
  SizedBy sizedBy;
  std::size_t perUnit;
  unsigned textureUnit;  ///< kNoTextureUnit: no view
  unsigned imageUnit;    ///< kNoImageUnit: not written through an image
  const char* header;

  /// Bytes per body, particle, bucket... (in all, for SizedBy::Fixed).
  constexpr std::size_t unitBytes() const { return elementBytes * perUnit; }
};

/// Format of a texture view: one texel per element of these types, none for the others.
constexpr GLenum viewFormat(std::string_view element) {
  if (element == "vec4") return GL_RGBA32F;
  if (element == "uvec4") return GL_RGBA32UI;
  if (element == "uint") return GL_R32UI;
  return GL_NONE;
}

/// gpu_buffers.def as a table, indexed by Binding.
inline constexpr GpuBufferSpec kGpuBuffers[kBindingCount] = {
#define SANDPHYS_TEXTURE_UNIT_View(Name) k##Name##Texture
#define SANDPHYS_TEXTURE_UNIT_ViewAndImage(Name) k##Name##Texture
#define SANDPHYS_TEXTURE_UNIT_NoView(Name) kNoTextureUnit
#define SANDPHYS_IMAGE_UNIT_View(Name) kNoImageUnit
#define SANDPHYS_IMAGE_UNIT_ViewAndImage(Name) k##Name##Image
#define SANDPHYS_IMAGE_UNIT_NoView(Name) kNoImageUnit
// gpu_buffers.def's fields in order: Name, array, MACRO, element, elementBytes, sizedBy, perUnit...
#define SANDPHYS_GPU_BUFFER(N, A, M, E, B, S, P, V, ...) \
  {.name = #N,                                           \
   .array = #A,                                          \
   .macro = #M,                                          \
   .element = #E,                                        \
   .elementBytes = B,                                    \
   .sizedBy = SizedBy::S,                                \
   .perUnit = P,                                         \
   .textureUnit = SANDPHYS_TEXTURE_UNIT_##V(N),          \
   .imageUnit = SANDPHYS_IMAGE_UNIT_##V(N),              \
   .header = #__VA_ARGS__},
#include "core/gpu_buffers.def"
#undef SANDPHYS_TEXTURE_UNIT_View
#undef SANDPHYS_TEXTURE_UNIT_ViewAndImage
#undef SANDPHYS_TEXTURE_UNIT_NoView
#undef SANDPHYS_IMAGE_UNIT_View
#undef SANDPHYS_IMAGE_UNIT_ViewAndImage
#undef SANDPHYS_IMAGE_UNIT_NoView
};

constexpr bool everyViewHasAFormat() {
  for (const GpuBufferSpec& spec : kGpuBuffers) {
    if (spec.textureUnit != kNoTextureUnit && viewFormat(spec.element) == GL_NONE) return false;
  }
  return true;
}
static_assert(everyViewHasAFormat(),
              "a View in gpu_buffers.def needs a vec4, uvec4 or uint element");
constexpr bool everyImageIsVec4() {
  for (const GpuBufferSpec& spec : kGpuBuffers) {
    if (spec.imageUnit != kNoImageUnit && viewFormat(spec.element) != GL_RGBA32F) return false;
  }
  return true;
}
static_assert(everyImageIsVec4(), "a ViewAndImage in gpu_buffers.def needs a vec4 element");
// The contact slot groups are addressed as kContactSlots0 + group: in a row, before kContactPairs.
static_assert(kContactSlots0 + kContactSlotGroups == kContactPairs);

/// Bytes before the contact list's records (the header in gpu_buffers.def).
inline constexpr std::size_t kContactListHeaderBytes = 16;

/// Where the shader loader serves generatedBufferDeclarations() (included by layout.glsl).
inline constexpr const char* kBufferDeclarationsFile = "sim/common/buffers.glsl";
/// The GLSL declarations of kGpuBuffers: MACRO(access) for each buffer, MACRO_TEXTURE for each
/// view, MACRO_IMAGE(access) for each image.
std::string generatedBufferDeclarations();

}  // namespace sandphys::detail
