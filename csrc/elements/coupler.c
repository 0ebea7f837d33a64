/* Constraint_Coupler: r1 q1 + r2 q2 [+ r3 q3] = 0 over the coordinates q of two or three joints
 * (DZ along zJ, or AZ about it), held as one equation of a joint (csrc/elements/joint.c): the
 * reaction lam holds the rate exactly; mu (< 0 when any coordinate is a rotation: AZ wraps at
 * pi, so such a relation is held at the velocity level alone; docs/deck-language.md, "Joints")
 * holds the coordinates. Ints: g, g' (slots), lam, mu (states), the joint's layout. */
#include "../assembly.h"

void ps_el_joint(const psModel* m, psData* d, const psuHD* c, int tape, const int* I, double t,
                 const double* y, const double* yp, Assembly* as);

void ps_el_coupler(const psModel* m, psData* d, const psuHD* c, int tape, const int* I,
                   double t, const double* y, const double* yp, Assembly* as) {
  ps_el_joint(m, d, c, tape, I, t, y, yp, as);
}
