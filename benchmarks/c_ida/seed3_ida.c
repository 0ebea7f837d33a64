/* Seed example 3 (particle between two lines, kg/mm/s/N) in plain C on SUNDIALS IDA with a
 * hand-written residual and Jacobian: the lower bound for pysolver's design (issue 5).
 *
 * Built against the SUNDIALS 7.9 shared libraries that the scikit-sundae wheel ships (see
 * build.sh); the wheel ships no headers, so the API declarations are in csrc/sundials_decls.h.
 * Usage: seed3_ida RTOL REPEAT -> prints "steps nres njac seconds" and the outputs.
 *        seed3_ida RTOL REPEAT CASES -> runs each line "K1 X0" of the file CASES (the penalty
 *        of line 1 and the particle's initial x: a sweep's cases) once, one after another,
 *        REPEAT times over; prints "ncases steps seconds": the total steps of one pass and
 *        the best pass's wall time.
 *        seed3_ida RTOL REPEAT CASES|"" 6 -> the same with the particle's three coordinates
 *        (6 states, as pysolver integrates a point body; "" for no cases file).
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "bench.h"

#define C 1e2
#define M 1.0
#define GRAV 9810.0
#define CF 1000.0

/* Penalties of line 1 and line 2 (a case sets the first) and the particle's initial x. */
static double KL[2] = {1e4, 1e4};
static double X0 = 100.0;

/* Smoothed penalty of g = 1 + sx x - z with stiffness K: force f, and df/dg, df/dgdot. */
static void penalty(double K, double g, double gd, double* f, double* fg, double* fgd) {
  *f = *fg = *fgd = 0.0;
  if (g <= 0.0) return;
  double d = g < 1.0 ? g : 1.0, s = d * d * (3 - 2 * d), ds = g < 1.0 ? 6 * d * (1 - d) : 0.0;
  *f = -K * s * g - C * s * gd;
  *fg = -K * (ds * g + s) - C * ds * gd;
  *fgd = -C * s;
}

static int res(sunrealtype t, N_Vector yy, N_Vector yyp, N_Vector rr, void* ud) {
  (void)t; (void)ud;
  double *y = N_VGetArrayPointer(yy), *yp = N_VGetArrayPointer(yyp), *r = N_VGetArrayPointer(rr);
  double fx = 0, fz = 0;
  for (int k = 0; k < 2; k++) {
    double sx = k ? -1.0 : 1.0, f, fg, fgd;
    penalty(KL[k], 1 + sx * y[0] - y[1], sx * y[2] - y[3], &f, &fg, &fgd);
    fx += f * sx;
    fz -= f;
  }
  r[0] = yp[0] - y[2];
  r[1] = yp[1] - y[3];
  r[2] = M * yp[2] - CF * fx;
  r[3] = M * (yp[3] + GRAV) - CF * fz;
  return 0;
}

static int jac(sunrealtype t, sunrealtype cj, N_Vector yy, N_Vector yyp, N_Vector rr, SUNMatrix J,
               void* ud, N_Vector t1, N_Vector t2, N_Vector t3) {
  (void)t; (void)yyp; (void)rr; (void)ud; (void)t1; (void)t2; (void)t3;
  double* y = N_VGetArrayPointer(yy);
  double* a = SUNDenseMatrix_Data(J); /* column-major 4 x 4 */
#define A(i, j) a[(j) * 4 + (i)]
  for (int i = 0; i < 16; i++) a[i] = 0.0;
  A(0, 0) = cj; A(0, 2) = -1; A(1, 1) = cj; A(1, 3) = -1; A(2, 2) = cj * M; A(3, 3) = cj * M;
  for (int k = 0; k < 2; k++) {
    double sx = k ? -1.0 : 1.0, f, fg, fgd;
    double grad[4] = {sx, -1, 0, 0}, gdot_v[4] = {0, 0, sx, -1}, dir[2] = {sx, -1};
    penalty(KL[k], 1 + sx * y[0] - y[1], sx * y[2] - y[3], &f, &fg, &fgd);
    for (int i = 0; i < 2; i++)     /* rows: generalized force on x (2) and z (3) */
      for (int j = 0; j < 4; j++)
        A(2 + i, j) -= CF * dir[i] * (fg * grad[j] + fgd * gdot_v[j]);
  }
#undef A
  return 0;
}

/* The same equations with the particle's three coordinates, as pysolver integrates a point
 * body (x y z vx vy vz; y carries no force): the comparator for pysolver's own formulation. */
static int res6(sunrealtype t, N_Vector yy, N_Vector yyp, N_Vector rr, void* ud) {
  (void)t; (void)ud;
  double *y = N_VGetArrayPointer(yy), *yp = N_VGetArrayPointer(yyp), *r = N_VGetArrayPointer(rr);
  double fx = 0, fz = 0;
  for (int k = 0; k < 2; k++) {
    double sx = k ? -1.0 : 1.0, f, fg, fgd;
    penalty(KL[k], 1 + sx * y[0] - y[2], sx * y[3] - y[5], &f, &fg, &fgd);
    fx += f * sx;
    fz -= f;
  }
  for (int i = 0; i < 3; i++) r[i] = yp[i] - y[3 + i];
  r[3] = M * yp[3] - CF * fx;
  r[4] = M * yp[4];
  r[5] = M * (yp[5] + GRAV) - CF * fz;
  return 0;
}

static int jac6(sunrealtype t, sunrealtype cj, N_Vector yy, N_Vector yyp, N_Vector rr, SUNMatrix J,
                void* ud, N_Vector t1, N_Vector t2, N_Vector t3) {
  (void)t; (void)yyp; (void)rr; (void)ud; (void)t1; (void)t2; (void)t3;
  double* y = N_VGetArrayPointer(yy);
  double* a = SUNDenseMatrix_Data(J); /* column-major 6 x 6 */
#define A(i, j) a[(j) * 6 + (i)]
  for (int i = 0; i < 36; i++) a[i] = 0.0;
  for (int i = 0; i < 3; i++) { A(i, i) = cj; A(i, 3 + i) = -1; A(3 + i, 3 + i) = cj * M; }
  for (int k = 0; k < 2; k++) {
    double sx = k ? -1.0 : 1.0, f, fg, fgd;
    double grad[6] = {sx, 0, -1, 0, 0, 0}, gdot_v[6] = {0, 0, 0, sx, 0, -1}, dir[2] = {sx, -1};
    penalty(KL[k], 1 + sx * y[0] - y[2], sx * y[3] - y[5], &f, &fg, &fgd);
    for (int i = 0; i < 2; i++)     /* rows: generalized force on x (3) and z (5) */
      for (int j = 0; j < 6; j++)
        A(3 + 2 * i, j) -= CF * dir[i] * (fg * grad[j] + fgd * gdot_v[j]);
  }
#undef A
  return 0;
}

/* States integrated: 4 (x z vx vz) or 6 (x y z vx vy vz). */
static int NY = 4;

/* One run from x = X0, z = 120 at rest to t = 3 s with outputs every 0.005 s into out (601 x
 * 2); returns its wall seconds (from IDACreate to the last output; a sweep's pass times
 * everything) and sets the step, residual and Jacobian counts. */
static double run(double rtol, double (*out)[2], long* nst, long* nre, long* nje) {
  SUNContext ctx;
  SUNContext_Create(0, &ctx);
  N_Vector y = N_VNew_Serial(NY, ctx), yp = N_VNew_Serial(NY, ctx);
  double *yv = N_VGetArrayPointer(y), *ypv = N_VGetArrayPointer(yp);
  const int iz = NY == 6 ? 2 : 1; /* where z and its velocity's rate are */
  for (int i = 0; i < NY; i++) yv[i] = ypv[i] = 0.0;
  yv[0] = X0; yv[iz] = 120; ypv[NY - 1] = -GRAV;
  struct timespec a, b;
  clock_gettime(CLOCK_MONOTONIC, &a);
  void* mem = IDACreate(ctx);
  IDAInit(mem, NY == 6 ? res6 : res, 0.0, y, yp);
  IDASStolerances(mem, rtol, rtol);
  IDASetMaxNumSteps(mem, 1000000);
  SUNMatrix J = SUNDenseMatrix(NY, NY, ctx);
  SUNLinearSolver LS = SUNLinSol_Dense(y, J, ctx);
  IDASetLinearSolver(mem, LS, J);
  IDASetJacFn(mem, NY == 6 ? jac6 : jac);
  IDASetStopTime(mem, 3.0);
  double t;
  out[0][0] = X0; out[0][1] = 120;
  /* like pysolver: the first call asks for the end time in one-step mode */
  IDASolve(mem, 3.0, &t, y, yp, 2 /* IDA_ONE_STEP */);
  for (int k = 1; k <= 600; k++) {
    double tp = 0.005 * k;
    if (t < tp) IDASolve(mem, tp, &t, y, yp, 1 /* IDA_NORMAL */);
    if (t > tp) { /* interpolate: IDA_NORMAL with tout behind tn returns the interpolant */
      IDASolve(mem, tp, &t, y, yp, 1);
    }
    out[k][0] = yv[0]; out[k][1] = yv[iz];
  }
  clock_gettime(CLOCK_MONOTONIC, &b);
  IDAGetNumSteps(mem, nst);
  IDAGetNumResEvals(mem, nre);
  IDAGetNumJacEvals(mem, nje);
  bench_free(mem, LS, J, y, yp, ctx);
  return (b.tv_sec - a.tv_sec) + 1e-9 * (b.tv_nsec - a.tv_nsec);
}

int main(int argc, char** argv) {
  double rtol = argc > 1 ? atof(argv[1]) : 1e-6;
  int repeat = argc > 2 ? atoi(argv[2]) : 5;
  double best = 1e30;
  long nst = 0, nre = 0, nje = 0;
  static double out[601][2];
  NY = argc > 4 && atoi(argv[4]) == 6 ? 6 : 4;
  if (argc > 3 && argv[3][0]) { /* a sweep's cases, one pass after another */
    FILE* fh = fopen(argv[3], "r");
    if (!fh) { perror(argv[3]); return 2; }
    static double cases[100000][2];
    int n = 0;
    while (n < 100000 && fscanf(fh, "%lf %lf", &cases[n][0], &cases[n][1]) == 2) n++;
    fclose(fh);
    long steps = 0;
    for (int rep = 0; rep < repeat; rep++) {
      struct timespec a, b;
      clock_gettime(CLOCK_MONOTONIC, &a);
      steps = 0;
      for (int i = 0; i < n; i++) {
        KL[0] = cases[i][0]; X0 = cases[i][1];
        run(rtol, out, &nst, &nre, &nje);
        steps += nst;
      }
      clock_gettime(CLOCK_MONOTONIC, &b);
      double sec = (b.tv_sec - a.tv_sec) + 1e-9 * (b.tv_nsec - a.tv_nsec);
      if (sec < best) best = sec;
    }
    printf("%d %ld %.9f\n", n, steps, best);
    return 0;
  }
  for (int rep = 0; rep < repeat; rep++) {
    double sec = run(rtol, out, &nst, &nre, &nje);
    if (sec < best) best = sec;
  }
  printf("%ld %ld %ld %.9f\n", nst, nre, nje, best);
  for (int k = 0; k <= 600; k++) printf("%.17g %.17g\n", out[k][0], out[k][1]);
  return 0;
}
