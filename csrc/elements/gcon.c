/* Constraint_General: an expression g(q, t) of displacements and time held at zero exactly as
 * one equation of a joint is (csrc/elements/joint.c): the reaction lam holds g' = 0 and mu
 * holds g = 0. Ints: g, g' (slots), lam, mu (states), the joint's layout. */
#include "../assembly.h"

void ps_el_joint(const psModel* m, psData* d, const psuHD* c, int tape, const int* I, double t,
                 const double* y, const double* yp, Assembly* as);

void ps_el_gcon(const psModel* m, psData* d, const psuHD* c, int tape, const int* I,
                double t, const double* y, const double* yp, Assembly* as) {
  ps_el_joint(m, d, c, tape, I, t, y, yp, as);
}
