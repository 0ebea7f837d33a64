/* Constraint_Joint (and every holonomic constraint equation g(q, t) = 0): one row of the
 * element table per equation, the equations of one joint sharing its tape. A reaction lam
 * holds g' = 0 (ps_hold_rate) and mu holds g = 0 (ps_hold_position). Ints: g, g' (slots),
 * lam, mu (states). */
#include "../assembly.h"

void ps_el_joint(const psModel* m, psData* d, const psuHD* c, int tape, const int* I,
                 double t, const double* y, const double* yp, Assembly* as) {
  (void)t; (void)yp;
  const double* g = ps_slot(m, d, I[0]);
  ps_hold_rate(m, d, c, tape, g, ps_slot(m, d, I[1]), I[2], y, as);
  /* mu < 0: a coupler of rotations, held at the velocity level alone */
  if (I[3] >= 0) ps_hold_position(m, d, c, tape, g, I[3], y, as);
}
