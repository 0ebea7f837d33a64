/* The residual F(t, y, yp) and its iteration matrix dF/dy + cj dF/dyp.
 *
 * The pipeline reads as a table of contents: inertia and kinematic rows, then penalty forces,
 * then scalar two-body forces. The residual and the Jacobian share one assembly pass; with
 * jac == NULL it computes values only.
 */
#define _POSIX_C_SOURCE 200809L   /* sigaction */
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>

#include "internal.h"

/* Scratch numbers for force assembly in d->tmp (PS_TMP_TAPE and up). */
#define F_RI 64
#define F_RJ 67
#define F_REL 70
#define F_LEN 73
#define F_DIR 74
#define F_VEC 77
#define F_MOM 80
#define F_P 83
#define F_CR 86
#define F_SC 89
#define F_Q 91
#define F_CI 92
#define F_PT 93
#define F_FV 96

/* Where derivatives go: a dense row-major matrix, or a list of (row, col, value) triplets
 * whose order depends only on the model's structure (used for sparse CSC matrices). */
typedef struct Assembly {
  double* res;
  double* jac;   /* dense (ny x ny), or NULL */
  double* trip;  /* triplet values, or NULL */
  int* trow;     /* triplet rows, or NULL (values only) */
  int* tcol;     /* triplet columns, or NULL */
  int k;         /* number of triplets written */
  int deriv;     /* 1 when derivatives are wanted */
  double cj;
  int ny;
} Assembly;

/* Add v to the iteration matrix entry (row, col). */
static void jadd(Assembly* as, int row, int col, double v) {
  if (as->jac) {
    as->jac[(long)row * as->ny + col] += v;
    return;
  }
  if (as->trow) {
    as->trow[as->k] = row;
    as->tcol[as->k] = col;
  }
  if (as->trip) as->trip[as->k] = v;
  as->k++;
}

/* Subtract force_scale * Q from residual row `row`, and its derivatives from the Jacobian. */
static void scatter(const psModel* m, const psuHD* c, int tape, int row, const double* Q,
                    Assembly* as) {
  double cf = m->force_scale;
  as->res[row] -= cf * Q[0];
  if (!as->deriv) return;
  int badr = m->tape_basis_adr[tape];
  for (int j = 0; j < c->n; j++) {
    int kind = m->basis_kind[badr + j];
    if (kind == PS_BASIS_T) continue;
    jadd(as, row, m->basis_idx[badr + j],
         -cf * Q[1 + j] * (kind == PS_BASIS_YP ? as->cj : 1.0));
  }
}

/* Inertia, gravity and the kinematic rows q' - N(q) u of every body. */
static void inertia_rows(const psModel* m, double t, const double* y, const double* yp,
                         Assembly* as) {
  (void)t;
  int J = as->deriv;
  for (int b = 0; b < m->nbody; b++) {
    int qa = m->body_qadr[b], ua = m->body_uadr[b];
    double mass = m->body_mass[b];
    for (int i = 0; i < 3; i++) {
      as->res[qa + i] = yp[qa + i] - y[ua + i];
      as->res[ua + i] = mass * (yp[ua + i] - m->gravity[i]);
      if (J) {
        jadd(as, qa + i, qa + i, as->cj);
        jadd(as, qa + i, ua + i, -1.0);
        jadd(as, ua + i, ua + i, as->cj * mass);
      }
    }
    if (m->body_type[b] != PS_BODY_RIGID) continue;
    /* Euler parameters: e' = 1/2 G(e) w = 1/2 M(w) e */
    const double* e = y + qa + 3;
    const double* w = y + ua + 3;
    double G[4][3] = {{-e[1], -e[2], -e[3]}, {e[0], -e[3], e[2]}, {e[3], e[0], -e[1]},
                      {-e[2], e[1], e[0]}};
    double M[4][4] = {{0, -w[0], -w[1], -w[2]}, {w[0], 0, w[2], -w[1]}, {w[1], -w[2], 0, w[0]},
                      {w[2], w[1], -w[0], 0}};
    for (int a = 0; a < 4; a++) {
      double r = yp[qa + 3 + a];
      for (int k = 0; k < 3; k++) r -= 0.5 * G[a][k] * w[k];
      as->res[qa + 3 + a] = r;
      if (J) {
        for (int bb = 0; bb < 4; bb++)
          jadd(as, qa + 3 + a, qa + 3 + bb, (a == bb ? as->cj : 0.0) - 0.5 * M[a][bb]);
        for (int k = 0; k < 3; k++) jadd(as, qa + 3 + a, ua + 3 + k, -0.5 * G[a][k]);
      }
    }
    /* Euler's equations in the body frame: I w' + w x (I w) */
    const double* I = m->body_inertia + 9 * b;
    const double* wd = yp + ua + 3;
    double Iw[3], Iwd[3];
    for (int i = 0; i < 3; i++) {
      Iw[i] = I[3 * i] * w[0] + I[3 * i + 1] * w[1] + I[3 * i + 2] * w[2];
      Iwd[i] = I[3 * i] * wd[0] + I[3 * i + 1] * wd[1] + I[3 * i + 2] * wd[2];
    }
    for (int i = 0; i < 3; i++) {
      int j = (i + 1) % 3, k = (i + 2) % 3;
      as->res[ua + 3 + i] = Iwd[i] + w[j] * Iw[k] - w[k] * Iw[j];
      if (!J) continue;
      for (int l = 0; l < 3; l++) {
        /* d/dw_l of w_j (I w)_k - w_k (I w)_j */
        double dv = w[j] * I[3 * k + l] - w[k] * I[3 * j + l];
        if (l == j) dv += Iw[k];
        if (l == k) dv -= Iw[j];
        jadd(as, ua + 3 + i, ua + 3 + l, as->cj * I[3 * i + l] + dv);
      }
    }
  }
}

/* Generalized forces on the body in tape slot `slot` of a global force F at the global point P
 * (hyper-duals; F, P or Mo may be NULL) and a global moment Mo. */
static void apply_at(const psModel* m, psData* d, const psuHD* c, int tape, int slot,
                     const double* P, const double* F, const double* Mo, double sign,
                     Assembly* as) {
  if (slot < 0) return;
  int s = c->stride;
  int b = m->tbody_body[m->tape_body_adr[tape] + slot];
  int ua = m->body_uadr[b];
  double* Q = ps_tmp(m, d, F_Q);
  for (int i = 0; i < 3; i++) {
    if (F) {
      psu_hd_lin(c, Q, sign, F + i * s, 0.0, NULL, 0.0);
      scatter(m, c, tape, ua + i, Q, as);
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
    scatter(m, c, tape, ua + 3 + k, Q, as);
  }
}

/* Generalized forces of a global force F at a marker and a global moment M on its body. */
static void apply_load(const psModel* m, psData* d, const psuHD* c, int tape, int mk, int slot,
                       const double* F, const double* Mo, double sign, Assembly* as) {
  if (slot < 0 || m->marker_body[mk] < 0) return;
  double* P = ps_tmp(m, d, F_PT);
  if (F && m->body_type[m->tbody_body[m->tape_body_adr[tape] + slot]] == PS_BODY_RIGID)
    ps_marker_pos(m, d, c, mk, slot, P);
  apply_at(m, d, c, tape, slot, P, F, Mo, sign, as);
}

/* Add Q_i = F c_i, c_i = d(g')/du_i, for every free body the tape reads; when lam >= 0 (a
 * motion's reaction, F = lam) also the Jacobian column of lam. */
static void rate_force(const psModel* m, psData* d, const psuHD* c, const double* g, int tape,
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
      scatter(m, c, tape, m->body_uadr[b] + i, Q, as);
      if (lam >= 0 && as->deriv) jadd(as, m->body_uadr[b] + i, lam, -m->force_scale * ci[0]);
    }
  }
}

/* Force_Penalty: Q_i = F * d(g')/du_i with F = -p g - p1 g' (smoothed when unilateral). */
static void penalty_forces(const psModel* m, psData* d, double t, const double* y,
                           const double* yp, Assembly* as) {
  for (int p = 0; p < m->npen; p++) {
    int tape = m->pen_tape[p];
    int order = as->deriv ? 2 : 1;
    ps_tape_run(m, d, tape, order, !as->deriv, t, y, yp);
    psuHD c = {m->tape_nbasis[tape], m->tape_nh[tape], order - 1, m->hd_stride};
    rate_force(m, d, &c, ps_slot(m, d, m->pen_g[p]), tape, ps_slot(m, d, m->pen_f[p]), -1, as);
  }
}

/* Force_Scalar_TwoBody: a force along the line from J to I, or a torque about z of J. */
static void scalar_forces(const psModel* m, psData* d, double t, const double* y,
                          const double* yp, Assembly* as) {
  for (int k = 0; k < m->nsf; k++) {
    int tape = m->sf_tape[k];
    int order = as->deriv + m->tape_order[tape];
    ps_tape_run(m, d, tape, order, !as->deriv, t, y, yp);
    psuHD c = {m->tape_nbasis[tape], m->tape_nh[tape], as->deriv, m->hd_stride};
    int s = c.stride;
    const double* f = ps_slot(m, d, m->sf_f[k]);
    int mi = m->sf_i[k], mj = m->sf_j[k];
    /* body slots of I and J in this tape: the compiler puts them first */
    int si = m->marker_body[mi] < 0 ? -1 : 0;
    int sj = m->marker_body[mj] < 0 ? -1 : (m->marker_body[mi] < 0 ||
                                             m->marker_body[mi] == m->marker_body[mj] ? 0 : 1);
    double* vec = ps_tmp(m, d, F_VEC);
    if (m->sf_torque[k]) {
      double* X = ps_tmp(m, d, F_RI);
      ps_marker_axes(m, d, &c, mj, sj, X);
      for (int i = 0; i < 3; i++) psu_hd_mul(&c, vec + i * s, f, X + (3 * i + 2) * s);
      apply_load(m, d, &c, tape, mi, si, NULL, vec, 1.0, as);
      apply_load(m, d, &c, tape, mj, sj, NULL, vec, -1.0, as);
    } else {
      double* ri = ps_tmp(m, d, F_RI);
      double* rj = ps_tmp(m, d, F_RJ);
      double* rel = ps_tmp(m, d, F_REL);
      double* len = ps_tmp(m, d, F_LEN);
      ps_marker_pos(m, d, &c, mi, si, ri);
      ps_marker_pos(m, d, &c, mj, sj, rj);
      for (int i = 0; i < 3; i++) psu_hd_lin(&c, rel + i * s, 1.0, ri + i * s, -1.0, rj + i * s, 0.0);
      psu_hd_dot(&c, len, rel, rel, ps_tmp(m, d, F_SC));
      double L = sqrt(len[0]);
      /* coincident markers: no direction, no force (derivatives still written as zeros) */
      if (L == 0.0)
        psu_hd_const(&c, len, 0.0);
      else
        psu_hd_unary(&c, len, len, 1.0 / L, -0.5 / (L * L * L), 0.0);
      for (int i = 0; i < 3; i++) {
        psu_hd_mul(&c, vec + i * s, rel + i * s, len);
        psu_hd_mul(&c, vec + i * s, vec + i * s, f);
      }
      apply_load(m, d, &c, tape, mi, si, vec, NULL, 1.0, as);
      apply_load(m, d, &c, tape, mj, sj, vec, NULL, -1.0, as);
    }
  }
}

/* Force_Vector_TwoBody: F = X f with X the reference marker's axes, on I's body at I and
 * opposite on J's body at the same point. */
static void vector_forces(const psModel* m, psData* d, double t, const double* y,
                          const double* yp, Assembly* as) {
  for (int k = 0; k < m->nvf; k++) {
    int tape = m->vf_tape[k];
    ps_tape_run(m, d, tape, as->deriv + m->tape_order[tape], !as->deriv, t, y, yp);
    psuHD c = {m->tape_nbasis[tape], m->tape_nh[tape], as->deriv, m->hd_stride};
    int s = c.stride;
    double* X = ps_tmp(m, d, F_RI);   /* 9 numbers: F_RI .. F_RI + 8 */
    double* F = ps_tmp(m, d, F_FV);
    double* sc = ps_tmp(m, d, F_SC);
    ps_marker_axes(m, d, &c, m->vf_r[k], m->vf_sr[k], X);
    for (int i = 0; i < 3; i++) {
      psu_hd_const(&c, F + i * s, 0.0);
      for (int j = 0; j < 3; j++) {
        psu_hd_mul(&c, sc, X + (3 * i + j) * s, ps_slot(m, d, m->vf_f[3 * k + j]));
        psu_hd_lin(&c, F + i * s, 1.0, F + i * s, 1.0, sc, 0.0);
      }
    }
    int mi = m->vf_i[k], si = m->vf_si[k];
    double* P = ps_tmp(m, d, F_PT);
    ps_marker_pos(m, d, &c, mi, si, P);
    apply_at(m, d, &c, tape, m->marker_body[mi] < 0 ? -1 : si, P, F, NULL, 1.0, as);
    apply_at(m, d, &c, tape, m->vf_sj[k], P, F, NULL, -1.0, as);
  }
}

/* Motion_Marker k: its reaction lam (a state, model force units) acts like a penalty force
 * F = lam, Q_i = lam c_i with c_i = d(g')/du_i; its own row holds g' to the target rate: 0 for
 * a displacement (g includes the expression), the expression for a velocity, and for an
 * acceleration the state w whose row integrates w' = expression. The row has no lam in it
 * (index 2): IDA leaves lam out of its error test. */
static void motion_rows(const psModel* m, psData* d, double t, const double* y,
                        const double* yp, Assembly* as) {
  for (int k = 0; k < m->nmotion; k++) {
    int tape = m->mot_tape[k], lam = m->mot_lam[k], w = m->mot_w[k], kind = m->mot_kind[k];
    int order = as->deriv ? 2 : 1;
    ps_tape_run(m, d, tape, order, !as->deriv, t, y, yp);
    psuHD c = {m->tape_nbasis[tape], m->tape_nh[tape], order - 1, m->hd_stride};
    const double* g = ps_slot(m, d, m->mot_g[k]);
    const double* gd = ps_slot(m, d, m->mot_gd[k]);
    const double* f = ps_slot(m, d, m->mot_f[k]);
    double* L = ps_tmp(m, d, F_LEN);
    psu_hd_const(&c, L, y[lam]);
    rate_force(m, d, &c, g, tape, L, lam, as);
    as->res[lam] = gd[0] - (kind == PS_MOTION_V ? f[0] : kind == PS_MOTION_A ? y[w] : 0.0);
    if (as->deriv) {
      int badr = m->tape_basis_adr[tape];
      for (int j = 0; j < c.n; j++) {
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
}

/* Record the first non-finite value found (kind, index, value) and a message. */
static int found_bad(psData* d, int kind, int index, double v) {
  d->bad_kind = kind;
  d->bad_index = index;
  d->bad_value = v;
  snprintf(d->msg, sizeof(d->msg), "non-finite value (%g)", v);
  return 1;
}

/* Whether any of the value and first partials of element value slots is not finite. */
static int bad_slots(const psModel* m, psData* d, int tape, int order, const int* slots,
                     int n, double* v) {
  int width = order > 0 ? 1 + m->tape_nbasis[tape] : 1;
  for (int k = 0; k < n; k++) {
    const double* x = ps_slot(m, d, slots[k]);
    for (int j = 0; j < width; j++)
      if (!isfinite(x[j])) {
        *v = x[j];
        d->bad_partial = j > 0;
        return 1;
      }
  }
  return 0;
}

/* A residual (deriv = 0) or Jacobian (deriv = 1) came out non-finite at (t, y, yp): find the
 * first state, element value (or, for the Jacobian, its first partials) that is, in the order
 * the residual assembles them. Runs only on that failure path. */
static void diagnose(const psModel* m, psData* d, double t, const double* y, const double* yp,
                     int deriv) {
  double v = 0.0;
  d->bad_t = t;
  d->bad_partial = 0;
  memcpy(d->bad_y, y, sizeof(double) * (size_t)m->ny);
  for (int i = 0; i < m->ny; i++) {
    if (!isfinite(y[i]) && found_bad(d, PS_BAD_STATE, i, y[i])) return;
    if (!isfinite(yp[i]) && found_bad(d, PS_BAD_RATE, i, yp[i])) return;
  }
  for (int p = 0; p < m->npen; p++) {
    int tape = m->pen_tape[p], slots[2] = {m->pen_g[p], m->pen_f[p]};
    ps_tape_run(m, d, tape, 1 + deriv, 1 - deriv, t, y, yp);
    if (bad_slots(m, d, tape, deriv, slots, 2, &v) && found_bad(d, PS_BAD_PENALTY, p, v))
      return;
  }
  for (int k = 0; k < m->nsf; k++) {
    int tape = m->sf_tape[k];
    ps_tape_run(m, d, tape, deriv + m->tape_order[tape], 1 - deriv, t, y, yp);
    if (bad_slots(m, d, tape, deriv, &m->sf_f[k], 1, &v) && found_bad(d, PS_BAD_SFORCE, k, v))
      return;
  }
  for (int k = 0; k < m->nvf; k++) {
    int tape = m->vf_tape[k];
    ps_tape_run(m, d, tape, deriv + m->tape_order[tape], 1 - deriv, t, y, yp);
    if (bad_slots(m, d, tape, deriv, &m->vf_f[3 * k], 3, &v) &&
        found_bad(d, PS_BAD_VFORCE, k, v))
      return;
  }
  for (int k = 0; k < m->nmotion; k++) {
    int tape = m->mot_tape[k], slots[2] = {m->mot_f[k], m->mot_gd[k]};
    ps_tape_run(m, d, tape, 1 + deriv, 1 - deriv, t, y, yp);
    if (bad_slots(m, d, tape, deriv, slots, 2, &v) && found_bad(d, PS_BAD_MOTION, k, v))
      return;
  }
  found_bad(d, deriv ? PS_BAD_JACOBIAN : PS_BAD_RESIDUAL, -1, NAN);
}

/* PS_OK if v[0..n) is finite; otherwise diagnose where the non-finite value came from. When no
 * element's value is, the entry is reported: v's index i if rows is set (a residual row, or
 * row * ny + column of a dense Jacobian), -1 otherwise. */
static int check_finite(const psModel* m, psData* d, double t, const double* y,
                        const double* yp, const double* v, long n, int deriv, int rows) {
  if (d->user_error) return PS_ERR_NONFINITE;   /* d->msg holds the subroutine's message */
  for (long i = 0; i < n; i++) {
    if (!isfinite(v[i])) {
      double bad = v[i];
      diagnose(m, d, t, y, yp, deriv);
      if (d->bad_kind == PS_BAD_RESIDUAL || d->bad_kind == PS_BAD_JACOBIAN) {
        d->bad_index = rows ? (int)i : -1;
        d->bad_value = bad;
      }
      return PS_ERR_NONFINITE;
    }
  }
  return PS_OK;
}

static int assemble(const psModel* m, psData* d, double t, const double* y, const double* yp,
                    Assembly* as) {
  if (as->jac) memset(as->jac, 0, sizeof(double) * (size_t)m->ny * (size_t)m->ny);
  as->k = 0;
  inertia_rows(m, t, y, yp, as);
  penalty_forces(m, d, t, y, yp, as);
  scalar_forces(m, d, t, y, yp, as);
  vector_forces(m, d, t, y, yp, as);
  motion_rows(m, d, t, y, yp, as);
  return PS_OK;
}

/* Ctrl-C during a run: the first SIGINT sets the flag the residual checks (the run stops at
 * its next residual, with the rows so far); a second one ends the process at once. */
static volatile sig_atomic_t interrupted = 0;
static struct sigaction previous;
static int armed = 0;

static void on_sigint(int sig) {
  if (interrupted) {
    signal(sig, SIG_DFL);
    raise(sig);
    return;
  }
  interrupted = 1;
}

void ps_interrupt_arm(void) {
  struct sigaction act;
  memset(&act, 0, sizeof(act));
  act.sa_handler = on_sigint;
  sigemptyset(&act.sa_mask);
  interrupted = 0;
  if (!armed && sigaction(SIGINT, &act, &previous) == 0) armed = 1;
}

void ps_interrupt_disarm(void) {
  if (armed) sigaction(SIGINT, &previous, NULL);
  armed = 0;
}

int ps_interrupted(void) { return interrupted; }

int ps_residual(const psModel* m, psData* d, double t, const double* y, const double* yp,
                double* res) {
  Assembly as = {res, NULL, NULL, NULL, NULL, 0, 0, 0.0, m->ny};
  if (interrupted) {
    snprintf(d->msg, sizeof(d->msg), "interrupted");
    d->user_error = 1;     /* not recoverable: IDA returns at once */
    return PS_ERR_NONFINITE;
  }
  d->nres++;
  /* A new time is a new step attempt; IDA retries a failed attempt (error test or
   * convergence) from the same base with a smaller step, so a new time below the last one
   * means the last attempt failed. The driver sets last_t to the time of every (re)start,
   * so steps taken = ntimes - nfail. */
  if (t != d->last_t) {
    long ntimes = d->ntimes + 1, nfail = d->nfail + (t < d->last_t);
    /* max_num_steps: the step this attempt would make is one too many (not recoverable) */
    if (d->step_limit > 0 && ntimes - nfail > d->step_limit) {
      d->steps_exceeded = 1;
      d->user_error = 1;
      snprintf(d->msg, sizeof(d->msg), "max_num_steps reached");
      return PS_ERR_NONFINITE;
    }
    d->ntimes = ntimes;
    d->nfail = nfail;
  }
  d->last_t = t;
  if (m->gen)
    m->gen->residual(m, d->senval, t, y, yp, 0.0, res);
  else
    assemble(m, d, t, y, yp, &as);
  return check_finite(m, d, t, y, yp, res, m->ny, 0, 1);
}

int ps_penalty_loads(const psModel* m, psData* d, double t, const double* y, const double* yp,
                     double* q) {
  Assembly as = {q, NULL, NULL, NULL, NULL, 0, 0, 0.0, m->ny};
  for (int i = 0; i < m->ny; i++) q[i] = 0.0;
  penalty_forces(m, d, t, y, yp, &as);
  /* scatter subtracted force_scale * Q: give Q */
  for (int i = 0; i < m->ny; i++) q[i] /= -m->force_scale;
  return check_finite(m, d, t, y, yp, q, m->ny, 0, 0);
}

/* Unit roundoff of a double (2^-53). */
#define PS_UNIT_ROUNDOFF 1.1102230246251565e-16

double ps_precision(const psModel* m, psData* d, double t, const double* y,
                    const double* yp, const int* trow, const int* tcol, int ntrip,
                    double* work, int* body) {
  int n = m->ny;
  double *noise = work, *net = work + n, *free_y = work + 2 * n, *zero = work + 3 * n;
  /* the counters and the step bookkeeping are the run's: this is not a step */
  long nres = d->nres, njac = d->njac;
  *body = -1;
  /* dF/dy at the state (cj = 0), as the kernel's triplets */
  if (m->gen) {
    trow = m->gen->trow;
    tcol = m->gen->tcol;
    ntrip = m->gen->ntrip;
    m->gen->jacobian(m, d->senval, t, y, yp, 0.0, d->trip);
  } else {
    Assembly as = {d->res, NULL, d->trip, NULL, NULL, 0, 1, 0.0, n};
    assemble(m, d, t, y, yp, &as);
  }
  /* the state's rounding: reactions are not rounded positions */
  for (int i = 0; i < n; i++) {
    noise[i] = 0.0;
    zero[i] = 0.0;
    free_y[i] = y[i];
  }
  for (int k = 0; k < m->nmotion; k++) free_y[m->mot_lam[k]] = 0.0;
  for (int k = 0; k < ntrip; k++)
    noise[trow[k]] += fabs(d->trip[k]) * fabs(free_y[tcol[k]]) * PS_UNIT_ROUNDOFF;
  /* the forces each row carries, in the residual's units: the net of every force but
   * reactions (the residual at yp = 0 without them) */
  if (m->gen)
    m->gen->residual(m, d->senval, t, free_y, zero, 0.0, net);
  else {
    Assembly as = {net, NULL, NULL, NULL, NULL, 0, 0, 0.0, n};
    assemble(m, d, t, free_y, zero, &as);
  }
  d->nres = nres;
  d->njac = njac;
  double g = sqrt(m->gravity[0] * m->gravity[0] + m->gravity[1] * m->gravity[1] +
                  m->gravity[2] * m->gravity[2]);
  double worst = 0.0;
  for (int b = 0; b < m->nbody; b++) {
    int u = m->body_uadr[b];
    double a = 0.0, f = 0.0, most = 0.0;
    for (int c = 0; c < 3; c++) {
      a += yp[u + c] * yp[u + c];
      f += net[u + c] * net[u + c];
      if (noise[u + c] > most) most = noise[u + c];
    }
    a = sqrt(a);
    double ref = m->body_mass[b] * (a > g ? a : g) + sqrt(f);
    if (ref > 0.0 && most / ref > worst) {
      worst = most / ref;
      *body = b;
    }
  }
  return worst;
}

int ps_jacobian(const psModel* m, psData* d, double t, const double* y, const double* yp,
                double cj, double* jac) {
  Assembly as = {d->res, jac, NULL, NULL, NULL, 0, 1, cj, m->ny};
  d->njac++;
  if (m->gen) {
    const psGen* gen = m->gen;
    memset(jac, 0, sizeof(double) * (size_t)m->ny * (size_t)m->ny);
    gen->jacobian(m, d->senval, t, y, yp, cj, d->trip);
    for (int k = 0; k < gen->ntrip; k++) jac[(long)gen->trow[k] * m->ny + gen->tcol[k]] = d->trip[k];
  } else {
    assemble(m, d, t, y, yp, &as);
  }
  return check_finite(m, d, t, y, yp, jac, (long)m->ny * m->ny, 1, 1);
}

int ps_jacobian_pattern(const psModel* m, psData* d, int* rows, int* cols) {
  if (m->gen) {
    if (rows)
      for (int k = 0; k < m->gen->ntrip; k++) {
        rows[k] = m->gen->trow[k];
        cols[k] = m->gen->tcol[k];
      }
    return m->gen->ntrip;
  }
  /* the structure does not depend on values: assemble once at a harmless state */
  double* y = d->res;
  for (int i = 0; i < m->ny; i++) y[i] = 0.0;
  for (int b = 0; b < m->nbody; b++)
    if (m->body_type[b] == PS_BODY_RIGID) y[m->body_qadr[b] + 3] = 1.0;
  Assembly as = {d->res + m->ny, NULL, NULL, rows, cols, 0, 1, 1.0, m->ny};
  assemble(m, d, 0.0, y, y, &as);
  return as.k;
}

int ps_jacobian_csc(const psModel* m, psData* d, double t, const double* y, const double* yp,
                    double cj, const int* map, int ntrip, double* data, int nnz) {
  Assembly as = {d->res, NULL, d->trip, NULL, NULL, 0, 1, cj, m->ny};
  d->njac++;
  if (m->gen)
    m->gen->jacobian(m, d->senval, t, y, yp, cj, d->trip);
  else
    assemble(m, d, t, y, yp, &as);
  for (int i = 0; i < nnz; i++) data[i] = 0.0;
  for (int k = 0; k < ntrip; k++) data[map[k]] += d->trip[k];
  return check_finite(m, d, t, y, yp, data, nnz, 1, 0);
}

/* Evaluate every sensor's expression into d->sensor_f (derivative order 0). */
static void sensor_values(const psModel* m, psData* d, double t, const double* y,
                          const double* yp) {
  if (m->gen) {
    m->gen->sensors(m, d->senval, t, y, yp, 0.0, d->sensor_f);
    return;
  }
  int last = -1;
  for (int k = 0; k < m->nsensor; k++) {
    int tape = m->sensor_tape[k];
    if (tape != last) ps_tape_run(m, d, tape, m->tape_order[tape], 1, t, y, yp);
    last = tape;
    d->sensor_f[k] = ps_slot(m, d, m->sensor_slot[k])[0];
  }
}

int ps_roots(const psModel* m, psData* d, double t, const double* y, const double* yp,
             double* g) {
  d->nroots++;
  sensor_values(m, d, t, y, yp);
  for (int k = 0; k < m->nsensor; k++)
    if (!isfinite(d->sensor_f[k])) {
      d->bad_t = t;
      d->bad_partial = 0;
      memcpy(d->bad_y, y, sizeof(double) * (size_t)m->ny);
      found_bad(d, PS_BAD_SENSOR, k, d->sensor_f[k]);
      return PS_ERR_NONFINITE;
    }
  for (int k = 0; k < m->nsensor; k++) {
    double f = d->sensor_f[k], v = m->sensor_value[k], tol = m->sensor_tol[k];
    int watching = d->sensor_armed[k];
    switch (m->sensor_compare[k]) {
      case PS_CMP_GE: g[k] = watching ? f - v : (v - tol) - f; break;
      case PS_CMP_LT: g[k] = watching ? v - f : f - (v + tol); break;
      default: {
        double side = d->sensor_side[k];
        g[k] = watching ? side * (v + side * tol - f) : fabs(f - v) - 2.0 * tol;
        break;
      }
    }
  }
  return PS_OK;
}

int ps_sensor_status(const psModel* m, psData* d, double t, const double* y, const double* yp,
                     int* holds, int* rearms) {
  sensor_values(m, d, t, y, yp);
  for (int k = 0; k < m->nsensor; k++) {
    double f = d->sensor_f[k], v = m->sensor_value[k], tol = m->sensor_tol[k];
    switch (m->sensor_compare[k]) {
      case PS_CMP_GE: holds[k] = f >= v; rearms[k] = f < v - tol; break;
      case PS_CMP_LT: holds[k] = f < v; rearms[k] = f > v + tol; break;
      default: holds[k] = fabs(f - v) <= tol; rearms[k] = fabs(f - v) > 2.0 * tol; break;
    }
  }
  return PS_OK;
}

double ps_power(const psModel* m, const double* y, const double* yp) {
  double p = 0.0;
  for (int b = 0; b < m->nbody; b++) {
    int ua = m->body_uadr[b];
    for (int i = 0; i < 3; i++) p += m->body_mass[b] * y[ua + i] * yp[ua + i];
    if (m->body_type[b] != PS_BODY_RIGID) continue;
    const double* I = m->body_inertia + 9 * b;
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) p += y[ua + 3 + i] * I[3 * i + j] * yp[ua + 3 + j];
  }
  return p;
}

int ps_outputs(const psModel* m, psData* d, double t, const double* y, const double* yp,
               double* out) {
  if (m->gen) {
    m->gen->outputs(m, d->senval, t, y, yp, 0.0, out);
    return PS_OK;
  }
  int last = -1;
  for (int k = 0; k < m->nout; k++) {
    int tape = m->out_tape[k];
    if (tape < 0) {
      out[k] = NAN;
      continue;
    }
    if (tape != last) ps_tape_run(m, d, tape, m->tape_order[tape], 1, t, y, yp);
    last = tape;
    out[k] = ps_slot(m, d, m->out_slot[k])[0];
  }
  return PS_OK;
}

double ps_eval_tape(const psModel* m, psData* d, int tape, int slot, double t, const double* y,
                    const double* yp) {
  ps_tape_run(m, d, tape, m->tape_order[tape], 1, t, y, yp);
  return ps_slot(m, d, slot)[0];
}

/* Solve A x = b in place (b becomes x) by LU with partial pivoting; A (n x n, row-major) is
 * overwritten. Returns PS_ERR_SINGULAR on a zero or non-finite pivot. */
static int lu_solve(int n, double* A, double* b, int* piv) {
  for (int k = 0; k < n; k++) {
    int p = k;
    for (int i = k + 1; i < n; i++)
      if (fabs(A[(long)i * n + k]) > fabs(A[(long)p * n + k])) p = i;
    double pivot = A[(long)p * n + k];
    if (pivot == 0.0 || !isfinite(pivot)) return PS_ERR_SINGULAR;
    piv[k] = p;
    if (p != k) {
      for (int j = 0; j < n; j++) {
        double tmp = A[(long)k * n + j];
        A[(long)k * n + j] = A[(long)p * n + j];
        A[(long)p * n + j] = tmp;
      }
      double tmp = b[k];
      b[k] = b[p];
      b[p] = tmp;
    }
    for (int i = k + 1; i < n; i++) {
      double f = A[(long)i * n + k] / pivot;
      if (f == 0.0) continue;
      for (int j = k + 1; j < n; j++) A[(long)i * n + j] -= f * A[(long)k * n + j];
      b[i] -= f * b[k];
    }
  }
  for (int i = n - 1; i >= 0; i--) {
    double s = b[i];
    for (int j = i + 1; j < n; j++) s -= A[(long)i * n + j] * b[j];
    b[i] = s / A[(long)i * n + i];
  }
  return PS_OK;
}

int ps_consistent_yp(const psModel* m, psData* d, double t, const double* y, double* yp,
                     double* work, int* piv, int iters) {
  int n = m->ny;
  double* A = work;
  double* J0 = work + (long)n * n;
  double* r = work + 2L * n * n;
  for (int i = 0; i < n; i++) yp[i] = 0.0;
  for (int it = 0; it < iters; it++) {
    int rc = ps_residual(m, d, t, y, yp, r);
    if (rc == PS_OK) rc = ps_jacobian(m, d, t, y, yp, 1.0, A);
    if (rc == PS_OK) rc = ps_jacobian(m, d, t, y, yp, 0.0, J0);
    if (rc != PS_OK) return rc;
    for (long k = 0; k < (long)n * n; k++) A[k] -= J0[k];
    for (int i = 0; i < n; i++) r[i] = -r[i];
    if (lu_solve(n, A, r, piv) != PS_OK) return PS_ERR_SINGULAR;
    double step = 0.0, size = 0.0;
    for (int i = 0; i < n; i++) {
      yp[i] += r[i];
      step = fmax(step, fabs(r[i]));
      size = fmax(size, fabs(yp[i]));
    }
    if (!isfinite(step)) return PS_ERR_SINGULAR;
    if (step <= 1e-14 * (1.0 + size)) break;
  }
  return PS_OK;
}
