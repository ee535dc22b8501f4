#include "core/gpu_buffers.h"

namespace sandphys::detail {

std::string generatedBufferDeclarations() {
  std::string out =
      "// Generated from sandphys/src/core/gpu_buffers.def, where each buffer's meaning is "
      "written.\n";
  for (unsigned b = 0; b < kBindingCount; ++b) {
    const GpuBufferSpec& spec = kGpuBuffers[b];
    const std::string header = *spec.header ? std::string(spec.header) + " " : std::string();
    out += "#define " + std::string(spec.macro) +
           "(access) layout(std430, binding = " + std::to_string(b) + ") access buffer " +
           spec.name + "Buffer { " + header + spec.element + " " + spec.array + "[]; };\n";
  }
  // The one binding past the table's: the buffer the sort of the granules moves at the time
  // (common/granule_order.glsl), as words.
  out += "#define ORDER_TARGET(access) layout(std430, binding = " + std::to_string(kOrderTarget) +
         ") access buffer OrderTargetBuffer { uint orderTarget[]; };\n";
  for (const GpuBufferSpec& spec : kGpuBuffers) {
    if (spec.textureUnit == kNoTextureUnit) continue;
    const char* sampler =
        viewFormat(spec.element) == GL_RGBA32F ? "samplerBuffer" : "usamplerBuffer";
    out += "#define " + std::string(spec.macro) +
           "_TEXTURE layout(binding = " + std::to_string(spec.textureUnit) + ") uniform " +
           sampler + " " + spec.array + "Texture;\n";
  }
  for (const GpuBufferSpec& spec : kGpuBuffers) {
    if (spec.imageUnit == kNoImageUnit) continue;
    out += "#define " + std::string(spec.macro) +
           "_IMAGE(access) layout(rgba32f, binding = " + std::to_string(spec.imageUnit) +
           ") uniform access imageBuffer " + spec.array + "Image;\n";
  }
  return out;
}

}  // namespace sandphys::detail
