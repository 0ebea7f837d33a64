/* Generalized forces of loads on bodies, shared by the element kinds (csrc/assembly.h). */
#include "assembly.h"

/* A planar body's generalized forces (Fx, Fy, Mz about its origin); a scene is planar only
 * when nothing loads a body out of its plane (pysolver/build/planar.py), so F_z, M_x and M_y
 * have nowhere to go. */
static void planar_load(const psModel* m, psData* d, const psuHD* c, int tape, int slot,
                        int ua, const double* P, const double* F, const double* Mo,
                        double sign, Assembly* as) {
  int s = c->stride;
  double* Q = ps_tmp(m, d, F_Q);
  double* sc = ps_tmp(m, d, F_SC);
  double* p = ps_tmp(m, d, F_P);
  psu_hd_const(c, Q, 0.0);
  if (F) {
    for (int i = 0; i < 2; i++) {
      psu_hd_lin(c, sc, sign, F + i * s, 0.0, NULL, 0.0);
      ps_scatter(m, c, tape, ua + i, sc, as);
    }
    /* (P - r) x F, its z component */
    const double* r = ps_bc(m, d, slot, PS_BC_R);
    for (int i = 0; i < 2; i++) psu_hd_lin(c, p + i * s, 1.0, P + i * s, -1.0, r + i * s, 0.0);
    psu_hd_mul(c, Q, p, F + s);
    psu_hd_mul(c, sc, p + s, F);
    psu_hd_lin(c, Q, 1.0, Q, -1.0, sc, 0.0);
  }
  if (Mo) psu_hd_lin(c, Q, 1.0, Q, 1.0, Mo + 2 * s, 0.0);
  psu_hd_lin(c, Q, sign, Q, 0.0, NULL, 0.0);
  ps_scatter(m, c, tape, ua + 2, Q, as);
}

void ps_apply_at(const psModel* m, psData* d, const psuHD* c, int tape, int slot,
                 const double* P, const double* F, const double* Mo, double sign, Assembly* as) {
  if (slot < 0) return;
  int s = c->stride;
  int b = m->tbody_body[m->tape_body_adr[tape] + slot];
  int ua = m->body_uadr[b];
  double* Q = ps_tmp(m, d, F_Q);
  if (m->body_type[b] == PS_BODY_PLANAR) {
    planar_load(m, d, c, tape, slot, ua, P, F, Mo, sign, as);
    return;
  }
  for (int i = 0; i < 3; i++) {
    if (F) {
      psu_hd_lin(c, Q, sign, F + i * s, 0.0, NULL, 0.0);
      ps_scatter(m, c, tape, ua + i, Q, as);
    }
  }
  if (m->body_type[b] != PS_BODY_RIGID) return;
  /* moment about the body origin, resolved in the body frame: A^T (p x F + M) */
  double* mom = ps_tmp(m, d, F_CR);
  double* sc = ps_tmp(m, d, F_SC);
  if (F) {
    double* p = ps_tmp(m, d, F_P);
    const double* r = ps_bc(m, d, slot, PS_BC_R);
    for (int i = 0; i < 3; i++) psu_hd_lin(c, p + i * s, 1.0, P + i * s, -1.0, r + i * s, 0.0);
    psu_hd_cross(c, mom, p, F, sc);
  } else {
    for (int i = 0; i < 3; i++) psu_hd_const(c, mom + i * s, 0.0);
  }
  if (Mo)
    for (int i = 0; i < 3; i++) psu_hd_lin(c, mom + i * s, 1.0, mom + i * s, 1.0, Mo + i * s, 0.0);
  const double* A = ps_bc(m, d, slot, PS_BC_A);
  for (int k = 0; k < 3; k++) {
    psu_hd_mul(c, Q, A + k * s, mom);
    for (int r = 1; r < 3; r++) {
      psu_hd_mul(c, sc, A + (3 * r + k) * s, mom + r * s);
      psu_hd_lin(c, Q, 1.0, Q, 1.0, sc, 0.0);
    }
    psu_hd_lin(c, Q, sign, Q, 0.0, NULL, 0.0);
    ps_scatter(m, c, tape, ua + 3 + k, Q, as);
  }
}

void ps_apply_load(const psModel* m, psData* d, const psuHD* c, int tape, int mk, int slot,
                   const double* F, const double* Mo, double sign, Assembly* as) {
  if (slot < 0 || m->marker_body[mk] < 0) return;
  double* P = ps_tmp(m, d, F_PT);
  if (F && m->body_type[m->tbody_body[m->tape_body_adr[tape] + slot]] != PS_BODY_POINT)
    ps_marker_pos(m, d, c, mk, slot, P);
  ps_apply_at(m, d, c, tape, slot, P, F, Mo, sign, as);
}

void ps_rate_force(const psModel* m, psData* d, const psuHD* c, const double* g, int tape,
                   const double* F, int lam, Assembly* as) {
  double* ci = ps_tmp(m, d, F_CI);
  double* Q = ps_tmp(m, d, F_Q);
  double* sc = ps_tmp(m, d, F_SC);
  int adr = m->tape_body_adr[tape];
  for (int slot = 0; slot < m->tape_nbody[tape]; slot++) {
    if (m->tbody_q[adr + slot] < 0) continue;
    int b = m->tbody_body[adr + slot];
    int nu = m->body_type[b] == PS_BODY_RIGID ? 6 : 3;
    for (int i = 0; i < nu; i++) {
      ps_rate_coeff(m, d, c, g, tape, slot, i, ci, sc);
      psu_hd_mul(c, Q, F, ci);
      ps_scatter(m, c, tape, m->body_uadr[b] + i, Q, as);
      if (lam >= 0 && as->deriv) jadd(as, m->body_uadr[b] + i, lam, -m->force_scale * ci[0]);
    }
  }
}

void ps_hold_position(const psModel* m, psData* d, const psuHD* c, int tape, const double* g,
                      int mu, const double* y, Assembly* as) {
  double* gj = ps_tmp(m, d, F_CI);
  int badr = m->tape_basis_adr[tape], nq = m->tape_nh[tape] - 1;
  double mv = y[mu];
  ps_hold_row(m, c, tape, mu, g, y, as);
  /* the leading nq basis entries are the positions q of the tape's bodies */
  for (int j = 0; j < nq; j++) {
    int row = m->basis_idx[badr + j];
    psu_hd_gradcomp(c, gj, g, j);
    as->res[row] -= mv * gj[0];
    if (!as->deriv) continue;
    jadd(as, row, mu, -gj[0]);
    for (int i = 0; i < nq; i++) jadd(as, row, m->basis_idx[badr + i], -mv * gj[1 + i]);
  }
}

void ps_hold_rate(const psModel* m, psData* d, const psuHD* c, int tape, const double* g,
                  const double* gd, int lam, const double* y, Assembly* as) {
  double* L = ps_tmp(m, d, F_LEN);
  psu_hd_const(c, L, y[lam]);
  ps_rate_force(m, d, c, g, tape, L, lam, as);
  ps_hold_row(m, c, tape, lam, gd, y, as);
}
