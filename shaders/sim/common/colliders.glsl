// Implicit, smooth colliders (docs/architecture.md, "colliders"). World keeps them sorted by
// type (SimParams.colliderEnds) so that kernels loop over each type in turn, every invocation
// running the same code. Each function returns the surfaces a
// sphere of radius r at p overlaps: hit = (unit normal towards the sphere, overlap xi > 0).
// Types and parameters (written by World, see gpu_layout.h):
//   PLANE       a = (n, offset): solid where dot(n, x) < offset
//   BOX         a = (centre, inside ? 1 : 0), b = (half extents, 0), c = orientation (x, y, z, w)
//   REVOLUTION  a = (axis base, 0), b = (r0, y0, r1, y1): the segment (r0, y0)-(r1, y1) of the
//               (radius, height) half-plane swept around the vertical axis: a thin wall
//               (cylinder: r0 = r1; funnel: r1 > r0, the outlet an open hole at y0)

#define COLLIDER_PLANE 1
#define COLLIDER_BOX 2
#define COLLIDER_REVOLUTION 3
#define MAX_COLLIDER_HITS 3

uint planeHits(Collider c, vec3 p, float r, out vec4 hits[MAX_COLLIDER_HITS]) {
  float xi = r - (dot(c.a.xyz, p) - c.a.w);
  hits[0] = vec4(c.a.xyz, xi);
  return xi > 0.0 ? 1u : 0u;
}

uint boxHits(Collider c, vec3 p, float r, out vec4 hits[MAX_COLLIDER_HITS]) {
  vec3 local = quatRotateInverse(c.c, p - c.a.xyz);
  vec3 h = c.b.xyz;
  uint count = 0u;
  if (c.a.w > 0.5) {
    // Container: each wall pushes inwards; a sphere in a corner touches up to three walls.
    for (int axis = 0; axis < 3; ++axis) {
      float toMax = h[axis] - local[axis];
      float toMin = h[axis] + local[axis];
      vec3 axisDir = vec3(0.0);
      axisDir[axis] = 1.0;
      if (toMax < toMin) {
        if (r - toMax > 0.0 && count < MAX_COLLIDER_HITS) hits[count++] = vec4(quatRotate(c.c, -axisDir), r - toMax);
      } else {
        if (r - toMin > 0.0 && count < MAX_COLLIDER_HITS) hits[count++] = vec4(quatRotate(c.c, axisDir), r - toMin);
      }
    }
    return count;
  }
  // Solid obstacle: push out of the nearest face, or away from the nearest point outside.
  vec3 nearest = clamp(local, -h, h);
  vec3 delta = local - nearest;
  float dist = length(delta);
  if (dist > 0.0) {
    hits[0] = vec4(quatRotate(c.c, delta / dist), r - dist);
    return r - dist > 0.0 ? 1u : 0u;
  }
  vec3 depth = h - abs(local);
  int axis = depth.x < depth.y ? (depth.x < depth.z ? 0 : 2) : (depth.y < depth.z ? 1 : 2);
  vec3 normal = vec3(0.0);
  normal[axis] = local[axis] >= 0.0 ? 1.0 : -1.0;
  hits[0] = vec4(quatRotate(c.c, normal), r + depth[axis]);
  return 1u;
}

uint revolutionHits(Collider c, vec3 p, float r, out vec4 hits[MAX_COLLIDER_HITS]) {
  vec3 rel = p - c.a.xyz;
  float radial = length(rel.xz);
  vec2 q = vec2(radial, rel.y);
  vec2 s0 = c.b.xy;
  vec2 s1 = c.b.zw;
  vec2 seg = s1 - s0;
  float t = clamp(dot(q - s0, seg) / dot(seg, seg), 0.0, 1.0);
  vec2 delta = q - (s0 + t * seg);
  float dist = length(delta);
  if (dist >= r) return 0u;
  vec2 n2;
  if (dist > 0.0) {
    n2 = delta / dist;
  } else {
    n2 = normalize(vec2(-seg.y, seg.x));  // centre on the wall: push towards the axis side
    if (n2.x > 0.0) n2 = -n2;
  }
  vec2 radialDir = radial > 0.0 ? rel.xz / radial : vec2(1.0, 0.0);
  hits[0] = vec4(n2.x * radialDir.x, n2.y, n2.x * radialDir.y, r - dist);
  return 1u;
}
