/* Motion_Marker: a reaction lam holds the driven measure's rate g' at its target
 * (ps_hold_rate): 0 for a displacement (g includes the expression), the expression for a
 * velocity, and for an acceleration the state w whose row integrates w' = expression. A
 * displacement is held at the position level too (ps_hold_position, with mu). Ints: f, g', g
 * (slots), PS_MOTION_* kind, lam, w, mu (states; w -1 unless an acceleration, mu -1 unless a
 * displacement). */
#include "../assembly.h"

void ps_el_motion(const psModel* m, psData* d, const psuHD* c, int tape, const int* I,
                  double t, const double* y, const double* yp, Assembly* as) {
  (void)t;
  int kind = I[3], lam = I[4], w = I[5], mu = I[6];
  const double* f = ps_slot(m, d, I[0]);
  const double* g = ps_slot(m, d, I[2]);
  ps_hold_rate(m, d, c, tape, g, ps_slot(m, d, I[1]), lam, y, as);
  if (kind == PS_MOTION_V) as->res[lam] -= f[0];
  if (kind == PS_MOTION_D) ps_hold_position(m, d, c, tape, g, mu, y, as);
  if (kind == PS_MOTION_A) {
    as->res[lam] -= y[w];
    if (as->deriv) jadd(as, lam, w, -1.0);
    as->res[w] = yp[w] - f[0];
    if (as->deriv) jadd(as, w, w, as->cj);
  }
}
