/* Force_Vector_TwoBody (and OneBody, a Force_Bushing's law): F = X f and T = X tau with X the
 * reference marker's axes (the global axes for -1), on I's body at I and opposite on J's body
 * at the same point (none when J's body slot is -1: action only). Ints: fx, fy, fz, tx, ty,
 * tz (slots), I (marker), its body slot, J's body slot, R (marker), its body slot (-1:
 * ground). */
#include "../assembly.h"

/* out = X v for the three slots v of ints I[0..2]. */
static void resolve(const psModel* m, psData* d, const psuHD* c, const double* X, const int* I,
                    double* out) {
  int s = c->stride;
  double* sc = ps_tmp(m, d, F_SC);
  for (int i = 0; i < 3; i++) {
    psu_hd_const(c, out + i * s, 0.0);
    for (int j = 0; j < 3; j++) {
      psu_hd_mul(c, sc, X + (3 * i + j) * s, ps_slot(m, d, I[j]));
      psu_hd_lin(c, out + i * s, 1.0, out + i * s, 1.0, sc, 0.0);
    }
  }
}

void ps_el_vforce(const psModel* m, psData* d, const psuHD* c, int tape, const int* I,
                  double t, const double* y, const double* yp, Assembly* as) {
  (void)t; (void)y; (void)yp;
  double* X = ps_tmp(m, d, F_RI);   /* 9 numbers: F_RI .. F_RI + 8 */
  double* F = ps_tmp(m, d, F_FV);
  double* T = ps_tmp(m, d, F_TV);
  ps_marker_axes(m, d, c, I[9], I[10], X);
  resolve(m, d, c, X, I, F);
  resolve(m, d, c, X, I + 3, T);
  int mi = I[6], si = I[7];
  double* P = ps_tmp(m, d, F_PT);
  ps_marker_pos(m, d, c, mi, si, P);
  ps_apply_at(m, d, c, tape, m->marker_body[mi] < 0 ? -1 : si, P, F, T, 1.0, as);
  ps_apply_at(m, d, c, tape, I[8], P, F, T, -1.0, as);
}
