/* Force_Scalar_TwoBody: a force of magnitude f along the line from J to I, or a torque f about
 * z of J; action only (is_action_only): a force f along z of J or a torque f about it, on I's
 * body alone. Ints: f (slot), mode (bit 0 a torque, bit 1 action only), I, J (markers). */
#include <math.h>

#include "../assembly.h"

void ps_el_sforce(const psModel* m, psData* d, const psuHD* c, int tape, const int* I,
                  double t, const double* y, const double* yp, Assembly* as) {
  (void)t; (void)y; (void)yp;
  int s = c->stride;
  const double* f = ps_slot(m, d, I[0]);
  int mi = I[2], mj = I[3];
  /* body slots of I and J in this tape: the compiler puts them first */
  int si = m->marker_body[mi] < 0 ? -1 : 0;
  int sj = m->marker_body[mj] < 0 ? -1 : (m->marker_body[mi] < 0 ||
                                           m->marker_body[mi] == m->marker_body[mj] ? 0 : 1);
  double* vec = ps_tmp(m, d, F_VEC);
  int torque = I[1] & 1, action_only = I[1] & 2;
  if (torque || action_only) {
    double* X = ps_tmp(m, d, F_RI);
    ps_marker_axes(m, d, c, mj, sj, X);
    for (int i = 0; i < 3; i++) psu_hd_mul(c, vec + i * s, f, X + (3 * i + 2) * s);
    ps_apply_load(m, d, c, tape, mi, si, torque ? NULL : vec, torque ? vec : NULL, 1.0, as);
    if (!action_only) ps_apply_load(m, d, c, tape, mj, sj, NULL, vec, -1.0, as);
    return;
  }
  double* ri = ps_tmp(m, d, F_RI);
  double* rj = ps_tmp(m, d, F_RJ);
  double* rel = ps_tmp(m, d, F_REL);
  double* len = ps_tmp(m, d, F_LEN);
  ps_marker_pos(m, d, c, mi, si, ri);
  ps_marker_pos(m, d, c, mj, sj, rj);
  for (int i = 0; i < 3; i++) psu_hd_lin(c, rel + i * s, 1.0, ri + i * s, -1.0, rj + i * s, 0.0);
  psu_hd_dot(c, len, rel, rel, ps_tmp(m, d, F_SC));
  double L = sqrt(len[0]);
  /* coincident markers: no direction. No force gives no load (derivatives written as
   * zeros); a force along no line is not a number, which the diagnosis words
   * (ps_el_sforce_undefined: the run fails naming the element) */
  if (L == 0.0)
    psu_hd_const(c, len, f[0] == 0.0 ? 0.0 : NAN);
  else
    psu_hd_unary(c, len, len, 1.0 / L, -0.5 / (L * L * L), 0.0);
  for (int i = 0; i < 3; i++) {
    psu_hd_mul(c, vec + i * s, rel + i * s, len);
    psu_hd_mul(c, vec + i * s, vec + i * s, f);
  }
  ps_apply_load(m, d, c, tape, mi, si, vec, NULL, 1.0, as);
  ps_apply_load(m, d, c, tape, mj, sj, vec, NULL, -1.0, as);
}

/* Whether a translational force has no direction where it acts: its markers coincide (the
 * line from J to I has none) and its value f is not 0. The value goes to *value. */
int ps_el_sforce_undefined(const psModel* m, psData* d, const psuHD* c, int tape, const int* I,
                           double* value) {
  (void)tape;
  const double* f = ps_slot(m, d, I[0]);
  int mi = I[2], mj = I[3];
  if ((I[1] & 3) || f[0] == 0.0 || !isfinite(f[0])) return 0;
  int si = m->marker_body[mi] < 0 ? -1 : 0;
  int sj = m->marker_body[mj] < 0 ? -1 : (m->marker_body[mi] < 0 ||
                                           m->marker_body[mi] == m->marker_body[mj] ? 0 : 1);
  double* ri = ps_tmp(m, d, F_RI);
  double* rj = ps_tmp(m, d, F_RJ);
  ps_marker_pos(m, d, c, mi, si, ri);
  ps_marker_pos(m, d, c, mj, sj, rj);
  int s = c->stride;
  double n2 = 0.0;            /* |rI - rJ|^2 as the contribution computes it */
  for (int i = 0; i < 3; i++) n2 += (ri[i * s] - rj[i * s]) * (ri[i * s] - rj[i * s]);
  if (n2 != 0.0) return 0;
  *value = f[0];
  return 1;
}
