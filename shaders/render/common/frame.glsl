// Per-pass constants of the renderer (samples/render/renderer.cpp, struct FrameParams). The
// shadow pass gets the light's camera in view/projection; every other pass the eye's.
layout(std140, binding = 0) uniform FrameParams {
  mat4 view;            // world -> view of this pass's camera
  mat4 projection;      // view -> clip
  mat4 inverseView;     // view -> world
  mat4 inverseProjection;
  mat4 lightMatrix;     // world -> light clip space (shadow map lookup)
  vec4 lightDirection;  // xyz: unit vector towards the light (world); w: 1 if this pass is orthographic
  vec4 lightColour;     // rgb: direct irradiance (linear)
  vec4 skyColour;       // rgb: ambient light from above (linear)
  vec4 groundColour;    // rgb: ambient light bounced from below (linear)
  vec4 params;          // x: particle radius (m); y: 1 / shadow map size; z: shadows on (1/0); w: AO radius (m)
  vec4 viewport;        // xy: size (px); zw: 1 / size
  vec4 cameraPosition;  // xyz: eye position (world)
};

bool orthographicPass() {
  return lightDirection.w > 0.5;
}
