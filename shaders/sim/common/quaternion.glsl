// Quaternions stored as (x, y, z, w).

vec3 quatRotate(vec4 q, vec3 v) {
  // v' = v + 2 w (q.xyz x v) + 2 q.xyz x (q.xyz x v)
  vec3 t = 2.0 * cross(q.xyz, v);
  return v + q.w * t + cross(q.xyz, t);
}

vec3 quatRotateInverse(vec4 q, vec3 v) {
  return quatRotate(vec4(-q.xyz, q.w), v);
}

vec4 quatMultiply(vec4 a, vec4 b) {
  return vec4(a.w * b.xyz + b.w * a.xyz + cross(a.xyz, b.xyz), a.w * b.w - dot(a.xyz, b.xyz));
}
