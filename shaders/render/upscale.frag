#version 450
// Scales the composite of a reduced-resolution frame (RenderSettings::renderScale < 1) up to the
// caller's framebuffer: colour filtered bilinearly, depth taken from the nearest texel, because
// averaging depths across a grain's silhouette would invent surfaces that are not there.
layout(binding = 1) uniform sampler2D colourTexture;
layout(binding = 2) uniform sampler2D depthTexture;

in vec2 vUv;
layout(location = 0) out vec4 outColour;

void main() {
  outColour = texture(colourTexture, vUv);
  gl_FragDepth = texture(depthTexture, vUv).r;
}
