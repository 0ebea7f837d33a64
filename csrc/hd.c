/* Hyper-dual arithmetic: exact first and second derivatives by forward-mode differentiation.
 *
 * Layout of one number: v[0] value, v[1 + i] dv/dx_i, v[1 + n + P(i, j)] d2v/dx_i dx_j for
 * i <= j < nh with P the packed upper-triangle index. Each function writes the Hessian first,
 * then the gradient, then the value, entry by entry, so an output may alias an input.
 */
#include "internal.h"

int psu_hd_size(int n, int nh, int order) {
  if (order <= 0) return 1;
  if (order == 1) return 1 + n;
  return 1 + n + nh * (nh + 1) / 2;
}

void psu_hd_const(const psuHD* c, double* out, double v) {
  int sz = psu_hd_size(c->n, c->nh, c->order);
  out[0] = v;
  for (int i = 1; i < sz; i++) out[i] = 0.0;
}

void psu_hd_var(const psuHD* c, double* out, double v, int pos) {
  psu_hd_const(c, out, v);
  if (c->order >= 1 && pos >= 0) out[1 + pos] = 1.0;
}

void psu_hd_copy(const psuHD* c, double* out, const double* a) {
  int sz = psu_hd_size(c->n, c->nh, c->order);
  if (out == a) return;
  for (int i = 0; i < sz; i++) out[i] = a[i];
}

void psu_hd_zero_hessian(const psuHD* c, double* out) {
  if (c->order < 2) return;
  int sz = psu_hd_size(c->n, c->nh, 2);
  for (int i = 1 + c->n; i < sz; i++) out[i] = 0.0;
}

/* out = ca*a + cb*b + c0; b may be NULL. */
void psu_hd_lin(const psuHD* c, double* out, double ca, const double* a, double cb,
                const double* b, double c0) {
  int sz = psu_hd_size(c->n, c->nh, c->order);
  if (b) {
    for (int i = sz - 1; i >= 1; i--) out[i] = ca * a[i] + cb * b[i];
    out[0] = ca * a[0] + cb * b[0] + c0;
  } else {
    for (int i = sz - 1; i >= 1; i--) out[i] = ca * a[i];
    out[0] = ca * a[0] + c0;
  }
}

/* out = f(a) given f(a), f'(a), f''(a). */
void psu_hd_unary(const psuHD* c, double* out, const double* a, double f0, double f1,
                  double f2) {
  int n = c->n, nh = c->nh;
  if (c->order >= 2) {
    const double* ga = a + 1;
    double* h = out + 1 + n;
    const double* ha = a + 1 + n;
    int p = 0;
    for (int i = 0; i < nh; i++)
      for (int j = i; j < nh; j++, p++) h[p] = f1 * ha[p] + f2 * ga[i] * ga[j];
  }
  if (c->order >= 1)
    for (int i = 1; i <= n; i++) out[i] = f1 * a[i];
  out[0] = f0;
}

/* out = f(a, b) given f and its first and second partial derivatives. */
void psu_hd_binary(const psuHD* c, double* out, const double* a, const double* b, double f0,
                   double fa, double fb, double faa, double fab, double fbb) {
  int n = c->n, nh = c->nh;
  if (c->order >= 2) {
    const double* ga = a + 1;
    const double* gb = b + 1;
    const double* ha = a + 1 + n;
    const double* hb = b + 1 + n;
    double* h = out + 1 + n;
    int p = 0;
    for (int i = 0; i < nh; i++)
      for (int j = i; j < nh; j++, p++)
        h[p] = fa * ha[p] + fb * hb[p] + faa * ga[i] * ga[j] +
               fab * (ga[i] * gb[j] + gb[i] * ga[j]) + fbb * gb[i] * gb[j];
  }
  if (c->order >= 1)
    for (int i = 1; i <= n; i++) out[i] = fa * a[i] + fb * b[i];
  out[0] = f0;
}

void psu_hd_mul(const psuHD* c, double* out, const double* a, const double* b) {
  psu_hd_binary(c, out, a, b, a[0] * b[0], b[0], a[0], 0.0, 1.0, 0.0);
}

void psu_hd_div(const psuHD* c, double* out, const double* a, const double* b) {
  double x = a[0], y = b[0];
  psu_hd_binary(c, out, a, b, x / y, 1.0 / y, -x / (y * y), 0.0, -1.0 / (y * y),
                2.0 * x / (y * y * y));
}

/* out = dg/dx_k as a number of order <= 1: value g_k, gradient row k of g's Hessian (zero
 * outside the first nh directions, where g has no second derivatives). g must have been
 * computed at order 2 when c->order >= 1. The output's Hessian is zero. */
void psu_hd_gradcomp(const psuHD* c, double* out, const double* g, int k) {
  int n = c->n, nh = c->nh;
  double gk = g[1 + k];
  if (c->order >= 1) {
    const double* h = g + 1 + n;
    for (int j = 0; j < n; j++) {
      if (k >= nh || j >= nh) {
        out[1 + j] = 0.0;
        continue;
      }
      int i0 = k < j ? k : j, j0 = k < j ? j : k;
      int p = i0 * nh - i0 * (i0 - 1) / 2 + (j0 - i0);
      out[1 + j] = h[p];
    }
  }
  psu_hd_zero_hessian(c, out);
  out[0] = gk;
}

/* out = a x b for 3-vectors of hyper-duals; scratch holds 2 numbers. */
void psu_hd_cross(const psuHD* c, double* out, const double* a, const double* b,
                  double* scratch) {
  int s = c->stride;
  double* t1 = scratch;
  double* t2 = scratch + s;
  /* out must not alias a or b: components are built one by one */
  for (int k = 0; k < 3; k++) {
    int i = (k + 1) % 3, j = (k + 2) % 3;
    psu_hd_mul(c, t1, a + i * s, b + j * s);
    psu_hd_mul(c, t2, a + j * s, b + i * s);
    psu_hd_lin(c, out + k * s, 1.0, t1, -1.0, t2, 0.0);
  }
}

/* out = a . b for 3-vectors; scratch holds 1 number. */
void psu_hd_dot(const psuHD* c, double* out, const double* a, const double* b,
                double* scratch) {
  int s = c->stride;
  psu_hd_mul(c, out, a, b);
  for (int k = 1; k < 3; k++) {
    psu_hd_mul(c, scratch, a + k * s, b + k * s);
    psu_hd_lin(c, out, 1.0, out, 1.0, scratch, 0.0);
  }
}

/* out = f(a_0, ..., a_{n-1}) given f, its first partials fi (n) and second partials fij
 * (n x n, symmetric, used at order 2). out must not alias an input. */
void psu_hd_nary(const psuHD* c, double* out, const double* const* a, int n, double f0,
                 const double* fi, const double* fij) {
  int nb = c->n, nh = c->nh;
  if (c->order >= 2) {
    double* h = out + 1 + nb;
    int p = 0;
    for (int r = 0; r < nh; r++)
      for (int s = r; s < nh; s++, p++) {
        double v = 0.0;
        for (int i = 0; i < n; i++) {
          v += fi[i] * a[i][1 + nb + p];
          for (int j = 0; j < n; j++) v += fij[i * n + j] * a[i][1 + r] * a[j][1 + s];
        }
        h[p] = v;
      }
  }
  if (c->order >= 1)
    for (int r = 1; r <= nb; r++) {
      double v = 0.0;
      for (int i = 0; i < n; i++) v += fi[i] * a[i][r];
      out[r] = v;
    }
  out[0] = f0;
}
