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
