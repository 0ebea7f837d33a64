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

#include "assembly.h"

/* Inertia, gravity and the kinematic rows q' - N(q) u of every body. */
static void inertia_rows(const psModel* m, double t, const double* y, const double* yp,
                         Assembly* as) {
  (void)t;
  int J = as->deriv;
  for (int b = 0; b < m->nbody; b++) {
    int qa = m->body_qadr[b], ua = m->body_uadr[b], planar = m->body_type[b] == PS_BODY_PLANAR;
    double mass = m->body_mass[b];
    for (int i = 0; i < 3; i++) {
      /* a planar body's third row is Izz wz' (no gravity about z) */
      double mi = planar && i == 2 ? m->body_inertia[9 * b + 8] : mass;
      double gi = planar && i == 2 ? 0.0 : m->gravity[i];
      as->res[qa + i] = yp[qa + i] - y[ua + i];
      as->res[ua + i] = mi * (yp[ua + i] - gi);
      if (J) {
        jadd(as, qa + i, qa + i, as->cj);
        jadd(as, qa + i, ua + i, -1.0);
        jadd(as, ua + i, ua + i, as->cj * mi);
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

/* The elements' contributions, in table order (only those of kind `only`, unless it is -1):
 * each runs its tape, then its kind's contribution (csrc/elements/<kind>.c). Consecutive
 * rows of one tape (the equations of a joint) run it once: contributions write only scratch
 * numbers, never the tape's slots or body kinematics. */
static void element_rows(const psModel* m, psData* d, double t, const double* y,
                         const double* yp, Assembly* as, int only) {
  int last_tape = -1, last_order = -1;
  for (int e = 0; e < m->nel; e++) {
    int kind = m->el_kind[e], tape = m->el_tape[e];
    if (only >= 0 && kind != only) continue;
    const psElementKind* k = &ps_element_kinds[kind];
    int base = m->tape_order[tape] > k->order ? m->tape_order[tape] : k->order;
    if (tape != last_tape || as->deriv + base != last_order)
      ps_tape_run(m, d, tape, as->deriv + base, !as->deriv, t, y, yp);
    last_tape = tape;
    last_order = as->deriv + base;
    psuHD c = {m->tape_nbasis[tape], m->tape_nh[tape], as->deriv, m->hd_stride};
    k->assemble(m, d, &c, tape, m->el_int + m->el_adr[e], t, y, yp, as);
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
 * first state that is, else an element whose load has no direction at these positions (a
 * translational force at coincident markers), else the first rate, element value (or, for the
 * Jacobian, its first partials) that is, in the order the residual assembles them. Runs only
 * on that failure path. */
static void diagnose(const psModel* m, psData* d, double t, const double* y, const double* yp,
                     int deriv) {
  double v = 0.0;
  d->bad_t = t;
  d->bad_partial = 0;
  memcpy(d->bad_y, y, sizeof(double) * (size_t)m->ny);
  for (int i = 0; i < m->ny; i++)
    if (!isfinite(y[i]) && found_bad(d, PS_BAD_STATE, i, y[i])) return;
  /* an element whose load has no direction at these positions (its value finite), before the
   * rates it makes not finite once solved for */
  for (int e = 0; e < m->nel; e++) {
    int tape = m->el_tape[e];
    const psElementKind* k = &ps_element_kinds[m->el_kind[e]];
    if (!k->undefined) continue;
    int base = m->tape_order[tape] > k->order ? m->tape_order[tape] : k->order;
    ps_tape_run(m, d, tape, base, 1, t, y, yp);
    psuHD c = {m->tape_nbasis[tape], m->tape_nh[tape], 0, m->hd_stride};
    if (k->undefined(m, d, &c, tape, m->el_int + m->el_adr[e], &v) &&
        found_bad(d, PS_BAD_DIRECTION, e, v))
      return;
  }
  for (int i = 0; i < m->ny; i++)
    if (!isfinite(yp[i]) && found_bad(d, PS_BAD_RATE, i, yp[i])) return;
  for (int e = 0; e < m->nel; e++) {
    int tape = m->el_tape[e];
    const psElementKind* k = &ps_element_kinds[m->el_kind[e]];
    int base = m->tape_order[tape] > k->order ? m->tape_order[tape] : k->order;
    ps_tape_run(m, d, tape, deriv + base, 1 - deriv, t, y, yp);
    if (bad_slots(m, d, tape, deriv, m->el_int + m->el_adr[e], k->nvalue, &v) &&
        found_bad(d, PS_BAD_ELEMENT, e, v))
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
  element_rows(m, d, t, y, yp, as, -1);
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
  /* Ctrl-C stops the run it came in (ps_interrupted still says so after it; a model compiled
   * or evaluated between runs is not stopped) */
  if (interrupted && armed) {
    snprintf(d->msg, sizeof(d->msg), "interrupted");
    d->user_error = 1;     /* not recoverable: IDA returns at once */
    d->user_t = NAN;       /* no routine's call */
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
      d->user_t = NAN;
      snprintf(d->msg, sizeof(d->msg), "max_num_steps reached");
      return PS_ERR_NONFINITE;
    }
    d->ntimes = ntimes;
    d->nfail = nfail;
  }
  d->last_t = t;
  if (m->gen)
    m->gen->residual(m, d, t, y, yp, 0.0, res);
  else
    assemble(m, d, t, y, yp, &as);
  return check_finite(m, d, t, y, yp, res, m->ny, 0, 1);
}

int ps_penalty_loads(const psModel* m, psData* d, double t, const double* y, const double* yp,
                     double* q) {
  Assembly as = {q, NULL, NULL, NULL, NULL, 0, 0, 0.0, m->ny};
  for (int i = 0; i < m->ny; i++) q[i] = 0.0;
  element_rows(m, d, t, y, yp, &as, PS_EL_PENALTY);
  /* scatter subtracted force_scale * Q: give Q */
  for (int i = 0; i < m->ny; i++) q[i] /= -m->force_scale;
  return check_finite(m, d, t, y, yp, q, m->ny, 0, 0);
}

/* Unit roundoff of a double (2^-53). */
#define PS_UNIT_ROUNDOFF 1.1102230246251565e-16

/* The net of every force but reactions on each row at (t, y): the residual at yp = 0 with the
 * reactions zero (free_y: y with them zeroed, zero: ny zeros). */
static void net_forces(const psModel* m, psData* d, double t, const double* y, double* free_y,
                       double* zero, double* net) {
  int n = m->ny;
  for (int i = 0; i < n; i++) {
    zero[i] = 0.0;
    free_y[i] = m->state_alg[i] == 1 ? 0.0 : y[i];   /* tracked angles (2) are kept */
  }
  if (m->gen)
    m->gen->residual(m, d, t, free_y, zero, 0.0, net);
  else {
    Assembly as = {net, NULL, NULL, NULL, NULL, 0, 0, 0.0, n};
    assemble(m, d, t, free_y, zero, &as);
  }
}

/* The translational force rows of body b: 2 for a planar body (its third is its moment). */
static int force_rows(const psModel* m, int b) {
  return m->body_type[b] == PS_BODY_PLANAR ? 2 : 3;
}

void ps_carried(const psModel* m, psData* d, double t, const double* y, double* work,
                double* carried) {
  int n = m->ny;
  long nres = d->nres;
  double *net = work, *free_y = work + n, *zero = work + 2 * n;
  for (int i = 0; i < n; i++) {
    zero[i] = 0.0;
    free_y[i] = m->state_alg[i] == 1 ? 0.0 : y[i];
  }
  /* the tapes' assembly, each force's magnitude summed (generated C has no such mode) */
  Assembly as = {net, NULL, NULL, NULL, NULL, 0, 0, 0.0, n, 1};
  assemble(m, d, t, free_y, zero, &as);
  d->nres = nres;
  for (int b = 0; b < m->nbody; b++) {
    int u = m->body_uadr[b];
    double f = 0.0;
    for (int c = 0; c < force_rows(m, b); c++) f += net[u + c] * net[u + c];
    carried[b] = sqrt(f);
  }
}

double ps_precision(const psModel* m, psData* d, double t, const double* y,
                    const double* yp, const int* trow, const int* tcol, int ntrip,
                    const double* carried, const double* at_start, double* work, int* body) {
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
    m->gen->jacobian(m, d, t, y, yp, 0.0, d->trip);
  } else {
    Assembly as = {d->res, NULL, d->trip, NULL, NULL, 0, 1, 0.0, n};
    assemble(m, d, t, y, yp, &as);
  }
  /* the forces each row carries, in the residual's units: the net of every force but
   * reactions (the residual at yp = 0 without them) */
  net_forces(m, d, t, y, free_y, zero, net);
  /* the state's rounding: reactions are not rounded positions */
  for (int i = 0; i < n; i++) noise[i] = 0.0;
  for (int k = 0; k < ntrip; k++)
    noise[trow[k]] += fabs(d->trip[k]) * fabs(free_y[tcol[k]]) * PS_UNIT_ROUNDOFF;
  d->nres = nres;
  d->njac = njac;
  double g = sqrt(m->gravity[0] * m->gravity[0] + m->gravity[1] * m->gravity[1] +
                  m->gravity[2] * m->gravity[2]);
  double worst = 0.0;
  for (int b = 0; b < m->nbody; b++) {
    int u = m->body_uadr[b];
    double a = 0.0, f = 0.0, most = 0.0;
    /* a planar body's third velocity row is its moment row (Izz wz'), not a force row */
    for (int c = 0; c < force_rows(m, b); c++) {
      a += yp[u + c] * yp[u + c];
      f += net[u + c] * net[u + c];
      if (noise[u + c] > most) most = noise[u + c];
    }
    a = sqrt(a);
    double ref = m->body_mass[b] * (a > g ? a : g) + sqrt(f);
    if (carried) {
      /* the most it carried over the run (a load that passed through zero at the end) */
      if (carried[b] > ref) ref = carried[b];
      /* no force acted on it at the deck's start, and none above its rounding since */
      if (g == 0.0 && at_start[b] == 0.0 && carried[b] <= most) continue;
    }
    /* a body that carries exactly nothing but would move by rounding: without what it
     * carried over the run (carried NULL) there is nothing to measure against, and the
     * caller measures again with it */
    double ratio = ref > 0.0 ? most / ref : most > 0.0 && !carried ? INFINITY : 0.0;
    if (ratio > worst) {
      worst = ratio;
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
    gen->jacobian(m, d, t, y, yp, cj, d->trip);
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
    m->gen->jacobian(m, d, t, y, yp, cj, d->trip);
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
    m->gen->sensors(m, d, t, y, yp, 0.0, d->sensor_f);
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
  if (d->user_error) return PS_ERR_NONFINITE;   /* d->msg holds the subroutine's message */
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
    if (m->body_type[b] == PS_BODY_PLANAR) {
      p += m->body_mass[b] * (y[ua] * yp[ua] + y[ua + 1] * yp[ua + 1]) +
           m->body_inertia[9 * b + 8] * y[ua + 2] * yp[ua + 2];
      continue;
    }
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
    m->gen->outputs(m, d, t, y, yp, 0.0, out);
  } else {
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
  }
  /* a defined channel that is not finite: the run's log names it (solve/nonfinite.py) */
  for (int k = 0; k < m->nout; k++)
    if (m->out_tape[k] >= 0 && !isfinite(out[k])) d->out_nonfinite = 1;
  return PS_OK;
}

double ps_eval_tape(const psModel* m, psData* d, int tape, int slot, double t, const double* y,
                    const double* yp) {
  ps_tape_run(m, d, tape, m->tape_order[tape], 1, t, y, yp);
  return ps_slot(m, d, slot)[0];
}

int psu_dense_solve(int n, double* A, double* b, int* piv) {
  for (int k = 0; k < n; k++) {
    int p = k;
    for (int i = k + 1; i < n; i++)
      if (fabs(A[(long)i * n + k]) > fabs(A[(long)p * n + k])) p = i;
    double pivot = A[(long)p * n + k];
    if (pivot == 0.0 || !isfinite(pivot)) return PS_ERR_SINGULAR;
    if (piv) piv[k] = p;
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
    if (psu_dense_solve(n, A, r, piv) != PS_OK) return PS_ERR_SINGULAR;
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
