/* Sparse LU factorization of IDA's iteration matrices (compressed sparse columns, a pattern
 * fixed for the whole integration).
 *
 * A left-looking factorization (Gilbert and Peierls: each column is a sparse triangular solve
 * whose nonzero pattern a depth-first search finds) with threshold partial pivoting that
 * prefers the diagonal, in a fill-reducing column order given by the caller. IDA asks for a
 * new factorization of a matrix with the same pattern and slowly changing values every few
 * steps, so after the first factorization ps_lu_refactor replays the same pivots and the same
 * patterns of L and U with no search at all (KLU's refactorization), and falls back to a full
 * factorization only when a pivot has become small next to its column. Every array is
 * allocated by ps_lu_new; a full factorization whose fill outgrows the first estimate
 * (pivots that changed) enlarges L or U, the one allocation after set-up.
 *
 * Entries of the pattern whose value is exactly zero are left out of the factorization's
 * pattern until they are nonzero once (since the last ps_lu_forget): a mechanism that moves in
 * a plane has half its iteration matrix's structural entries zero for the whole run (the
 * out-of-plane couplings; IFToMM A02: 11,901 of 23,770), and a fill grown through them is
 * made of zeros (A02: 51,348 entries of L and U with them; without, about 22,000 at a run's
 * first factorization and 27,000 at its end). A replay that meets a nonzero outside the
 * pattern factors afresh, with that entry in.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

/* Threshold partial pivoting: the diagonal entry is the pivot when it is at least this
 * fraction of the largest candidate in its column. */
#define PS_LU_DIAGONAL 0.1

/* A replayed pivot smaller than this fraction of the largest entry below it in its column
 * sends ps_lu_refactor back to a full factorization. */
#define PS_LU_REPLAY 1e-3

struct psLU {
  int n;            /* order of the matrix                                          */
  const int* Ap;    /* (n + 1) column pointers of the pattern (not owned)           */
  const int* Ai;    /* (nnz) row indices of the pattern (not owned)                 */
  int* q;           /* (n) step k factors column q[k]                               */
  int* pinv;        /* (n) row i is the pivot of step pinv[i]                       */
  int* Lp;          /* (n + 1) column pointers of L                                 */
  int* Li;          /* (lcap) rows of L in pivot order, the unit diagonal first     */
  double* Lx;       /* (lcap) values of L                                           */
  int* Up;          /* (n + 1) column pointers of U                                 */
  int* Ui;          /* (ucap) rows of U in the order the solve needs, diagonal last */
  double* Ux;       /* (ucap) values of U                                           */
  long lcap, ucap;  /* capacity of L and U                                          */
  double* x;        /* (n) dense column, zero between columns                       */
  double* y;        /* (n) work of ps_lu_solve                                      */
  int* xi;          /* (n) the reach of a column, in topological order              */
  int* stack;       /* (n) depth-first search stack                                 */
  int* pstack;      /* (n) where each stacked node resumes                          */
  int* mark;        /* (n) column stamp of the rows visited                         */
  int* unseen;      /* (nnz) the entries left out by the last factorization ...      */
  long nunseen;     /* ... and how many: all a replay checks                         */
  unsigned char* seen; /* (nnz) 1: the entry was nonzero in a factorization since the
                          last ps_lu_forget; the others are left out of the pattern   */
  int valid;        /* 1: pivots and patterns of a factorization are in place       */
  long counts[3];   /* full factorizations, replays, replays that fell back         */
};

void ps_lu_free(psLU* f) {
  if (!f) return;
  free(f->q);
  free(f->pinv);
  free(f->Lp);
  free(f->Li);
  free(f->Lx);
  free(f->Up);
  free(f->Ui);
  free(f->Ux);
  free(f->x);
  free(f->y);
  free(f->xi);
  free(f->stack);
  free(f->pstack);
  free(f->mark);
  free(f->seen);
  free(f->unseen);
  free(f);
}

psLU* ps_lu_new(int n, const int* colptr, const int* rowind, const int* colorder) {
  psLU* f = calloc(1, sizeof(*f));
  if (!f || n <= 0) {
    free(f);
    return NULL;
  }
  size_t sn = (size_t)n;
  long nnz = colptr[n];
  f->n = n;
  f->Ap = colptr;
  f->Ai = rowind;
  /* a first estimate of the fill; a factorization enlarges L or U when it needs to */
  f->lcap = f->ucap = 2 * nnz + n;
  f->q = malloc(sn * sizeof(int));
  f->pinv = malloc(sn * sizeof(int));
  f->Lp = calloc(sn + 1, sizeof(int));
  f->Up = calloc(sn + 1, sizeof(int));
  f->Li = malloc((size_t)f->lcap * sizeof(int));
  f->Lx = malloc((size_t)f->lcap * sizeof(double));
  f->Ui = malloc((size_t)f->ucap * sizeof(int));
  f->Ux = malloc((size_t)f->ucap * sizeof(double));
  f->x = calloc(sn, sizeof(double));
  f->y = calloc(sn, sizeof(double));
  f->xi = malloc(sn * sizeof(int));
  f->stack = malloc(sn * sizeof(int));
  f->pstack = malloc(sn * sizeof(int));
  f->mark = malloc(sn * sizeof(int));
  f->seen = calloc((size_t)(nnz > 0 ? nnz : 1), 1);
  f->unseen = malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof(int));
  if (!f->seen || !f->unseen || !f->q || !f->pinv || !f->Lp || !f->Up || !f->Li || !f->Lx || !f->Ui || !f->Ux || !f->x ||
      !f->y || !f->xi || !f->stack || !f->pstack || !f->mark) {
    ps_lu_free(f);
    return NULL;
  }
  for (int k = 0; k < n; k++) f->q[k] = colorder ? colorder[k] : k;
  return f;
}

/* Make room for `more` entries in L (which = 0) or U (1); 0 on success. */
static int reserve(psLU* f, int which, long used, long more) {
  long* cap = which ? &f->ucap : &f->lcap;
  if (used + more <= *cap) return 0;
  long want = 2 * (used + more);
  int** idx = which ? &f->Ui : &f->Li;
  double** val = which ? &f->Ux : &f->Lx;
  int* ni = realloc(*idx, (size_t)want * sizeof(int));
  if (!ni) return -1;
  *idx = ni;
  double* nv = realloc(*val, (size_t)want * sizeof(double));
  if (!nv) return -1;
  *val = nv;
  *cap = want;
  return 0;
}

/* The rows that the entries of column `col` of A in the pattern (f->seen) reach through the
 * columns of L factored so far (rows in the original numbering; a pivotal row leads to the
 * rows below the diagonal of its L column), written to xi[top..n-1] in topological order.
 * Returns top. */
static int reach(psLU* f, int col, int stamp) {
  int top = f->n;
  for (int p = f->Ap[col]; p < f->Ap[col + 1]; p++) {
    if (!f->seen[p]) continue;
    int start = f->Ai[p];
    if (f->mark[start] == stamp) continue;
    int head = 0;
    f->stack[0] = start;
    while (head >= 0) {
      int j = f->stack[head];
      int J = f->pinv[j];
      if (f->mark[j] != stamp) {
        f->mark[j] = stamp;
        f->pstack[head] = J < 0 ? 0 : f->Lp[J] + 1;
      }
      int end = J < 0 ? 0 : f->Lp[J + 1], pushed = 0;
      for (int p2 = f->pstack[head]; p2 < end; p2++) {
        int i = f->Li[p2];
        if (f->mark[i] == stamp) continue;
        f->pstack[head] = p2 + 1;
        f->stack[++head] = i;
        pushed = 1;
        break;
      }
      if (!pushed) {
        head--;
        f->xi[--top] = j;
      }
    }
  }
  return top;
}

int ps_lu_factor(psLU* f, const double* Ax) {
  int n = f->n;
  long lnz = 0, unz = 0;
  f->valid = 0;
  f->counts[0]++;
  for (int i = 0; i < n; i++) {
    f->pinv[i] = -1;
    f->mark[i] = -1;
  }
  f->nunseen = 0;
  for (long p = 0; p < f->Ap[n]; p++) {
    f->seen[p] |= Ax[p] != 0.0;
    if (!f->seen[p]) f->unseen[f->nunseen++] = (int)p;
  }
  for (int k = 0; k < n; k++) {
    int col = f->q[k];
    f->Lp[k] = (int)lnz;
    f->Up[k] = (int)unz;
    int top = reach(f, col, k);
    if (reserve(f, 0, lnz, n - top) || reserve(f, 1, unz, n - top)) return -1;
    /* x = L \ A(:, col) over the reach; rows of L are still in the original numbering */
    for (int p = f->Ap[col]; p < f->Ap[col + 1]; p++)
      if (f->seen[p]) f->x[f->Ai[p]] = Ax[p];
    for (int px = top; px < n; px++) {
      int j = f->xi[px], J = f->pinv[j];
      if (J < 0) continue;
      double xj = f->x[j];
      for (int p = f->Lp[J] + 1; p < f->Lp[J + 1]; p++) f->x[f->Li[p]] -= f->Lx[p] * xj;
    }
    /* the entries above the pivot go to U (in the order of the solve); pick the pivot */
    int ipiv = -1;
    double big = 0.0;
    for (int px = top; px < n; px++) {
      int j = f->xi[px];
      if (f->pinv[j] >= 0) {
        f->Ui[unz] = f->pinv[j];
        f->Ux[unz++] = f->x[j];
      } else if (fabs(f->x[j]) > big) {
        big = fabs(f->x[j]);
        ipiv = j;
      }
    }
    if (f->pinv[col] < 0 && fabs(f->x[col]) >= PS_LU_DIAGONAL * big && big > 0.0) ipiv = col;
    double pivot = ipiv >= 0 ? f->x[ipiv] : 0.0;
    if (!(fabs(pivot) > 0.0) || !isfinite(pivot)) {
      for (int px = top; px < n; px++) f->x[f->xi[px]] = 0.0;
      return k + 1;
    }
    f->Ui[unz] = k;
    f->Ux[unz++] = pivot;
    f->pinv[ipiv] = k;
    f->Li[lnz] = ipiv;
    f->Lx[lnz++] = 1.0;
    for (int px = top; px < n; px++) {
      int j = f->xi[px];
      if (f->pinv[j] < 0) {
        f->Li[lnz] = j;
        f->Lx[lnz++] = f->x[j] / pivot;
      }
      f->x[j] = 0.0;
    }
  }
  f->Lp[n] = (int)lnz;
  f->Up[n] = (int)unz;
  /* rows of L in pivot order, as the replay and the solves use them */
  for (long p = 0; p < lnz; p++) f->Li[p] = f->pinv[f->Li[p]];
  f->valid = 1;
  return 0;
}

int ps_lu_refactor(psLU* f, const double* Ax) {
  if (!f->valid) return -1;
  int n = f->n;
  f->counts[1]++;
  /* a nonzero outside the pattern: the next factorization takes it in */
  for (long u = 0; u < f->nunseen; u++)
    if (Ax[f->unseen[u]] != 0.0) {
      f->counts[2]++;
      return 1;
    }
  for (int k = 0; k < n; k++) {
    int col = f->q[k];
    for (int p = f->Ap[col]; p < f->Ap[col + 1]; p++)
      if (f->seen[p]) f->x[f->pinv[f->Ai[p]]] = Ax[p];
    int u1 = f->Up[k + 1] - 1;
    for (int p = f->Up[k]; p < u1; p++) {
      int J = f->Ui[p];
      double u = f->x[J];
      f->Ux[p] = u;
      f->x[J] = 0.0;
      for (int p2 = f->Lp[J] + 1; p2 < f->Lp[J + 1]; p2++) f->x[f->Li[p2]] -= f->Lx[p2] * u;
    }
    double pivot = f->x[k], big = 0.0;
    f->x[k] = 0.0;
    for (int p = f->Lp[k] + 1; p < f->Lp[k + 1]; p++) {
      double v = fabs(f->x[f->Li[p]]);
      if (v > big) big = v;
    }
    int ok = fabs(pivot) > 0.0 && isfinite(pivot) && fabs(pivot) >= PS_LU_REPLAY * big;
    f->Ux[u1] = pivot;
    for (int p = f->Lp[k] + 1; p < f->Lp[k + 1]; p++) {
      f->Lx[p] = f->x[f->Li[p]] / pivot;
      f->x[f->Li[p]] = 0.0;
    }
    if (!ok) {
      /* a stale pivot: the next factorization chooses again (x is clean up to column k,
       * whose remaining rows were just cleared) */
      f->counts[2]++;
      return 1;
    }
  }
  return 0;
}

void ps_lu_solve(const psLU* f, double* b) {
  int n = f->n;
  double* y = f->y;
  for (int i = 0; i < n; i++) y[f->pinv[i]] = b[i];
  for (int k = 0; k < n; k++) {
    double yk = y[k];
    if (yk != 0.0)
      for (int p = f->Lp[k] + 1; p < f->Lp[k + 1]; p++) y[f->Li[p]] -= f->Lx[p] * yk;
  }
  for (int k = n - 1; k >= 0; k--) {
    int u1 = f->Up[k + 1] - 1;
    double yk = y[k] / f->Ux[u1];
    y[k] = yk;
    if (yk != 0.0)
      for (int p = f->Up[k]; p < u1; p++) y[f->Ui[p]] -= f->Ux[p] * yk;
  }
  for (int k = 0; k < n; k++) b[f->q[k]] = y[k];
}

void ps_lu_forget(psLU* f) {
  f->valid = 0;
  memset(f->seen, 0, (size_t)(f->Ap[f->n] > 0 ? f->Ap[f->n] : 1));
}

long ps_lu_nnz(const psLU* f) { return f->valid ? (long)f->Lp[f->n] + f->Up[f->n] : 0; }

void ps_lu_counts(const psLU* f, long* out) { memcpy(out, f->counts, sizeof(f->counts)); }
