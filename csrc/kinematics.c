/* Body and marker kinematics as hyper-dual numbers in the basis of one tape.
 *
 * A tape's prologue lists the bodies it touches with the basis positions of their q, u and u'
 * entries. ps_body_cache seeds those entries and derives rotation matrices, global angular
 * velocities and accelerations once per tape run; the marker functions build on that cache.
 */
#include <math.h>
#include <stddef.h>

#include "internal.h"

/* Scratch numbers in d->tmp reserved for the marker functions and the body cache. */
#define TMP_P 48     /* body-fixed offset rotated to global (3) */
#define TMP_X 51     /* cross-product scratch (2)               */
#define TMP_C1 53    /* (3) */
#define TMP_C2 56    /* (3) */
#define TMP_PROD 0   /* products e_i e_j while building A (10) and 1/|e|^2 (1) */

double* ps_tmp(const psModel* m, psData* d, int k) { return d->tmp + (long)k * m->hd_stride; }

double* ps_bc(const psModel* m, psData* d, int slot, int k) {
  return d->bcache + ((long)slot * PS_BC_SIZE + k) * m->hd_stride;
}

/* out = M v for a 3x3 row-major matrix of numbers M and a 3-vector v. */
static void mat_vec(const psuHD* c, double* out, const double* M, const double* v, double* tmp) {
  int s = c->stride;
  for (int i = 0; i < 3; i++) {
    psu_hd_mul(c, out + i * s, M + (3 * i) * s, v);
    for (int j = 1; j < 3; j++) {
      psu_hd_mul(c, tmp, M + (3 * i + j) * s, v + j * s);
      psu_hd_lin(c, out + i * s, 1.0, out + i * s, 1.0, tmp, 0.0);
    }
  }
}

/* Rotation matrix from (not necessarily unit) Euler parameters: A = R(e) / |e|^2. */
static void rotation_from_e(const psModel* m, psData* d, const psuHD* c, double* A,
                            const double* e) {
  int s = c->stride;
  double* p[4][4];
  int k = TMP_PROD;
  for (int i = 0; i < 4; i++)
    for (int j = i; j < 4; j++) {
      p[i][j] = p[j][i] = ps_tmp(m, d, k++);
      psu_hd_mul(c, p[i][j], e + i * s, e + j * s);
    }
  double* inv = ps_tmp(m, d, k);
  psu_hd_lin(c, inv, 1.0, p[0][0], 1.0, p[1][1], 0.0);
  psu_hd_lin(c, inv, 1.0, inv, 1.0, p[2][2], 0.0);
  psu_hd_lin(c, inv, 1.0, inv, 1.0, p[3][3], 0.0);
  {
    double v = inv[0];
    psu_hd_unary(c, inv, inv, 1.0 / v, -1.0 / (v * v), 2.0 / (v * v * v));
  }
  /* diagonal: e0^2 + ei^2 - ej^2 - ek^2 */
  for (int i = 0; i < 3; i++) {
    double* a = A + (4 * i) * s;
    int j = (i + 1) % 3 + 1, kk = (i + 2) % 3 + 1, ii = i + 1;
    psu_hd_lin(c, a, 1.0, p[0][0], 1.0, p[ii][ii], 0.0);
    psu_hd_lin(c, a, 1.0, a, -1.0, p[j][j], 0.0);
    psu_hd_lin(c, a, 1.0, a, -1.0, p[kk][kk], 0.0);
  }
  /* off-diagonal: A_ij = 2 (e_i e_j -/+ e0 e_k) */
  psu_hd_lin(c, A + 1 * s, 2.0, p[1][2], -2.0, p[0][3], 0.0);
  psu_hd_lin(c, A + 3 * s, 2.0, p[1][2], 2.0, p[0][3], 0.0);
  psu_hd_lin(c, A + 2 * s, 2.0, p[1][3], 2.0, p[0][2], 0.0);
  psu_hd_lin(c, A + 6 * s, 2.0, p[1][3], -2.0, p[0][2], 0.0);
  psu_hd_lin(c, A + 5 * s, 2.0, p[2][3], -2.0, p[0][1], 0.0);
  psu_hd_lin(c, A + 7 * s, 2.0, p[2][3], 2.0, p[0][1], 0.0);
  for (int i = 0; i < 9; i++) psu_hd_mul(c, A + i * s, A + i * s, inv);
}

/* The entries of body slot `slot` in the cache that every kind of body fills. */
typedef struct {
  double *r, *A, *v, *w, *acc, *al;
} BodySlots;

static BodySlots body_slots(const psModel* m, psData* d, int slot) {
  BodySlots k = {ps_bc(m, d, slot, PS_BC_R),   ps_bc(m, d, slot, PS_BC_A),
                 ps_bc(m, d, slot, PS_BC_V),   ps_bc(m, d, slot, PS_BC_W),
                 ps_bc(m, d, slot, PS_BC_ACC), ps_bc(m, d, slot, PS_BC_AL)};
  return k;
}

/* A planar body (PS_BODY_PLANAR): q = (x, y, rz), u = (vx, vy, wz). Its origin is at
 * (x, y, z0), its axes A = Rz(rz) A0, its velocity (vx, vy, 0), angular velocity (0, 0, wz)
 * and angular acceleration (0, 0, wz'); ps_body_cache seeded r, v, acc from the state's first
 * three entries, which hold (x, y, rz), (vx, vy, wz), (vx', vy', wz'): they move to their
 * places here. */
static void planar_cache(const psModel* m, psData* d, const psuHD* c, int b, int slot,
                         const double* y, const double* yp, int qp, int up, int ap) {
  int s = c->stride, qa = m->body_qadr[b], ua = m->body_uadr[b];
  const double* P = m->body_plane + 10 * b;
  BodySlots k = body_slots(m, d, slot);
  double *r = k.r, *A = k.A, *v = k.v, *w = k.w, *acc = k.acc, *al = k.al;
  double* th = ps_tmp(m, d, TMP_C1);
  double* cs = ps_tmp(m, d, TMP_C1 + 1);
  double* sn = ps_tmp(m, d, TMP_C1 + 2);
  psu_hd_var(c, th, y[qa + 2], qp >= 0 ? qp + 2 : -1);
  psu_hd_const(c, r + 2 * s, P[9]);
  psu_hd_var(c, w + 2 * s, y[ua + 2], up >= 0 ? up + 2 : -1);
  psu_hd_var(c, al + 2 * s, yp ? yp[ua + 2] : 0.0, ap >= 0 ? ap + 2 : -1);
  for (int i = 0; i < 2; i++) {
    psu_hd_const(c, w + i * s, 0.0);
    psu_hd_const(c, al + i * s, 0.0);
  }
  psu_hd_const(c, v + 2 * s, 0.0);
  psu_hd_const(c, acc + 2 * s, 0.0);
  double ct = cos(th[0]), st = sin(th[0]);
  psu_hd_unary(c, cs, th, ct, -st, -ct);
  psu_hd_unary(c, sn, th, st, ct, -st);
  /* A = Rz(rz) A0: rows 0 and 1 turn, row 2 is A0's */
  for (int j = 0; j < 3; j++) {
    psu_hd_lin(c, A + j * s, P[j], cs, -P[3 + j], sn, 0.0);
    psu_hd_lin(c, A + (3 + j) * s, P[j], sn, P[3 + j], cs, 0.0);
    psu_hd_const(c, A + (6 + j) * s, P[6 + j]);
  }
}

void ps_body_cache(const psModel* m, psData* d, const psuHD* c, int tape, double t,
                   const double* y, const double* yp) {
  int s = c->stride;
  int adr = m->tape_body_adr[tape];
  (void)t;
  for (int slot = 0; slot < m->tape_nbody[tape]; slot++) {
    int b = m->tbody_body[adr + slot];
    int qp = m->tbody_q[adr + slot], up = m->tbody_u[adr + slot], ap = m->tbody_a[adr + slot];
    int qa = m->body_qadr[b], ua = m->body_uadr[b];
    BodySlots k = body_slots(m, d, slot);
    double *r = k.r, *A = k.A, *v = k.v, *w = k.w, *acc = k.acc, *al = k.al;
    double* e = ps_bc(m, d, slot, PS_BC_E);
    double* wb = ps_bc(m, d, slot, PS_BC_WB);
    /* translation */
    for (int i = 0; i < 3; i++) {
      psu_hd_var(c, r + i * s, y[qa + i], qp >= 0 ? qp + i : -1);
      psu_hd_var(c, v + i * s, y[ua + i], up >= 0 ? up + i : -1);
      psu_hd_var(c, acc + i * s, yp ? yp[ua + i] : 0.0, ap >= 0 ? ap + i : -1);
    }
    /* a point body has no rotation: the marker functions never read its A, w, alpha, e */
    if (m->body_type[b] == PS_BODY_POINT) continue;
    if (m->body_type[b] == PS_BODY_PLANAR) {
      planar_cache(m, d, c, b, slot, y, yp, qp, up, ap);
      continue;
    }
    /* rotation: Euler parameters, body angular velocity, and their global images */
    for (int i = 0; i < 4; i++) psu_hd_var(c, e + i * s, y[qa + 3 + i], qp >= 0 ? qp + 3 + i : -1);
    rotation_from_e(m, d, c, A, e);
    for (int i = 0; i < 3; i++) psu_hd_var(c, wb + i * s, y[ua + 3 + i], up >= 0 ? up + 3 + i : -1);
    /* global angular velocity and acceleration only for tapes that measure them */
    if (m->tbody_w[adr + slot]) mat_vec(c, w, A, wb, ps_tmp(m, d, TMP_X));
    if (ap >= 0) {
      double* wdot = ps_tmp(m, d, TMP_C1);
      for (int i = 0; i < 3; i++)
        psu_hd_var(c, wdot + i * s, yp ? yp[ua + 3 + i] : 0.0, ap >= 0 ? ap + 3 + i : -1);
      mat_vec(c, al, A, wdot, ps_tmp(m, d, TMP_X));
    }
  }
}

/* Rotated body-fixed offset p = A s of a marker on a moving body. */
static double* marker_offset(const psModel* m, psData* d, const psuHD* c, int mk, int slot) {
  int s = c->stride;
  double* p = ps_tmp(m, d, TMP_P);
  const double* A = ps_bc(m, d, slot, PS_BC_A);
  const double* sp = m->marker_pos + 3 * mk;
  for (int i = 0; i < 3; i++) {
    psu_hd_lin(c, p + i * s, sp[0], A + (3 * i) * s, sp[1], A + (3 * i + 1) * s, 0.0);
    psu_hd_lin(c, p + i * s, 1.0, p + i * s, sp[2], A + (3 * i + 2) * s, 0.0);
  }
  return p;
}

static int on_ground(const psModel* m, int mk, int slot) {
  return mk < 0 || slot < 0 || m->marker_body[mk] < 0;
}

/* A marker on a point body: translated rigidly, never rotated. */
static int on_point(const psModel* m, int mk) {
  return m->body_type[m->marker_body[mk]] == PS_BODY_POINT;
}

void ps_marker_pos(const psModel* m, psData* d, const psuHD* c, int mk, int slot, double* R) {
  int s = c->stride;
  if (on_ground(m, mk, slot)) {
    for (int i = 0; i < 3; i++) psu_hd_const(c, R + i * s, mk < 0 ? 0.0 : m->marker_pos[3 * mk + i]);
    return;
  }
  const double* r = ps_bc(m, d, slot, PS_BC_R);
  if (on_point(m, mk)) {
    for (int i = 0; i < 3; i++)
      psu_hd_lin(c, R + i * s, 1.0, r + i * s, 0.0, NULL, m->marker_pos[3 * mk + i]);
    return;
  }
  double* p = marker_offset(m, d, c, mk, slot);
  for (int i = 0; i < 3; i++) psu_hd_lin(c, R + i * s, 1.0, r + i * s, 1.0, p + i * s, 0.0);
}

void ps_marker_axes(const psModel* m, psData* d, const psuHD* c, int mk, int slot, double* X) {
  int s = c->stride;
  if (on_ground(m, mk, slot) || on_point(m, mk)) {
    for (int i = 0; i < 9; i++)
      psu_hd_const(c, X + i * s, mk < 0 ? ((i % 4 == 0) ? 1.0 : 0.0) : m->marker_rot[9 * mk + i]);
    return;
  }
  const double* A = ps_bc(m, d, slot, PS_BC_A);
  const double* Rm = m->marker_rot + 9 * mk;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double* x = X + (3 * i + j) * s;
      psu_hd_lin(c, x, Rm[j], A + (3 * i) * s, Rm[3 + j], A + (3 * i + 1) * s, 0.0);
      psu_hd_lin(c, x, 1.0, x, Rm[6 + j], A + (3 * i + 2) * s, 0.0);
    }
}

void ps_marker_vel(const psModel* m, psData* d, const psuHD* c, int mk, int slot, double* V) {
  int s = c->stride;
  if (on_ground(m, mk, slot)) {
    for (int i = 0; i < 3; i++) psu_hd_const(c, V + i * s, 0.0);
    return;
  }
  if (on_point(m, mk)) {
    for (int i = 0; i < 3; i++) psu_hd_copy(c, V + i * s, ps_bc(m, d, slot, PS_BC_V) + i * s);
    return;
  }
  double* p = marker_offset(m, d, c, mk, slot);
  double* wxp = ps_tmp(m, d, TMP_C1);
  psu_hd_cross(c, wxp, ps_bc(m, d, slot, PS_BC_W), p, ps_tmp(m, d, TMP_X));
  const double* v = ps_bc(m, d, slot, PS_BC_V);
  for (int i = 0; i < 3; i++) psu_hd_lin(c, V + i * s, 1.0, v + i * s, 1.0, wxp + i * s, 0.0);
}

/* A body vector of the cache (angular velocity or acceleration) for a marker; zero on ground. */
static void body_vector(const psModel* m, psData* d, const psuHD* c, int mk, int slot, int k,
                        double* out) {
  int s = c->stride;
  for (int i = 0; i < 3; i++) {
    if (on_ground(m, mk, slot) || on_point(m, mk))
      psu_hd_const(c, out + i * s, 0.0);
    else
      psu_hd_copy(c, out + i * s, ps_bc(m, d, slot, k) + i * s);
  }
}

void ps_marker_omega(const psModel* m, psData* d, const psuHD* c, int mk, int slot, double* W) {
  body_vector(m, d, c, mk, slot, PS_BC_W, W);
}

void ps_marker_alpha(const psModel* m, psData* d, const psuHD* c, int mk, int slot, double* Al) {
  body_vector(m, d, c, mk, slot, PS_BC_AL, Al);
}

void ps_marker_acc(const psModel* m, psData* d, const psuHD* c, int mk, int slot, double* Acc) {
  int s = c->stride;
  if (on_ground(m, mk, slot)) {
    for (int i = 0; i < 3; i++) psu_hd_const(c, Acc + i * s, 0.0);
    return;
  }
  if (on_point(m, mk)) {
    for (int i = 0; i < 3; i++)
      psu_hd_copy(c, Acc + i * s, ps_bc(m, d, slot, PS_BC_ACC) + i * s);
    return;
  }
  /* a = a0 + alpha x p + w x (w x p) */
  double* p = marker_offset(m, d, c, mk, slot);
  double* c1 = ps_tmp(m, d, TMP_C1);
  double* c2 = ps_tmp(m, d, TMP_C2);
  double* x = ps_tmp(m, d, TMP_X);
  const double* w = ps_bc(m, d, slot, PS_BC_W);
  psu_hd_cross(c, c1, w, p, x);
  psu_hd_cross(c, c2, w, c1, x);
  psu_hd_cross(c, c1, ps_bc(m, d, slot, PS_BC_AL), p, x);
  const double* a0 = ps_bc(m, d, slot, PS_BC_ACC);
  for (int i = 0; i < 3; i++) {
    psu_hd_lin(c, Acc + i * s, 1.0, a0 + i * s, 1.0, c1 + i * s, 0.0);
    psu_hd_lin(c, Acc + i * s, 1.0, Acc + i * s, 1.0, c2 + i * s, 0.0);
  }
}
