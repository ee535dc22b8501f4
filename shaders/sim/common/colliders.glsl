// Implicit, smooth colliders (docs/architecture.md, "colliders"). World keeps them sorted by
// type (params.planesEnd, boxesEnd, revolutionsEnd) so that kernels loop over each type in turn,
// every invocation running the same code. Each function returns one surface that a sphere of
// radius r at p may overlap: hit = (unit normal towards the sphere, overlap xi), a contact when
// xi > 0. A value, not an array of hits: llvmpipe runs dynamically indexed arrays lane by lane.
// Types and parameters (written by World, see gpu_layout.h):
//   PLANE       a = (n, offset): solid where dot(n, x) < offset
//   BOX         a = (centre, inside ? 1 : 0), b = (half extents, 0), c = orientation (x, y, z, w)
//   REVOLUTION  a = (axis base, 0), b = (r0, y0, r1, y1): the segment (r0, y0)-(r1, y1) of the
//               (radius, height) half-plane swept around the vertical axis: a thin wall
//               (cylinder: r0 = r1; funnel: r1 > r0, the outlet an open hole at y0)

#define COLLIDER_PLANE 1
#define COLLIDER_BOX 2
#define COLLIDER_REVOLUTION 3
// A container box touches a sphere in a corner with up to three walls: boxHit is asked per axis.
#define BOX_AXES 3

vec4 planeHit(Collider c, vec3 p, float r) {
  return vec4(c.a.xyz, r - (dot(c.a.xyz, p) - c.a.w));
}

// The sphere's centre in the box's frame, for boxHit.
vec3 boxLocal(Collider c, vec3 p) {
  return quatRotateInverse(c.c, p - c.a.xyz);
}

vec4 boxHit(Collider c, vec3 local, float r, int axis) {
  vec3 h = c.b.xyz;
  if (c.a.w > 0.5) {
    // Container: the nearer of the two walls across this axis pushes inwards.
    float toMax = h[axis] - local[axis];
    float toMin = h[axis] + local[axis];
    vec3 axisDir = vec3(0.0);
    axisDir[axis] = 1.0;
    return toMax < toMin ? vec4(quatRotate(c.c, -axisDir), r - toMax)
                         : vec4(quatRotate(c.c, axisDir), r - toMin);
  }
  // Solid obstacle, one contact (asked for on the first axis): push out of the nearest face, or
  // away from the nearest point outside.
  if (axis != 0) return vec4(0.0);
  vec3 nearest = clamp(local, -h, h);
  vec3 delta = local - nearest;
  float dist = length(delta);
  if (dist > 0.0) return vec4(quatRotate(c.c, delta / dist), r - dist);
  vec3 depth = h - abs(local);
  int nearestAxis = depth.x < depth.y ? (depth.x < depth.z ? 0 : 2) : (depth.y < depth.z ? 1 : 2);
  vec3 normal = vec3(0.0);
  normal[nearestAxis] = local[nearestAxis] >= 0.0 ? 1.0 : -1.0;
  return vec4(quatRotate(c.c, normal), r + depth[nearestAxis]);
}

// Which face of the box boxHit(c, local, r, axis) reports, for the contact's slot: a container's
// wall (axis, and the side it is on), 0 for a solid obstacle's single contact.
uint boxFace(Collider c, vec3 local, int axis) {
  if (c.a.w <= 0.5) return 0u;
  bool maxSide = c.b[axis] - local[axis] < c.b[axis] + local[axis];  // as boxHit decides
  return uint(axis) * 2u + (maxSide ? 1u : 0u);
}

vec4 revolutionHit(Collider c, vec3 p, float r) {
  vec3 rel = p - c.a.xyz;
  float radial = length(rel.xz);
  vec2 q = vec2(radial, rel.y);
  vec2 s0 = c.b.xy;
  vec2 s1 = c.b.zw;
  vec2 seg = s1 - s0;
  float t = clamp(dot(q - s0, seg) / dot(seg, seg), 0.0, 1.0);
  vec2 delta = q - (s0 + t * seg);
  float dist = length(delta);
  if (dist >= r) return vec4(0.0);
  vec2 n2;
  if (dist > 0.0) {
    n2 = delta / dist;
  } else {
    n2 = normalize(vec2(-seg.y, seg.x));  // centre on the wall: push towards the axis side
    if (n2.x > 0.0) n2 = -n2;
  }
  vec2 radialDir = radial > 0.0 ? rel.xz / radial : vec2(1.0, 0.0);
  return vec4(n2.x * radialDir.x, n2.y, n2.x * radialDir.y, r - dist);
}
