/* The tracked angle s of a rotation that turns through any number of turns (SCREW,
 * RACK_PINION, a coupler's rotation): an algebraic state whose row is w = atan2(sin e, cos e),
 * e = theta - s, with theta the measured angle in (-pi, pi]. The row holds s at theta plus the
 * whole turns IDA's predictor carries it through, and the constraints read the unwrapped
 * angle s + w, whose derivative in s is zero (pysolver.build.compiler, "turned"). Ints: w
 * (slot), s (state). */
#include "../assembly.h"

void ps_el_turn(const psModel* m, psData* d, const psuHD* c, int tape, const int* I, double t,
                const double* y, const double* yp, Assembly* as) {
  (void)t; (void)y; (void)yp;
  const double* w = ps_slot(m, d, I[0]);
  int s = I[1];
  as->res[s] = w[0];
  if (as->deriv) ps_row_gradient(m, c, tape, s, w, 1.0, as);
}
