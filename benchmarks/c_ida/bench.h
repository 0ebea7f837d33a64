/* What the two plain C benchmarks share: the SUNDIALS declarations (csrc/sundials_decls.h, the
 * same list pysolver's C driver uses) and the teardown of one integration. */
#ifndef PS_BENCH_H
#define PS_BENCH_H

#include "sundials_decls.h"

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
