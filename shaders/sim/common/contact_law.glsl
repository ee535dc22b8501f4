// The contact law of the paper, eq. 9 and 10, with the Tsuji damping exponent (xi^1/4) so that the
// restitution does not depend on the impact speed (docs/architecture.md, "contacts"):
//   F_n = k_n xi^3/2 + gamma_n xi^1/4 xi',   gamma_n = c(e) sqrt(m* k_n),   F_n >= 0
//   F_s = -min(mu F_n, gamma_s |v_s|) v_s / |v_s|
// n points from the other body towards this particle; vRel = v_this - v_other. The result is
// exactly antisymmetric (swapping the two particles negates every input term by term), so the
// gathered forces obey Newton's third law to the last bit of each term.

struct ContactResult {
  vec3 force;
  float normalForce;
  vec3 tangentialForce;
};

ContactResult contactForce(float xi, vec3 n, vec3 vRel, float kn, float dampingFactor,
                           float invMassSum, float friction, float tangentialDamping) {
  float effectiveMass = 1.0 / invMassSum;
  float xiDot = -dot(vRel, n);
  float rootXi = sqrt(xi);
  float fn = kn * xi * rootXi + dampingFactor * sqrt(effectiveMass * kn) * sqrt(rootXi) * xiDot;
  fn = max(fn, 0.0);
  vec3 vs = vRel + xiDot * n;
  float vsLength = length(vs);
  vec3 fs = vec3(0.0);
  if (vsLength > 0.0) {
    fs = vs * (-min(friction * fn, tangentialDamping * vsLength) / vsLength);
  }
  ContactResult result;
  result.force = fn * n + fs;
  result.normalForce = fn;
  result.tangentialForce = fs;
  return result;
}

// ContactLaw::HertzMindlin (docs/architecture.md, "contacts"), as LAMMPS pair granular with
// hertz/material, damping tsuji and tangential mindlin (x_gamma_t = 1):
//   F_n = k_n xi^3/2 + eta_n xi',            eta_n = c(e) sqrt(m* k_n) xi^1/4,  F_n >= 0
//   delta <- delta rotated into the tangent plane (length kept) + v_t dt
//   F_t = -k_t delta - eta_n v_t,            k_t = k_t0 xi^1/2
//   |F_t| > mu F_n: F_t <- mu F_n F_t/|F_t|, delta <- -(F_t + eta_n v_t) / k_t   (slip)
// n points from the other body towards this particle; vRel is this body's velocity minus the
// other's at the contact point, so friction sees both spins. Every step is an odd function of
// (n, vRel, delta), and the two sides of a pair start from the same zero spring: the two sides
// keep exactly negated springs and forces, bit for bit. invMassSum = n_pairs (1/M_a + 1/M_b).

struct MindlinResult {
  vec3 force;
  float normalForce;
  vec3 tangentialForce;
  vec3 spring;
};

MindlinResult hertzMindlin(float xi, vec3 n, vec3 vRel, float kn, float kt0, float dampingFactor,
                           float invMassSum, float friction, float dt, vec3 spring) {
  float rootXi = sqrt(xi);
  float eta = dampingFactor * sqrt(kn / invMassSum) * sqrt(rootXi);
  float xiDot = -dot(vRel, n);
  float fn = max(kn * xi * rootXi + eta * xiDot, 0.0);
  vec3 vt = vRel + xiDot * n;

  // The spring turns with the contact: drop its normal part, keep its length.
  float length0 = length(spring);
  vec3 planar = spring - dot(spring, n) * n;
  float planarLength = length(planar);
  spring = planarLength > 0.0 ? planar * (length0 / planarLength) : vec3(0.0);
  spring += vt * dt;

  float kt = kt0 * rootXi;
  vec3 ft = -kt * spring - eta * vt;
  float ftLength = length(ft);
  float cap = friction * fn;
  if (ftLength > cap) {
    ft *= cap / ftLength;
    spring = -(ft + eta * vt) / kt;
  }
  MindlinResult r;
  r.force = fn * n + ft;
  r.normalForce = fn;
  r.tangentialForce = ft;
  r.spring = spring;
  return r;
}

#ifdef ROLLING_FRICTION
// Rolling friction (Material::rollingFriction, mu_r), as LIGGGHTS rolling_friction cdt: a couple
// against the relative rolling of the two bodies, the part of their relative spin
// w = w_this - w_other in the tangent plane, of size mu_r R F_n, R the effective rolling radius.
// A constant size would reverse a slow rolling within one substep and chatter about rest, so it
// is at most what stops, in one substep, a sphere of radius R with the contact's share of the
// masses (1/invMassShare): the couple vanishes with w, so it has no static part (a loaded body
// creeps; docs/architecture.md, "contacts"). Odd in (w, n), so the two sides of a pair get
// exactly opposite couples.
vec3 rollingTorque(vec3 relativeSpin, vec3 n, float normalForce, float radius, float invMassShare,
                   float dt) {
  vec3 rolling = relativeSpin - dot(relativeSpin, n) * n;
  float rate = length(rolling);
  float stopping = 0.4 * radius * radius * rate / (invMassShare * dt);
  float size = min(params.rollingFriction * radius * normalForce, stopping);
  return rate > 0.0 ? rolling * (-size / rate) : vec3(0.0);
}
#endif
