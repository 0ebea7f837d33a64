/* The stiff penalty pendulum of issue 5 in plain C on SUNDIALS IDA with a hand-written residual
 * and exact Jacobian: a 1 kg point mass on a bilateral penalty rod g = |r| - 1 (k, c), under
 * gravity 9.81, released horizontally at rest; 10 s, outputs every 0.01 s.
 *
 * Built like seed3_ida (see build.sh). Usage:
 *   pendulum_ida RTOL K C ETA_MAX NLCONV REPEAT
 * ETA_MAX, NLCONV <= 0 keep IDA's defaults (2, 0.33); pysolver's C driver uses 1.1 (switched
 * on when the error test keeps failing) and 0.033. Prints "steps nres njac netf ncfn seconds"
 * and then the 1001 outputs x y.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "bench.h"

static double K, CD;
static const double G = 9.81;

static int res(sunrealtype t, N_Vector yy, N_Vector yyp, N_Vector rr, void* ud) {
  (void)t; (void)ud;
  double *y = N_VGetArrayPointer(yy), *yp = N_VGetArrayPointer(yyp), *r = N_VGetArrayPointer(rr);
  double L = hypot(y[0], y[1]), nx = y[0] / L, ny = y[1] / L;
  double f = -K * (L - 1) - CD * (nx * y[2] + ny * y[3]);
  r[0] = yp[0] - y[2];
  r[1] = yp[1] - y[3];
  r[2] = yp[2] - f * nx;
  r[3] = yp[3] - f * ny + G;
  return 0;
}

static int jac(sunrealtype t, sunrealtype cj, N_Vector yy, N_Vector yyp, N_Vector rr, SUNMatrix J,
               void* ud, N_Vector t1, N_Vector t2, N_Vector t3) {
  (void)t; (void)yyp; (void)rr; (void)ud; (void)t1; (void)t2; (void)t3;
  double* y = N_VGetArrayPointer(yy);
  double* a = SUNDenseMatrix_Data(J); /* column-major 4 x 4 */
  double L = hypot(y[0], y[1]), n[2] = {y[0] / L, y[1] / L}, v[2] = {y[2], y[3]};
  double f = -K * (L - 1) - CD * (n[0] * v[0] + n[1] * v[1]), P[2][2], dgd[2];
  /* P = dn/dq = (I - n n^T) / L; d(gdot)/dq = P v */
  for (int i = 0; i < 2; i++)
    for (int j = 0; j < 2; j++) P[i][j] = ((i == j) - n[i] * n[j]) / L;
  for (int i = 0; i < 2; i++) dgd[i] = P[i][0] * v[0] + P[i][1] * v[1];
#define A(i, j) a[(j) * 4 + (i)]
  for (int i = 0; i < 16; i++) a[i] = 0.0;
  A(0, 0) = cj; A(0, 2) = -1; A(1, 1) = cj; A(1, 3) = -1; A(2, 2) = cj; A(3, 3) = cj;
  for (int i = 0; i < 2; i++)
    for (int j = 0; j < 2; j++) {
      A(2 + i, j) = n[i] * (K * n[j] + CD * dgd[j]) - f * P[i][j];
      A(2 + i, 2 + j) += CD * n[i] * n[j];
    }
#undef A
  return 0;
}

int main(int argc, char** argv) {
  if (argc < 7) {
    fprintf(stderr, "usage: pendulum_ida RTOL K C ETA_MAX NLCONV REPEAT\n");
    return 2;
  }
  double rtol = atof(argv[1]), etamax = atof(argv[4]), nlconv = atof(argv[5]);
  K = atof(argv[2]);
  CD = atof(argv[3]);
  int repeat = atoi(argv[6]);
  double best = 1e30;
  long nst = 0, nre = 0, nje = 0, netf = 0, ncfn = 0;
  static double out[1001][2];
  for (int rep = 0; rep < repeat; rep++) {
    SUNContext ctx;
    SUNContext_Create(0, &ctx);
    N_Vector y = N_VNew_Serial(4, ctx), yp = N_VNew_Serial(4, ctx);
    double *yv = N_VGetArrayPointer(y), *ypv = N_VGetArrayPointer(yp);
    yv[0] = 1; yv[1] = 0; yv[2] = 0; yv[3] = 0;
    ypv[0] = 0; ypv[1] = 0; ypv[2] = 0; ypv[3] = -G;
    struct timespec a, b;
    clock_gettime(CLOCK_MONOTONIC, &a);
    void* mem = IDACreate(ctx);
    IDAInit(mem, res, 0.0, y, yp);
    IDASStolerances(mem, rtol, rtol);
    IDASetMaxNumSteps(mem, 100000000);
    if (etamax > 0) IDASetEtaMax(mem, etamax);
    if (nlconv > 0) IDASetNonlinConvCoef(mem, nlconv);
    SUNMatrix J = SUNDenseMatrix(4, 4, ctx);
    SUNLinearSolver LS = SUNLinSol_Dense(y, J, ctx);
    IDASetLinearSolver(mem, LS, J);
    IDASetJacFn(mem, jac);
    IDASetStopTime(mem, 10.0);
    double t;
    out[0][0] = 1; out[0][1] = 0;
    for (int k = 1; k <= 1000; k++) {
      IDASolve(mem, 0.01 * k, &t, y, yp, 1 /* IDA_NORMAL */);
      out[k][0] = yv[0]; out[k][1] = yv[1];
    }
    clock_gettime(CLOCK_MONOTONIC, &b);
    double sec = (b.tv_sec - a.tv_sec) + 1e-9 * (b.tv_nsec - a.tv_nsec);
    if (sec < best) best = sec;
    IDAGetNumSteps(mem, &nst);
    IDAGetNumResEvals(mem, &nre);
    IDAGetNumJacEvals(mem, &nje);
    IDAGetNumErrTestFails(mem, &netf);
    IDAGetNumNonlinSolvConvFails(mem, &ncfn);
    bench_free(mem, LS, J, y, yp, ctx);
  }
  printf("%ld %ld %ld %ld %ld %.9f\n", nst, nre, nje, netf, ncfn, best);
  for (int k = 0; k <= 1000; k++) printf("%.17g %.17g\n", out[k][0], out[k][1]);
  return 0;
}
