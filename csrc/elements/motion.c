/* Motion_Marker: its reaction lam (a state, model force units) acts like a penalty force
 * F = lam, Q_i = lam c_i with c_i = d(g')/du_i; its own row holds g' to the target rate: 0 for
 * a displacement (g includes the expression), the expression for a velocity, and for an
 * acceleration the state w whose row integrates w' = expression. The row has no lam in it
 * (index 2): IDA leaves lam out of its error test. Ints: f, g', g (slots), PS_MOTION_* kind,
 * lam, w (states; w -1 unless an acceleration). */
#include "../assembly.h"

void ps_el_motion(const psModel* m, psData* d, const psuHD* c, int tape, const int* I,
                  double t, const double* y, const double* yp, Assembly* as) {
  (void)t;
  int kind = I[3], lam = I[4], w = I[5];
  const double* f = ps_slot(m, d, I[0]);
  const double* gd = ps_slot(m, d, I[1]);
  const double* g = ps_slot(m, d, I[2]);
  double* L = ps_tmp(m, d, F_LEN);
  psu_hd_const(c, L, y[lam]);
  ps_rate_force(m, d, c, g, tape, L, lam, as);
  as->res[lam] = gd[0] - (kind == PS_MOTION_V ? f[0] : kind == PS_MOTION_A ? y[w] : 0.0);
  if (as->deriv) {
    int badr = m->tape_basis_adr[tape];
    for (int j = 0; j < c->n; j++) {
      int bk = m->basis_kind[badr + j];
      if (bk == PS_BASIS_T) continue;
      jadd(as, lam, m->basis_idx[badr + j], gd[1 + j] * (bk == PS_BASIS_YP ? as->cj : 1.0));
    }
    if (kind == PS_MOTION_A) jadd(as, lam, w, -1.0);
  }
  if (kind == PS_MOTION_A) {
    as->res[w] = yp[w] - f[0];
    if (as->deriv) jadd(as, w, w, as->cj);
  }
}
