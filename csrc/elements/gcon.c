/* Constraint_General: an expression g(q, t) of displacements and time held at zero, as one
 * equation of a joint is (csrc/elements/joint.c): the reaction lam holds g' = 0
 * (ps_hold_rate) and mu holds g = 0 (ps_hold_position). Ints: g, g' (slots), lam, mu
 * (states). */
#include "../assembly.h"

void ps_el_gcon(const psModel* m, psData* d, const psuHD* c, int tape, const int* I,
                double t, const double* y, const double* yp, Assembly* as) {
  (void)t; (void)yp;
  const double* g = ps_slot(m, d, I[0]);
  ps_hold_rate(m, d, c, tape, g, ps_slot(m, d, I[1]), I[2], y, as);
  ps_hold_position(m, d, c, tape, g, I[3], y, as);
}
