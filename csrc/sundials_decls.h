/* The SUNDIALS 7 declarations pysolver uses, written out from the SUNDIALS 7 API because the
 * scikit-sundae wheel ships the shared libraries but no headers. One list for two users:
 * csrc/ida.c opens the libraries at run time and calls these through pointers whose types are
 * taken from the prototypes below; the plain C benchmarks (benchmarks/c_ida) link against the
 * same libraries and call them directly. */
#ifndef PS_SUNDIALS_DECLS_H
#define PS_SUNDIALS_DECLS_H

#include <stdint.h>

typedef double sunrealtype;
typedef int32_t sunindextype; /* the wheel's SUNDIALS_INDEX_SIZE is 32 (see its c_config.pxi) */
typedef struct _generic_N_Vector* N_Vector;
typedef struct _generic_SUNMatrix* SUNMatrix;
typedef struct _generic_SUNLinearSolver* SUNLinearSolver;
typedef struct SUNContext_* SUNContext;
typedef int (*IDAResFn)(sunrealtype, N_Vector, N_Vector, N_Vector, void*);
typedef int (*IDALsJacFn)(sunrealtype, sunrealtype, N_Vector, N_Vector, N_Vector, SUNMatrix, void*,
                          N_Vector, N_Vector, N_Vector);
typedef int (*IDAEwtFn)(N_Vector y, N_Vector ewt, void* user_data);
typedef int (*IDARootFn)(sunrealtype, N_Vector, N_Vector, sunrealtype*, void*);

/* core */
int SUNContext_Create(int comm, SUNContext* ctx);
int SUNContext_Free(SUNContext* ctx);
int SUNContext_ClearErrHandlers(SUNContext ctx);
void SUNMatDestroy(SUNMatrix a);
int SUNLinSolFree(SUNLinearSolver ls);
/* serial vectors */
N_Vector N_VNew_Serial(sunindextype n, SUNContext ctx);
sunrealtype* N_VGetArrayPointer(N_Vector v);
void N_VDestroy(N_Vector v);
/* dense and band matrices and their direct solvers */
SUNMatrix SUNDenseMatrix(sunindextype m, sunindextype n, SUNContext ctx);
sunrealtype* SUNDenseMatrix_Data(SUNMatrix a);
SUNLinearSolver SUNLinSol_Dense(N_Vector y, SUNMatrix a, SUNContext ctx);
SUNMatrix SUNBandMatrix(sunindextype n, sunindextype mu, sunindextype ml, SUNContext ctx);
sunrealtype* SUNBandMatrix_Data(SUNMatrix a);
sunindextype SUNBandMatrix_LDim(SUNMatrix a);
SUNLinearSolver SUNLinSol_Band(N_Vector y, SUNMatrix a, SUNContext ctx);
/* compressed-sparse-column matrices and SuperLU_MT (CSC_MAT = 0) */
SUNMatrix SUNSparseMatrix(sunindextype m, sunindextype n, sunindextype nnz, int sparsetype,
                          SUNContext ctx);
sunrealtype* SUNSparseMatrix_Data(SUNMatrix a);
sunindextype* SUNSparseMatrix_IndexValues(SUNMatrix a);
sunindextype* SUNSparseMatrix_IndexPointers(SUNMatrix a);
SUNLinearSolver SUNLinSol_SuperLUMT(N_Vector y, SUNMatrix a, int num_threads, SUNContext ctx);
/* a linear solver of one's own: an empty object whose operations the caller fills in; the dense
 * solver's operations, exported, locate those slots (csrc/ida.c) */
SUNLinearSolver SUNLinSolNewEmpty(SUNContext ctx);
int SUNLinSolGetType_Dense(SUNLinearSolver s);
int SUNLinSolSetup_Dense(SUNLinearSolver s, SUNMatrix a);
int SUNLinSolSolve_Dense(SUNLinearSolver s, SUNMatrix a, N_Vector x, N_Vector b, sunrealtype tol);
/* IDA */
void* IDACreate(SUNContext ctx);
int IDAInit(void* mem, IDAResFn res, sunrealtype t0, N_Vector y0, N_Vector yp0);
int IDAReInit(void* mem, sunrealtype t0, N_Vector y0, N_Vector yp0);
int IDASStolerances(void* mem, sunrealtype rtol, sunrealtype atol);
int IDAWFtolerances(void* mem, IDAEwtFn efun);
int IDASetUserData(void* mem, void* user_data);
int IDASetLinearSolver(void* mem, SUNLinearSolver ls, SUNMatrix a);
int IDASetJacFn(void* mem, IDALsJacFn jac);
int IDASetMaxNumSteps(void* mem, long mxsteps);
int IDASetMaxStep(void* mem, sunrealtype hmax);
int IDASetId(void* mem, N_Vector id);
int IDASetSuppressAlg(void* mem, int suppressalg);
int IDASetMinStep(void* mem, sunrealtype hmin);
int IDASetInitStep(void* mem, sunrealtype hin);
int IDASetStopTime(void* mem, sunrealtype tstop);
int IDASetEtaMax(void* mem, sunrealtype eta);
int IDASetNonlinConvCoef(void* mem, sunrealtype coef);
int IDARootInit(void* mem, int nrtfn, IDARootFn g);
int IDASetRootDirection(void* mem, int* rootdir);
int IDASetNoInactiveRootWarn(void* mem);
int IDASolve(void* mem, sunrealtype tout, sunrealtype* tret, N_Vector y, N_Vector yp, int itask);
int IDAGetRootInfo(void* mem, int* rootsfound);
int IDAGetNumSteps(void* mem, long* n);
int IDAGetNumResEvals(void* mem, long* n);
int IDAGetNumJacEvals(void* mem, long* n);
int IDAGetNumErrTestFails(void* mem, long* n);
int IDAGetNumNonlinSolvConvFails(void* mem, long* n);
int IDAGetNumGEvals(void* mem, long* n);
int IDAGetLastStep(void* mem, sunrealtype* hlast);
int IDAGetCurrentStep(void* mem, sunrealtype* hcur);
int IDAGetCurrentTime(void* mem, sunrealtype* tcur);
int IDAGetSolution(void* mem, sunrealtype t, N_Vector yret, N_Vector ypret);
void IDAFree(void** mem);

#endif
