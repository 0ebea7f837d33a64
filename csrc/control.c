/* LoadControl in C (seed 002): the controller's law (pysolver/solve/loadlaw.py is its reference
 * in Python and its documentation), one task's update (load, target, law, the new velocity made
 * consistent with the state) and the restart that makes a scene with motions and joints
 * consistent again (pysolver/build/consistent.py's consistent() away from the initial state,
 * dense). The general driver and the batched path both call these, so their runs agree to the
 * last bit. */
#include <math.h>
#include <string.h>

#include "internal.h"

/* Newton steps of the position and rate corrections, and of the accelerations (as
 * consistent.py: its iters and the fixed 4). */
#define PS_RESTART_ITERS 8
#define PS_RESTART_ACC_ITERS 4

/* Most Newton steps of the assembly, toward the least change in the mass metric, the last
 * PS_PLAIN_ITERS of them plain least-change steps, and the bounds of the pull's step length
 * (as consistent.ASSEMBLY_ITERS, PLAIN_ITERS and PULL_BOUNDS: pysolver/build/icmetric.py). */
#define PS_ASSEMBLY_ITERS 50
#define PS_PLAIN_ITERS 5
#define PS_PULL_MIN 0.05
#define PS_PULL_MAX 20.0

/* The accelerations' Newton iteration stops at a step below this fraction of the values' size:
 * with exact Jacobians the error left is about its square, and on rows linear in yp the steps
 * after the first are rounding (the particle bed's: 2e-12 of the size, where 1e-14 took all
 * four iterations, twice the work). */
#define PS_RESTART_ACC_TOL 1e-10

/* The median of v[0..n-1] (sorted into tmp), as Python's statistics.median. */
static double median(const double* v, int n, double* tmp) {
  memcpy(tmp, v, sizeof(double) * (size_t)n);
  for (int i = 1; i < n; i++) {
    double x = tmp[i];
    int j = i - 1;
    for (; j >= 0 && tmp[j] > x; j--) tmp[j + 1] = tmp[j];
    tmp[j + 1] = x;
  }
  return n % 2 ? tmp[n / 2] : (tmp[n / 2 - 1] + tmp[n / 2]) / 2.0;
}

/* A_t from A_{t-1}, x and the filtered load L (loadlaw.LoadLaw._ratio). */
static void law_ratio(psLaw* w, double x, double L) {
  if (!w->has_A) {
    if (L != 0.0 && x != 0.0) {
      w->A = L / x;
      w->has_A = 1;
    }
    return;
  }
  double prev = w->A, a = w->smooth;
  if (L == 0.0 || x == 0.0) return;
  double denom = L * L + (prev * x) * (prev * x), pp = prev * prev;
  if (denom == 0.0 || pp == 0.0) return;
  double lam = 2.0 * (1.0 - a) / denom, gam = a / pp;
  double den = lam * x * x + gam;
  if (den == 0.0 || !isfinite(den)) return;
  double next = (lam * L * x + gam * prev) / den;
  if (!isfinite(next) || next == 0.0 || (next > 0) != (prev > 0)) return;
  w->A = next;
}

void ps_law_reset(psLaw* w) {
  w->has_A = 0;
  w->A = 0.0;
  w->e = w->ie = w->e2 = 0.0;
  w->velocity = w->velocity0;
  w->x_onset = 0.0;
  w->nloads = 0;
}

double ps_law_update(psLaw* w, double t, double x, double load, double target, double* row) {
  double a = w->smooth;
  if (w->nloads == w->window) {
    memmove(w->loads, w->loads + 1, sizeof(double) * (size_t)(w->window - 1));
    w->nloads--;
  }
  w->loads[w->nloads++] = load;
  double L = w->window > 1 ? median(w->loads, w->nloads, w->sorted) : load;
  if (!w->has_A && L == 0.0) w->x_onset = x;
  x = x - w->x_onset;
  law_ratio(w, x, L);
  double de = 0.0;
  int clamped = 0;
  if (w->has_A) {
    double err = (target - L) / w->A;
    w->e = (1.0 - a) * err + a * w->e;
    double ie = err + w->ie;
    w->e2 = (1.0 - a) * w->e + a * w->e2;
    de = (1.0 - a) / a * (w->e - w->e2);
    double v = w->kp * w->e + w->ki * ie + 0.25 * w->ki * de;
    clamped = fabs(v) > w->max_velocity;
    if (clamped)
      v = copysign(w->max_velocity, v);
    else
      w->ie = ie;
    w->velocity = v;
  }
  double out[PS_LAW_FIELDS] = {t,   target, load, L,          x,      w->has_A ? w->A : NAN,
                               w->e, w->ie, de,   w->velocity, clamped};
  memcpy(row, out, sizeof(out));
  return w->velocity;
}

/* The largest magnitude of v[idx[k]] (idx NULL: v[k]) over k < n. */
static double maxabs(const double* v, const int* idx, int n) {
  double m = 0.0;
  for (int k = 0; k < n; k++) m = fmax(m, fabs(v[idx ? idx[k] : k]));
  return m;
}

/* The iteration matrix at cj into J: full (row-major ny x ny), or the values of the kernel's
 * CSC pattern (a sparse restart). */
static int jacobian(const psModel* m, psData* d, const psRestart* r, double t, const double* y,
                    const double* yp, double cj, double* J) {
  if (r->sparse) return ps_jacobian_csc(m, d, t, y, yp, cj, r->jmap, r->ntrip, J, r->jnnz);
  return ps_jacobian(m, d, t, y, yp, cj, J);
}

/* The least-norm x (written into the velocities of dx, which is zeroed first) with
 * J[rows, u] x = rhs, rows the reactions ks[0..nr-1]: x = C^T (C C^T)^-1 rhs, C = J[rows, u]
 * (J row-major ny x ny). With weights wt (one per state, read at the velocities; NULL: all 1)
 * the least in the norm sum x^2 / wt: x = W C^T (C W C^T)^-1 rhs, W = diag(wt). */
static int least_change_dense(const psRestart* r, int ny, const double* J, const int* ks,
                              int nr, const double* rhs, const double* wt, double* dx) {
  const int* cols = r->uidx;
  int nc = r->nu;
  double* CC = r->cc;
  double* z = r->z;
  for (int i = 0; i < nr; i++) {
    long ri = (long)r->lam[ks[i]] * ny;
    for (int j = 0; j < nr; j++) {
      long rj = (long)r->lam[ks[j]] * ny;
      double s = 0.0;
      for (int k = 0; k < nc; k++)
        s += J[ri + cols[k]] * (wt ? wt[cols[k]] : 1.0) * J[rj + cols[k]];
      CC[(long)i * nr + j] = s;
    }
    z[i] = rhs[i];
  }
  if (psu_dense_solve(nr, CC, z, NULL) != PS_OK) return PS_ERR_SINGULAR;
  memset(dx, 0, sizeof(double) * (size_t)ny);
  for (int k = 0; k < nc; k++) {
    double s = 0.0;
    for (int i = 0; i < nr; i++) s += J[(long)r->lam[ks[i]] * ny + cols[k]] * z[i];
    s *= wt ? wt[cols[k]] : 1.0;
    if (!isfinite(s)) return PS_ERR_SINGULAR;
    dx[cols[k]] = s;
  }
  return PS_OK;
}

/* least_change_dense on the pattern's values J: the reactions' rows from lrow_*. */
static int least_change_sparse(const psRestart* r, int ny, const double* J, const int* ks,
                               int nr, const double* rhs, const double* wt, double* dx) {
  double* CC = r->cc;
  double* z = r->z;
  double* w = r->w;
  for (int i = 0; i < nr; i++) {
    int a = r->lrow_ptr[ks[i]], b = r->lrow_ptr[ks[i] + 1];
    for (int p = a; p < b; p++) {
      int c = r->lrow_col[p];
      if (r->is_u[c]) w[c] = J[r->lrow_at[p]] * (wt ? wt[c] : 1.0);
    }
    for (int j = 0; j < nr; j++) {
      double s = 0.0;
      for (int p = r->lrow_ptr[ks[j]]; p < r->lrow_ptr[ks[j] + 1]; p++)
        s += J[r->lrow_at[p]] * w[r->lrow_col[p]];
      CC[(long)i * nr + j] = s;
    }
    for (int p = a; p < b; p++) w[r->lrow_col[p]] = 0.0;
    z[i] = rhs[i];
  }
  if (psu_dense_solve(nr, CC, z, NULL) != PS_OK) return PS_ERR_SINGULAR;
  memset(dx, 0, sizeof(double) * (size_t)ny);
  for (int i = 0; i < nr; i++)
    for (int p = r->lrow_ptr[ks[i]]; p < r->lrow_ptr[ks[i] + 1]; p++)
      if (r->is_u[r->lrow_col[p]]) dx[r->lrow_col[p]] += J[r->lrow_at[p]] * z[i];
  for (int k = 0; k < r->nu; k++) {
    int c = r->uidx[k];
    if (wt) dx[c] *= wt[c];
    if (!isfinite(dx[c])) return PS_ERR_SINGULAR;
  }
  return PS_OK;
}

static int least_change(const psRestart* r, int ny, const double* J, const int* ks, int nr,
                        const double* rhs, const double* wt, double* dx) {
  return r->sparse ? least_change_sparse(r, ny, J, ks, nr, rhs, wt, dx)
                   : least_change_dense(r, ny, J, ks, nr, rhs, wt, dx);
}

/* out[i] = J[lam[ks[i]], u] v[u] over the velocities u (J as least_change takes it). */
static void rows_times(const psRestart* r, int ny, const double* J, const int* ks, int nr,
                       const double* v, double* out) {
  for (int i = 0; i < nr; i++) {
    double s = 0.0;
    if (r->sparse) {
      for (int p = r->lrow_ptr[ks[i]]; p < r->lrow_ptr[ks[i] + 1]; p++)
        if (r->is_u[r->lrow_col[p]]) s += J[r->lrow_at[p]] * v[r->lrow_col[p]];
    } else {
      long ri = (long)r->lam[ks[i]] * ny;
      for (int k = 0; k < r->nu; k++) s += J[ri + r->uidx[k]] * v[r->uidx[k]];
    }
    out[i] = s;
  }
}

/* q += N(q) du: translate by du's velocities, rotate by its body angular velocities (Euler
 * parameters renormalised), as consistent._move. */
static void move(const psModel* m, double* y, const double* du) {
  static const int gi[4][3] = {{1, 2, 3}, {0, 3, 2}, {3, 0, 1}, {2, 1, 0}};
  static const double gs[4][3] = {{-1, -1, -1}, {1, -1, 1}, {1, 1, -1}, {-1, 1, 1}};
  for (int b = 0; b < m->nbody; b++) {
    int qa = m->body_qadr[b], ua = m->body_uadr[b];
    for (int i = 0; i < 3; i++) y[qa + i] += du[ua + i];
    if (m->body_type[b] != PS_BODY_RIGID) continue;
    double e[4], w[3] = {du[ua + 3], du[ua + 4], du[ua + 5]}, norm = 0.0;
    for (int a = 0; a < 4; a++) {
      double s = 0.0;
      for (int k = 0; k < 3; k++) s += gs[a][k] * y[qa + 3 + gi[a][k]] * w[k];
      e[a] = y[qa + 3 + a] + 0.5 * s;
      norm += e[a] * e[a];
    }
    norm = sqrt(norm);
    for (int a = 0; a < 4; a++) y[qa + 3 + a] = e[a] / norm;
  }
}

/* Each tracked angle onto its measured angle (its row is the wrapped error). */
static int track_turns(const psModel* m, psData* d, const psRestart* r, double t, double* y,
                       const double* yp) {
  if (!r->nturn) return PS_OK;
  int rc = ps_residual(m, d, t, y, yp, r->res);
  if (rc != PS_OK) return rc;
  for (int k = 0; k < r->nturn; k++) y[r->turns[k]] += r->res[r->turns[k]];
  return PS_OK;
}

/* Each body velocity's inverse weight in the assembly's mass metric (icmetric.weights): 1 /
 * its body's mass, or for an angular velocity 1 / its inertia about that axis (1 where not
 * positive); zero at the other states. */
static void metric_weights(const psModel* m, double* wt) {
  memset(wt, 0, sizeof(double) * (size_t)m->ny);
  for (int b = 0; b < m->nbody; b++) {
    int ua = m->body_uadr[b], type = m->body_type[b];
    const double* in = m->body_inertia + 9 * b;
    double w[6] = {m->body_mass[b], m->body_mass[b], m->body_mass[b], in[0], in[4], in[8]};
    int n = type == PS_BODY_RIGID ? 6 : 3;
    if (type == PS_BODY_PLANAR) w[2] = in[8];
    for (int k = 0; k < n; k++) wt[ua + k] = w[k] > 0 ? 1.0 / w[k] : 1.0;
  }
}

/* The change from y0 to y whose least size the assembly seeks (icmetric.change): each body's
 * translation (a planar body's x, y, rz), and for a rigid body's turn phi (the logarithm of
 * conj(e0) e, body axes) W J_r(phi)^-T W^-1 phi, W its weights. */
static void metric_change(const psModel* m, const double* y0, const double* y, const double* wt,
                          double* out) {
  memset(out, 0, sizeof(double) * (size_t)m->ny);
  for (int b = 0; b < m->nbody; b++) {
    int qa = m->body_qadr[b], ua = m->body_uadr[b];
    for (int k = 0; k < 3; k++) out[ua + k] = y[qa + k] - y0[qa + k];
    if (m->body_type[b] != PS_BODY_RIGID) continue;
    const double* e = y0 + qa + 3;
    const double* f = y + qa + 3;
    double s = e[0] * f[0] + e[1] * f[1] + e[2] * f[2] + e[3] * f[3];
    double v[3] = {e[0] * f[1] - f[0] * e[1] - (e[2] * f[3] - e[3] * f[2]),
                   e[0] * f[2] - f[0] * e[2] - (e[3] * f[1] - e[1] * f[3]),
                   e[0] * f[3] - f[0] * e[3] - (e[1] * f[2] - e[2] * f[1])};
    if (s < 0.0) {
      s = -s;
      for (int k = 0; k < 3; k++) v[k] = -v[k];
    }
    double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]), phi[3] = {0.0, 0.0, 0.0};
    if (n > 0.0)
      for (int k = 0; k < 3; k++) phi[k] = v[k] * (2.0 * atan2(n, s) / n);
    /* J_r(phi)^-T x = x - phi x x / 2 + c phi x (phi x x), x = W^-1 phi */
    double t2 = phi[0] * phi[0] + phi[1] * phi[1] + phi[2] * phi[2], th = sqrt(t2);
    double c = th < 0.01 ? 1.0 / 12.0 + t2 / 720.0 + t2 * t2 / 30240.0
                         : 1.0 / t2 - cos(0.5 * th) / (2.0 * th * sin(0.5 * th));
    double x[3], px[3], ppx[3];
    for (int k = 0; k < 3; k++) x[k] = phi[k] / wt[ua + 3 + k];
    for (int k = 0; k < 3; k++) px[k] = phi[(k + 1) % 3] * x[(k + 2) % 3] -
                                        phi[(k + 2) % 3] * x[(k + 1) % 3];
    for (int k = 0; k < 3; k++) ppx[k] = phi[(k + 1) % 3] * px[(k + 2) % 3] -
                                         phi[(k + 2) % 3] * px[(k + 1) % 3];
    for (int k = 0; k < 3; k++)
      out[ua + 3 + k] = wt[ua + 3 + k] * (x[k] - 0.5 * px[k] + c * ppx[k]);
  }
}

/* a . b in the metric (sum a b / wt) over the velocities. */
static double metric_dot(const psRestart* r, const double* a, const double* b, const double* wt) {
  double s = 0.0;
  for (int k = 0; k < r->nu; k++) s += a[r->uidx[k]] * b[r->uidx[k]] / wt[r->uidx[k]];
  return s;
}

/* Step 1: positions (consistent._assemble away from the initial state): Newton steps, each
 * the least change that zeroes the constraints' linearization plus a pull along them toward
 * the least change from the start in the mass metric (icmetric.py), until on the constraints
 * with a step below 1e-12 of the change (or rounding) or a change below 1e-8 of the state; the
 * last PS_PLAIN_ITERS without the pull. */
static int assemble(const psModel* m, psData* d, const psRestart* r, double t, double* y,
                    const double* yp) {
  int ny = m->ny, nd = r->ndisp, settled = 1, have = 0;
  double alpha = 1.0;
  if (!nd) return PS_OK;
  double* pull = r->pull;
  double* before = r->pull + ny;
  metric_weights(m, r->wt);
  memcpy(r->y0, y, sizeof(double) * (size_t)ny);
  for (int it = 0; it <= PS_ASSEMBLY_ITERS; it++) {
    int rc = ps_residual(m, d, t, y, yp, r->res);
    if (rc != PS_OK) return rc;
    for (int k = 0; k < nd; k++) r->g[k] = r->res[r->mu[r->disp[k]]];
    double gmax = maxabs(r->g, NULL, nd), tol = 1.0 + maxabs(y, NULL, ny);
    if (it < PS_ASSEMBLY_ITERS && gmax <= 1e-13 * tol && settled) return PS_OK;
    if (it == PS_ASSEMBLY_ITERS) return gmax <= 1e-9 * tol ? PS_OK : PS_ERR_ASSEMBLY;
    rc = jacobian(m, d, r, t, y, yp, 0.0, r->J0);
    if (rc != PS_OK) return rc;
    for (int k = 0; k < nd; k++) {
      r->rows[k] = r->disp[k];
      r->z2[k] = -r->g[k];
    }
    metric_change(m, r->y0, y, r->wt, r->chg);
    int pulls = it < PS_ASSEMBLY_ITERS - PS_PLAIN_ITERS && maxabs(r->chg, r->uidx, r->nu) > 0;
    if (pulls) {
      /* the change's part along the constraints, taken back by alpha (1: its Gauss-Newton
       * length; then the secant length of the last two pulls) */
      rows_times(r, ny, r->J0, r->rows, nd, r->chg, r->z2);
      if (least_change(r, ny, r->J0, r->rows, nd, r->z2, r->wt, pull) != PS_OK)
        return PS_ERR_SINGULAR;
      for (int k = 0; k < r->nu; k++) pull[r->uidx[k]] -= r->chg[r->uidx[k]];
      if (have) {
        for (int k = 0; k < r->nu; k++)
          r->dx[r->uidx[k]] = before[r->uidx[k]] - pull[r->uidx[k]];
        double bend = metric_dot(r, before, r->dx, r->wt);
        alpha = bend > 0 ? fmin(fmax(alpha * metric_dot(r, before, before, r->wt) / bend,
                                     PS_PULL_MIN), PS_PULL_MAX)
                         : 1.0;
      }
      memcpy(before, pull, sizeof(double) * (size_t)ny);
      have = 1;
      for (int k = 0; k < nd; k++) r->z2[k] = -r->g[k];
    } else {
      memset(r->chg, 0, sizeof(double) * (size_t)ny);
    }
    if (least_change(r, ny, r->J0, r->rows, nd, r->z2, r->wt, r->dx) != PS_OK)
      return PS_ERR_SINGULAR;
    double whole = 0.0;
    for (int k = 0; k < r->nu; k++) {
      int c = r->uidx[k];
      if (pulls) r->dx[c] += alpha * pull[c];
      whole = fmax(whole, fabs(r->chg[c] + r->dx[c]));
    }
    settled = whole <= 1e-8 * tol ||
              sqrt(metric_dot(r, r->dx, r->dx, r->wt)) <=
                  1e-12 * sqrt(metric_dot(r, r->chg, r->chg, r->wt)) ||
              maxabs(r->dx, r->uidx, r->nu) <= 1e-13 * tol;
    move(m, y, r->dx);
  }
  return PS_OK;
}

/* Step 2: the rate rows (acceleration motions take w = g', the others change u). */
static int rates(const psModel* m, psData* d, const psRestart* r, double t, double* y,
                 const double* yp) {
  int ny = m->ny, nl = r->nlam, nh = 0;
  int rc = ps_residual(m, d, t, y, yp, r->res);
  if (rc != PS_OK) return rc;
  for (int k = 0; k < nl; k++) {
    r->g[k] = r->res[r->lam[k]];
    if (r->rate[k] >= 0) {
      y[r->rate[k]] += r->g[k];
      r->g[k] = 0.0;
    } else {
      r->rows[nh++] = k;
    }
  }
  for (int it = 0; it < (nh ? PS_RESTART_ITERS : 0); it++) {
    rc = jacobian(m, d, r, t, y, yp, 0.0, r->J0);
    if (rc != PS_OK) return rc;
    for (int k = 0, h = 0; k < nl; k++)
      if (r->rate[k] < 0) r->z2[h++] = -r->g[k];
    if (least_change(r, ny, r->J0, r->rows, nh, r->z2, NULL, r->dx) != PS_OK)
      return PS_ERR_SINGULAR;
    for (int k = 0; k < r->nu; k++) y[r->uidx[k]] += r->dx[r->uidx[k]];
    rc = ps_residual(m, d, t, y, yp, r->res);
    if (rc != PS_OK) return rc;
    double held = 0.0;
    for (int k = 0; k < nl; k++) {
      r->g[k] = r->res[r->lam[k]];
      if (r->rate[k] < 0) held = fmax(held, fabs(r->g[k]));
    }
    if (held <= 1e-14 * (1.0 + maxabs(y, r->uidx, r->nu))) break;
  }
  return PS_OK;
}

/* The dense saddle-point system of accelerations: S and its right-hand side z. */
static void saddle_dense(const psRestart* r, int ny, double h, const double* yp, double* S,
                         double* z) {
  int nr = r->nrow, nl = r->nlam, n = nr + nl;
  for (int i = 0; i < nr; i++) {
    int ri = r->row[i];
    for (int j = 0; j < nr; j++) {
      long e = (long)ri * ny + r->row[j];
      S[(long)i * n + j] = r->J1[e] - r->J0[e];
    }
    for (int j = 0; j < nl; j++) S[(long)i * n + nr + j] = r->J0[(long)ri * ny + r->lam[j]];
    z[i] = -r->res[ri];
  }
  for (int i = 0; i < nl; i++) {
    int li = r->lam[i];
    for (int j = 0; j < nr; j++) S[(long)(nr + i) * n + j] = r->J0[(long)li * ny + r->row[j]];
    for (int j = 0; j < nl; j++) S[(long)(nr + i) * n + nr + j] = 0.0;
    double jyp = 0.0;
    for (int j = 0; j < ny; j++) jyp += r->J0[(long)li * ny + j] * yp[j];
    double rt = (r->g[i] - r->res2[li]) / (2 * h);
    z[nr + i] = -(jyp + rt);
  }
}

/* The saddle-point system on the pattern (its values gathered from J0 and J1) and its
 * right-hand side, factored and solved: the solution in z. */
static int saddle_sparse(const psRestart* r, double h, const double* yp, double* z) {
  int nr = r->nrow, nl = r->nlam;
  for (int k = 0; k < r->snnz; k++)
    r->sval[k] =
        (r->s_one[k] >= 0 ? r->J1[r->s_one[k]] : 0.0) + r->s_sign[k] * r->J0[r->s_zero[k]];
  for (int i = 0; i < nr; i++) z[i] = -r->res[r->row[i]];
  for (int i = 0; i < nl; i++) {
    double jyp = 0.0;
    for (int p = r->lrow_ptr[i]; p < r->lrow_ptr[i + 1]; p++)
      jyp += r->J0[r->lrow_at[p]] * yp[r->lrow_col[p]];
    double rt = (r->g[i] - r->res2[r->lam[i]]) / (2 * h);
    z[nr + i] = -(jyp + rt);
  }
  /* a full factorization each time, forgetting which entries were nonzero before: the
   * answer does not depend on the runs before */
  ps_lu_forget(r->slu);
  if (ps_lu_factor(r->slu, r->sval) != 0) return PS_ERR_SINGULAR;
  ps_lu_solve(r->slu, z);
  return PS_OK;
}

/* A residual at t + h or t - h for the rate rows' time derivative: only the reactions' rows
 * are read, so a value that is not finite elsewhere (a force that blows up right there) is no
 * failure, as in consistent(); its diagnosis is dropped. */
static int rate_residual(const psModel* m, psData* d, const psRestart* r, double t,
                         const double* y, const double* yp, double* res) {
  int rc = ps_residual(m, d, t, y, yp, res);
  if (rc != PS_ERR_NONFINITE || d->user_error) return rc;
  for (int k = 0; k < r->nlam; k++)
    if (!isfinite(res[r->lam[k]])) return rc;
  d->bad_kind = 0;
  return PS_OK;
}

/* One Newton step of step 3 (accelerations and reactions from the residual rows and the time
 * derivative of the rate rows, a saddle-point system) at (t, y, yp), in place; *done: the
 * step was below PS_RESTART_ACC_TOL of the values' size. r->res keeps the residual it started
 * from. */
static int acc_step(const psModel* m, psData* d, const psRestart* r, double t, double* y,
                    double* yp, int timed, int* done) {
  int ny = m->ny, nr = r->nrow, nl = r->nlam, n = nr + nl;
  double* S = r->saddle;
  double* z = r->rhs;
  int rc = jacobian(m, d, r, t, y, yp, 0.0, r->J0);
  if (rc == PS_OK) rc = jacobian(m, d, r, t, y, yp, 1.0, r->J1);
  if (rc == PS_OK) rc = ps_residual(m, d, t, y, yp, r->res);
  /* the rate rows' time derivative from after t (the run goes on from t: a motion's rate
   * may kink there, a spline's data start), second order: (4 R(t+h) - 3 R(t) - R(t+2h)) /
   * 2h, in the order consistent() takes it, so that both give the same bits */
  double h = 1e-6 * fmax(1.0, fabs(t));
  if (rc == PS_OK && timed) rc = rate_residual(m, d, r, t + h, y, yp, r->res2);
  for (int k = 0; k < nl && rc == PS_OK; k++)
    r->g[k] = timed ? 4 * r->res2[r->lam[k]] - 3 * r->res[r->lam[k]] : 0.0;
  if (rc == PS_OK && timed) rc = rate_residual(m, d, r, t + 2 * h, y, yp, r->res2);
  if (rc != PS_OK) return rc;
  /* rate rows that do not read time: their time derivative is zero */
  for (int k = 0; k < nl && !timed; k++) r->res2[r->lam[k]] = 0.0;
  if (r->sparse) {
    if (saddle_sparse(r, h, yp, z) != PS_OK) return PS_ERR_SINGULAR;
  } else {
    saddle_dense(r, ny, h, yp, S, z);
    if (psu_dense_solve(n, S, z, NULL) != PS_OK) return PS_ERR_SINGULAR;
  }
  for (int i = 0; i < nr; i++) yp[r->row[i]] += z[i];
  for (int i = 0; i < nl; i++) y[r->lam[i]] += z[nr + i];
  double step = maxabs(z, NULL, n);
  if (!isfinite(step)) return PS_ERR_SINGULAR;
  double size = fmax(maxabs(yp, NULL, ny), maxabs(y, r->lam, nl));
  *done = step <= PS_RESTART_ACC_TOL * (1.0 + size);
  return PS_OK;
}

/* Step 3: accelerations and reactions, Newton steps until one is below the tolerance. */
static int accelerations(const psModel* m, psData* d, const psRestart* r, double t, double* y,
                         double* yp) {
  int done = 0;
  for (int it = 0; it < PS_RESTART_ACC_ITERS && !done; it++) {
    int rc = acc_step(m, d, r, t, y, yp, 1, &done);
    if (rc != PS_OK) return rc;
  }
  return PS_OK;
}

/* The largest |residual| over the force rows (r->row) of res. */
static double force_rows_max(const psRestart* r, const double* res) {
  double e = 0.0;
  for (int i = 0; i < r->nrow; i++) e = fmax(e, fabs(res[r->row[i]]));
  return e;
}

int ps_row_exact(const psModel* m, psData* d, const psRestart* r, double t, double* y,
                 double* yp) {
  int ny = m->ny;
  /* its residuals at t + h are not step attempts, nor bound by max_num_steps; an error a
   * user routine or a value reports here (past the run's end, say) is the row's, not the
   * run's: the flags and the message are put back with the row */
  long ntimes = d->ntimes, nfail = d->nfail, limit = d->step_limit;
  double last = d->last_t, user_t = d->user_t;
  int user_error = d->user_error, bad_kind = d->bad_kind;
  char msg[sizeof(d->msg)];
  memcpy(msg, d->msg, sizeof(msg));
  d->step_limit = 0;
  memcpy(r->ybak, y, sizeof(double) * (size_t)ny);
  memcpy(r->ypbak, yp, sizeof(double) * (size_t)ny);
  /* the position multipliers are zero on the exact solution (on BDF's they move the
   * positions' rates, and the accelerations with them), and so are the reactions' rates
   * (through the rate rows' compliance, g' + c lam, IDA's lam' would enter the
   * accelerations: it is out of the error test, noise) */
  for (int k = 0; k < r->nlam; k++) {
    if (r->mu[k] >= 0) y[r->mu[k]] = 0.0;
    yp[r->lam[k]] = 0.0;
    if (r->mu[k] >= 0) yp[r->mu[k]] = 0.0;
  }
  int rc = PS_OK, done = 0;
  for (int it = 0; it < PS_RESTART_ACC_ITERS && !done && rc == PS_OK; it++) {
    rc = acc_step(m, d, r, t, y, yp, r->row_timed, &done);
    if (rc != PS_OK || done || r->row_linear) break;
    /* rows linear in yp and the reactions (no force reads an acceleration) are solved by
     * the one step: the force rows' residual falls to rounding of where it started */
    double before = force_rows_max(r, r->res);
    rc = ps_residual(m, d, t, y, yp, r->res2);
    done = rc == PS_OK && force_rows_max(r, r->res2) <= 1e-12 * before;
  }
  /* near a singular configuration the saddle-point system is ill-conditioned and its
   * solution is rounding divided by a vanishing singular value (IFToMM A02 3e-8 m from its
   * crossing: pin forces of 2.7e7 N for 25, 1e6 x): reactions a thousand times IDA's
   * largest are that (a row on a knot where an acceleration jumps may take 20 x IDA's, which
   * is its left limit), and the row keeps IDA's, which the rate rows' compliance holds */
  if (rc == PS_OK && maxabs(y, r->lam, r->nlam) > 1e3 * maxabs(r->ybak, r->lam, r->nlam))
    rc = PS_ERR_SINGULAR;
  if (rc != PS_OK) {
    memcpy(y, r->ybak, sizeof(double) * (size_t)ny);
    memcpy(yp, r->ypbak, sizeof(double) * (size_t)ny);
    d->user_error = user_error;
    d->user_t = user_t;
    d->bad_kind = bad_kind;
    memcpy(d->msg, msg, sizeof(msg));
  }
  d->ntimes = ntimes;
  d->nfail = nfail;
  d->last_t = last;
  d->step_limit = limit;
  return rc;
}

/* The restart proper (ps_restart_consistent). */
static int restart_state(const psModel* m, psData* d, const psRestart* r, double t, double* y,
                         double* yp) {
  for (int k = 0; k < r->nlam; k++) {
    y[r->lam[k]] = 0.0;
    if (r->mu[k] >= 0) y[r->mu[k]] = 0.0;
  }
  memset(yp, 0, sizeof(double) * (size_t)m->ny);
  int rc = track_turns(m, d, r, t, y, yp);
  if (rc == PS_OK) rc = assemble(m, d, r, t, y, yp);
  if (rc == PS_OK) rc = track_turns(m, d, r, t, y, yp);
  if (rc == PS_OK) rc = rates(m, d, r, t, y, yp);
  if (rc == PS_OK) rc = accelerations(m, d, r, t, y, yp);
  return rc;
}

int ps_restart_consistent(const psModel* m, psData* d, const psRestart* r, double t, double* y,
                          double* yp) {
  /* its residuals at t +- h are not step attempts, nor bound by max_num_steps */
  long ntimes = d->ntimes, nfail = d->nfail, limit = d->step_limit;
  double last = d->last_t;
  d->step_limit = 0;
  int rc = restart_state(m, d, r, t, y, yp);
  d->ntimes = ntimes;
  d->nfail = nfail;
  d->last_t = last;
  d->step_limit = limit;
  return rc;
}

int ps_motion_reactions(const psModel* m, psData* d, const psRestart* r, double t,
                        const double* y, const double* yp, double* lam) {
  int ny = m->ny, nr = r->nrow, nl = r->nlam;
  double* yy = r->dx;
  memcpy(yy, y, sizeof(double) * (size_t)ny);
  for (int k = 0; k < nl; k++) {
    yy[r->lam[k]] = 0.0;
    if (r->mu[k] >= 0) yy[r->mu[k]] = 0.0;
  }
  int rc = ps_residual(m, d, t, yy, yp, r->res);
  if (rc == PS_OK) rc = jacobian(m, d, r, t, yy, yp, 0.0, r->J0);
  if (rc != PS_OK) return rc;
  /* least squares C x = -r over the force rows by Householder QR (C: nr x nl, nr >= nl) */
  double* C = r->sparse ? r->qr : r->saddle;
  double* b = r->rhs;
  if (r->sparse) {
    /* the reactions' columns of the pattern, on the force rows */
    memset(C, 0, sizeof(double) * (size_t)nr * (size_t)nl);
    for (int j = 0; j < nl; j++)
      for (int p = r->jcolptr[r->lam[j]]; p < r->jcolptr[r->lam[j] + 1]; p++)
        if (r->rowpos[r->jrowind[p]] >= 0) C[(long)r->rowpos[r->jrowind[p]] * nl + j] = r->J0[p];
  } else {
    for (int i = 0; i < nr; i++)
      for (int j = 0; j < nl; j++) C[(long)i * nl + j] = r->J0[(long)r->row[i] * ny + r->lam[j]];
  }
  for (int i = 0; i < nr; i++) b[i] = -r->res[r->row[i]];
  for (int k = 0; k < nl; k++) {
    double norm = 0.0;
    for (int i = k; i < nr; i++) norm += C[(long)i * nl + k] * C[(long)i * nl + k];
    norm = sqrt(norm);
    if (!(norm > 0.0) || !isfinite(norm)) return PS_ERR_SINGULAR;
    double alpha = C[(long)k * nl + k] > 0 ? -norm : norm;
    C[(long)k * nl + k] -= alpha;
    double vv = 0.0;
    for (int i = k; i < nr; i++) vv += C[(long)i * nl + k] * C[(long)i * nl + k];
    for (int j = k + 1; j <= nl; j++) {
      double s = 0.0;
      for (int i = k; i < nr; i++) s += C[(long)i * nl + k] * (j < nl ? C[(long)i * nl + j] : b[i]);
      double f = 2.0 * s / vv;
      for (int i = k; i < nr; i++) {
        if (j < nl)
          C[(long)i * nl + j] -= f * C[(long)i * nl + k];
        else
          b[i] -= f * C[(long)i * nl + k];
      }
    }
    r->g[k] = alpha; /* R's diagonal */
  }
  for (int k = nl - 1; k >= 0; k--) {
    double s = b[k];
    for (int j = k + 1; j < nl; j++) s -= C[(long)k * nl + j] * lam[j];
    lam[k] = s / r->g[k];
  }
  return PS_OK;
}

int ps_control_start(const psModel* m, psData* d, const psRestart* r, psControl* c, double t,
                     double* y, double* yp) {
  c->t0 = t;
  c->x0 = y[c->q];
  c->n = 1;
  c->nlog = 0;
  ps_law_reset(&c->law);
  d->senval[c->value] = c->law.velocity;
  return ps_restart_consistent(m, d, r, t, y, yp);
}

double ps_control_next(const psControl* c) { return c->t0 + (double)c->n * c->dt; }

int ps_control_update(const psModel* m, psData* d, const psRestart* r, psControl* c, double t,
                      double* y, double* yp) {
  double load;
  int rc;
  if (c->contact) {
    rc = ps_penalty_loads(m, d, t, y, yp, r->res2);
    load = r->res2[c->u];
  } else {
    rc = ps_motion_reactions(m, d, r, t, y, yp, r->lamv);
    load = -r->lamv[c->lam];
  }
  if (rc != PS_OK && d->user_error) return rc;
  if (rc != PS_OK) load = NAN; /* not finite, or the reactions not determined */
  double target = ps_eval_tape(m, d, c->tape, c->slot, t, y, yp);
  c->bad[0] = load;
  c->bad[1] = target;
  if (!isfinite(load)) return PS_CTRL_LOAD;
  if (!isfinite(target)) return PS_CTRL_TARGET;
  if (c->nlog >= c->cap) return PS_CTRL_LOG;
  double v = ps_law_update(&c->law, t, y[c->q] - c->x0, load, target,
                           c->log + c->nlog * PS_LAW_FIELDS);
  c->nlog++;
  c->bad[2] = v;
  if (!isfinite(v)) return PS_CTRL_VELOCITY;
  d->senval[c->value] = v;
  rc = ps_restart_consistent(m, d, r, t, y, yp);
  c->n++;
  return rc;
}
