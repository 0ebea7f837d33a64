/* Constraint_General: an expression g(q, t) of displacements and time held at zero exactly as
 * one equation of a joint is (csrc/elements/joint.c): the reaction lam holds g' = 0 and mu
 * holds g = 0. An expression g(q, u, t) of velocities (non-holonomic; mu < 0) is held as it
 * is: row lam is g + c lam, and lam acts on every velocity u_j the tape reads with dg/du_j
 * (its tape puts u among the directions with second derivatives, so the iteration matrix is
 * exact). Ints: g, g' (slots; g' = g for a velocity-level one), lam, mu (states). */
#include "../assembly.h"

void ps_el_joint(const psModel* m, psData* d, const psuHD* c, int tape, const int* I, double t,
                 const double* y, const double* yp, Assembly* as);

/* g(q, u, t) = 0 at the velocity level. */
static void hold_velocities(const psModel* m, psData* d, const psuHD* c, int tape,
                            const double* g, int lam, const double* y, Assembly* as) {
  int badr = m->tape_basis_adr[tape], adr = m->tape_body_adr[tape];
  double L = y[lam], cf = m->force_scale;
  double* gj = ps_tmp(m, d, F_CI);
  ps_hold_row(m, c, tape, lam, g, y, as);
  for (int slot = 0; slot < m->tape_nbody[tape]; slot++) {
    int up = m->tbody_u[adr + slot];
    if (up < 0) continue;
    int nu = m->body_type[m->tbody_body[adr + slot]] == PS_BODY_RIGID ? 6 : 3;
    for (int k = 0; k < nu; k++) {
      int j = up + k, row = m->basis_idx[badr + j];
      psu_hd_gradcomp(c, gj, g, j);
      as->res[row] -= cf * L * gj[0];
      if (!as->deriv) continue;
      jadd(as, row, lam, -cf * gj[0]);
      for (int i = 0; i < c->nh; i++) {
        if (m->basis_kind[badr + i] == PS_BASIS_T) continue;
        jadd(as, row, m->basis_idx[badr + i], -cf * L * gj[1 + i]);
      }
    }
  }
}

void ps_el_gcon(const psModel* m, psData* d, const psuHD* c, int tape, const int* I,
                double t, const double* y, const double* yp, Assembly* as) {
  if (I[3] < 0) {
    hold_velocities(m, d, c, tape, ps_slot(m, d, I[0]), I[2], y, as);
    return;
  }
  ps_el_joint(m, d, c, tape, I, t, y, yp, as);
}
