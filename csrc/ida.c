/* IDA called from C: the kernel's residual, Jacobian and root functions handed to SUNDIALS IDA
 * directly, so no Python runs per callback.
 *
 * SUNDIALS is not linked at build time: ps_ida_load opens the shared libraries at run time
 * (those the scikit-sundae wheel ships) and looks up the few functions used here, declared
 * below from the SUNDIALS 7 API. If loading fails the Python driver uses scikit-sundae.
 */
#include <dlfcn.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "internal.h"

typedef double sunrealtype;
typedef long long sunindextype; /* SUNDIALS_INDEX_SIZE 64; harmless for small sizes if 32 */
typedef void* N_Vector;
typedef void* SUNMatrix;
typedef void* SUNLinearSolver;
typedef void* SUNContext;
typedef int (*ResFn)(sunrealtype, N_Vector, N_Vector, N_Vector, void*);
typedef int (*JacFn)(sunrealtype, sunrealtype, N_Vector, N_Vector, N_Vector, SUNMatrix, void*,
                     N_Vector, N_Vector, N_Vector);
typedef int (*RootFn)(sunrealtype, N_Vector, N_Vector, sunrealtype*, void*);

/* The functions used, in the order of psIDA.fn. */
enum {
  F_CTX_CREATE, F_CTX_FREE, F_CTX_CLEAR_ERR, F_NV_NEW, F_NV_DATA, F_NV_DESTROY, F_MAT_DENSE,
  F_MAT_DATA, F_MAT_DESTROY, F_LS_DENSE, F_LS_FREE, F_IDA_CREATE, F_IDA_INIT, F_IDA_REINIT,
  F_IDA_SSTOL, F_IDA_USERDATA, F_IDA_SETLS, F_IDA_SETJAC, F_IDA_MAXSTEPS, F_IDA_MAXSTEP,
  F_IDA_MINSTEP, F_IDA_INITSTEP, F_IDA_STOPTIME, F_IDA_ROOTINIT, F_IDA_ROOTDIR,
  F_IDA_NOWARN, F_IDA_SOLVE, F_IDA_ROOTINFO, F_IDA_NSTEPS, F_IDA_NRES, F_IDA_NJAC,
  F_IDA_NETF, F_IDA_NCFN, F_IDA_NGE, F_IDA_FREE, F_MAT_BAND, F_MAT_BAND_DATA, F_LS_BAND,
  F_IDA_ETAMAX, F_IDA_NLCONV, F_IDA_LASTSTEP, F_COUNT
};
static const struct { int lib; const char* name; } FNS[F_COUNT] = {
  {0, "SUNContext_Create"}, {0, "SUNContext_Free"}, {0, "SUNContext_ClearErrHandlers"},
  {1, "N_VNew_Serial"}, {1, "N_VGetArrayPointer"}, {1, "N_VDestroy"},
  {2, "SUNDenseMatrix"}, {2, "SUNDenseMatrix_Data"}, {0, "SUNMatDestroy"},
  {3, "SUNLinSol_Dense"}, {0, "SUNLinSolFree"},
  {4, "IDACreate"}, {4, "IDAInit"}, {4, "IDAReInit"}, {4, "IDASStolerances"},
  {4, "IDASetUserData"}, {4, "IDASetLinearSolver"}, {4, "IDASetJacFn"},
  {4, "IDASetMaxNumSteps"}, {4, "IDASetMaxStep"}, {4, "IDASetMinStep"}, {4, "IDASetInitStep"},
  {4, "IDASetStopTime"}, {4, "IDARootInit"}, {4, "IDASetRootDirection"},
  {4, "IDASetNoInactiveRootWarn"}, {4, "IDASolve"}, {4, "IDAGetRootInfo"},
  {4, "IDAGetNumSteps"}, {4, "IDAGetNumResEvals"}, {4, "IDAGetNumJacEvals"},
  {4, "IDAGetNumErrTestFails"}, {4, "IDAGetNumNonlinSolvConvFails"}, {4, "IDAGetNumGEvals"},
  {4, "IDAFree"}, {5, "SUNBandMatrix"}, {5, "SUNBandMatrix_Data"}, {6, "SUNLinSol_Band"},
  {4, "IDASetEtaMax"}, {4, "IDASetNonlinConvCoef"}, {4, "IDAGetLastStep"},
};

#define FN(s, k, type) ((type)(s)->fn[k])

/* Steps per window over which watch() counts IDA's error-test failures. */
#define PS_IDA_WINDOW 50
_Static_assert(F_COUNT <= (int)(sizeof(((psIDA*)0)->fn) / sizeof(void*)), "psIDA.fn too small");

int ps_ida_load(psIDA* s, const char* core, const char* nvec, const char* mat, const char* ls,
                const char* ida, const char* bandmat, const char* bandls) {
  const char* paths[7] = {core, nvec, mat, ls, ida, bandmat, bandls};
  memset(s, 0, sizeof(*s));
  for (int i = 0; i < 7; i++) {
    s->lib[i] = dlopen(paths[i], RTLD_NOW | RTLD_LOCAL);
    if (!s->lib[i]) {
      snprintf(s->msg, sizeof(s->msg), "cannot open %s: %s", paths[i], dlerror());
      return -1;
    }
  }
  for (int k = 0; k < F_COUNT; k++) {
    /* SUNMatDestroy and SUNLinSolFree live in the core library in SUNDIALS 7 */
    s->fn[k] = dlsym(s->lib[FNS[k].lib], FNS[k].name);
    if (!s->fn[k]) {
      for (int i = 0; i < 7 && !s->fn[k]; i++) s->fn[k] = dlsym(s->lib[i], FNS[k].name);
    }
    if (!s->fn[k]) {
      snprintf(s->msg, sizeof(s->msg), "SUNDIALS function %s not found", FNS[k].name);
      return -1;
    }
  }
  s->loaded = 1;
  return PS_OK;
}

static int res_fn(sunrealtype t, N_Vector yy, N_Vector yp, N_Vector rr, void* ud) {
  psIDA* s = (psIDA*)ud;
  double* (*data)(N_Vector) = FN(s, F_NV_DATA, double* (*)(N_Vector));
  /* a non-finite residual is a recoverable failure: IDA retries with a smaller step */
  return ps_residual(s->m, s->d, t, data(yy), data(yp), data(rr)) == PS_OK ? 0 : 1;
}

/* Called with each Jacobian evaluation (IDA forms one after every error-test failure, so about
 * once per step when the error test keeps failing): over windows of PS_IDA_WINDOW steps, switch
 * the step-growth limit auto_eta on if more than half of the steps failed the error test while
 * the step size stayed within a factor 4: the steady cycle "grow the step 2x, fail, shrink it"
 * of a stiff penalty mode, not the burst of failures of an impact, where the step collapses. */
static void watch(psIDA* s) {
  long nst, netf;
  double h;
  FN(s, F_IDA_NSTEPS, int (*)(void*, long*))(s->mem, &nst);
  FN(s, F_IDA_NETF, int (*)(void*, long*))(s->mem, &netf);
  FN(s, F_IDA_LASTSTEP, int (*)(void*, double*))(s->mem, &h);
  h = fabs(h);
  if (h > 0 && (s->win_h[0] == 0 || h < s->win_h[0])) s->win_h[0] = h;
  if (h > s->win_h[1]) s->win_h[1] = h;
  long dn = nst - s->win[0];
  if (dn < PS_IDA_WINDOW) return;
  if (2 * (netf - s->win[1]) > dn && s->win_h[1] < 4 * s->win_h[0]) {
    FN(s, F_IDA_ETAMAX, int (*)(void*, double))(s->mem, s->auto_eta);
    s->limited_at = s->acc[0] + nst;
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
  double* (*data)(N_Vector) = FN(s, F_NV_DATA, double* (*)(N_Vector));
  if (s->band) {
    /* kernel triplets scattered into band storage through a precomputed map */
    double* b = FN(s, F_MAT_BAND_DATA, double* (*)(SUNMatrix))(J);
    return ps_jacobian_csc(s->m, s->d, t, data(yy), data(yp), cj, s->map, s->ntrip, b,
                           (int)s->nstore) == PS_OK ? 0 : 1;
  }
  double* a = FN(s, F_MAT_DATA, double* (*)(SUNMatrix))(J);
  int n = s->m->ny;
  /* the kernel writes row-major; the dense matrix is column-major: transpose in place */
  int rc = ps_jacobian(s->m, s->d, t, data(yy), data(yp), cj, a);
  for (int i = 0; i < n; i++)
    for (int j = i + 1; j < n; j++) {
      double tmp = a[(long)i * n + j];
      a[(long)i * n + j] = a[(long)j * n + i];
      a[(long)j * n + i] = tmp;
    }
  return rc == PS_OK ? 0 : 1;
}

static int root_fn(sunrealtype t, N_Vector yy, N_Vector yp, sunrealtype* g, void* ud) {
  psIDA* s = (psIDA*)ud;
  double* (*data)(N_Vector) = FN(s, F_NV_DATA, double* (*)(N_Vector));
  return ps_roots(s->m, s->d, t, data(yy), data(yp), g);
}

void ps_ida_free(psIDA* s) {
  if (s->mem) FN(s, F_IDA_FREE, void (*)(void**))(&s->mem);
  if (s->LS) FN(s, F_LS_FREE, int (*)(void*))(s->LS);
  if (s->A) FN(s, F_MAT_DESTROY, void (*)(void*))(s->A);
  if (s->y) FN(s, F_NV_DESTROY, void (*)(void*))(s->y);
  if (s->yp) FN(s, F_NV_DESTROY, void (*)(void*))(s->yp);
  if (s->ctx) FN(s, F_CTX_FREE, int (*)(void**))(&s->ctx);
  s->mem = s->LS = s->A = s->y = s->yp = s->ctx = NULL;
}

int ps_ida_init(psIDA* s, const psModel* m, psData* d, double t0, const double* y0,
                const double* yp0, double rtol, double atol, double hmax, double hmin, double h0,
                long mxsteps, const int* rootdir, int mu, int ml, const int* map, int ntrip) {
  int n = m->ny;
  ps_ida_free(s);
  s->m = m;
  s->d = d;
  if (FN(s, F_CTX_CREATE, int (*)(int, void**))(0, &s->ctx)) goto fail;
  FN(s, F_CTX_CLEAR_ERR, int (*)(void*))(s->ctx); /* C never prints: flags are returned */
  s->y = FN(s, F_NV_NEW, void* (*)(sunindextype, void*))(n, s->ctx);
  s->yp = FN(s, F_NV_NEW, void* (*)(sunindextype, void*))(n, s->ctx);
  if (!s->y || !s->yp) goto fail;
  memcpy(FN(s, F_NV_DATA, double* (*)(void*))(s->y), y0, sizeof(double) * (size_t)n);
  memcpy(FN(s, F_NV_DATA, double* (*)(void*))(s->yp), yp0, sizeof(double) * (size_t)n);
  s->mem = FN(s, F_IDA_CREATE, void* (*)(void*))(s->ctx);
  if (!s->mem) goto fail;
  if (FN(s, F_IDA_INIT, int (*)(void*, ResFn, double, void*, void*))(s->mem, res_fn, t0, s->y,
                                                                       s->yp) < 0)
    goto fail;
  FN(s, F_IDA_USERDATA, int (*)(void*, void*))(s->mem, s);
  FN(s, F_IDA_SSTOL, int (*)(void*, double, double))(s->mem, rtol, atol);
  s->band = mu >= 0 && ml >= 0;
  if (s->band) {
    int smu = mu + ml < n - 1 ? mu + ml : n - 1;
    s->map = map;
    s->ntrip = ntrip;
    s->nstore = (long)(smu + ml + 1) * n;
    s->A = FN(s, F_MAT_BAND, void* (*)(sunindextype, sunindextype, sunindextype, void*))(
        n, mu, ml, s->ctx);
    s->LS = FN(s, F_LS_BAND, void* (*)(void*, void*, void*))(s->y, s->A, s->ctx);
  } else {
    s->A = FN(s, F_MAT_DENSE, void* (*)(sunindextype, sunindextype, void*))(n, n, s->ctx);
    s->LS = FN(s, F_LS_DENSE, void* (*)(void*, void*, void*))(s->y, s->A, s->ctx);
  }
  if (!s->A || !s->LS) goto fail;
  if (FN(s, F_IDA_SETLS, int (*)(void*, void*, void*))(s->mem, s->LS, s->A) < 0) goto fail;
  FN(s, F_IDA_SETJAC, int (*)(void*, JacFn))(s->mem, jac_fn);
  FN(s, F_IDA_MAXSTEPS, int (*)(void*, long))(s->mem, mxsteps);
  memset(s->acc, 0, sizeof(s->acc));
  memset(s->win, 0, sizeof(s->win));
  s->win_h[0] = s->win_h[1] = 0.0;
  s->auto_eta = 0.0;
  s->limited_at = 0;
  if (hmax > 0) FN(s, F_IDA_MAXSTEP, int (*)(void*, double))(s->mem, hmax);
  if (hmin > 0) FN(s, F_IDA_MINSTEP, int (*)(void*, double))(s->mem, hmin);
  if (h0 > 0) FN(s, F_IDA_INITSTEP, int (*)(void*, double))(s->mem, h0);
  if (m->nsensor > 0) {
    FN(s, F_IDA_ROOTINIT, int (*)(void*, int, RootFn))(s->mem, m->nsensor, root_fn);
    FN(s, F_IDA_ROOTDIR, int (*)(void*, const int*))(s->mem, rootdir);
    FN(s, F_IDA_NOWARN, int (*)(void*))(s->mem);
  }
  return PS_OK;
fail:
  snprintf(s->msg, sizeof(s->msg), "could not set up IDA");
  ps_ida_free(s);
  return -1;
}

int ps_ida_tune(psIDA* s, double eta_max, double nlconv, double auto_eta) {
  int rc = 0;
  if (eta_max > 0) rc |= FN(s, F_IDA_ETAMAX, int (*)(void*, double))(s->mem, eta_max);
  if (nlconv > 0) rc |= FN(s, F_IDA_NLCONV, int (*)(void*, double))(s->mem, nlconv);
  s->auto_eta = eta_max > 0 ? 0.0 : auto_eta;
  return rc;
}

/* IDA's counters since the last (re)start: steps, nres, njac, netf, ncfn, ngevals. */
static void ida_counters(psIDA* s, long* c) {
  FN(s, F_IDA_NSTEPS, int (*)(void*, long*))(s->mem, c + 0);
  FN(s, F_IDA_NRES, int (*)(void*, long*))(s->mem, c + 1);
  FN(s, F_IDA_NJAC, int (*)(void*, long*))(s->mem, c + 2);
  FN(s, F_IDA_NETF, int (*)(void*, long*))(s->mem, c + 3);
  FN(s, F_IDA_NCFN, int (*)(void*, long*))(s->mem, c + 4);
  FN(s, F_IDA_NGE, int (*)(void*, long*))(s->mem, c + 5);
}

int ps_ida_reinit(psIDA* s, double t0, const double* y0, const double* yp0) {
  int n = s->m->ny;
  memcpy(FN(s, F_NV_DATA, double* (*)(void*))(s->y), y0, sizeof(double) * (size_t)n);
  memcpy(FN(s, F_NV_DATA, double* (*)(void*))(s->yp), yp0, sizeof(double) * (size_t)n);
  /* IDA's counters restart from zero: keep those of the run so far */
  long c[6];
  ida_counters(s, c);
  for (int i = 0; i < 6; i++) s->acc[i] += c[i];
  memset(s->win, 0, sizeof(s->win));
  s->win_h[0] = s->win_h[1] = 0.0;
  return FN(s, F_IDA_REINIT, int (*)(void*, double, void*, void*))(s->mem, t0, s->y, s->yp);
}

int ps_ida_solve(psIDA* s, double tout, double tstop, int onestep, double* tret, double* y,
                 double* yp, int* rootsfound) {
  int n = s->m->ny;
  FN(s, F_IDA_STOPTIME, int (*)(void*, double))(s->mem, tstop);
  int flag = FN(s, F_IDA_SOLVE, int (*)(void*, double, double*, void*, void*, int))(
      s->mem, tout, tret, s->y, s->yp, onestep ? 2 : 1);
  memcpy(y, FN(s, F_NV_DATA, double* (*)(void*))(s->y), sizeof(double) * (size_t)n);
  memcpy(yp, FN(s, F_NV_DATA, double* (*)(void*))(s->yp), sizeof(double) * (size_t)n);
  if (flag == 2 && rootsfound)
    FN(s, F_IDA_ROOTINFO, int (*)(void*, int*))(s->mem, rootsfound);
  return flag;
}

int ps_ida_outputs(psIDA* s, const double* tout, int nout, double tstop, double* y_out,
                   double* yp_out, double* req_out, int* nreached, double* tret, int* rootsfound) {
  int n = s->m->ny, flag = 0;
  *nreached = 0;
  for (int k = 0; k < nout; k++) {
    flag = ps_ida_solve(s, tout[k], tstop, 0, tret, y_out + (long)k * n, yp_out + (long)k * n,
                        rootsfound);
    if (flag < 0 || flag == 2) return flag;
    if (s->m->nout > 0)
      ps_outputs(s->m, s->d, *tret, y_out + (long)k * n, yp_out + (long)k * n,
                 req_out + (long)k * s->m->nout);
    *nreached = k + 1;
  }
  return flag;
}

void ps_ida_stats(psIDA* s, long* out) {
  ida_counters(s, out);
  for (int i = 0; i < 6; i++) out[i] += s->acc[i];
  out[6] = s->limited_at;
}
