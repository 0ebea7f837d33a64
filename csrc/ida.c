/* IDA called from C: the kernel's residual, Jacobian and root functions handed to SUNDIALS IDA
 * directly, so no Python runs per callback.
 *
 * SUNDIALS is not linked at build time: ps_ida_load opens the shared libraries at run time
 * (those the scikit-sundae wheel ships) and looks up the functions listed in SUNDIALS_FNS; the
 * type of each pointer comes from its prototype in sundials_decls.h, so a call through the
 * table is checked by the compiler like a direct call. If loading fails the Python driver uses
 * scikit-sundae.
 */
#include <dlfcn.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "sundials_decls.h"

/* Every SUNDIALS function used, with the library it lives in (index into the paths of
 * ps_ida_load: 0 core, 1 nvecserial, 2 sunmatrixdense, 3 sunlinsoldense, 4 ida,
 * 5 sunmatrixband, 6 sunlinsolband). */
#define SUNDIALS_FNS(X)                                                                       \
  X(0, SUNContext_Create) X(0, SUNContext_Free) X(0, SUNContext_ClearErrHandlers)             \
  X(0, SUNMatDestroy) X(0, SUNLinSolFree) X(1, N_VNew_Serial) X(1, N_VGetArrayPointer)        \
  X(1, N_VDestroy) X(2, SUNDenseMatrix) X(2, SUNDenseMatrix_Data) X(3, SUNLinSol_Dense)       \
  X(5, SUNBandMatrix) X(5, SUNBandMatrix_Data) X(5, SUNBandMatrix_LDim) X(6, SUNLinSol_Band)   \
  X(4, IDACreate)                                                                             \
  X(4, IDAInit) X(4, IDAReInit) X(4, IDASStolerances) X(4, IDASetUserData) X(4, IDAWFtolerances) \
  X(4, IDASetLinearSolver) X(4, IDASetJacFn) X(4, IDASetMaxNumSteps) X(4, IDASetMaxStep)      \
  X(4, IDASetMinStep) X(4, IDASetInitStep) X(4, IDASetStopTime) X(4, IDASetEtaMax)            \
  X(4, IDASetNonlinConvCoef) X(4, IDARootInit) X(4, IDASetRootDirection)                      \
  X(4, IDASetNoInactiveRootWarn) X(4, IDASolve) X(4, IDAGetRootInfo) X(4, IDAGetNumSteps)     \
  X(4, IDAGetNumResEvals) X(4, IDAGetNumJacEvals) X(4, IDAGetNumErrTestFails)                 \
  X(4, IDAGetNumNonlinSolvConvFails) X(4, IDAGetNumGEvals) X(4, IDAGetLastStep) X(4, IDAFree)   \
  X(4, IDASetId) X(4, IDASetSuppressAlg) X(4, IDAGetCurrentStep) X(4, IDAGetCurrentTime) X(4, IDAGetSolution) \
  X(7, SUNSparseMatrix)                                                                     \
  X(7, SUNSparseMatrix_Data) X(7, SUNSparseMatrix_IndexValues)                                \
  X(7, SUNSparseMatrix_IndexPointers) X(8, SUNLinSol_SuperLUMT) X(0, SUNLinSolNewEmpty)          \
  X(3, SUNLinSolGetType_Dense) X(3, SUNLinSolSetup_Dense) X(3, SUNLinSolSolve_Dense)

/* IDA's default step-growth limit (IDASetEtaMax), restored when a limit auto_eta switched on
 * goes with new step bounds. */
#define PS_IDA_ETA_MAX_DEFAULT 2.0

/* A step shorter than this times |t| is at rounding level. */
#define PS_IDA_ROUNDING 1e-10

#define PS_ENUM(lib, name) F_##name,
enum { SUNDIALS_FNS(PS_ENUM) F_COUNT };
#define PS_ENTRY(lib, name) {lib, #name},
static const struct { int lib; const char* name; } FNS[F_COUNT] = {SUNDIALS_FNS(PS_ENTRY)};

/* The function `name` of s's table, with the type of its prototype. */
#define CALL(s, name) ((__typeof__(&name))(s)->fn[F_##name])

#define PS_NLIBS 9

/* Libraries from this index on are optional (the sparse matrix and SuperLU_MT): without them
 * the C driver does dense and band only. The functions from SUNLinSolNewEmpty on are optional
 * too: without them there is no sparse LU of pysolver's own (csrc/sparselu.c). */
#define PS_FIRST_OPTIONAL 7
#define PS_OPTIONAL_FN(k) (FNS[k].lib >= PS_FIRST_OPTIONAL || (k) >= F_SUNLinSolNewEmpty)

/* SUNLS_LUFACT_FAIL: a singular matrix, a failure IDA recovers from with a smaller step. */
#define PS_LS_LUFACT_FAIL 808

/* The most states whose dense solves multiply by the inverse of the factored matrix, and the
 * largest 1-norm condition number it is used at (dense_solve; docs/numerics.md). */
#define PS_INV_MAX 16
#define PS_INV_COND 1e8

/* Where a run's rates are taken just past a break of a function of time, relative to
 * max(1, |t|) (pysolver/solve/breaks.py's SIDE). */
#define PS_BREAK_SIDE 1e-12

/* Steps per window over which watch() counts IDA's error-test failures. */
#define PS_IDA_WINDOW 50

struct psIDA {
  void* lib[PS_NLIBS];    /* dlopen handles (kept open for the process's life)      */
  void* fn[F_COUNT];      /* SUNDIALS functions, in SUNDIALS_FNS order              */
  SUNContext ctx;         /* context of the current integration                     */
  void* mem;              /* IDA memory                                             */
  N_Vector y, yp;         /* state and its derivative                               */
  N_Vector yi, ypi;       /* an interpolated state and derivative (ps_ida_interpolate) */
  SUNMatrix A;            /* dense or band matrix                                   */
  SUNLinearSolver LS;     /* linear solver                                          */
  int band;               /* 1: band matrix filled through map                      */
  int hit;                /* 1: the model has reactions; IDA ends a step at every
                             requested time (ps_ida_solve) and leaves them out of
                             its tests (weights)                                    */
  double rtol, atol;      /* the tolerances                                         */
  int sparse;             /* CSC matrix filled through map: 1 factored by lu,
                             2 by SuperLU_MT (0: dense or band)                     */
  psLU* lu;               /* the sparse LU of a sparse integration (sparse == 1)    */
  int own_dense;          /* 1: a dense matrix factored by pysolver's own LU
                             (dense_setup / dense_solve)                           */
  double* rpiv;           /* (ny) reciprocals of its pivots                         */
  int* piv;               /* (ny) row exchanged with row k at step k                */
  int nsolve;             /* solves with the current factors                        */
  double* inv;            /* (2 x nl x nl) the inverse from those factors (column-
                             major) and room to make it, when nl <= PS_INV_MAX     */
  int use_inv;            /* 1: the solves multiply by inv                          */
  long ninv;              /* solves by the inverse since ps_ida_load (tests)        */
  int slot[4];            /* the word of a linear solver object that points to its
                             operations, and where gettype, setup and solve sit in
                             that table (-1: unknown, no solver of pysolver's own)  */
  const int* map;         /* (ntrip x 1) band or CSC storage index of each triplet  */
  const int* colptr;      /* (ny + 1) CSC column pointers of the fixed pattern      */
  const int* rowind;      /* (nnz) CSC row indices of the fixed pattern             */
  int nnz;                /* entries of the CSC pattern                             */
  int ntrip;              /* number of Jacobian triplets                            */
  long nstore;            /* doubles of band storage                                */
  const psModel* m;       /* model being integrated                                 */
  psData* d;              /* its workspace                                          */
  double auto_eta;        /* step-growth limit to switch on when IDA's error test
                             fails most steps (0: never)                            */
  long win[2];            /* steps and netf at the start of the window              */
  double win_h[2];        /* smallest and largest step seen in the window           */
  long acc[6];            /* IDA's counters of the run before the last restart      */
  long limited_at;        /* step at which auto_eta was switched on (0: not)        */
  long first_limited;     /* the first such step of the run (ps_ida_stats)          */
  double bounds[3];       /* the step bounds set: hmax, hmin, first step (0: IDA's) */
  double base[3];         /* those of ps_ida_init (a run starts from them)          */
  psStream* stream;       /* where output rows are written as made (NULL: nowhere)  */
  int* hold;              /* (nhold) states the scene may hold at their start values
                             (ps_ida_hold), ascending                               */
  int nhold;              /* their number                                          */
  int holdable;           /* 1: this integration may hold them (a dense matrix, and
                             a state left to integrate)                            */
  int held;               /* 1: this integration holds them: IDA's vectors have the
                             nl live states, the kernel sees full ones (fy, fyp)    */
  int nl;                 /* states IDA integrates (ny when nothing is held)       */
  int* live;              /* (nl) the state each of IDA's entries is               */
  double *fy, *fyp, *fr;  /* (ny) full state, rate and residual of a held run       */
  double* fjac;           /* (ny x ny) full dense Jacobian of a held run            */
  double wscale;          /* sqrt(nl / ny): IDA's norms over nl entries then equal
                             those over all ny, the held ones' errors being zero    */
  char msg[256];          /* message of the last error                              */
  double* brk;            /* (nbrk) ascending times where a function of time alone
                             has a kink or jump (ps_ida_breaks): ps_ida_controlled
                             stops and restarts at each                             */
  int nbrk;               /* their number                                           */
  int kbrk;               /* the next one (those before are passed)                 */
  double* bwork;          /* ps_consistent_yp's workspace at a break (not owned)    */
  int* bpiv;
  void (*set_threads)(int); /* SuperLU_MT's libgomp omp_set_num_threads (NULL: none)    */
};

/* The first break after t (the breaks at t and before it are passed). */
static int breaks_after(const psIDA* s, double t) {
  int k = 0;
  while (k < s->nbrk && s->brk[k] <= t) k++;
  return k;
}

/* A linear solver object: its content first, its table of operations at word s->slot[0]
 * (SUNDIALS 7.5 put a field between the two). */
#define LS_CONTENT(ls) (*(void**)(ls))
#define LS_OPS(s, ls) (((void***)(ls))[(s)->slot[0]])

/* Held states (ps_ida_hold): a state the scene holds at its start value (a point body's
 * coordinate nothing moves, and its velocity) is left out of IDA's vectors, error test and
 * matrix; the kernel still sees the full state, the held entries at their values of the last
 * (re)start and their rates zero. */

/* IDA's vector v (s->nl entries) into the full state `full`; its held entries stay. */
static void scatter(const psIDA* s, const double* v, double* full) {
  for (int k = 0; k < s->nl; k++) full[s->live[k]] = v[k];
}

/* The live entries of the full state `full` into IDA's vector v. */
static void gather(const psIDA* s, const double* full, double* v) {
  for (int k = 0; k < s->nl; k++) v[k] = full[s->live[k]];
}

/* Whether the states ps_ida_hold named can be held from a start with rates yp0: each one's
 * rate is zero there (a position's is its velocity, a velocity's its load). */
static int at_rest(const psIDA* s, const double* yp0) {
  for (int i = 0; i < s->nhold; i++)
    if (yp0[s->hold[i]] != 0.0) return 0;
  return s->nhold > 0;
}

/* IDA's vector v as a full state into out: the held entries from `full` (s->fy: their held
 * values; s->fyp: zero rates), the rest from v. */
static void put_full(psIDA* s, N_Vector v, double* out, const double* full);

/* Whether a (re)start at (t0, y0, yp0) can hold the states: at rest in them, and their
 * equations exactly satisfied there (a start whose yp0 is stale, after an actor changed the
 * scene, is not). The check's residual is not one of the run's: the counters it moves, and a
 * non-finite value's record, are put back. */
static int holds(psIDA* s, double t0, const double* y0, const double* yp0) {
  if (!s->holdable || !at_rest(s, yp0)) return 0;
  psData* d = s->d;
  long nres = d->nres, ntimes = d->ntimes, nfail = d->nfail;
  double last_t = d->last_t;
  int bad_kind = d->bad_kind;
  int ok = ps_residual(s->m, d, t0, y0, yp0, s->fr) == PS_OK;
  for (int i = 0; ok && i < s->nhold; i++) ok = s->fr[s->hold[i]] == 0.0;
  d->nres = nres;
  d->ntimes = ntimes;
  d->nfail = nfail;
  d->last_t = last_t;
  d->bad_kind = bad_kind;
  return ok;
}

/* Find where a linear solver object keeps its table of operations, and where gettype, setup
 * and solve sit in that table (both changed between SUNDIALS versions): an empty solver holds
 * nothing but the table and its context, and a dense solver's table holds the dense solver's
 * exported functions at those places. s->slot stays -1 (no sparse LU of pysolver's own) when
 * the functions are missing or the layout is not recognised. */
static void find_slots(psIDA* s) {
  void* want[3] = {s->fn[F_SUNLinSolGetType_Dense], s->fn[F_SUNLinSolSetup_Dense],
                   s->fn[F_SUNLinSolSolve_Dense]};
  for (int j = 0; j < 4; j++) s->slot[j] = -1;
  if (!want[0] || !want[1] || !want[2] || !s->fn[F_SUNLinSolNewEmpty]) return;
  SUNContext ctx = NULL;
  if (CALL(s, SUNContext_Create)(0, &ctx) != 0) return;
  /* the table: the one non-NULL word before the context's in an empty solver */
  int at = -1, found_ctx = 0;
  SUNLinearSolver empty = CALL(s, SUNLinSolNewEmpty)(ctx);
  for (int i = 0; empty && i < 4 && !found_ctx; i++) {
    void* w = ((void**)empty)[i];
    if (w == (void*)ctx) found_ctx = 1;
    else if (w && at < 0) at = i;
  }
  if (empty) CALL(s, SUNLinSolFree)(empty);
  N_Vector v = CALL(s, N_VNew_Serial)(1, ctx);
  SUNMatrix a = v ? CALL(s, SUNDenseMatrix)(1, 1, ctx) : NULL;
  SUNLinearSolver ls = a && found_ctx && at > 0 ? CALL(s, SUNLinSol_Dense)(v, a, ctx) : NULL;
  int slot[4] = {at, -1, -1, -1}, found = 0;
  void** ops = ls ? ((void***)ls)[at] : NULL;
  /* scan no further than the last of the three (slot 9 in SUNDIALS 7.5's table) */
  for (int i = 0; ops && i < 16 && found < 3; i++)
    for (int j = 0; j < 3; j++)
      if (slot[j + 1] < 0 && ops[i] == want[j]) {
        slot[j + 1] = i;
        found++;
      }
  if (found == 3 && slot[1] < slot[2] && slot[2] < slot[3]) memcpy(s->slot, slot, sizeof(slot));
  if (ls) CALL(s, SUNLinSolFree)(ls);
  if (a) CALL(s, SUNMatDestroy)(a);
  if (v) CALL(s, N_VDestroy)(v);
  CALL(s, SUNContext_Free)(&ctx);
}

/* The sparse linear solver's operations: a direct solver over csrc/sparselu.c. */
static int ls_type(SUNLinearSolver ls) {
  (void)ls;
  return 0; /* SUNLINEARSOLVER_DIRECT */
}

/* Factor the matrix IDA just filled (jac_fn): replay the last pivots, else choose anew; a
 * singular matrix is a recoverable failure (IDA retries with a smaller step). */
static int ls_setup(SUNLinearSolver ls, SUNMatrix a) {
  psIDA* s = LS_CONTENT(ls);
  const double* v = CALL(s, SUNSparseMatrix_Data)(a);
  if (ps_lu_refactor(s->lu, v) == 0) return 0;
  int rc = ps_lu_factor(s->lu, v);
  return rc == 0 ? 0 : rc > 0 ? PS_LS_LUFACT_FAIL : -1;
}

static int ls_solve(SUNLinearSolver ls, SUNMatrix a, N_Vector x, N_Vector b, sunrealtype tol) {
  (void)a;
  (void)tol;
  psIDA* s = LS_CONTENT(ls);
  __typeof__(&N_VGetArrayPointer) data = CALL(s, N_VGetArrayPointer);
  memcpy(data(x), data(b), sizeof(double) * (size_t)s->nl);
  ps_lu_solve(s->lu, data(x));
  return 0;
}

/* Solve in place with the factors of dense_setup (lu, n x n): SUNDIALS' dense solve with a
 * multiplication by each pivot's reciprocal where it divides (a chain of divisions was most of
 * its time on a six-state scene), and the columns of zero entries skipped. */
static void lu_solve(const psIDA* s, const double* lu, int n, double* v) {
  for (int k = 0; k < n; k++) {
    int p = s->piv[k];
    if (p != k) {
      double t = v[k];
      v[k] = v[p];
      v[p] = t;
    }
  }
  for (int k = 0; k < n; k++) {
    double vk = v[k];
    if (vk != 0.0)
      for (int i = k + 1; i < n; i++) v[i] -= lu[(long)k * n + i] * vk;
  }
  for (int k = n - 1; k >= 0; k--) {
    double vk = v[k] * s->rpiv[k];
    v[k] = vk;
    if (vk != 0.0)
      for (int i = 0; i < k; i++) v[i] -= lu[(long)k * n + i] * vk;
  }
}

/* The inverse X (row-major) of the matrix whose factors dense_setup left in lu (n x n): the
 * solves of lu_solve for the n columns of the identity at once, row operations on X. */
static void invert(const psIDA* s, const double* lu, int n, double* X) {
  for (int i = 0; i < n * n; i++) X[i] = 0.0;
  for (int i = 0; i < n; i++) X[i * n + i] = 1.0;
  for (int k = 0; k < n; k++) {
    int p = s->piv[k];
    if (p != k)
      for (int j = 0; j < n; j++) {
        double t = X[k * n + j];
        X[k * n + j] = X[p * n + j];
        X[p * n + j] = t;
      }
  }
  for (int k = 0; k < n; k++)
    for (int i = k + 1; i < n; i++) {
      double l = lu[(long)k * n + i];
      if (l != 0.0)
        for (int j = 0; j < n; j++) X[i * n + j] -= l * X[k * n + j];
    }
  for (int k = n - 1; k >= 0; k--) {
    double r = s->rpiv[k];
    for (int j = 0; j < n; j++) X[k * n + j] *= r;
    for (int i = 0; i < k; i++) {
      double u = lu[(long)k * n + i];
      if (u != 0.0)
        for (int j = 0; j < n; j++) X[i * n + j] -= u * X[k * n + j];
    }
  }
}

/* Factor a dense matrix (column-major) in place with partial pivoting, as SUNDIALS' dense LU
 * does (the same pivots and operations) but keeping the pivots' reciprocals; a zero or
 * non-finite pivot is a recoverable failure. */
static int dense_setup(SUNLinearSolver ls, SUNMatrix a) {
  psIDA* s = LS_CONTENT(ls);
  int n = s->nl;
  double* lu = CALL(s, SUNDenseMatrix_Data)(a);
  for (int k = 0; k < n; k++) {
    double* ck = lu + (long)k * n;
    int p = k;
    for (int i = k + 1; i < n; i++)
      if (fabs(ck[i]) > fabs(ck[p])) p = i;
    s->piv[k] = p;
    if (!(fabs(ck[p]) > 0.0) || !isfinite(ck[p])) return PS_LS_LUFACT_FAIL;
    if (p != k)
      for (int j = 0; j < n; j++) {
        double t = lu[(long)j * n + k];
        lu[(long)j * n + k] = lu[(long)j * n + p];
        lu[(long)j * n + p] = t;
      }
    double r = 1.0 / ck[k];
    s->rpiv[k] = r;
    for (int i = k + 1; i < n; i++) ck[i] *= r;
    for (int j = k + 1; j < n; j++) {
      double* cj = lu + (long)j * n;
      double u = cj[k];
      if (u != 0.0)
        for (int i = k + 1; i < n; i++) cj[i] -= ck[i] * u;
    }
  }
  s->nsolve = 0;
  s->use_inv = 0;
  return 0;
}

/* v = A r for the n x n column-major A (n <= PS_INV_MAX). */
static inline __attribute__((always_inline)) void matvec(const double* restrict A,
                                                         const double* restrict r,
                                                         double* restrict v, const int n) {
  double acc[PS_INV_MAX];
  for (int i = 0; i < n; i++) acc[i] = A[i] * r[0];
  for (int j = 1; j < n; j++)
    for (int i = 0; i < n; i++) acc[i] += A[(long)j * n + i] * r[j];
  for (int i = 0; i < n; i++) v[i] = acc[i];
}

/* The larger of m and a column sum x, NaN once a sum is not finite. */
static double norm_max(double m, double x) { return x > m || !isfinite(x) ? x : m; }

/* Make s->inv, the inverse of the matrix A whose factors P A = L U dense_setup left in lu, and
 * use it (s->use_inv) when a bound on A's 1-norm condition number, ||L|| ||U|| ||A^-1||
 * (>= ||A|| ||A^-1||, from the factors: A itself is gone), is finite and at most PS_INV_COND. */
static void make_inverse(psIDA* s, const double* lu, int n) {
  double* X = s->inv + (long)n * n;     /* row-major scratch */
  invert(s, lu, n, X);
  double xnorm = 0.0, lnorm = 0.0, unorm = 0.0;
  for (int j = 0; j < n; j++) {
    double sx = 0.0, sl = 1.0, su = 0.0;  /* L's unit diagonal */
    for (int i = 0; i < n; i++) {
      double e = lu[(long)j * n + i];
      sx += fabs(s->inv[(long)j * n + i] = X[(long)i * n + j]);
      if (i > j) sl += fabs(e);
      else su += fabs(e);
    }
    xnorm = norm_max(xnorm, sx);
    lnorm = norm_max(lnorm, sl);
    unorm = norm_max(unorm, su);
  }
  double cond = lnorm * unorm * xnorm;
  s->use_inv = isfinite(cond) && cond <= PS_INV_COND;
}

/* The solve with a factorization at which its inverse is made: the second for up to 4
 * states, later for more (the inverse costs about n / 1.5 solves), so that factors used for
 * few solves (a LoadControl update's restart) are not inverted. */
static int inverse_at(int n) { return n <= 4 ? 2 : n / 2; }

/* Solve with the factors of dense_setup. A small, well-conditioned system (PS_INV_MAX,
 * PS_INV_COND) is solved from its inverse_at solve on by a product with the inverse, made
 * once from the factors: a triangular solve is a chain of dependent operations, the product
 * is not (docs/numerics.md, "The dense solve"). */
static int dense_solve(SUNLinearSolver ls, SUNMatrix a, N_Vector x, N_Vector b, sunrealtype tol) {
  (void)tol;
  psIDA* s = LS_CONTENT(ls);
  int n = s->nl;
  double* v = CALL(s, N_VGetArrayPointer)(x);
  const double* r = CALL(s, N_VGetArrayPointer)(b);
  if (s->inv && ++s->nsolve == inverse_at(n))
    make_inverse(s, CALL(s, SUNDenseMatrix_Data)(a), n);
  if (s->use_inv && v != r) {
    s->ninv++;
    switch (n) {   /* n known: the sums stay in registers */
#define PS_MATVEC(k) case k: matvec(s->inv, r, v, k); break;
      PS_MATVEC(1) PS_MATVEC(2) PS_MATVEC(3) PS_MATVEC(4) PS_MATVEC(5) PS_MATVEC(6)
      PS_MATVEC(7) PS_MATVEC(8) PS_MATVEC(9) PS_MATVEC(10) PS_MATVEC(11) PS_MATVEC(12)
      PS_MATVEC(13) PS_MATVEC(14) PS_MATVEC(15) PS_MATVEC(16)
#undef PS_MATVEC
      default: matvec(s->inv, r, v, n);
    }
    return 0;
  }
  memcpy(v, r, sizeof(double) * (size_t)n);
  lu_solve(s, CALL(s, SUNDenseMatrix_Data)(a), n, v);
  return 0;
}

/* A linear solver object for IDA whose content is s and whose setup and solve are these, or
 * NULL. */
static SUNLinearSolver own_solver_with(psIDA* s, void* setup, void* solve) {
  SUNLinearSolver ls = CALL(s, SUNLinSolNewEmpty)(s->ctx);
  if (!ls) return NULL;
  LS_CONTENT(ls) = s;
  LS_OPS(s, ls)[s->slot[1]] = (void*)ls_type;
  LS_OPS(s, ls)[s->slot[2]] = setup;
  LS_OPS(s, ls)[s->slot[3]] = solve;
  return ls;
}

/* A linear solver object for IDA that factors with s->lu, or NULL. */
static SUNLinearSolver own_solver(psIDA* s) {
  return own_solver_with(s, (void*)ls_setup, (void*)ls_solve);
}

psIDA* ps_ida_load(const char* const* paths, char* msg, int msglen) {
  psIDA* s = calloc(1, sizeof(*s));
  if (!s) {
    snprintf(msg, (size_t)msglen, "out of memory");
    return NULL;
  }
  for (int i = 0; i < PS_NLIBS; i++) {
    if (!paths[i] && i >= PS_FIRST_OPTIONAL) continue;
    s->lib[i] = dlopen(paths[i], RTLD_NOW | RTLD_LOCAL);
    if (!s->lib[i] && i >= PS_FIRST_OPTIONAL) continue;
    if (!s->lib[i]) {
      snprintf(msg, (size_t)msglen, "cannot open %s: %s", paths[i], dlerror());
      free(s);
      return NULL;
    }
  }
  if (s->lib[8]) s->set_threads = (void (*)(int))dlsym(s->lib[8], "omp_set_num_threads");
  for (int k = 0; k < F_COUNT; k++) {
    if (s->lib[FNS[k].lib]) s->fn[k] = dlsym(s->lib[FNS[k].lib], FNS[k].name);
    /* a function may sit in another library of the set in other SUNDIALS builds */
    for (int i = 0; i < PS_NLIBS && !s->fn[k]; i++)
      if (s->lib[i]) s->fn[k] = dlsym(s->lib[i], FNS[k].name);
    if (!s->fn[k] && PS_OPTIONAL_FN(k)) continue;
    if (!s->fn[k]) {
      snprintf(msg, (size_t)msglen, "SUNDIALS function %s not found", FNS[k].name);
      free(s);
      return NULL;
    }
  }
  find_slots(s);
  return s;
}

psIDA* ps_ida_new(const psIDA* loaded) {
  psIDA* s = calloc(1, sizeof(*s));
  if (!s) return NULL;
  memcpy(s->lib, loaded->lib, sizeof(s->lib));
  memcpy(s->fn, loaded->fn, sizeof(s->fn));
  memcpy(s->slot, loaded->slot, sizeof(s->slot));
  s->set_threads = loaded->set_threads;
  return s;
}

const char* ps_ida_message(const psIDA* s) { return s->msg; }

/* Whether the sparse matrix's functions are there. */
static int has_csc(const psIDA* s) {
  return s->fn[F_SUNSparseMatrix] && s->fn[F_SUNSparseMatrix_Data] &&
         s->fn[F_SUNSparseMatrix_IndexValues] && s->fn[F_SUNSparseMatrix_IndexPointers];
}

int ps_ida_has_sparse(const psIDA* s) { return has_csc(s) && s->slot[3] >= 0; }

int ps_ida_has_superlumt(const psIDA* s) { return has_csc(s) && s->fn[F_SUNLinSol_SuperLUMT]; }

static int res_fn(sunrealtype t, N_Vector yy, N_Vector yp, N_Vector rr, void* ud) {
  psIDA* s = (psIDA*)ud;
  __typeof__(&N_VGetArrayPointer) data = CALL(s, N_VGetArrayPointer);
  double *y = data(yy), *ypv = data(yp), *r = data(rr);
  if (s->held) {
    scatter(s, y, s->fy);
    scatter(s, ypv, s->fyp);
    y = s->fy;
    ypv = s->fyp;
    r = s->fr;
  }
  /* a non-finite residual is a recoverable failure: IDA retries with a smaller step, unless
   * the step is already at rounding level (the solution itself runs into the NaN: it would
   * creep towards it forever); an error a user subroutine reported is not: the run ends */
  if (ps_residual(s->m, s->d, t, y, ypv, r) == PS_OK) {
    if (!s->held) return 0;
    /* a held state's own equation must hold exactly at rest, or holding it was wrong: the
     * run ends rather than answer for a scene it did not integrate */
    for (int i = 0; i < s->nhold; i++)
      if (r[s->hold[i]] != 0.0) {
        s->d->user_error = 1;
        s->d->user_t = NAN;   /* no routine's call */
        snprintf(s->d->msg, sizeof(s->d->msg),
                 "state %d was held at rest, but its equation gives %.6g "
                 "(run with PYSOLVER_HELD=off and report this)", s->hold[i], r[s->hold[i]]);
        return -1;
      }
    gather(s, r, data(rr));
    return 0;
  }
  if (s->d->user_error) return -1;
  sunrealtype h = 1.0;
  CALL(s, IDAGetCurrentStep)(s->mem, &h);
  return fabs(h) <= PS_IDA_ROUNDING * fabs(t) ? -1 : 1;
}

/* Called with each Jacobian evaluation (IDA forms one after every error-test failure, so about
 * once per step when the error test keeps failing): over windows of PS_IDA_WINDOW steps, switch
 * the step-growth limit auto_eta on if more than half of the steps failed the error test while
 * the step size stayed within a factor 4: the steady cycle "grow the step 2x, fail, shrink it"
 * of a stiff penalty mode, not the burst of failures of an impact, where the step collapses. */
static void watch(psIDA* s) {
  long nst, netf;
  double h;
  CALL(s, IDAGetNumSteps)(s->mem, &nst);
  CALL(s, IDAGetNumErrTestFails)(s->mem, &netf);
  CALL(s, IDAGetLastStep)(s->mem, &h);
  h = fabs(h);
  if (h > 0 && (s->win_h[0] == 0 || h < s->win_h[0])) s->win_h[0] = h;
  if (h > s->win_h[1]) s->win_h[1] = h;
  long dn = nst - s->win[0];
  if (dn < PS_IDA_WINDOW) return;
  if (2 * (netf - s->win[1]) > dn && s->win_h[1] < 4 * s->win_h[0] &&
      CALL(s, IDASetEtaMax)(s->mem, s->auto_eta) == 0) {
    s->limited_at = s->acc[0] + nst;
    if (!s->first_limited) s->first_limited = s->limited_at;
  }
  s->win[0] = nst;
  s->win[1] = netf;
  s->win_h[0] = s->win_h[1] = 0.0;
}

static int jac_fn(sunrealtype t, sunrealtype cj, N_Vector yy, N_Vector yp, N_Vector rr,
                  SUNMatrix J, void* ud, N_Vector t1, N_Vector t2, N_Vector t3) {
  (void)rr; (void)t1; (void)t2; (void)t3;
  psIDA* s = (psIDA*)ud;
  if (s->auto_eta > 0 && !s->limited_at) watch(s);
  __typeof__(&N_VGetArrayPointer) data = CALL(s, N_VGetArrayPointer);
  if (s->sparse) {
    /* IDA zeroes the matrix, pattern included, before each call: write the fixed pattern,
     * then the kernel's triplets summed into the CSC values through the map */
    sunindextype* rows = CALL(s, SUNSparseMatrix_IndexValues)(J);
    sunindextype* cols = CALL(s, SUNSparseMatrix_IndexPointers)(J);
    for (int k = 0; k < s->nnz; k++) rows[k] = s->rowind[k];
    for (int j = 0; j <= s->m->ny; j++) cols[j] = s->colptr[j];
    double* v = CALL(s, SUNSparseMatrix_Data)(J);
    if (ps_jacobian_csc(s->m, s->d, t, data(yy), data(yp), cj, s->map, s->ntrip, v, s->nnz) ==
        PS_OK)
      return 0;
    return s->d->user_error ? -1 : 1;
  }
  if (s->band) {
    /* kernel triplets scattered into band storage through a precomputed map */
    double* b = CALL(s, SUNBandMatrix_Data)(J);
    if (ps_jacobian_csc(s->m, s->d, t, data(yy), data(yp), cj, s->map, s->ntrip, b,
                        (int)s->nstore) == PS_OK) return 0;
    return s->d->user_error ? -1 : 1;
  }
  double* a = CALL(s, SUNDenseMatrix_Data)(J);
  int n = s->m->ny;
  if (s->held) {
    /* the full matrix, then its live rows and columns, column-major */
    scatter(s, data(yy), s->fy);
    scatter(s, data(yp), s->fyp);
    int rc = ps_jacobian(s->m, s->d, t, s->fy, s->fyp, cj, s->fjac);
    for (int j = 0; j < s->nl; j++)
      for (int i = 0; i < s->nl; i++)
        a[(long)j * s->nl + i] = s->fjac[(long)s->live[i] * n + s->live[j]];
    if (rc == PS_OK) return 0;
    return s->d->user_error ? -1 : 1;
  }
  /* the kernel writes row-major; the dense matrix is column-major: transpose in place */
  int rc = ps_jacobian(s->m, s->d, t, data(yy), data(yp), cj, a);
  for (int i = 0; i < n; i++)
    for (int j = i + 1; j < n; j++) {
      double tmp = a[(long)i * n + j];
      a[(long)i * n + j] = a[(long)j * n + i];
      a[(long)j * n + i] = tmp;
    }
  if (rc == PS_OK) return 0;
  return s->d->user_error ? -1 : 1;
}

static int root_fn(sunrealtype t, N_Vector yy, N_Vector yp, sunrealtype* g, void* ud) {
  psIDA* s = (psIDA*)ud;
  __typeof__(&N_VGetArrayPointer) data = CALL(s, N_VGetArrayPointer);
  if (!s->held) return ps_roots(s->m, s->d, t, data(yy), data(yp), g);
  scatter(s, data(yy), s->fy);
  scatter(s, data(yp), s->fyp);
  return ps_roots(s->m, s->d, t, s->fy, s->fyp, g);
}

/* Free the current integration's SUNDIALS objects; s itself and its table stay. */
static void release(psIDA* s) {
  if (s->mem) CALL(s, IDAFree)(&s->mem);
  /* the own solver's content is s itself: not SUNDIALS' to free */
  if (s->LS && (s->sparse == 1 || s->own_dense)) LS_CONTENT(s->LS) = NULL;
  if (s->LS) CALL(s, SUNLinSolFree)(s->LS);
  ps_lu_free(s->lu);
  s->lu = NULL;
  free(s->rpiv);
  free(s->piv);
  free(s->inv);
  s->rpiv = NULL;
  s->piv = NULL;
  s->inv = NULL;
  s->use_inv = s->nsolve = 0;
  free(s->live);
  free(s->fy);
  free(s->fyp);
  free(s->fr);
  free(s->fjac);
  s->live = NULL;
  s->fy = s->fyp = s->fr = s->fjac = NULL;
  s->held = s->holdable = 0;
  if (s->A) CALL(s, SUNMatDestroy)(s->A);
  if (s->y) CALL(s, N_VDestroy)(s->y);
  if (s->yp) CALL(s, N_VDestroy)(s->yp);
  if (s->yi) CALL(s, N_VDestroy)(s->yi);
  if (s->ypi) CALL(s, N_VDestroy)(s->ypi);
  if (s->ctx) CALL(s, SUNContext_Free)(&s->ctx);
  s->mem = NULL;
  s->LS = NULL;
  s->A = NULL;
  s->y = s->yp = s->yi = s->ypi = NULL;
  s->ctx = NULL;
}

void ps_ida_delete(psIDA* s) {
  if (!s) return;
  release(s);
  free(s->hold);
  free(s->brk);
  free(s);
}

/* Record a failed set-up step in s->msg and return -1. */
static int fail(psIDA* s, const char* what, int flag) {
  snprintf(s->msg, sizeof(s->msg), "could not set up IDA: %s returned %d", what, flag);
  release(s);
  return -1;
}

/* Run one IDASet call; on a negative flag leave through fail(). */
#define SET(s, call, name)                          \
  do {                                              \
    int flag_ = (call);                             \
    if (flag_ < 0) return fail(s, name, flag_);     \
  } while (0)

/* IDA's error weights 1 / (rtol |y_i| + atol), times wscale when states are held (IDA's
 * root-mean-square norms over the live entries then equal those over every state, as if the
 * held ones, whose errors are zero, were integrated: the same steps), zero for the reactions
 * (algebraic states):
 * they are outside the error test (IDASetSuppressAlg) and, with a zero weight, outside the
 * corrector's convergence test too. A reaction's correction follows the velocities' (M u' =
 * f - G^T lam): once those have converged, so have the reactions along every direction the
 * constraints determine. Weighed in, they only harm: a residual of rounding size e in a
 * constraint row moves its multiplier by about e / h (an index-2 variable), which fails the
 * corrector at the tiny first steps of a tight tolerance (IDA's first step is about
 * atol / |yp|) even scaled by h as Hairer and Wanner do, and near a singular configuration
 * (IFToMM A02) a combination of multipliers is barely determined. docs/numerics.md,
 * "Constraints". */
static int weights(N_Vector y, N_Vector ewt, void* user_data) {
  psIDA* s = user_data;
  const double* v = CALL(s, N_VGetArrayPointer)(y);
  double* w = CALL(s, N_VGetArrayPointer)(ewt);
  for (int k = 0; k < s->nl; k++)
    w[k] = s->m->state_alg[s->held ? s->live[k] : k]
               ? 0.0 : s->wscale / (s->rtol * fabs(v[k]) + s->atol);
  return 0;
}

int ps_ida_init(psIDA* s, const psModel* m, psData* d, double t0, const double* y0,
                const double* yp0, double rtol, double atol, double hmax, double hmin, double h0,
                long mxsteps, const int* rootdir, int mu, int ml, const int* map, int ntrip,
                const int* colptr, const int* rowind, int nnz, const int* colorder) {
  int n = m->ny;
  release(s);
  s->own_dense = 0;
  s->kbrk = breaks_after(s, t0);
  s->m = m;
  s->d = d;
  s->nl = n;
  s->wscale = 1.0;
  for (int i = 0; i < s->nhold; i++)
    if (s->hold[i] < 0 || s->hold[i] >= n || (i > 0 && s->hold[i] <= s->hold[i - 1]))
      return fail(s, "ps_ida_hold (a state index out of order or range)", -1);
  /* held states: a dense matrix, a start at rest in them, and a state left to integrate */
  int dense = !(mu >= 0 && ml >= 0) && mu != PS_IDA_SPARSE && mu != PS_IDA_SUPERLU_MT;
  s->holdable = dense && s->nhold < n;
  if (s->holdable) {
    s->live = malloc(sizeof(int) * (size_t)(n - s->nhold));
    s->fy = malloc(sizeof(double) * (size_t)n);
    s->fyp = calloc((size_t)n, sizeof(double));
    s->fr = malloc(sizeof(double) * (size_t)n);
    s->fjac = malloc(sizeof(double) * (size_t)n * (size_t)n);
    if (!s->live || !s->fy || !s->fyp || !s->fr || !s->fjac) return fail(s, "malloc", -1);
  }
  if (holds(s, t0, y0, yp0)) {
    s->held = 1;
    s->nl = 0;
    for (int i = 0, h = 0; i < n; i++) {
      if (h < s->nhold && s->hold[h] == i) h++;
      else s->live[s->nl++] = i;
    }
    memcpy(s->fy, y0, sizeof(double) * (size_t)n);
    s->wscale = sqrt((double)s->nl / (double)n);
  }
  s->hit = 0;
  for (int i = 0; i < m->ny; i++) s->hit |= m->state_alg[i];
  s->msg[0] = '\0';
  SET(s, CALL(s, SUNContext_Create)(0, &s->ctx), "SUNContext_Create");
  CALL(s, SUNContext_ClearErrHandlers)(s->ctx); /* C never prints: flags are returned */
  n = s->nl; /* IDA's size from here on */
  s->y = CALL(s, N_VNew_Serial)(n, s->ctx);
  s->yp = CALL(s, N_VNew_Serial)(n, s->ctx);
  s->yi = CALL(s, N_VNew_Serial)(n, s->ctx);
  s->ypi = CALL(s, N_VNew_Serial)(n, s->ctx);
  if (!s->y || !s->yp || !s->yi || !s->ypi) return fail(s, "N_VNew_Serial", -1);
  if (s->held) {
    gather(s, y0, CALL(s, N_VGetArrayPointer)(s->y));
    gather(s, yp0, CALL(s, N_VGetArrayPointer)(s->yp));
  } else {
    memcpy(CALL(s, N_VGetArrayPointer)(s->y), y0, sizeof(double) * (size_t)n);
    memcpy(CALL(s, N_VGetArrayPointer)(s->yp), yp0, sizeof(double) * (size_t)n);
  }
  s->mem = CALL(s, IDACreate)(s->ctx);
  if (!s->mem) return fail(s, "IDACreate", -1);
  SET(s, CALL(s, IDAInit)(s->mem, res_fn, t0, s->y, s->yp), "IDAInit");
  SET(s, CALL(s, IDASetUserData)(s->mem, s), "IDASetUserData");
  s->rtol = rtol;
  s->atol = atol;
  if (s->hit || s->held)
    SET(s, CALL(s, IDAWFtolerances)(s->mem, weights), "IDAWFtolerances");
  else
    SET(s, CALL(s, IDASStolerances)(s->mem, rtol, atol), "IDASStolerances");
  s->band = mu >= 0 && ml >= 0;
  s->sparse = mu == PS_IDA_SPARSE ? 1 : mu == PS_IDA_SUPERLU_MT ? 2 : 0;
  /* SuperLU_MT's OpenMP (the wheel's own copy of libgomp, private to SUNDIALS) runs one
   * thread, set in the calling thread (the setting is per thread): IDA's sparse systems are
   * small next to a team's start-up, whose idle threads spin on a core another process of a
   * batch needs (A02, N = 40: 0.33 s alone, 1.8 s beside one busy process) */
  if (s->sparse == 2 && s->set_threads) s->set_threads(1);
  if (s->sparse) {
    if (s->sparse == 1 && !ps_ida_has_sparse(s))
      return fail(s, "the sparse LU (no SUNLinSolNewEmpty in this SUNDIALS build)", -1);
    if (s->sparse == 2 && !ps_ida_has_superlumt(s))
      return fail(s, "SuperLU_MT (not in this SUNDIALS build)", -1);
    s->map = map;
    s->ntrip = ntrip;
    s->colptr = colptr;
    s->rowind = rowind;
    s->nnz = nnz;
    s->A = CALL(s, SUNSparseMatrix)(n, n, nnz, 0, s->ctx);
    if (s->A && s->sparse == 1) {
      s->lu = ps_lu_new(n, colptr, rowind, colorder);
      s->LS = s->lu ? own_solver(s) : NULL;
    } else if (s->A) {
      s->LS = CALL(s, SUNLinSol_SuperLUMT)(s->y, s->A, 1, s->ctx);
    }
  } else if (s->band) {
    /* SUNBandMatrix stores mu + ml diagonals above the main one (room for the LU's fill),
     * even past n - 1: the layout kernel.band_map writes (checked on the matrix made) */
    long ldim = (long)mu + 2L * ml + 1;
    s->map = map;
    s->ntrip = ntrip;
    s->nstore = ldim * n;
    s->A = CALL(s, SUNBandMatrix)(n, mu, ml, s->ctx);
    if (s->A && CALL(s, SUNBandMatrix_LDim)(s->A) != ldim)
      return fail(s, "SUNBandMatrix (a storage layout other than mu + 2 ml + 1 rows)", -1);
    if (s->A) s->LS = CALL(s, SUNLinSol_Band)(s->y, s->A, s->ctx);
  } else {
    s->A = CALL(s, SUNDenseMatrix)(n, n, s->ctx);
    /* pysolver's own LU (SUNDIALS' dense solve, through its chain of divisions, calls and
     * column pointers, was a fifth of seed example 3's run; 1.02-1.46x faster runs from 6 to
     * 173 states) */
    s->own_dense = s->slot[0] >= 0 && mu != PS_IDA_SUNDIALS_DENSE;
    if (s->own_dense) {
      s->rpiv = malloc(sizeof(double) * (size_t)n);
      s->piv = malloc(sizeof(int) * (size_t)n);
      s->inv = n <= PS_INV_MAX ? malloc(2 * sizeof(double) * (size_t)n * (size_t)n) : NULL;
      if (!s->rpiv || !s->piv || (n <= PS_INV_MAX && !s->inv)) return fail(s, "malloc", -1);
    }
    if (s->A && s->own_dense) s->LS = own_solver_with(s, (void*)dense_setup, (void*)dense_solve);
    else if (s->A) s->LS = CALL(s, SUNLinSol_Dense)(s->y, s->A, s->ctx);
  }
  if (!s->A || !s->LS)
    return fail(s, s->sparse ? "SUNSparseMatrix" : s->band ? "SUNBandMatrix" : "SUNDenseMatrix",
                -1);
  SET(s, CALL(s, IDASetLinearSolver)(s->mem, s->LS, s->A), "IDASetLinearSolver");
  SET(s, CALL(s, IDASetJacFn)(s->mem, jac_fn), "IDASetJacFn");
  SET(s, CALL(s, IDASetMaxNumSteps)(s->mem, mxsteps), "IDASetMaxNumSteps");
  int nalg = 0;
  for (int i = 0; i < m->ny; i++) nalg += m->state_alg[i];
  if (nalg > 0) {
    /* reactions are algebraic: out of the error test (IDA copies id) */
    N_Vector id = CALL(s, N_VNew_Serial)(n, s->ctx);
    if (!id) return fail(s, "N_VNew_Serial", -1);
    double* v = CALL(s, N_VGetArrayPointer)(id);
    for (int i = 0; i < n; i++) v[i] = m->state_alg[s->held ? s->live[i] : i] ? 0.0 : 1.0;
    int flag = CALL(s, IDASetId)(s->mem, id);
    CALL(s, N_VDestroy)(id);
    if (flag < 0) return fail(s, "IDASetId", flag);
    SET(s, CALL(s, IDASetSuppressAlg)(s->mem, 1), "IDASetSuppressAlg");
  }
  memset(s->acc, 0, sizeof(s->acc));
  memset(s->win, 0, sizeof(s->win));
  s->win_h[0] = s->win_h[1] = 0.0;
  s->auto_eta = 0.0;
  s->limited_at = s->first_limited = 0;
  s->bounds[0] = s->base[0] = hmax;
  s->bounds[1] = s->base[1] = hmin;
  s->bounds[2] = s->base[2] = h0;
  if (hmax > 0) SET(s, CALL(s, IDASetMaxStep)(s->mem, hmax), "IDASetMaxStep");
  if (hmin > 0) SET(s, CALL(s, IDASetMinStep)(s->mem, hmin), "IDASetMinStep");
  if (h0 > 0) SET(s, CALL(s, IDASetInitStep)(s->mem, h0), "IDASetInitStep");
  if (m->nsensor > 0) {
    SET(s, CALL(s, IDARootInit)(s->mem, m->nsensor, root_fn), "IDARootInit");
    SET(s, CALL(s, IDASetRootDirection)(s->mem, (int*)rootdir), "IDASetRootDirection");
    SET(s, CALL(s, IDASetNoInactiveRootWarn)(s->mem), "IDASetNoInactiveRootWarn");
  }
  return PS_OK;
}

int ps_ida_tune(psIDA* s, double eta_max, double nlconv, double auto_eta) {
  if (eta_max > 0) SET(s, CALL(s, IDASetEtaMax)(s->mem, eta_max), "IDASetEtaMax");
  if (nlconv > 0) SET(s, CALL(s, IDASetNonlinConvCoef)(s->mem, nlconv), "IDASetNonlinConvCoef");
  s->auto_eta = eta_max > 0 ? 0.0 : auto_eta;
  return PS_OK;
}

/* IDA's counters since the last (re)start: steps, nres, njac, netf, ncfn, ngevals. */
static void ida_counters(psIDA* s, long* c) {
  memset(c, 0, 6 * sizeof(long));
  if (!s->mem) return;
  CALL(s, IDAGetNumSteps)(s->mem, c + 0);
  CALL(s, IDAGetNumResEvals)(s->mem, c + 1);
  CALL(s, IDAGetNumJacEvals)(s->mem, c + 2);
  CALL(s, IDAGetNumErrTestFails)(s->mem, c + 3);
  CALL(s, IDAGetNumNonlinSolvConvFails)(s->mem, c + 4);
  CALL(s, IDAGetNumGEvals)(s->mem, c + 5);
}

/* ps_ida_reinit once the start is known to suit the held states (holds). */
static int reinit(psIDA* s, double t0, const double* y0, const double* yp0) {
  int n = s->m->ny;
  if (s->held) {
    /* the held states keep the values of this start */
    memcpy(s->fy, y0, sizeof(double) * (size_t)n);
    gather(s, y0, CALL(s, N_VGetArrayPointer)(s->y));
    gather(s, yp0, CALL(s, N_VGetArrayPointer)(s->yp));
  } else {
    memcpy(CALL(s, N_VGetArrayPointer)(s->y), y0, sizeof(double) * (size_t)n);
    memcpy(CALL(s, N_VGetArrayPointer)(s->yp), yp0, sizeof(double) * (size_t)n);
  }
  /* IDA's counters restart from zero: keep those of the run so far */
  long c[6];
  ida_counters(s, c);
  for (int i = 0; i < 6; i++) s->acc[i] += c[i];
  memset(s->win, 0, sizeof(s->win));
  s->win_h[0] = s->win_h[1] = 0.0;
  if (s->lu) ps_lu_forget(s->lu);
  return CALL(s, IDAReInit)(s->mem, t0, s->y, s->yp);
}

int ps_ida_reinit(psIDA* s, double t0, const double* y0, const double* yp0) {
  /* a held integration's restart must be at rest in the held states */
  if (s->held && !holds(s, t0, y0, yp0)) {
    snprintf(s->msg, sizeof(s->msg), "a restart moves a state this integration holds");
    return PS_IDA_HELD;
  }
  return reinit(s, t0, y0, yp0);
}

int ps_ida_solve(psIDA* s, double tout, double tstop, int onestep, double* tret, double* y,
                 double* yp, int* rootsfound) {
  /* constraints hold at the steps, not on IDA's interpolant between them: with reactions,
   * every requested time is a step's end; one the last step already passed (a print time a
   * rounding error after the restart it began at) is interpolated, as without reactions */
  if (s->hit && !onestep && tout < tstop) {
    sunrealtype tn = tout;
    CALL(s, IDAGetCurrentTime)(s->mem, &tn);
    tstop = tout < tn ? tstop : tout;
  }
  int flag = CALL(s, IDASetStopTime)(s->mem, tstop);
  if (flag < 0) return flag;
  flag = CALL(s, IDASolve)(s->mem, tout, tret, s->y, s->yp, onestep ? 2 : 1);
  put_full(s, s->y, y, s->fy);
  put_full(s, s->yp, yp, s->fyp);
  if (flag == 2 && rootsfound) CALL(s, IDAGetRootInfo)(s->mem, rootsfound);
  return flag;
}

int ps_ida_interpolate(psIDA* s, double t, double* y, double* yp) {
  int flag = CALL(s, IDAGetSolution)(s->mem, t, s->yi, s->ypi);
  if (flag < 0) return flag;
  put_full(s, s->yi, y, s->fy);
  put_full(s, s->ypi, yp, s->fyp);
  return 0;
}

static void put_full(psIDA* s, N_Vector v, double* out, const double* full) {
  const double* a = CALL(s, N_VGetArrayPointer)(v);
  if (!s->held) {
    memcpy(out, a, sizeof(double) * (size_t)s->nl);
    return;
  }
  memcpy(out, full, sizeof(double) * (size_t)s->m->ny);
  scatter(s, a, out);
}

int ps_ida_hold(psIDA* s, const int* hold, int nhold) {
  free(s->hold);
  s->hold = NULL;
  s->nhold = 0;
  if (nhold <= 0) return 0;
  s->hold = malloc(sizeof(int) * (size_t)nhold);
  if (!s->hold) return -1;
  memcpy(s->hold, hold, sizeof(int) * (size_t)nhold);
  s->nhold = nhold;
  return 0;
}

int ps_ida_held(const psIDA* s) { return s->held ? s->nhold : 0; }


int ps_ida_breaks(psIDA* s, const double* times, int n, double* work, int* piv) {
  free(s->brk);
  s->brk = NULL;
  s->nbrk = s->kbrk = 0;
  s->bwork = work;
  s->bpiv = piv;
  if (n <= 0) return 0;
  s->brk = malloc(sizeof(double) * (size_t)n);
  if (!s->brk) return -1;
  memcpy(s->brk, times, sizeof(double) * (size_t)n);
  s->nbrk = n;
  return 0;
}

long ps_ida_inverse_solves(const psIDA* s) { return s->ninv; }

void ps_ida_set_stream(psIDA* s, psStream* st) { s->stream = st; }

/* Write the request channels of output rows k0..k1-1 (and stream the rows). */
/* Stream rows k0..k1-1 (times tout, request channels req_out). */
static void stream_rows(psIDA* s, int k0, int k1, const double* tout, const double* req_out) {
  int nout = s->m->nout > 0 ? s->m->nout : 1;
  /* a failed write ends the streaming, not the run: the rows are kept in memory */
  if (s->stream && k1 > k0 &&
      ps_stream_rows(s->stream, tout + k0, req_out + (long)k0 * nout, k1 - k0, nout,
                     s->m->nuser > 0) != 0)
    s->stream = NULL;
}

/* Rows k0..k1-1: their accelerations and reactions made exact (a scene with reactions), then
 * their request channels, without streaming them. Returns the first row a user routine failed
 * at (a REQSUB, a VARSUB only a request reads: the run ends at that row, which is not kept),
 * else k1. */
static int row_channels(psIDA* s, int k0, int k1, const double* tout, double* y_out,
                        double* yp_out, double* req_out) {
  int n = s->m->ny, before = s->d->user_error;
  for (int k = k0; k < k1; k++) {
    /* the row's accelerations and reactions exact at its state (ps_row_exact) */
    if (s->d->rows)
      ps_row_exact(s->m, s->d, s->d->rows, tout[k], y_out + (long)k * n, yp_out + (long)k * n);
    if (s->m->nout > 0)
      ps_outputs(s->m, s->d, tout[k], y_out + (long)k * n, yp_out + (long)k * n,
                 req_out + (long)k * s->m->nout);
    if (s->d->user_error && !before) return k;
  }
  return k1;
}

/* Write the request channels of output rows k0..k1-1 and stream the rows; returns the rows
 * kept's end (row_channels). */
static int row_outputs(psIDA* s, int k0, int k1, const double* tout, double* y_out,
                       double* yp_out, double* req_out) {
  int end = row_channels(s, k0, k1, tout, y_out, yp_out, req_out);
  stream_rows(s, k0, end, tout, req_out);
  return end;
}

int ps_ida_outputs(psIDA* s, const double* tout, int nout, double tstop, int fresh,
                   double* y_out, double* yp_out, double* req_out, int* nreached, double* tret,
                   int* rootsfound) {
  int n = s->m->ny, flag = 0, k = 0;
  *nreached = 0;
  if (fresh && nout > 0) {
    /* the first step of a (re)start, taken into row 0 */
    flag = ps_ida_solve(s, tstop, tstop, 1, tret, y_out, yp_out, rootsfound);
    if (flag < 0 || flag == 2) return flag;
    double tn = *tret;
    int m = 0;
    while (m < nout && tout[m] <= tn) m++;
    /* an output time at the step's end is the step itself; earlier ones are interpolated */
    int last = m > 0 && tout[m - 1] == tn ? m - 1 : m;
    if (last < m && last > 0) {
      memcpy(y_out + (long)last * n, y_out, sizeof(double) * (size_t)n);
      memcpy(yp_out + (long)last * n, yp_out, sizeof(double) * (size_t)n);
    }
    for (k = 0; k < last; k++) {
      flag = ps_ida_interpolate(s, tout[k], y_out + (long)k * n, yp_out + (long)k * n);
      if (flag < 0) return flag;
    }
    *nreached = k = row_outputs(s, 0, m, tout, y_out, yp_out, req_out);
    *tret = k < m ? tout[k] : tn;      /* the run ends at a row a routine failed at */
    if (k < m) return PS_IDA_USER;
  }
  for (; k < nout; k++) {
    flag = ps_ida_solve(s, tout[k], tstop, 0, tret, y_out + (long)k * n, yp_out + (long)k * n,
                        rootsfound);
    if (flag < 0 || flag == 2) break;
    if (row_outputs(s, k, k + 1, tout, y_out, yp_out, req_out) == k) {
      *tret = tout[k];
      flag = PS_IDA_USER;
      break;
    }
    *nreached = k + 1;
  }
  if (s->stream && ps_stream_flush(s->stream) != 0) s->stream = NULL;
  return flag;
}

int ps_ida_rerun(psIDA* s, double t0, const double* y0, const double* yp0) {
  s->kbrk = breaks_after(s, t0);
  if (!s->mem || s->limited_at || s->sparse == 2) return 1;
  /* a start that can hold states this integration does not, or the other way round */
  if (s->holdable && holds(s, t0, y0, yp0) != s->held) return 1;
  if (memcmp(s->bounds, s->base, sizeof(s->bounds)) != 0 &&
      ps_ida_bounds(s, s->base[0], s->base[1], s->base[2]) != 0)
    return 1;
  int flag = reinit(s, t0, y0, yp0);   /* holds() was checked above */
  memset(s->acc, 0, sizeof(s->acc));
  s->first_limited = 0;
  return flag;
}

int ps_ida_bounds(psIDA* s, double hmax, double hmin, double h0) {
  /* 0 is IDA's default for each: no bound, no bound, its own first step */
  int flag = CALL(s, IDASetMaxStep)(s->mem, hmax);
  if (flag >= 0) flag = CALL(s, IDASetMinStep)(s->mem, hmin);
  if (flag >= 0) flag = CALL(s, IDASetInitStep)(s->mem, h0);
  /* a step-growth limit auto_eta switched on goes, as with a new IDA object */
  if (flag >= 0 && s->limited_at) {
    flag = CALL(s, IDASetEtaMax)(s->mem, PS_IDA_ETA_MAX_DEFAULT);
    s->limited_at = 0;
  }
  if (flag < 0) {
    snprintf(s->msg, sizeof(s->msg), "could not set IDA's step bounds: flag %d", flag);
    return -1;
  }
  s->bounds[0] = hmax;
  s->bounds[1] = hmin;
  s->bounds[2] = h0;
  return 0;
}

void ps_ida_stats(psIDA* s, long* out) {
  ida_counters(s, out);
  for (int i = 0; i < 6; i++) out[i] += s->acc[i];
  out[6] = s->first_limited;
}

/* Run every LoadControl update due at t (ps_control_next(c) <= t), in task order. Returns 1
 * when one ran, 0 when none was due, -1 when one failed (ctl: its index and code). */
static int updates_due(psIDA* s, const psRestart* r, psControl* const* c, int nctl, double t,
                       double* y, double* yp, int* ctl) {
  int any = 0;
  for (int i = 0; i < nctl; i++) {
    if (ps_control_next(c[i]) > t) continue;
    int rc = ps_control_update(s->m, s->d, r, c[i], t, y, yp);
    if (rc != PS_OK) {
      ctl[0] = i;
      ctl[1] = rc;
      return -1;
    }
    any = 1;
  }
  return any;
}

/* Remember the converged step (t, y, yp) with everything an action may change, as the
 * general driver's Run.remember_step (onestep mode): the oldest of PS_SNAPS goes. */
static void remember(psIDA* s, psSensors* S, double t, const double* y, const double* yp) {
  const psModel* m = s->m;
  psData* d = s->d;
  int n = m->ny, ns = S->n, i;
  if (S->nsnap < PS_SNAPS) {
    i = (S->snap_first + S->nsnap++) % PS_SNAPS;
  } else {
    i = S->snap_first;
    S->snap_first = (S->snap_first + 1) % PS_SNAPS;
  }
  S->snap_t[i] = t;
  S->snap_hmax[i] = s->bounds[0];
  S->snap_interval[i] = S->interval;
  S->snap_anchor[i] = S->anchor;
  S->snap_nrearms[i] = S->nrearms;
  S->snap_records[i] = S->drained + S->nev;
  memcpy(S->snap_y + (long)i * n, y, sizeof(double) * (size_t)n);
  memcpy(S->snap_yp + (long)i * n, yp, sizeof(double) * (size_t)n);
  memcpy(S->snap_armed + (long)i * ns, d->sensor_armed, sizeof(int) * (size_t)ns);
  memcpy(S->snap_side + (long)i * ns, d->sensor_side, sizeof(double) * (size_t)ns);
  memcpy(S->snap_verbose + (long)i * ns, S->verbose_on, sizeof(int) * (size_t)ns);
  memcpy(S->snap_senval + (long)i * S->nsenval, d->senval, sizeof(double) * (size_t)S->nsenval);
  /* the LoadControl tasks: schedule, law and log count, and the law's last loads */
  for (int k = 0, at = 0; k < S->nctl; k++) {
    const psControl* c = S->ctl[k];
    S->snap_ctl[(long)i * S->nctl + k] = *c;
    memcpy(S->snap_loads + (long)i * S->nloads + at, c->law.loads,
           sizeof(double) * (size_t)c->law.window);
    at += c->law.window;
  }
}

/* A cold restart of IDA at (t, y, yp) with the largest and smallest steps hmax and hmin and
 * the first step `first` (0: the run's own), as the general driver's Run.start (which, in
 * onestep mode, starts the remembered steps again from this one). Returns 0, or -1 when the
 * bounds cannot be set. */
static int restart(psIDA* s, psSensors* S, double t, const double* y, const double* yp,
                   double hmax, double hmin, double first, int* fresh, long* nrestarts) {
  double b[3] = {hmax, hmin, first > 0 ? first : s->base[2]};
  if ((b[0] != s->bounds[0] || b[1] != s->bounds[1] || b[2] != s->bounds[2]) &&
      ps_ida_bounds(s, b[0], b[1], b[2]))
    return -1;
  s->d->last_t = t; /* restarts are not step attempts (see ps_residual) */
  if (ps_ida_reinit(s, t, y, yp) == PS_IDA_HELD) return -1;
  *fresh = 1;
  (*nrestarts)++;
  if (S && S->nzc) {
    S->nsnap = 0;
    remember(s, S, t, y, yp);
  }
  return 0;
}

/* Act at t as the general driver does (Run.act_due): the updates due, then a restart (also
 * at a break of a function of time: solve/breaks.py's TimeBreaks). */
static int act(psIDA* s, const psRestart* r, psControl* const* c, int nctl, psSensors* S,
               double t, double* y, double* yp, int* fresh, long* nrestarts, int* ctl) {
  int due = updates_due(s, r, c, nctl, t, y, yp, ctl);
  if (due < 0) return PS_IDA_CONTROL_FAILED;
  if (s->kbrk < s->nbrk && s->brk[s->kbrk] <= t) {
    /* the rates just past the break (TimeBreaks.on_time): IDA restarts with a force's value
     * after its jump; these evaluations are not step attempts */
    double tp = t + PS_BREAK_SIDE * fmax(1.0, fabs(t));
    due = 1;
    s->kbrk = breaks_after(s, t);
    s->d->last_t = tp;
    if (ps_consistent_yp(s->m, s->d, tp, y, yp, s->bwork, s->bpiv, 4) != PS_OK) {
      if (s->d->user_error) return PS_IDA_USER;
      for (int i = 0; i < s->m->ny; i++) yp[i] = NAN;
    }
  }
  if (due && restart(s, S, t, y, yp, s->bounds[0], s->bounds[1], 0.0, fresh, nrestarts))
    return PS_IDA_BOUNDS;
  return 0;
}

/* Where the C loop writes its rows: the output times (k of nout used), the rows (r of cap
 * written) and their arrays, and the rows streamed (those before `streamed`: the last row is
 * held back, for a row at an event may replace it). */
typedef struct Rows {
  const double* tout;
  int nout, k;
  double *t_out, *y_out, *yp_out, *req_out;
  int cap, r, streamed;
  psSensors* S; /* told of every row (verbose sensors), or NULL */
  int hold;     /* 1: rows are streamed only before the oldest remembered step           */
  int first;    /* the run's first row (-row0): a restore may take rows back down to it  */
} Rows;

/* Write row o->r at time tm with state (y, yp) (NULL: there already) and its request
 * channels, streaming the rows before it. Returns PS_IDA_USER, the row not kept, when a user
 * routine failed at it, else 0. */
static int put_row(psIDA* s, Rows* o, double tm, const double* y, const double* yp) {
  int n = s->m->ny;
  if (!o->hold) {
    stream_rows(s, o->streamed, o->r, o->t_out, o->req_out);
    if (o->r > o->streamed) o->streamed = o->r;
  }
  o->t_out[o->r] = tm;
  if (y) memcpy(o->y_out + (long)o->r * n, y, sizeof(double) * (size_t)n);
  if (yp) memcpy(o->yp_out + (long)o->r * n, yp, sizeof(double) * (size_t)n);
  if (row_channels(s, o->r, o->r + 1, o->t_out, o->y_out, o->yp_out, o->req_out) == o->r)
    return PS_IDA_USER;
  if (o->S && o->S->nverbose)
    ps_sensors_verbose(s->m, s->d, o->S, tm, o->y_out + (long)o->r * n,
                       o->yp_out + (long)o->r * n);
  o->r++;
  return 0;
}

/* Whether a verbose sensor is active: the general loop then writes rows one at a time. */
static int watching(const psSensors* S) {
  for (int k = 0; S && k < S->n; k++)
    if (S->verbose_on[k]) return 1;
  return 0;
}

/* Write the rows of the output times that lie at or before t (Printer.emit_due): the current
 * state at t itself, IDA's interpolant over its last step before it. Returns 0 or IDA's flag
 * of a failed interpolation. */
static int emit_due(psIDA* s, Rows* o, double t, const double* y, const double* yp) {
  int n = s->m->ny;
  for (; o->k < o->nout && o->tout[o->k] <= t; o->k++) {
    int flag = o->tout[o->k] == t ? 0 : ps_ida_interpolate(s, o->tout[o->k],
                                                            o->y_out + (long)o->r * n,
                                                            o->yp_out + (long)o->r * n);
    if (flag < 0) return flag;
    flag = o->tout[o->k] == t ? put_row(s, o, t, y, yp)
                              : put_row(s, o, o->tout[o->k], NULL, NULL);
    if (flag) return flag;
  }
  return 0;
}

/* The sensors' instant at (t, y, yp) after IDA's roots, carried out as the general driver's
 * Run.apply: a restart, then a row at the instant (Printer.emit: it replaces a row at the same
 * time), then the end of the run, of the command, or a new print interval. Returns 0 to go on
 * or one of ps_ida_controlled's codes. */
static int instant(psIDA* s, psSensors* S, Rows* o, double t, double tend, double* y,
                   double* yp, int* fresh, long* nrestarts) {
  long base = S->rows;
  S->rows += o->r;  /* the rows before the instant, as the general loop counts them */
  S->tend = tend;
  int rc = ps_sensors_roots(s->m, s->d, S, S->roots, t, y, yp);
  S->rows = base;
  if (rc == PS_SE_BUDGET) return PS_IDA_BUDGET;
  if (rc == PS_SE_USER) return PS_IDA_USER;
  if (rc == PS_SE_RESTART) return PS_IDA_SENSOR_RESTART;
  if (rc != PS_OK) return PS_IDA_CHATTER;
  if (S->restore) return PS_IDA_RESTORED; /* the caller goes back (zc_restore) */
  /* a new largest step or a first step restarts too (Sensors._fire, Run.apply); the bounds
   * of the run before zero-crossing searches come back when the last one ends */
  double hmax = S->hmax > 0 ? S->hmax : S->back ? S->back_hmax : s->bounds[0];
  double hmin = S->back ? S->back_hmin : s->bounds[1];
  if ((S->restart || S->hmax > 0 || S->first_step > 0) &&
      restart(s, S, t, y, yp, hmax, hmin, S->first_step, fresh, nrestarts))
    return PS_IDA_BOUNDS;
  S->emitted = 0;
  if (S->emit || S->halt >= 0 || S->ret >= 0) {
    if (o->r > o->streamed && o->t_out[o->r - 1] == t) {
      /* it replaces the last row, which is not streamed yet */
      o->r--;
      S->emitted = 2;
    } else {
      S->emitted = 1;
    }
    if (put_row(s, o, t, y, yp)) return PS_IDA_USER;
  }
  if (S->halt >= 0) return PS_IDA_HALTED;
  if (S->ret >= 0) return PS_IDA_RETURN;
  if (S->dt > 0) return PS_IDA_REGRID;
  /* room for the next instant's events and row, and the log lines of the rows left */
  long lines = (long)S->nverbose * (o->nout - o->k + 2);
  if (S->nev + S->n + lines > S->cap || o->r + (o->nout - o->k) + 1 > o->cap)
    return PS_IDA_DRAIN;
  return 0;
}

/* Back to the last converged step before a zero_crossing sensor's first firing at *t
 * (Sensors._restore_and_shrink, Run.restore_last_step): the state, the sensors' state and
 * records, the largest step and print interval as they were there, the rows after it taken
 * back; the bounds (kept for when the searches end) shrunk by S->restore_zc around the size of
 * the last step, a log line for each sensor searched (S->now), and a restart there. Returns
 * PS_IDA_RESTORED, or PS_IDA_BOUNDS when the bounds cannot be set. */
static int zc_restore(psIDA* s, psSensors* S, Rows* o, double* t, double* y, double* yp,
                      int* fresh, long* nrestarts) {
  psData* d = s->d;
  int n = s->m->ny, ns = S->n;
  int last = (S->snap_first + S->nsnap - 1) % PS_SNAPS;
  double tp = S->snap_t[last], hmax = S->snap_hmax[last];
  /* the "current h_max": the bound then, else the size of the last step completed before */
  double current = hmax > 0      ? hmax
                   : S->nsnap >= 2 ? tp - S->snap_t[(last + PS_SNAPS - 1) % PS_SNAPS]
                                   : *t - tp;
  *t = tp;
  memcpy(y, S->snap_y + (long)last * n, sizeof(double) * (size_t)n);
  memcpy(yp, S->snap_yp + (long)last * n, sizeof(double) * (size_t)n);
  memcpy(d->sensor_armed, S->snap_armed + (long)last * ns, sizeof(int) * (size_t)ns);
  memcpy(d->sensor_side, S->snap_side + (long)last * ns, sizeof(double) * (size_t)ns);
  memcpy(S->verbose_on, S->snap_verbose + (long)last * ns, sizeof(int) * (size_t)ns);
  memcpy(d->senval, S->snap_senval + (long)last * S->nsenval,
         sizeof(double) * (size_t)S->nsenval);
  S->nrearms = S->snap_nrearms[last];
  S->interval = S->snap_interval[last];
  S->anchor = S->snap_anchor[last];
  for (int k = 0, at = 0; k < S->nctl; k++) {
    psControl* c = (psControl*)S->ctl[k];
    *c = S->snap_ctl[(long)last * S->nctl + k];
    memcpy(c->law.loads, S->snap_loads + (long)last * S->nloads + at,
           sizeof(double) * (size_t)c->law.window);
    at += c->law.window;
  }
  long keep = S->snap_records[last];
  if (keep >= S->drained) {
    S->nev = keep - S->drained;
  } else { /* some were handed over already: the caller takes them back */
    S->nev = 0;
    S->undo = keep;
  }
  while (o->r > o->first && o->t_out[o->r - 1] > tp) o->r--;
  if (!S->saved) {
    S->saved = 1;
    S->saved_hmax = hmax;
    S->saved_hmin = s->bounds[1];
  }
  double new_hmax = S->restore_zc * current, new_hmin = S->restore_zc * s->bounds[1];
  for (int k = 0; k < ns; k++) {
    if (!S->now[k]) continue;
    S->zc_pending[k] = 1;
    if (S->nev >= S->cap) continue;
    S->ev_time[S->nev] = tp;
    S->ev_value[S->nev] = new_hmax;
    S->ev_sensor[S->nev++] = -1 - ns - k;
  }
  /* a remembered step at a break was taken after its restart: the breaks after tp are ahead */
  s->kbrk = breaks_after(s, tp);
  if (restart(s, S, tp, y, yp, new_hmax, new_hmin, 0.0, fresh, nrestarts)) return PS_IDA_BOUNDS;
  return PS_IDA_RESTORED;
}

/* Stream the rows no action can take back any more: those before the oldest remembered step
 * (onestep mode), as the general loop's Printer.flush_stream. */
static void flush_held(psIDA* s, const psSensors* S, Rows* o) {
  double oldest = S->snap_t[S->snap_first];
  int k = o->streamed;
  while (k < o->r && o->t_out[k] < oldest) k++;
  stream_rows(s, o->streamed, k, o->t_out, o->req_out);
  if (k > o->streamed) o->streamed = k;
}

int ps_ida_controlled(psIDA* s, const psRestart* r, psControl* const* c, int nctl, psSensors* S,
                      const double* tout, int nout, double tend, double* t, double* y,
                      double* yp, int* fresh, int cap, int row0, int held, double* t_out,
                      double* y_out, double* yp_out, double* req_out, int* nreached,
                      int* nused, int* nstreamed, double* tret, long* nrestarts, int* ctl) {
  int n = s->m->ny, flag = 0;
  size_t row = sizeof(double) * (size_t)n;
  int* roots = S ? S->roots : NULL;
  /* zero_crossing sensors: one step at a time, every converged step remembered */
  int onestep = S && S->nzc > 0;
  if (S) { /* the tasks are remembered with the steps where the caller made room */
    S->ctl = c;
    S->nctl = S->snap_ctl ? nctl : 0;
  }
  Rows o = {tout, nout, 0, t_out, y_out, yp_out, req_out, cap, 0, -held, S, onestep, -row0};
  if (onestep && S->nsnap == 0) remember(s, S, *t, y, yp); /* the run's start (Run.start) */
  *tret = *t;
  int code = 0;
  while (o.k < nout) {
    if (ps_interrupted()) break;
    code = act(s, r, c, nctl, S, *t, y, yp, fresh, nrestarts, ctl);
    if (code) break;
    s->d->bad_kind = 0;
    /* IDA stops exactly at the next update, or the command's end */
    double tstop = tend;
    for (int i = 0; i < nctl; i++) tstop = fmin(tstop, ps_control_next(c[i]));
    if (s->kbrk < s->nbrk) tstop = fmin(tstop, s->brk[s->kbrk]);
    if (onestep) flush_held(s, S, &o);
    if (*fresh || onestep) {
      /* the first step of a (re)start, or every step in onestep mode, toward the stop */
      flag = ps_ida_solve(s, tstop, tstop, 1, tret, y, yp, roots);
      *fresh = 0;
    } else if (tout[o.k] <= tstop) {
      /* the output times up to the stop (a root ends the batch: row r holds its state);
       * one at a time while a verbose sensor is active, as the general loop */
      int one = watching(S);
      for (; o.k < nout && tout[o.k] <= tstop; o.k++) {
        flag = ps_ida_solve(s, tout[o.k], tstop, 0, tret, y_out + (long)o.r * n,
                            yp_out + (long)o.r * n, roots);
        if (flag < 0 || flag == 2) break;
        if (put_row(s, &o, tout[o.k], NULL, NULL)) {
          *tret = tout[o.k]; /* the row a routine failed at ends the run */
          flag = PS_IDA_USER;
          break;
        }
        if (one) {
          o.k++;
          break;
        }
      }
      if (flag >= 0) {
        int j = flag == 2 ? o.r : o.r - 1;
        memcpy(y, y_out + (long)j * n, row);
        memcpy(yp, yp_out + (long)j * n, row);
      }
    } else {
      flag = ps_ida_solve(s, tstop, tstop, 0, tret, y, yp, roots);
    }
    if (flag < 0) {
      code = flag;
      break;
    }
    *t = *tret;
    int root = flag == 2;
    code = emit_due(s, &o, *t, y, yp);
    if (code) {
      *tret = o.tout[o.k]; /* the print time whose row failed (Printer.emit_due's Step) */
      break;
    }
    if (root) {
      code = instant(s, S, &o, *t, tend, y, yp, fresh, nrestarts);
      if (code == PS_IDA_RESTORED) code = zc_restore(s, S, &o, t, y, yp, fresh, nrestarts);
      if (code) break;
    } else if (onestep && *t > S->snap_t[(S->snap_first + S->nsnap - 1) % PS_SNAPS]) {
      remember(s, S, *t, y, yp);
    }
  }
  /* the rows before the last (or, in onestep mode, before the oldest remembered step) go out
   * now */
  if (onestep) {
    flush_held(s, S, &o);
  } else {
    stream_rows(s, o.streamed, o.r - 1, t_out, req_out);
    if (o.r - 1 > o.streamed) o.streamed = o.r - 1;
  }
  if (s->stream && ps_stream_flush(s->stream) != 0) s->stream = NULL;
  *nreached = o.r;
  *nused = o.k;
  *nstreamed = o.streamed;
  if (code || ps_interrupted()) return code;
  /* the command's end: the updates due there */
  return act(s, r, c, nctl, S, *t, y, yp, fresh, nrestarts, ctl);
}
