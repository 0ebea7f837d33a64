/* The few SUNDIALS 7 declarations the plain C benchmarks use. The scikit-sundae wheel ships
 * the libraries but no headers, so they are written out here from the SUNDIALS 7 API. */
#ifndef PS_BENCH_SUNDIALS_DECLS_H
#define PS_BENCH_SUNDIALS_DECLS_H

#include <stdint.h>

typedef double sunrealtype;
typedef int64_t sunindextype;
typedef struct _generic_N_Vector* N_Vector;
typedef struct _generic_SUNMatrix* SUNMatrix;
typedef struct _generic_SUNLinearSolver* SUNLinearSolver;
typedef struct SUNContext_* SUNContext;
typedef int (*IDAResFn)(sunrealtype, N_Vector, N_Vector, N_Vector, void*);
typedef int (*IDALsJacFn)(sunrealtype, sunrealtype, N_Vector, N_Vector, N_Vector, SUNMatrix, void*,
                          N_Vector, N_Vector, N_Vector);
int SUNContext_Create(int comm, SUNContext* ctx);
int SUNContext_Free(SUNContext* ctx);
N_Vector N_VNew_Serial(sunindextype n, SUNContext ctx);
sunrealtype* N_VGetArrayPointer(N_Vector v);
void N_VDestroy(N_Vector v);
void* IDACreate(SUNContext ctx);
int IDAInit(void* mem, IDAResFn res, sunrealtype t0, N_Vector y0, N_Vector yp0);
int IDASStolerances(void* mem, sunrealtype rtol, sunrealtype atol);
int IDASetMaxNumSteps(void* mem, long mxsteps);
int IDASetStopTime(void* mem, sunrealtype tstop);
SUNMatrix SUNDenseMatrix(sunindextype m, sunindextype n, SUNContext ctx);
sunrealtype* SUNDenseMatrix_Data(SUNMatrix a);
SUNLinearSolver SUNLinSol_Dense(N_Vector y, SUNMatrix a, SUNContext ctx);
int IDASetLinearSolver(void* mem, SUNLinearSolver ls, SUNMatrix a);
int IDASetJacFn(void* mem, IDALsJacFn jac);
int IDASolve(void* mem, sunrealtype tout, sunrealtype* tret, N_Vector y, N_Vector yp, int itask);
int IDAGetNumSteps(void* mem, long* n);
int IDAGetNumResEvals(void* mem, long* n);
int IDAGetNumJacEvals(void* mem, long* n);
void IDAFree(void** mem);
int SUNLinSolFree(SUNLinearSolver ls);
void SUNMatDestroy(SUNMatrix a);
int IDAGetNumErrTestFails(void* mem, long* n);
int IDAGetNumNonlinSolvConvFails(void* mem, long* n);
int IDASetEtaMax(void* mem, sunrealtype eta);
int IDASetNonlinConvCoef(void* mem, sunrealtype coef);

/* Free one integration's IDA memory, solver, matrix, vectors and context. */
static inline void bench_free(void* mem, SUNLinearSolver ls, SUNMatrix a, N_Vector y,
                              N_Vector yp, SUNContext ctx) {
  IDAFree(&mem);
  SUNLinSolFree(ls);
  SUNMatDestroy(a);
  N_VDestroy(y);
  N_VDestroy(yp);
  SUNContext_Free(&ctx);
}

#endif
