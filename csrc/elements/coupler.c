/* Constraint_Coupler: r1 q1 + r2 q2 [+ r3 q3] = 0 over the coordinates q of two or three joints
 * (DZ along zJ, or AZ about it). The reaction lam holds the rate, r1 q1' + ... = 0, exactly;
 * mu holds the coordinates themselves only when every one is a translation (mu < 0 else: AZ
 * wraps at pi, so a relation of rotations is held at the velocity level alone;
 * docs/deck-language.md, "Joints"). Ints: g, g' (slots), lam, mu (states). */
#include "../assembly.h"

void ps_el_coupler(const psModel* m, psData* d, const psuHD* c, int tape, const int* I,
                   double t, const double* y, const double* yp, Assembly* as) {
  (void)t; (void)yp;
  const double* g = ps_slot(m, d, I[0]);
  ps_hold_rate(m, d, c, tape, g, ps_slot(m, d, I[1]), I[2], y, as);
  if (I[3] >= 0) ps_hold_position(m, d, c, tape, g, I[3], y, as);
}
