/* Expression tapes: a register machine over hyper-dual numbers.
 *
 * Instruction i of a tape writes register (slot) i; operands name earlier slots, so common
 * subexpressions are computed once. Time is basis entry nh - 1, after the positions.
 */
#include <math.h>
#include <stddef.h>

#include "internal.h"

/* Scratch numbers in d->tmp used by measures (all below 48, see kinematics.c). */
#define T_RI 0
#define T_RJ 3
#define T_REL 6
#define T_X 9
#define T_VI 18
#define T_VJ 21
#define T_VREL 24
#define T_WL 27
#define T_C1 30
#define T_C2 33
#define T_SC 36
#define T_XJ 38
#define T_G 30 /* GDOT: 4 numbers */

double* ps_slot(const psModel* m, psData* d, int slot) {
  return d->slots + (long)slot * m->hd_stride;
}

static void hd_atan2(const psuHD* c, double* out, const double* y, const double* x) {
  double a = y[0], b = x[0], r2 = a * a + b * b;
  if (r2 == 0.0) {
    psu_hd_binary(c, out, y, x, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    return;
  }
  psu_hd_binary(c, out, y, x, atan2(a, b), b / r2, -a / r2, -2.0 * a * b / (r2 * r2),
                (a * a - b * b) / (r2 * r2), 2.0 * a * b / (r2 * r2));
}

/* out = column col of the 3x3 axes X dotted with the 3-vector v. */
static void dot_col(const psuHD* c, double* out, const double* v, const double* X, int col,
                    double* sc) {
  int s = c->stride;
  psu_hd_mul(c, out, v, X + col * s);
  for (int r = 1; r < 3; r++) {
    psu_hd_mul(c, sc, v + r * s, X + (3 * r + col) * s);
    psu_hd_lin(c, out, 1.0, out, 1.0, sc, 0.0);
  }
}

/* out = column a of X dotted with column b of Y. */
static void dot_cols(const psuHD* c, double* out, const double* X, int a, const double* Y, int b,
                     double* sc) {
  int s = c->stride;
  psu_hd_mul(c, out, X + a * s, Y + b * s);
  for (int r = 1; r < 3; r++) {
    psu_hd_mul(c, sc, X + (3 * r + a) * s, Y + (3 * r + b) * s);
    psu_hd_lin(c, out, 1.0, out, 1.0, sc, 0.0);
  }
}

/* Project the global vector v on axis comp of marker k (k < 0: the global axis). */
static void project(const psModel* m, psData* d, const psuHD* c, double* out, const double* v,
                    int k, int ks, int comp) {
  if (k < 0) {
    psu_hd_copy(c, out, v + comp * c->stride);
    return;
  }
  double* X = ps_tmp(m, d, T_X);
  ps_marker_axes(m, d, c, k, ks, X);
  dot_col(c, out, v, X, comp, ps_tmp(m, d, T_SC));
}

static void vec_lin(const psuHD* c, double* out, double ca, const double* a, double cb,
                    const double* b) {
  for (int i = 0; i < 3; i++)
    psu_hd_lin(c, out + i * c->stride, ca, a + i * c->stride, cb, b + i * c->stride, 0.0);
}

static void norm3(const psuHD* c, double* out, const double* v, double* sc) {
  psu_hd_dot(c, out, v, v, sc);
  double r = sqrt(out[0]);
  if (r == 0.0)
    psu_hd_const(c, out, 0.0);
  else
    psu_hd_unary(c, out, out, r, 0.5 / r, -0.25 / (r * r * r));
}

/* Relative velocity of i with respect to j as seen from the frame of marker l. */
static void rel_velocity(const psModel* m, psData* d, const psuHD* c, const int* a, double* vrel,
                         const double* rel) {
  double* vi = ps_tmp(m, d, T_VI);
  double* vj = ps_tmp(m, d, T_VJ);
  ps_marker_vel(m, d, c, a[1], a[5], vi);
  ps_marker_vel(m, d, c, a[2], a[6], vj);
  vec_lin(c, vrel, 1.0, vi, -1.0, vj);
  if (a[4] >= 0) {
    double* wl = ps_tmp(m, d, T_WL);
    double* cr = ps_tmp(m, d, T_C1);
    ps_marker_omega(m, d, c, a[4], a[8], wl);
    psu_hd_cross(c, cr, wl, rel, ps_tmp(m, d, T_SC));
    vec_lin(c, vrel, 1.0, vrel, -1.0, cr);
  }
}

/* Relative acceleration of i with respect to j, second derivative in the frame of marker l. */
static void rel_acceleration(const psModel* m, psData* d, const psuHD* c, const int* a,
                             double* arel, const double* rel) {
  double* ai = ps_tmp(m, d, T_VI);
  double* aj = ps_tmp(m, d, T_VJ);
  ps_marker_acc(m, d, c, a[1], a[5], ai);
  ps_marker_acc(m, d, c, a[2], a[6], aj);
  vec_lin(c, arel, 1.0, ai, -1.0, aj);
  if (a[4] < 0) return;
  /* r'' (frame L) = a - alpha x r - 2 w x r'(L) - w x (w x r) */
  double* wl = ps_tmp(m, d, T_WL);
  double* c1 = ps_tmp(m, d, T_C1);
  double* c2 = ps_tmp(m, d, T_C2);
  double* sc = ps_tmp(m, d, T_SC);
  double* vrel = ps_tmp(m, d, T_VREL);
  rel_velocity(m, d, c, a, vrel, rel);
  ps_marker_omega(m, d, c, a[4], a[8], wl);
  psu_hd_cross(c, c1, wl, vrel, sc);
  vec_lin(c, arel, 1.0, arel, -2.0, c1);
  psu_hd_cross(c, c1, wl, rel, sc);
  psu_hd_cross(c, c2, wl, c1, sc);
  vec_lin(c, arel, 1.0, arel, -1.0, c2);
  ps_marker_alpha(m, d, c, a[4], a[8], c2);
  psu_hd_cross(c, c1, c2, rel, sc);
  vec_lin(c, arel, 1.0, arel, -1.0, c1);
}

static void measure(const psModel* m, psData* d, const psuHD* c, double* out, const int* a) {
  int kind = a[0];
  double* rel = ps_tmp(m, d, T_REL);
  double* sc = ps_tmp(m, d, T_SC);
  if (kind >= PS_M_AX) {
    double* Xi = ps_tmp(m, d, T_X);
    double* Xj = ps_tmp(m, d, T_XJ);
    double* p = ps_tmp(m, d, T_C1);
    double* q = ps_tmp(m, d, T_C2);
    ps_marker_axes(m, d, c, a[1], a[5], Xi);
    ps_marker_axes(m, d, c, a[2], a[6], Xj);
    if (kind == PS_M_AX) {
      dot_cols(c, p, Xi, 2, Xj, 1, sc);
      psu_hd_lin(c, p, -1.0, p, 0.0, NULL, 0.0);
      dot_cols(c, q, Xi, 2, Xj, 2, sc);
    } else if (kind == PS_M_AY) {
      dot_cols(c, p, Xi, 2, Xj, 0, sc);
      dot_cols(c, q, Xi, 2, Xj, 2, sc);
    } else {
      dot_cols(c, p, Xi, 0, Xj, 1, sc);
      dot_cols(c, q, Xi, 0, Xj, 0, sc);
    }
    hd_atan2(c, out, p, q);
    return;
  }
  if (kind >= PS_M_WDTX) {
    /* angular acceleration of i relative to j: alpha_i - alpha_j, the derivative taken in
     * the frame of marker l less w_l x (w_i - w_j) */
    double* ai = ps_tmp(m, d, T_VI);
    double* aj = ps_tmp(m, d, T_VJ);
    ps_marker_alpha(m, d, c, a[1], a[5], ai);
    ps_marker_alpha(m, d, c, a[2], a[6], aj);
    vec_lin(c, rel, 1.0, ai, -1.0, aj);
    if (a[4] >= 0) {
      double* c1 = ps_tmp(m, d, T_C1);
      double* c2 = ps_tmp(m, d, T_C2);
      double* wl = ps_tmp(m, d, T_WL);
      ps_marker_omega(m, d, c, a[1], a[5], c1);
      ps_marker_omega(m, d, c, a[2], a[6], c2);
      vec_lin(c, c1, 1.0, c1, -1.0, c2);
      ps_marker_omega(m, d, c, a[4], a[8], wl);
      psu_hd_cross(c, c2, wl, c1, sc);
      vec_lin(c, rel, 1.0, rel, -1.0, c2);
    }
    project(m, d, c, out, rel, a[3], a[7], kind - PS_M_WDTX);
    return;
  }
  if (kind >= PS_M_WX) {
    double* wi = ps_tmp(m, d, T_VI);
    double* wj = ps_tmp(m, d, T_VJ);
    ps_marker_omega(m, d, c, a[1], a[5], wi);
    ps_marker_omega(m, d, c, a[2], a[6], wj);
    vec_lin(c, rel, 1.0, wi, -1.0, wj);
    project(m, d, c, out, rel, a[3], a[7], kind - PS_M_WX);
    return;
  }
  {
    double* ri = ps_tmp(m, d, T_RI);
    double* rj = ps_tmp(m, d, T_RJ);
    ps_marker_pos(m, d, c, a[1], a[5], ri);
    ps_marker_pos(m, d, c, a[2], a[6], rj);
    vec_lin(c, rel, 1.0, ri, -1.0, rj);
  }
  switch (kind) {
    case PS_M_DX: case PS_M_DY: case PS_M_DZ:
      project(m, d, c, out, rel, a[3], a[7], kind - PS_M_DX);
      return;
    case PS_M_DM:
      norm3(c, out, rel, sc);
      return;
    case PS_M_VX: case PS_M_VY: case PS_M_VZ: case PS_M_VM: {
      double* vrel = ps_tmp(m, d, T_VREL);
      rel_velocity(m, d, c, a, vrel, rel);
      if (kind == PS_M_VM)
        norm3(c, out, vrel, sc);
      else
        project(m, d, c, out, vrel, a[3], a[7], kind - PS_M_VX);
      return;
    }
    case PS_M_VR: {
      double* vrel = ps_tmp(m, d, T_VREL);
      double* len = ps_tmp(m, d, T_C2);
      rel_velocity(m, d, c, a, vrel, rel);
      psu_hd_dot(c, out, vrel, rel, sc);
      norm3(c, len, rel, sc);
      if (len[0] == 0.0)
        psu_hd_const(c, out, 0.0);
      else
        psu_hd_div(c, out, out, len);
      return;
    }
    default: { /* accelerations */
      double* arel = ps_tmp(m, d, T_C2 + 3 * 4);
      rel_acceleration(m, d, c, a, arel, rel);
      project(m, d, c, out, arel, a[3], a[7], kind - PS_M_ACCX);
      return;
    }
  }
}

/* c_i = sum_a dg/dq_a dq_a'/du_i for u entry i of the body in tape slot `slot`; sc: 2 numbers. */
void ps_rate_coeff(const psModel* m, psData* d, const psuHD* c, const double* g, int tape,
                   int slot, int i, double* out, double* sc) {
  /* e' = 1/2 G(e) w_body with G(e) = [[-e1,-e2,-e3],[e0,-e3,e2],[e3,e0,-e1],[-e2,e1,e0]] */
  static const int gidx[4][3] = {{1, 2, 3}, {0, 3, 2}, {3, 0, 1}, {2, 1, 0}};
  static const double gsgn[4][3] = {{-1, -1, -1}, {1, -1, 1}, {1, 1, -1}, {-1, 1, 1}};
  int qp = m->tbody_q[m->tape_body_adr[tape] + slot];
  if (i < 3) {
    psu_hd_gradcomp(c, out, g, qp + i);
    return;
  }
  int k = i - 3;
  const double* e = ps_bc(m, d, slot, PS_BC_E);
  psu_hd_const(c, out, 0.0);
  for (int a = 0; a < 4; a++) {
    psu_hd_gradcomp(c, sc, g, qp + 3 + a);
    psu_hd_mul(c, sc, sc, e + gidx[a][k] * c->stride);
    psu_hd_lin(c, out, 1.0, out, 0.5 * gsgn[a][k], sc, 0.0);
  }
}

/* Total time derivative of a displacement expression g: g_t + sum_i c_i u_i. */
static void gdot(const psModel* m, psData* d, const psuHD* c, int tape, const double* g,
                 double* out) {
  /* the rate is one order lower than g: a tape with GDOT runs one order higher than needed */
  psuHD c1 = *c;
  c1.order = c->order > 0 ? c->order - 1 : 0;
  double* ci = ps_tmp(m, d, T_G);
  double* sc = ps_tmp(m, d, T_G + 1);
  psu_hd_const(c, out, 0.0);
  psu_hd_gradcomp(&c1, out, g, c->nh - 1);
  int adr = m->tape_body_adr[tape];
  for (int slot = 0; slot < m->tape_nbody[tape]; slot++) {
    if (m->tbody_q[adr + slot] < 0) continue;
    int type = m->body_type[m->tbody_body[adr + slot]];
    int nu = type == PS_BODY_RIGID ? 6 : 3;
    for (int i = 0; i < nu; i++) {
      /* u: the origin's velocity, then the body-frame angular velocity; a planar body's
       * third u is wz, the z component of its global angular velocity */
      int which = i >= 3 ? PS_BC_WB : type == PS_BODY_PLANAR && i == 2 ? PS_BC_W : PS_BC_V;
      const double* u = ps_bc(m, d, slot, which) + (i % 3) * c->stride;
      ps_rate_coeff(m, d, &c1, g, tape, slot, i, ci, sc);
      psu_hd_mul(&c1, ci, ci, u);
      psu_hd_lin(&c1, out, 1.0, out, 1.0, ci, 0.0);
    }
  }
}

static double sgn(double x) { return x >= 0.0 ? 1.0 : -1.0; }

/* STEP, STEP5 or HAVSIN of x between constant points (x0, h0) and (x1, h1) in one instruction:
 * h0 + (h1 - h0) S(D) with D = (x - x0) / (x1 - x0) clamped to [0, 1], as the elementary
 * operations would give it (flat, with zero derivatives, outside the open interval). */
static void step_const(const psuHD* c, double* out, const double* xv, const double* consts,
                       const int* a) {
  double x0 = consts[a[1]], h0 = consts[a[2]], x1 = consts[a[3]], h1 = consts[a[4]];
  double w = x1 - x0, dh = h1 - h0, D = (xv[0] - x0) / w;
  if (D <= 0.0 || D >= 1.0) {
    psu_hd_unary(c, out, xv, D <= 0.0 ? h0 : h1, 0.0, 0.0);
    return;
  }
  double s, s1, s2;
  switch (a[5]) {
    case 0: s = D * D * (3 - 2 * D); s1 = 6 * D * (1 - D); s2 = 6 * (1 - 2 * D); break;
    case 1:
      s = D * D * D * (10 - 15 * D + 6 * D * D);
      s1 = 30 * D * D * (1 - D) * (1 - D);
      s2 = 60 * D * (1 - D) * (1 - 2 * D);
      break;
    default:
      s = 0.5 * (1 - cos(M_PI * D));
      s1 = 0.5 * M_PI * sin(M_PI * D);
      s2 = 0.5 * M_PI * M_PI * cos(M_PI * D);
      break;
  }
  psu_hd_unary(c, out, xv, h0 + dh * s, dh * s1 / w, dh * s2 / (w * w));
}

/* Elementary functions of one argument: value and first two derivatives. */
static void unary(const psuHD* c, int op, double* out, const double* a) {
  double x = a[0], f = 0, f1 = 0, f2 = 0;
  switch (op) {
    case PS_OP_NEG: f = -x; f1 = -1; break;
    case PS_OP_ABS: f = fabs(x); f1 = sgn(x); break;
    case PS_OP_ACOS: { double r = 1 - x * x; f = acos(x); f1 = -1 / sqrt(r); f2 = -x / (r * sqrt(r)); break; }
    case PS_OP_ASIN: { double r = 1 - x * x; f = asin(x); f1 = 1 / sqrt(r); f2 = x / (r * sqrt(r)); break; }
    case PS_OP_ATAN: { double r = 1 + x * x; f = atan(x); f1 = 1 / r; f2 = -2 * x / (r * r); break; }
    case PS_OP_COS: f = cos(x); f1 = -sin(x); f2 = -f; break;
    case PS_OP_COSH: f = cosh(x); f1 = sinh(x); f2 = f; break;
    case PS_OP_SIN: f = sin(x); f1 = cos(x); f2 = -f; break;
    case PS_OP_SINH: f = sinh(x); f1 = cosh(x); f2 = f; break;
    case PS_OP_TAN: f = tan(x); f1 = 1 + f * f; f2 = 2 * f * f1; break;
    case PS_OP_TANH: f = tanh(x); f1 = 1 - f * f; f2 = -2 * f * f1; break;
    case PS_OP_EXP: f = f1 = f2 = exp(x); break;
    case PS_OP_LOG: f = log(x); f1 = 1 / x; f2 = -1 / (x * x); break;
    case PS_OP_LOG10: f = log10(x); f1 = 1 / (x * M_LN10); f2 = -1 / (x * x * M_LN10); break;
    case PS_OP_SQRT: f = sqrt(x); f1 = 0.5 / f; f2 = -0.25 / (x * f); break;
    case PS_OP_AINT: f = trunc(x); break;
    case PS_OP_ANINT: f = round(x); break;
    case PS_OP_CLAMP01:
      if (x <= 0) f = 0;
      else if (x >= 1) f = 1;
      else { f = x; f1 = 1; }
      break;
    default: break;
  }
  psu_hd_unary(c, out, a, f, f1, f2);
}

/* Elementary functions of two arguments. */
static void binary(const psuHD* c, int op, double* out, const double* a, const double* b,
                   int const_exponent) {
  double x = a[0], y = b[0];
  switch (op) {
    case PS_OP_ADD: psu_hd_lin(c, out, 1.0, a, 1.0, b, 0.0); return;
    case PS_OP_SUB: psu_hd_lin(c, out, 1.0, a, -1.0, b, 0.0); return;
    case PS_OP_MUL: psu_hd_mul(c, out, a, b); return;
    case PS_OP_DIV: psu_hd_div(c, out, a, b); return;
    case PS_OP_POW: {
      double f = pow(x, y);
      if (const_exponent) {
        double f1 = y == 0 ? 0 : y * pow(x, y - 1);
        double f2 = (y == 0 || y == 1) ? 0 : y * (y - 1) * pow(x, y - 2);
        psu_hd_unary(c, out, a, f, f1, f2);
      } else {
        double l = log(x);
        psu_hd_binary(c, out, a, b, f, y * pow(x, y - 1), f * l, y * (y - 1) * pow(x, y - 2),
                      pow(x, y - 1) * (1 + y * l), f * l * l);
      }
      return;
    }
    case PS_OP_ATAN2: hd_atan2(c, out, a, b); return;
    case PS_OP_MOD: psu_hd_lin(c, out, 1.0, a, -trunc(x / y), b, 0.0); return;
    case PS_OP_MAX: psu_hd_copy(c, out, x >= y ? a : b); return;
    case PS_OP_MIN: psu_hd_copy(c, out, x <= y ? a : b); return;
    case PS_OP_SIGN: psu_hd_lin(c, out, sgn(x) * sgn(y), a, 0.0, NULL, 0.0); return;
    case PS_OP_DIM:
      if (x > y) psu_hd_lin(c, out, 1.0, a, -1.0, b, 0.0);
      else psu_hd_const(c, out, 0.0);
      return;
    default: return;
  }
}

void ps_tape_run(const psModel* m, psData* d, int tape, int order, int values_only, double t,
                 const double* y, const double* yp) {
  int nh = m->tape_nh[tape];
  psuHD c = {values_only ? nh : m->tape_nbasis[tape], nh, order, m->hd_stride};
  const int* code = m->code + (long)m->tape_code_adr[tape] * PS_INSTR_WIDTH;
  int len = m->tape_len[tape];
  ps_body_cache(m, d, &c, tape, t, y, yp);
  for (int i = 0; i < len; i++) {
    const int* ins = code + (long)i * PS_INSTR_WIDTH;
    const int* a = ins + 1;
    double* out = ps_slot(m, d, i);
    int op = ins[0];
    switch (op) {
      case PS_OP_CONST: psu_hd_const(&c, out, m->consts[a[0]]); break;
      case PS_OP_TIME: psu_hd_var(&c, out, t, c.nh - 1); break;
      case PS_OP_ADD: case PS_OP_SUB: case PS_OP_MUL: case PS_OP_DIV: case PS_OP_POW:
      case PS_OP_ATAN2: case PS_OP_MOD: case PS_OP_MAX: case PS_OP_MIN: case PS_OP_SIGN:
      case PS_OP_DIM:
        binary(&c, op, out, ps_slot(m, d, a[0]), ps_slot(m, d, a[1]), a[2]);
        break;
      case PS_OP_IF: {
        double s = ps_slot(m, d, a[0])[0];
        psu_hd_copy(&c, out, ps_slot(m, d, s < 0 ? a[1] : (s == 0 ? a[2] : a[3])));
        break;
      }
      case PS_OP_MEASURE: measure(m, d, &c, out, a); break;
      case PS_OP_GDOT: gdot(m, d, &c, tape, ps_slot(m, d, a[0]), out); break;
      case PS_OP_SENVAL: psu_hd_const(&c, out, d->senval[a[0]]); break;
      case PS_OP_USER: ps_user_call(m, d, &c, out, a, t); break;
      case PS_OP_STATE: {
        int pos = m->tape_nbasis[tape] - m->tape_nstate[tape] + a[1];
        psu_hd_var(&c, out, y[a[0]], pos < c.n ? pos : -1);
        break;
      }
      case PS_OP_STEPC: step_const(&c, out, ps_slot(m, d, a[0]), m->consts + 0, a); break;
      case PS_OP_AXDOT: {
        double* X1 = ps_tmp(m, d, T_X);
        double* X2 = ps_tmp(m, d, T_XJ);
        ps_marker_axes(m, d, &c, a[0], a[4], X1);
        ps_marker_axes(m, d, &c, a[2], a[5], X2);
        dot_cols(&c, out, X1, a[1], X2, a[3], ps_tmp(m, d, T_SC));
        break;
      }
      default: unary(&c, op, out, ps_slot(m, d, a[0])); break;
    }
  }
}
