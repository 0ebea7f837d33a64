/* Internal declarations shared by the kernel's translation units. */
#ifndef PYSOLVER_INTERNAL_H
#define PYSOLVER_INTERNAL_H

#include "pysolver.h"

/* A hyper-dual number is a double array [value, gradient (n), packed upper Hessian (nh(nh+1)/2)].
 * A context says how many basis directions there are, how many leading ones carry second
 * derivatives (a tape's positions and time: second derivatives are only ever needed of
 * displacement expressions), and up to which order derivatives are kept: order 0 = value only,
 * 1 = value and gradient, 2 = value, gradient and the Hessian block of the first nh directions.
 */
typedef struct psuHD {
  int n;      /* basis size */
  int nh;     /* leading directions with second derivatives (nh <= n) */
  int order;  /* 0, 1 or 2 */
  int stride; /* doubles between consecutive numbers in an array */
} psuHD;

/* Doubles per body in the kinematics cache, and the offsets of each quantity in it. */
#define PS_BC_SIZE 32
#define PS_BC_R 0    /* position of the body origin, global (3)               */
#define PS_BC_A 3    /* rotation matrix body->global, row-major (9)           */
#define PS_BC_V 12   /* velocity of the body origin, global (3)               */
#define PS_BC_W 15   /* angular velocity, global (3)                          */
#define PS_BC_ACC 18 /* acceleration of the body origin, global (3)           */
#define PS_BC_AL 21  /* angular acceleration, global (3)                      */
#define PS_BC_E 24   /* Euler parameters e0..e3 (4)                           */
#define PS_BC_WB 28  /* angular velocity, body frame (3)                      */

/* Scratch hyper-duals in psData.tmp: the tape uses [0, PS_TMP_TAPE), force assembly the rest. */
#define PS_TMP_TAPE 64

/* hd.c: hyper-dual arithmetic. Every output may alias an input. */
int psu_hd_size(int n, int nh, int order);
void psu_hd_const(const psuHD* c, double* out, double v);
void psu_hd_var(const psuHD* c, double* out, double v, int pos);
void psu_hd_copy(const psuHD* c, double* out, const double* a);
void psu_hd_lin(const psuHD* c, double* out, double ca, const double* a, double cb,
                const double* b, double c0);
void psu_hd_unary(const psuHD* c, double* out, const double* a, double f0, double f1, double f2);
void psu_hd_binary(const psuHD* c, double* out, const double* a, const double* b, double f0,
                   double fa, double fb, double faa, double fab, double fbb);
void psu_hd_mul(const psuHD* c, double* out, const double* a, const double* b);
void psu_hd_nary(const psuHD* c, double* out, const double* const* a, int n, double f0,
                 const double* fi, const double* fij);
void psu_hd_div(const psuHD* c, double* out, const double* a, const double* b);
void psu_hd_gradcomp(const psuHD* c, double* out, const double* g, int k);
void psu_hd_zero_hessian(const psuHD* c, double* out);

/* kinematics.c: body and marker kinematics as hyper-duals in a tape's basis. */
void ps_body_cache(const psModel* m, psData* d, const psuHD* c, int tape, double t,
                   const double* y, const double* yp);
double* ps_bc(const psModel* m, psData* d, int slot, int k);
void ps_marker_pos(const psModel* m, psData* d, const psuHD* c, int marker, int slot, double* R);
void ps_marker_axes(const psModel* m, psData* d, const psuHD* c, int marker, int slot, double* X);
void ps_marker_vel(const psModel* m, psData* d, const psuHD* c, int marker, int slot, double* V);
void ps_marker_omega(const psModel* m, psData* d, const psuHD* c, int marker, int slot,
                     double* W);
void ps_marker_acc(const psModel* m, psData* d, const psuHD* c, int marker, int slot,
                   double* Acc);
void ps_marker_alpha(const psModel* m, psData* d, const psuHD* c, int marker, int slot,
                     double* Al);
void psu_hd_cross(const psuHD* c, double* out, const double* a, const double* b, double* scratch);
void psu_hd_dot(const psuHD* c, double* out, const double* a, const double* b, double* scratch);
double* ps_tmp(const psModel* m, psData* d, int k);

/* tape.c: run a tape at the given order; results stay in d->slots. With values_only the caller
 * reads only values and derivatives along the positions and time (the leading nh basis
 * directions: GDOT and the penalties' rate coefficients), so the other directions (velocities,
 * accelerations) are not carried. */
void ps_tape_run(const psModel* m, psData* d, int tape, int order, int values_only, double t,
                 const double* y, const double* yp);
double* ps_slot(const psModel* m, psData* d, int slot);
void ps_rate_coeff(const psModel* m, psData* d, const psuHD* c, const double* g, int tape,
                   int slot, int i, double* out, double* sc);

/* residual.c: solve A x = b in place (b becomes x) by LU with partial pivoting; A (n x n,
 * row-major) is overwritten; piv (n, or NULL) receives the pivot rows. Returns
 * PS_ERR_SINGULAR on a zero or non-finite pivot. */
int psu_dense_solve(int n, double* A, double* b, int* piv);

/* usersub.c: a PS_OP_USER instruction (operands a) at time t into out. */
void ps_user_call(const psModel* m, psData* d, const psuHD* c, double* out, const int* a,
                  double t);

#endif
