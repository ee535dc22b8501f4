// Direct light with a PCF shadow lookup, and the hemisphere ambient the composite pass scales by
// its occlusion term. Everything linear; the composite pass encodes sRGB.
layout(binding = 0) uniform sampler2DShadow shadowMap;

float shadowFactor(vec3 worldPosition, vec3 worldNormal) {
  if (params.z < 0.5) return 1.0;
  // Normal offset: a sphere's own shadow-map depth at grazing angles would otherwise shadow it.
  vec3 p = worldPosition + worldNormal * (0.2 * params.x) + lightDirection.xyz * (0.1 * params.x);
  vec4 clip = lightMatrix * vec4(p, 1.0);
  vec3 ndc = clip.xyz / clip.w;
  vec3 uvz = ndc * 0.5 + 0.5;
  if (any(lessThan(uvz.xy, vec2(0.0))) || any(greaterThan(uvz.xy, vec2(1.0))) || uvz.z > 1.0) {
    return 1.0;  // outside the region the shadow map covers: lit
  }
  // 3x3 taps of bilinear comparisons: soft enough edges at a few texels per grain.
  float sum = 0.0;
  for (int y = -1; y <= 1; ++y) {
    for (int x = -1; x <= 1; ++x) {
      sum += texture(shadowMap, vec3(uvz.xy + vec2(x, y) * params.y, uvz.z));
    }
  }
  return sum / 9.0;
}

// Writes the three targets of the scene pass.
layout(location = 0) out vec4 outDirect;   // albedo * direct light * shadow (linear)
layout(location = 1) out vec4 outAmbient;  // albedo * ambient light, before occlusion (linear)
layout(location = 2) out vec4 outNormal;   // view-space normal * 0.5 + 0.5

void writeShaded(vec3 albedo, vec3 worldPosition, vec3 worldNormal) {
  float lambert = max(dot(worldNormal, lightDirection.xyz), 0.0);
  float shadow = lambert > 0.0 ? shadowFactor(worldPosition, worldNormal) : 0.0;
  vec3 ambient = mix(groundColour.rgb, skyColour.rgb, 0.5 + 0.5 * worldNormal.y);
  outDirect = vec4(albedo * lightColour.rgb * lambert * shadow, 1.0);
  outAmbient = vec4(albedo * ambient, 1.0);
  vec3 viewNormal = normalize(mat3(view) * worldNormal);
  outNormal = vec4(viewNormal * 0.5 + 0.5, 1.0);
}
