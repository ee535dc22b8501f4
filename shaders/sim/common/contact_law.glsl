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
  float shearStiffness;  // k_t
  float damping;         // eta_n
};

// A contact's spring turns with the contact: its normal part is dropped, its length kept.
vec3 turnedIntoPlane(vec3 spring, vec3 n) {
  float length0 = length(spring);
  vec3 planar = spring - dot(spring, n) * n;
  float planarLength = length(planar);
  return planarLength > 0.0 ? planar * (length0 / planarLength) : vec3(0.0);
}

MindlinResult hertzMindlin(float xi, vec3 n, vec3 vRel, float kn, float kt0, float dampingFactor,
                           float invMassSum, float friction, float dt, vec3 spring) {
  float rootXi = sqrt(xi);
  float eta = dampingFactor * sqrt(kn / invMassSum) * sqrt(rootXi);
  float xiDot = -dot(vRel, n);
  float fn = max(kn * xi * rootXi + eta * xiDot, 0.0);
  vec3 vt = vRel + xiDot * n;

  spring = turnedIntoPlane(spring, n) + vt * dt;

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
  r.shearStiffness = kt;
  r.damping = eta;
  return r;
}

#ifdef ROLLING_FRICTION
// Rolling resistance (Material::rollingFriction, mu_r), as LAMMPS pair granular's rolling sds: a
// spring-dashpot-slider on the contact's rolling displacement, with the tangential spring's
// stiffness and damping, so that a loaded contact holds still below its limit:
//   v_r = R (w x n),  w = w_this - w_other the bodies' relative spin, R the rolling radius
//   delta_r <- delta_r turned into the tangent plane (length kept) + v_r dt
//   F_r = -k_t delta_r - eta_n v_r
//   |F_r| > mu_r F_n: F_r <- mu_r F_n F_r/|F_r|, delta_r <- -(F_r + eta_n v_r) / k_t   (rolls)
//   couple on this body: R n x F_r, at most mu_r R F_n, against w's tangential part.
// v_r and delta_r are even in (w, n): the two sides of a pair keep the same spring, bit for bit,
// and get exactly opposite couples.
struct RollingResult {
  vec3 torque;
  vec3 spring;
};

RollingResult rollingResistance(vec3 relativeSpin, vec3 n, float radius, MindlinResult contact,
                                float dt, vec3 spring) {
  vec3 vr = radius * cross(relativeSpin, n);
  spring = turnedIntoPlane(spring, n) + vr * dt;
  float kt = contact.shearStiffness;
  vec3 fr = -kt * spring - contact.damping * vr;
  float frLength = length(fr);
  float cap = params.rollingFriction * contact.normalForce;
  if (frLength > cap) {
    fr *= cap / frLength;
    spring = -(fr + contact.damping * vr) / kt;
  }
  RollingResult r;
  r.torque = radius * cross(n, fr);
  r.spring = spring;
  return r;
}
#endif
