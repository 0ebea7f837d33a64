/* Force_Vector_TwoBody: F = X f with X the reference marker's axes (the global axes for -1),
 * on I's body at I and opposite on J's body at the same point. Ints: fx, fy, fz (slots), I
 * (marker), its body slot, J's body slot, R (marker), its body slot (-1: ground). */
#include "../assembly.h"

void ps_el_vforce(const psModel* m, psData* d, const psuHD* c, int tape, const int* I,
                  double t, const double* y, const double* yp, Assembly* as) {
  (void)t; (void)y; (void)yp;
  int s = c->stride;
  double* X = ps_tmp(m, d, F_RI);   /* 9 numbers: F_RI .. F_RI + 8 */
  double* F = ps_tmp(m, d, F_FV);
  double* sc = ps_tmp(m, d, F_SC);
  ps_marker_axes(m, d, c, I[6], I[7], X);
  for (int i = 0; i < 3; i++) {
    psu_hd_const(c, F + i * s, 0.0);
    for (int j = 0; j < 3; j++) {
      psu_hd_mul(c, sc, X + (3 * i + j) * s, ps_slot(m, d, I[j]));
      psu_hd_lin(c, F + i * s, 1.0, F + i * s, 1.0, sc, 0.0);
    }
  }
  int mi = I[3], si = I[4];
  double* P = ps_tmp(m, d, F_PT);
  ps_marker_pos(m, d, c, mi, si, P);
  ps_apply_at(m, d, c, tape, m->marker_body[mi] < 0 ? -1 : si, P, F, NULL, 1.0, as);
  ps_apply_at(m, d, c, tape, I[5], P, F, NULL, -1.0, as);
}
