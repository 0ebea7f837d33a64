/* Force_Penalty: Q_i = F d(g')/du_i with F = -p g - p1 g' (smoothed when unilateral), both
 * computed by its tape. Ints: g, F (slots). */
#include "../assembly.h"

void ps_el_penalty(const psModel* m, psData* d, const psuHD* c, int tape, const int* I,
                   double t, const double* y, const double* yp, Assembly* as) {
  (void)t; (void)y; (void)yp;
  ps_rate_force(m, d, c, ps_slot(m, d, I[0]), tape, ps_slot(m, d, I[1]), -1, as);
}
