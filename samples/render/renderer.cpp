#include "render/renderer.h"

#include <GL/glew.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <string>

#include <sandphys/error.h>
#include <sandphys/gl_interop.h>

#include "gl/shader_library.h"
#include "render/collider_mesh.h"
#include "render/render_shaders.h"
#include "render/surface_mesh.h"

namespace sandphys::render {

namespace {

// uniform FrameParams in shaders/render/common/frame.glsl (std140).
struct FrameParams {
  float view[16];
  float projection[16];
  float inverseView[16];
  float inverseProjection[16];
  float lightMatrix[16];
  float lightDirection[4];
  float lightColour[4];
  float skyColour[4];
  float groundColour[4];
  float params[4];
  float viewport[4];
  float cameraPosition[4];
};
static_assert(sizeof(FrameParams) == 5 * 64 + 7 * 16);

// Binding points of shaders/render/common/world_buffers.glsl.
constexpr GLuint kBodyPositionBinding = 0;
constexpr GLuint kBodyOrientationBinding = 1;
constexpr GLuint kBodyInfoBinding = 2;
constexpr GLuint kParticleLocalBinding = 3;
constexpr GLuint kParticleBodyBinding = 4;
constexpr GLuint kBodyVelocityBinding = 5;
// The renderer's own: shaders/render/particles.vert's surfaceBodies.
constexpr GLuint kSurfaceBodiesBinding = 6;
constexpr GLuint kBodyIdsBinding = 7;
constexpr GLint kVertexStorageBlocks = 8;
constexpr GLuint kFrameParamsBinding = 0;

// Timestamps per frame: before the shadow pass, then after each of the three passes.
constexpr int kStamps = 4;

void copyMatrix(float (&out)[16], const Eigen::Matrix4f& m) {
  std::memcpy(out, m.data(), sizeof out);  // both column-major
}

void copyVector(float (&out)[4], const Eigen::Vector3f& v, float w) {
  out[0] = v.x();
  out[1] = v.y();
  out[2] = v.z();
  out[3] = w;
}

}  // namespace

struct Renderer::Impl {
  RenderSettings settings;
  RenderStats stats;

  // Point sprites for every particle that fits one; quads for the ones too large (close-ups).
  GLuint pointsShadow = 0;
  GLuint pointsScene = 0;
  GLuint particlesShadow = 0;
  GLuint particlesScene = 0;
  float maxPointSize = 1.0f;  // px
  GLuint meshShadow = 0;
  GLuint meshScene = 0;
  GLuint surfaceShadow = 0;
  GLuint surfaceScene = 0;
  GLint surfaceAlbedo = -1;
  GLint meshFocusMin = -1;
  GLint meshFocusMax = -1;
  GLuint composite = 0;
  GLuint upscale = 0;
  GLint compositeAoSamples = -1;
  GLint compositeBackground = -1;

  GLuint emptyVao = 0;
  GLuint meshVao = 0;
  GLuint meshBuffer = 0;
  std::size_t meshCapacity = 0;  // vertices
  // The bodies' surfaces (surface_mesh.h) as last uploaded, and which bodies have one.
  GLuint surfaceVao = 0;
  GLuint surfaceBuffer = 0;
  GLsizei surfaceVertices = 0;
  std::uint64_t surfaceHash = 0;
  bool surfacesUploaded = false;
  GLuint surfaceBodies = 0;
  GLuint surfaceBodyWords = 0;
  GLuint frameParams[2] = {};  // 0: light's pass, 1: eye's passes

  int shadowSize = 0;
  GLuint shadowFramebuffer = 0;
  GLuint shadowDepth = 0;

  int width = 0;
  int height = 0;
  GLuint sceneFramebuffer = 0;
  GLuint sceneTextures[4] = {};  // direct, ambient, normal, depth
  // The composite of a scaled frame (renderScale < 1), before it is scaled up.
  GLuint scaledFramebuffer = 0;
  GLuint scaledTextures[2] = {};  // colour, depth

  // Two sets of timestamps, used in turn, so that reading a frame's times never waits.
  GLuint queries[2][kStamps] = {};
  bool pending[2] = {false, false};
  std::uint64_t pendingFrame[2] = {0, 0};
  std::uint32_t pendingParticles[2] = {0, 0};
  int pendingWidth[2] = {0, 0};
  int pendingHeight[2] = {0, 0};
  int nextSet = 0;
  int lastSet = 0;
  std::uint64_t frames = 0;

  Impl() {
    GLint vertexBlocks = 0;
    glGetIntegerv(GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS, &vertexBlocks);
    if (vertexBlocks < kVertexStorageBlocks) {
      throw GpuError("the renderer reads the World's buffers in its vertex shader and needs " +
                     std::to_string(kVertexStorageBlocks) +
                     " shader storage blocks there; this GL offers " +
                     std::to_string(vertexBlocks));
    }
    gl::ShaderLibrary library(gl::renderShaders());
    const std::vector<gl::ShaderStage> particles = {{GL_VERTEX_SHADER, "render/particles.vert"},
                                                    {GL_FRAGMENT_SHADER, "render/particles.frag"}};
    const std::vector<gl::ShaderStage> mesh = {{GL_VERTEX_SHADER, "render/mesh.vert"},
                                               {GL_FRAGMENT_SHADER, "render/mesh.frag"}};
    pointsShadow = library.compileProgram(particles, {"SHADOW_PASS 1", "POINT_SPRITES 1"});
    pointsScene = library.compileProgram(particles, {"POINT_SPRITES 1"});
    particlesShadow = library.compileProgram(particles, {"SHADOW_PASS 1"});
    particlesScene = library.compileProgram(particles);
    GLfloat pointRange[2] = {1.0f, 1.0f};
    glGetFloatv(GL_POINT_SIZE_RANGE, pointRange);
    maxPointSize = std::max(pointRange[1], 1.0f);
    for (GLuint program : {pointsShadow, pointsScene, particlesShadow, particlesScene}) {
      glProgramUniform1f(program, glGetUniformLocation(program, "maxPointSize"), maxPointSize);
    }
    meshShadow = library.compileProgram(mesh, {"SHADOW_PASS 1"});
    meshScene = library.compileProgram(mesh);
    meshFocusMin = glGetUniformLocation(meshScene, "focusMin");
    meshFocusMax = glGetUniformLocation(meshScene, "focusMax");
    const std::vector<gl::ShaderStage> surface = {{GL_VERTEX_SHADER, "render/surface.vert"},
                                                  {GL_FRAGMENT_SHADER, "render/surface.frag"}};
    const std::string materials = "BODY_MATERIALS " + std::to_string(scenes::kBodyMaterials);
    surfaceShadow = library.compileProgram(surface, {"SHADOW_PASS 1", materials});
    surfaceScene = library.compileProgram(surface, {materials});
    surfaceAlbedo = glGetUniformLocation(surfaceScene, "materialAlbedo");
    composite = library.compileProgram({{GL_VERTEX_SHADER, "render/fullscreen.vert"},
                                        {GL_FRAGMENT_SHADER, "render/composite.frag"}});
    upscale = library.compileProgram({{GL_VERTEX_SHADER, "render/fullscreen.vert"},
                                      {GL_FRAGMENT_SHADER, "render/upscale.frag"}});
    compositeAoSamples = glGetUniformLocation(composite, "aoSamples");
    compositeBackground = glGetUniformLocation(composite, "background");

    glCreateVertexArrays(1, &emptyVao);
    glCreateVertexArrays(1, &meshVao);
    glCreateVertexArrays(1, &surfaceVao);
    glCreateBuffers(2, frameParams);
    for (GLuint buffer : frameParams) {
      glNamedBufferStorage(buffer, sizeof(FrameParams), nullptr, GL_DYNAMIC_STORAGE_BIT);
    }
    glGenQueries(2 * kStamps, &queries[0][0]);
  }

  ~Impl() {
    for (GLuint program : {pointsShadow, pointsScene, particlesShadow, particlesScene, meshShadow,
                           meshScene, surfaceShadow, surfaceScene, composite, upscale}) {
      glDeleteProgram(program);
    }
    glDeleteVertexArrays(1, &emptyVao);
    glDeleteVertexArrays(1, &meshVao);
    glDeleteVertexArrays(1, &surfaceVao);
    glDeleteBuffers(1, &meshBuffer);
    glDeleteBuffers(1, &surfaceBuffer);
    glDeleteBuffers(1, &surfaceBodies);
    glDeleteBuffers(2, frameParams);
    releaseShadowMap();
    releaseSceneTargets();
    glDeleteQueries(2 * kStamps, &queries[0][0]);
  }

  void releaseShadowMap() {
    glDeleteFramebuffers(1, &shadowFramebuffer);
    glDeleteTextures(1, &shadowDepth);
    shadowFramebuffer = shadowDepth = 0;
    shadowSize = 0;
  }

  void releaseSceneTargets() {
    glDeleteFramebuffers(1, &sceneFramebuffer);
    glDeleteTextures(4, sceneTextures);
    glDeleteFramebuffers(1, &scaledFramebuffer);
    glDeleteTextures(2, scaledTextures);
    sceneFramebuffer = scaledFramebuffer = 0;
    std::fill(std::begin(sceneTextures), std::end(sceneTextures), 0u);
    std::fill(std::begin(scaledTextures), std::end(scaledTextures), 0u);
    width = height = 0;
  }

  static void makeTexture(GLuint& texture, GLenum format, int w, int h, GLenum filter) {
    glCreateTextures(GL_TEXTURE_2D, 1, &texture);
    glTextureStorage2D(texture, 1, format, w, h);
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GLint(filter));
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GLint(filter));
    glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }

  void ensureShadowMap(int size) {
    if (size == shadowSize) return;
    releaseShadowMap();
    glCreateTextures(GL_TEXTURE_2D, 1, &shadowDepth);
    glTextureStorage2D(shadowDepth, 1, GL_DEPTH_COMPONENT32F, size, size);
    // Hardware comparison with bilinear filtering: each tap is already a 2x2 PCF.
    glTextureParameteri(shadowDepth, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(shadowDepth, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(shadowDepth, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTextureParameteri(shadowDepth, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    glTextureParameteri(shadowDepth, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(shadowDepth, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glCreateFramebuffers(1, &shadowFramebuffer);
    glNamedFramebufferTexture(shadowFramebuffer, GL_DEPTH_ATTACHMENT, shadowDepth, 0);
    glNamedFramebufferDrawBuffer(shadowFramebuffer, GL_NONE);
    glNamedFramebufferReadBuffer(shadowFramebuffer, GL_NONE);
    checkComplete(shadowFramebuffer, "shadow map");
    shadowSize = size;
  }

  void ensureSceneTargets(int w, int h) {
    if (w == width && h == height) return;
    releaseSceneTargets();
    const GLenum formats[4] = {GL_RGBA16F, GL_RGBA16F, GL_RGBA8, GL_DEPTH_COMPONENT32F};
    glCreateFramebuffers(1, &sceneFramebuffer);
    for (int i = 0; i < 4; ++i) {
      makeTexture(sceneTextures[i], formats[i], w, h, GL_NEAREST);
      glNamedFramebufferTexture(sceneFramebuffer,
                                i < 3 ? GLenum(GL_COLOR_ATTACHMENT0 + i) : GL_DEPTH_ATTACHMENT,
                                sceneTextures[i], 0);
    }
    const GLenum drawBuffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1,
                                   GL_COLOR_ATTACHMENT2};
    glNamedFramebufferDrawBuffers(sceneFramebuffer, 3, drawBuffers);
    checkComplete(sceneFramebuffer, "scene targets");
    // Made with the scene targets even at full scale: a few bytes per pixel, and a quality
    // change never reallocates in the middle of an interaction.
    makeTexture(scaledTextures[0], GL_RGBA8, w, h, GL_LINEAR);
    makeTexture(scaledTextures[1], GL_DEPTH_COMPONENT32F, w, h, GL_NEAREST);
    glCreateFramebuffers(1, &scaledFramebuffer);
    glNamedFramebufferTexture(scaledFramebuffer, GL_COLOR_ATTACHMENT0, scaledTextures[0], 0);
    glNamedFramebufferTexture(scaledFramebuffer, GL_DEPTH_ATTACHMENT, scaledTextures[1], 0);
    checkComplete(scaledFramebuffer, "scaled composite");
    width = w;
    height = h;
  }

  static void checkComplete(GLuint framebuffer, const char* what) {
    const GLenum status = glCheckNamedFramebufferStatus(framebuffer, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
      throw GpuError(std::string("renderer: the ") + what + " framebuffer is incomplete (status " +
                     std::to_string(status) + ")");
    }
  }

  void uploadMesh(const std::vector<MeshVertex>& vertices) {
    if (vertices.size() > meshCapacity) {
      glDeleteBuffers(1, &meshBuffer);
      meshCapacity = std::max<std::size_t>(vertices.size(), 1024);
      glCreateBuffers(1, &meshBuffer);
      glNamedBufferStorage(meshBuffer, GLsizeiptr(meshCapacity * sizeof(MeshVertex)), nullptr,
                           GL_DYNAMIC_STORAGE_BIT);
      glVertexArrayVertexBuffer(meshVao, 0, meshBuffer, 0, sizeof(MeshVertex));
      for (GLuint attribute : {0u, 1u}) {
        glEnableVertexArrayAttrib(meshVao, attribute);
        glVertexArrayAttribFormat(meshVao, attribute, 4, GL_FLOAT, GL_FALSE,
                                  attribute * 4 * sizeof(float));
        glVertexArrayAttribBinding(meshVao, attribute, 0);
      }
    }
    if (!vertices.empty()) {
      glNamedBufferSubData(meshBuffer, 0, GLsizeiptr(vertices.size() * sizeof(MeshVertex)),
                           vertices.data());
    }
  }

  // Uploads the surfaces' triangles and the bit set of the bodies they cover, when they are not
  // those of the last upload.
  void uploadSurfaces(std::span<const scenes::SceneSurface> surfaces) {
    const std::uint64_t hash = surfacesHash(surfaces);
    if (surfacesUploaded && hash == surfaceHash) return;
    surfaceHash = hash;
    surfacesUploaded = true;
    const std::vector<SurfaceVertex> vertices = buildSurfaceMesh(surfaces);
    std::vector<GLuint> bits;
    for (const scenes::SceneSurface& s : surfaces) {
      if (!s.body.isValid()) continue;
      const std::size_t word = s.body.index / 32u;
      if (bits.size() <= word) bits.resize(word + 1, 0u);
      bits[word] |= 1u << (s.body.index % 32u);
    }
    glDeleteBuffers(1, &surfaceBuffer);
    glDeleteBuffers(1, &surfaceBodies);
    surfaceBuffer = surfaceBodies = 0;
    surfaceVertices = GLsizei(vertices.size());
    surfaceBodyWords = GLuint(bits.size());
    if (!vertices.empty()) {
      glCreateBuffers(1, &surfaceBuffer);
      glNamedBufferStorage(surfaceBuffer, GLsizeiptr(vertices.size() * sizeof(SurfaceVertex)),
                           vertices.data(), 0);
      glVertexArrayVertexBuffer(surfaceVao, 0, surfaceBuffer, 0, sizeof(SurfaceVertex));
      glVertexArrayAttribFormat(surfaceVao, 0, 3, GL_FLOAT, GL_FALSE, offsetof(SurfaceVertex, x));
      glVertexArrayAttribIFormat(surfaceVao, 1, 1, GL_UNSIGNED_INT, offsetof(SurfaceVertex, body));
      glVertexArrayAttribFormat(surfaceVao, 2, 3, GL_FLOAT, GL_FALSE, offsetof(SurfaceVertex, nx));
      glVertexArrayAttribIFormat(surfaceVao, 3, 1, GL_UNSIGNED_INT,
                                 offsetof(SurfaceVertex, material));
      for (GLuint attribute = 0; attribute < 4; ++attribute) {
        glEnableVertexArrayAttrib(surfaceVao, attribute);
        glVertexArrayAttribBinding(surfaceVao, attribute, 0);
      }
    }
    // Never empty, so that binding 6 always names a buffer.
    if (bits.empty()) bits.push_back(0u);
    glCreateBuffers(1, &surfaceBodies);
    glNamedBufferStorage(surfaceBodies, GLsizeiptr(bits.size() * sizeof(GLuint)), bits.data(), 0);
  }

  // Reads a finished set of timestamps into `stats`; waits only when asked to.
  void collect(int set, bool wait) {
    if (!pending[set]) return;
    if (!wait) {
      GLint available = 0;
      glGetQueryObjectiv(queries[set][kStamps - 1], GL_QUERY_RESULT_AVAILABLE, &available);
      if (!available) return;
    }
    GLuint64 t[kStamps] = {};
    for (int i = 0; i < kStamps; ++i) {
      glGetQueryObjectui64v(queries[set][i], GL_QUERY_RESULT, &t[i]);
    }
    auto ms = [&](int a, int b) { return t[b] > t[a] ? double(t[b] - t[a]) * 1e-6 : 0.0; };
    stats.shadowMs = ms(0, 1);
    stats.sceneMs = ms(1, 2);
    stats.compositeMs = ms(2, 3);
    stats.totalMs = ms(0, 3);
    stats.particles = pendingParticles[set];
    stats.renderWidth = pendingWidth[set];
    stats.renderHeight = pendingHeight[set];
    stats.frame = pendingFrame[set];
    pending[set] = false;
  }

  // Points for every particle that fits one, then (when `quads` is a program) quads for the rest.
  void drawParticles(GLsizei count, GLuint points, GLuint quads) const {
    if (count <= 0) return;
    glBindVertexArray(emptyVao);
    glEnable(GL_PROGRAM_POINT_SIZE);
    glUseProgram(points);
    glDrawArrays(GL_POINTS, 0, count);
    glDisable(GL_PROGRAM_POINT_SIZE);
    if (quads != 0) {
      glUseProgram(quads);
      glDrawArrays(GL_TRIANGLES, 0, 6 * count);
    }
  }

  void draw(const World& world, const Camera& camera, const scenes::SceneBounds& bounds, int w,
            int h, std::span<const scenes::SceneSurface> surfaces);

  // The surfaces' triangles with `program` (the shadow or the scene pass).
  void drawSurfaces(GLuint program) const {
    glUseProgram(program);
    glBindVertexArray(surfaceVao);
    glDrawArrays(GL_TRIANGLES, 0, surfaceVertices);
  }
};

void Renderer::Impl::draw(const World& world, const Camera& camera,
                          const scenes::SceneBounds& bounds, int w, int h,
                          std::span<const scenes::SceneSurface> surfaces) {
  if (w < 1 || h < 1) {
    throw InvalidArgument("Renderer::draw viewport " + std::to_string(w) + "x" + std::to_string(h) +
                          ": each side must be >= 1");
  }
  const int mapSize = std::clamp(settings.shadowMapSize, 16, 8192);
  const float scale =
      settings.renderScale > 0.0f ? std::clamp(settings.renderScale, 0.25f, 1.0f) : 1.0f;
  const bool scaled = scale < 1.0f;
  // The size the scene is lit and composited at.
  const int sw = scaled ? std::max(1, int(std::lround(float(w) * scale))) : w;
  const int sh = scaled ? std::max(1, int(std::lround(float(h) * scale))) : h;
  GLint target = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
  ensureShadowMap(mapSize);
  ensureSceneTargets(sw, sh);
  const int set = nextSet;
  nextSet = 1 - nextSet;
  // The set about to be reused is two frames old (waits only if that frame is still running);
  // then the previous frame's, if it is done, so that stats() shows the newest times.
  collect(set, true);
  collect(nextSet, false);

  const RenderBuffers buffers = renderBuffers(world);
  const float radius = 0.5f * buffers.particleDiameter;

  // --- Per-pass constants ----------------------------------------------------------------------
  const Eigen::Vector3f lo(bounds.min.x, bounds.min.y, bounds.min.z);
  const Eigen::Vector3f hi(bounds.max.x, bounds.max.y, bounds.max.z);
  const Eigen::Vector3f centre = 0.5f * (lo + hi);
  const float sceneRadius = std::max(0.5f * (hi - lo).norm(), 4.0f * buffers.particleDiameter);
  Eigen::Vector3f toLight = settings.light.direction;
  if (!(toLight.norm() > 1e-6f)) toLight = Eigen::Vector3f::UnitY();
  toLight.normalize();
  // An orthographic light fitted around the bounding sphere of the scene.
  const Eigen::Matrix4f lightView =
      lookAt(centre + 2.0f * sceneRadius * toLight, centre,
             std::abs(toLight.y()) < 0.99f ? Eigen::Vector3f::UnitY() : Eigen::Vector3f::UnitX());
  const Eigen::Matrix4f lightProjection = orthographic(
      -sceneRadius, sceneRadius, -sceneRadius, sceneRadius, 0.5f * sceneRadius, 3.5f * sceneRadius);
  const Eigen::Matrix4f lightMatrix = lightProjection * lightView;
  const float aspect = float(w) / float(h);
  const Eigen::Matrix4f view = camera.view();
  const Eigen::Matrix4f projection = camera.projection(aspect);

  FrameParams eye{};
  copyMatrix(eye.view, view);
  copyMatrix(eye.projection, projection);
  copyMatrix(eye.inverseView, view.inverse());
  copyMatrix(eye.inverseProjection, projection.inverse());
  copyMatrix(eye.lightMatrix, lightMatrix);
  copyVector(eye.lightDirection, toLight, 0.0f);
  copyVector(eye.lightColour, settings.light.colour, 0.0f);
  copyVector(eye.skyColour, settings.light.sky, 0.0f);
  copyVector(eye.groundColour, settings.light.ground, 0.0f);
  eye.params[0] = radius;
  eye.params[1] = 1.0f / float(mapSize);
  eye.params[2] = settings.shadows ? 1.0f : 0.0f;
  eye.params[3] = std::max(settings.aoRadius, 0.01f) * buffers.particleDiameter;
  eye.viewport[0] = float(sw);
  eye.viewport[1] = float(sh);
  eye.viewport[2] = 1.0f / float(sw);
  eye.viewport[3] = 1.0f / float(sh);
  copyVector(eye.cameraPosition, camera.eye(), 1.0f);
  FrameParams light = eye;
  copyMatrix(light.view, lightView);
  copyMatrix(light.projection, lightProjection);
  copyMatrix(light.inverseView, lightView.inverse());
  copyMatrix(light.inverseProjection, lightProjection.inverse());
  light.lightDirection[3] = 1.0f;  // orthographic pass
  light.viewport[0] = light.viewport[1] = float(mapSize);
  light.viewport[2] = light.viewport[3] = 1.0f / float(mapSize);
  glNamedBufferSubData(frameParams[0], 0, sizeof light, &light);
  glNamedBufferSubData(frameParams[1], 0, sizeof eye, &eye);

  std::vector<MeshVertex> mesh;
  if (settings.drawColliders) {
    // Planes cut to the scene's bounds (a little wider, so that a floor at their bottom face
    // is not cut at a rounding's whim).
    const Eigen::Vector3f room = 0.02f * (hi - lo) + Eigen::Vector3f::Constant(1e-4f);
    mesh = buildColliderMesh(world.colliders(), lo - room, hi + room);
  }
  uploadMesh(mesh);
  uploadSurfaces(surfaces);

  // --- Bind the World's buffers (read-only) ----------------------------------------------------
  // The simulation's last writes must be visible to the vertex shader's storage reads.
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBodyPositionBinding, buffers.bodyPosition);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBodyOrientationBinding, buffers.bodyOrientation);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBodyInfoBinding, buffers.bodyInfo);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kParticleLocalBinding, buffers.particleLocal);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kParticleBodyBinding, buffers.particleBody);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBodyVelocityBinding, buffers.bodyVelocity);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSurfaceBodiesBinding, surfaceBodies);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBodyIdsBinding, buffers.bodyIds);
  const GLuint asleepFrom = settings.tintSleeping ? buffers.sleepSubsteps : 0u;
  for (GLuint program : {pointsScene, particlesScene}) {
    glProgramUniform1ui(program, glGetUniformLocation(program, "asleepFrom"), asleepFrom);
  }
  // The surfaces stand in for their bodies' particles, unless the particles are asked for.
  const GLuint hiddenWords = settings.bodyParticles ? 0u : surfaceBodyWords;
  for (GLuint program : {pointsShadow, pointsScene, particlesShadow, particlesScene}) {
    glProgramUniform1ui(program, glGetUniformLocation(program, "surfaceBodyWords"), hiddenWords);
  }
  const GLsizei surfaceCount = settings.bodyParticles ? 0 : surfaceVertices;
  float albedo[3 * scenes::kBodyMaterials];
  for (std::size_t m = 0; m < scenes::kBodyMaterials; ++m) {
    for (int c = 0; c < 3; ++c) {
      albedo[3 * m + c] = std::pow(std::clamp(settings.materialColours[m][c], 0.0f, 1.0f), 2.2f);
    }
  }
  glProgramUniform3fv(surfaceScene, surfaceAlbedo, GLsizei(scenes::kBodyMaterials), albedo);
  const scenes::SceneBounds focus = camera.focus.value_or(scenes::SceneBounds{});
  glProgramUniform4f(meshScene, meshFocusMin, focus.min.x, focus.min.y, focus.min.z,
                     camera.focus ? 1.0f : 0.0f);
  glProgramUniform3f(meshScene, meshFocusMax, focus.max.x, focus.max.y, focus.max.z);
  const GLsizei particles = GLsizei(buffers.particleCount);
  // Whether some particle may need a larger square than a point sprite allows, so that the quad
  // draw must follow the points. From the light: every particle has the same size. From the
  // eye: the nearest a particle inside the scene's bounds can come, with a factor 2 for the
  // stretch of off-axis spheres in a wide view.
  const float lightSpritePx = 2.0f * radius * float(mapSize) / (2.0f * sceneRadius);
  const bool lightNeedsQuads = lightSpritePx + 1.0f > maxPointSize;
  const Eigen::Vector3f eyePosition = camera.eye();
  const Eigen::Vector3f nearestInBounds = eyePosition.cwiseMax(lo).cwiseMin(hi);
  const float nearest = (eyePosition - nearestInBounds).norm();
  const float focalPx = projection(1, 1) * 0.5f * float(sh);
  const bool eyeNeedsQuads =
      nearest <= 1.5f * radius ||
      2.0f * 2.0f * radius * focalPx / (nearest - radius) + 1.0f > maxPointSize;

  glQueryCounter(queries[set][0], GL_TIMESTAMP);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);

  // --- 1. Shadow map: depth of the impostors and colliders seen from the light -----------------
  if (settings.shadows) {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, shadowFramebuffer);
    glViewport(0, 0, mapSize, mapSize);
    const float one = 1.0f;
    glClearNamedFramebufferfv(shadowFramebuffer, GL_DEPTH, 0, &one);
    glBindBufferBase(GL_UNIFORM_BUFFER, kFrameParamsBinding, frameParams[0]);
    drawParticles(particles, pointsShadow, lightNeedsQuads ? particlesShadow : 0);
    if (!mesh.empty()) {
      glEnable(GL_POLYGON_OFFSET_FILL);
      glPolygonOffset(2.0f, 4.0f);
      glUseProgram(meshShadow);
      glBindVertexArray(meshVao);
      glDrawArrays(GL_TRIANGLES, 0, GLsizei(mesh.size()));
      glDisable(GL_POLYGON_OFFSET_FILL);
    }
    if (surfaceCount > 0) {
      glEnable(GL_POLYGON_OFFSET_FILL);
      glPolygonOffset(2.0f, 4.0f);
      drawSurfaces(surfaceShadow);
      glDisable(GL_POLYGON_OFFSET_FILL);
    }
  }
  glQueryCounter(queries[set][1], GL_TIMESTAMP);

  // --- 2. Scene: lit impostors and colliders into the renderer's targets -----------------------
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, sceneFramebuffer);
  glViewport(0, 0, sw, sh);
  const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  const float one = 1.0f;
  for (GLint i = 0; i < 3; ++i) glClearNamedFramebufferfv(sceneFramebuffer, GL_COLOR, i, zero);
  glClearNamedFramebufferfv(sceneFramebuffer, GL_DEPTH, 0, &one);
  glBindBufferBase(GL_UNIFORM_BUFFER, kFrameParamsBinding, frameParams[1]);
  glBindTextureUnit(0, shadowDepth);
  drawParticles(particles, pointsScene, eyeNeedsQuads ? particlesScene : 0);
  if (!mesh.empty()) {
    glUseProgram(meshScene);
    glBindVertexArray(meshVao);
    glDrawArrays(GL_TRIANGLES, 0, GLsizei(mesh.size()));
  }
  if (surfaceCount > 0) drawSurfaces(surfaceScene);
  glQueryCounter(queries[set][2], GL_TIMESTAMP);

  // --- 3. Composite: ambient occlusion, tone, sRGB, depth into the caller's framebuffer --------
  // (through the scaled target and a scale-up when the frame is lit below full size).
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, scaled ? scaledFramebuffer : GLuint(target));
  glViewport(0, 0, sw, sh);
  glDepthFunc(GL_ALWAYS);
  glUseProgram(composite);
  glProgramUniform1i(composite, compositeAoSamples, std::max(settings.aoSamples, 0));
  glProgramUniform3f(composite, compositeBackground, settings.background.x(),
                     settings.background.y(), settings.background.z());
  for (GLuint i = 0; i < 4; ++i) glBindTextureUnit(1 + i, sceneTextures[i]);
  glBindVertexArray(emptyVao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  if (scaled) {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(target));
    glViewport(0, 0, w, h);
    glUseProgram(upscale);
    glBindTextureUnit(1, scaledTextures[0]);
    glBindTextureUnit(2, scaledTextures[1]);
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  glDepthFunc(GL_LESS);
  glQueryCounter(queries[set][3], GL_TIMESTAMP);

  glBindVertexArray(0);
  glUseProgram(0);
  ++frames;
  pending[set] = true;
  pendingFrame[set] = frames;
  pendingParticles[set] = buffers.particleCount;
  pendingWidth[set] = sw;
  pendingHeight[set] = sh;
  lastSet = set;
}

Renderer::Renderer() : m_impl(std::make_unique<Impl>()) {}
Renderer::~Renderer() = default;

RenderSettings& Renderer::settings() {
  return m_impl->settings;
}
const RenderSettings& Renderer::settings() const {
  return m_impl->settings;
}

void Renderer::draw(const World& world, const Camera& camera,
                    const scenes::SceneBounds& shadowBounds, int width, int height,
                    std::span<const scenes::SceneSurface> surfaces) {
  m_impl->draw(world, camera, shadowBounds, width, height, surfaces);
}

const RenderStats& Renderer::stats() const {
  return m_impl->stats;
}

const RenderStats& Renderer::finishStats() {
  m_impl->collect(m_impl->lastSet, true);
  return m_impl->stats;
}

}  // namespace sandphys::render
