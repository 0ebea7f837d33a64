/* The assembly pass shared by the residual (csrc/residual.c) and the element kinds'
 * contributions (csrc/elements/<kind>.c): where rows and iteration-matrix entries go, and the
 * generalized forces of loads on bodies. */
#ifndef PYSOLVER_ASSEMBLY_H
#define PYSOLVER_ASSEMBLY_H

#include <math.h>
#include <stddef.h>

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
#define F_TV 99

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
  int absolute;  /* 1: each force adds its magnitude to its rows (ps_carried), not itself */
} Assembly;

/* Add v to the iteration matrix entry (row, col). */
static inline void jadd(Assembly* as, int row, int col, double v) {
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

/* Add scale * (dg/dy + cj dg/dyp) of the hyper-dual g, over its tape's basis, to row `row` of
 * the iteration matrix. */
static inline void ps_row_gradient(const psModel* m, const psuHD* c, int tape, int row,
                                   const double* g, double scale, Assembly* as) {
  int badr = m->tape_basis_adr[tape];
  for (int j = 0; j < c->n; j++) {
    int kind = m->basis_kind[badr + j];
    if (kind == PS_BASIS_T) continue;
    jadd(as, row, m->basis_idx[badr + j],
         scale * g[1 + j] * (kind == PS_BASIS_YP ? as->cj : 1.0));
  }
}

/* Subtract force_scale * Q from residual row `row`, and its derivatives from the Jacobian. */
static inline void ps_scatter(const psModel* m, const psuHD* c, int tape, int row,
                              const double* Q, Assembly* as) {
  double cf = m->force_scale;
  if (as->absolute) {
    as->res[row] += fabs(cf * Q[0]);
    return;
  }
  as->res[row] -= cf * Q[0];
  if (as->deriv) ps_row_gradient(m, c, tape, row, Q, -cf, as);
}

/* The row of a constraint state x (a reaction lam or mu): g + c_x x, with its derivatives. */
static inline void ps_hold_row(const psModel* m, const psuHD* c, int tape, int x,
                               const double* g, const double* y, Assembly* as) {
  as->res[x] = g[0] + m->compliance[x] * y[x];
  if (!as->deriv) return;
  jadd(as, x, x, m->compliance[x]);
  ps_row_gradient(m, c, tape, x, g, 1.0, as);
}

/* Generalized forces on the body in tape slot `slot` (-1: none) of a global force F at the
 * global point P and a global moment Mo (hyper-duals; F, P or Mo may be NULL), times sign. */
void ps_apply_at(const psModel* m, psData* d, const psuHD* c, int tape, int slot,
                 const double* P, const double* F, const double* Mo, double sign, Assembly* as);

/* Generalized forces of a global force F at marker mk and a global moment Mo on its body. */
void ps_apply_load(const psModel* m, psData* d, const psuHD* c, int tape, int mk, int slot,
                   const double* F, const double* Mo, double sign, Assembly* as);

/* Q_i = F c_i, c_i = d(g')/du_i, for every free body the tape reads; when lam >= 0 (a
 * reaction, F = y[lam]) also the Jacobian column of lam. */
void ps_rate_force(const psModel* m, psData* d, const psuHD* c, const double* g, int tape,
                   const double* F, int lam, Assembly* as);

/* A reaction lam (a state, model force units) that holds g' at a target: it acts like a
 * penalty force F = lam along c_i = d(g')/du_i, and its own row is g' (the caller subtracts
 * the target). The row has no lam in it (index 2): lam is left out of IDA's error test. */
void ps_hold_rate(const psModel* m, psData* d, const psuHD* c, int tape, const double* g,
                  const double* gd, int lam, const double* y, Assembly* as);

/* Hold g = 0 at the position level (the stabilization of Gear, Gupta and Leimkuhler, with
 * the velocity level g' = 0 in the reaction's own row): row mu is g, and every position row
 * q_j of the tape's bodies gets -mu dg/dq_j, which vanishes on the exact solution (mu = 0)
 * and lets the corrector satisfy both levels. g's tape ran at one order above as->deriv. */
void ps_hold_position(const psModel* m, psData* d, const psuHD* c, int tape, const double* g,
                      int mu, const double* y, Assembly* as);

/* One element kind: its contribution to the rows (csrc/elements/<kind>.c), given the element's
 * ints I (its layout in pysolver/catalogue.py) after its tape has run, and how the kernel runs
 * that tape and diagnoses it. */
typedef struct psElementKind {
  void (*assemble)(const psModel* m, psData* d, const psuHD* c, int tape, const int* I,
                   double t, const double* y, const double* yp, Assembly* as);
  int nint;     /* ints of its layout in el_int                                       */
  int nvalue;   /* its leading ints that are tape slots of its values (diagnosis)      */
  int order;    /* least derivative order of its tape's run (1: rates of g read)       */
  /* NULL, or whether the element's load is undefined at this state though its values are
   * finite (a translational force whose markers coincide), its value in *value: the
   * diagnosis of a non-finite residual (PS_BAD_DIRECTION) */
  int (*undefined)(const psModel* m, psData* d, const psuHD* c, int tape, const int* I,
                   double* value);
} psElementKind;

/* The kinds, indexed by PS_EL_* (csrc/elements/table.c). */
extern const psElementKind ps_element_kinds[PS_EL_COUNT];

#endif
