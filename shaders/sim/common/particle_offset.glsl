// Where a particle sits on its body: its template offset turned by the body's orientation. The
// includer declares BODY_ORIENTATION_TEXTURE and PARTICLE_LOCAL_TEXTURE (and includes
// quaternion.glsl).
vec3 particleOffset(int body, int particle) {
  return quatRotate(texelFetch(bodyOrientationTexture, body),
                    texelFetch(particleLocalTexture, particle).xyz);
}
