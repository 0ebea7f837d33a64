/* pysolver kernel: public C interface.
 *
 * A compiled scene (psModel) is immutable after compilation; the workspace (psData) holds every
 * scratch array the kernel needs, so nothing is allocated during integration. Both are filled by
 * the Python compiler (pysolver/build/compiler.py); the arrays they point to are owned by the caller.
 *
 * Naming: ps_ functions take (model, data) or an IDA object; psu_ are pure math helpers
 * (csrc/internal.h). cffi's cdef is derived from this header by pysolver/_build_ffi.py
 * (comments and preprocessor lines stripped), so this file is the one interface definition.
 */
#ifndef PYSOLVER_H
#define PYSOLVER_H

#include "pysolver_usersub.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Body kinds. */
#define PS_BODY_POINT 0 /* 3 translational DOF: q = (x, y, z), u = (vx, vy, vz) */
#define PS_BODY_RIGID 1 /* q = (x, y, z, e0, e1, e2, e3), u = (vx, vy, vz, wx, wy, wz) body frame */
#define PS_BODY_PLANAR 2 /* a rigid body in the global x-y plane: q = (x, y, rz), u = (vx, vy, wz),
                          * its axes Rz(rz) A0 and its z fixed (body_plane) */

/* Kinds of a basis entry: what a local derivative direction of a tape stands for. A tape's
 * basis lists the positions q of its bodies, then time, then their velocities u, then u'. */
#define PS_BASIS_Y 0    /* a state entry y[idx] */
#define PS_BASIS_YP 1   /* a state derivative entry yp[idx] */
#define PS_BASIS_T 2    /* time */

/* Width of one tape instruction in ints: op followed by 9 operands a0..a8. */
#define PS_INSTR_WIDTH 10
#define PS_TMP_TOTAL 104   /* scratch hyper-duals in psData.tmp */

/* Tape opcodes. Operands a0..a8 follow the op; "slot" means an earlier instruction's result.
 * Each is declared in pysolver/catalogue.py too (tests/test_catalogue.py checks they agree). */
enum psOp {
  PS_OP_CONST = 0,   /* a0: index into consts */
  PS_OP_TIME,        /* simulation time */
  PS_OP_ADD,         /* slot a0 + slot a1 */
  PS_OP_SUB,
  PS_OP_MUL,
  PS_OP_DIV,
  PS_OP_POW,
  PS_OP_NEG,
  PS_OP_ABS, PS_OP_ACOS, PS_OP_ASIN, PS_OP_ATAN, PS_OP_COS, PS_OP_COSH, PS_OP_SIN, PS_OP_SINH,
  PS_OP_TAN, PS_OP_TANH, PS_OP_EXP, PS_OP_LOG, PS_OP_LOG10, PS_OP_SQRT, PS_OP_AINT, PS_OP_ANINT,
  PS_OP_CLAMP01,     /* min(max(x, 0), 1) */
  PS_OP_ATAN2, PS_OP_MOD, PS_OP_MAX, PS_OP_MIN, PS_OP_SIGN, PS_OP_DIM,
  PS_OP_IF,          /* a0 selector; a1 if < 0, a2 if == 0, a3 if > 0 */
  PS_OP_MEASURE,     /* a0 measure kind (psMeasure); a1..a4 markers i j k l (-1 = global);
                        a5..a8 their body slots in the tape (-1 = ground or global) */
  PS_OP_GDOT,        /* total time derivative of slot a0, a displacement expression */
  PS_OP_AXDOT,       /* dot of axis a1 of marker a0 with axis a3 of marker a2 (-1 = global);
                        a4, a5 their body slots */
  PS_OP_SENVAL,      /* stored value d->senval[a0] of a Sensor_Evaluate (constant between events) */
  PS_OP_STEPC,       /* STEP-family function of slot a0 with constant bounds consts[a1..a4] =
                        x0, h0, x1, h1; a5 the shape: 0 STEP, 1 STEP5, 2 HAVSIN */
  PS_OP_USER,        /* a user subroutine: routine a0, called with the values of the slots
                        user_in[a1 .. a1+a2-1] as the system values it declared; result channel a3
                        (REQSUB: 0..7, others 0); a4 its entry in d->user_cache */
  PS_OP_STATE,       /* the state entry y[a0] (a motion's reaction), the tape's a1-th extra
                        basis entry (the last tape_nstate entries of its basis) */
  PS_OP_COUNT
};

/* Marker measures, in the order of pysolver/catalogue.py (tests/test_catalogue.py). */
enum psMeasure {
  PS_M_DX = 0, PS_M_DY, PS_M_DZ, PS_M_DM,
  PS_M_VX, PS_M_VY, PS_M_VZ, PS_M_VM, PS_M_VR,
  PS_M_ACCX, PS_M_ACCY, PS_M_ACCZ,
  PS_M_WX, PS_M_WY, PS_M_WZ,
  PS_M_WDTX, PS_M_WDTY, PS_M_WDTZ,
  PS_M_AX, PS_M_AY, PS_M_AZ,
  PS_M_COUNT
};

/* Element kinds: what an entry of psModel's element table is (the contribution of each is
 * csrc/elements/<kind>.c, its ints' layout declared in pysolver/catalogue.py). */
enum psElement {
  PS_EL_PENALTY = 0, /* Force_Penalty */
  PS_EL_SFORCE,      /* Force_Scalar_TwoBody */
  PS_EL_VFORCE,      /* Force_Vector_TwoBody */
  PS_EL_MOTION,      /* Motion_Marker */
  PS_EL_JOINT,       /* one equation of a Constraint_Joint */
  PS_EL_GCON,        /* a Constraint_General */
  PS_EL_COUPLER,     /* a Constraint_Coupler */
  PS_EL_TURN,        /* the tracked angle of a screw, a rack and pinion or a coupler */
  PS_EL_COUNT
};

/* Motion kinds: what follows the expression (csrc/residual.c). */
#define PS_MOTION_D 0  /* the displacement: g = measure - expr, g' = 0           */
#define PS_MOTION_V 1  /* the velocity: g' = expr                               */
#define PS_MOTION_A 2  /* the acceleration: g' = w with w' = expr               */

/* Sensor comparisons. */
#define PS_CMP_GE 0
#define PS_CMP_LT 1
#define PS_CMP_EQ 2

/* Argument lists of user subroutines (Adams/MotionSolve conventions). */
#define PS_USER_DFLAG 0  /* f(int* id, double* time, double* par, int* npar, int* dflag,
                            int* iflag, double* value): PFOSUB, VARSUB, SFOSUB */
#define PS_USER_PLAIN 1  /* f(int* id, double* time, double* par, int* npar, int* iflag,
                            double* value): SENSUB, SEVSUB, REQSUB (value[8]) */
#define PS_USER_IORD 2   /* as PS_USER_DFLAG with iord in dflag's place, always 0 (the
                            value; its derivatives are differenced): MOTSUB */
#define PS_USER_KEY 32   /* bytes of one canonical input key */
#define PS_USER_MAXIN 16 /* most inputs one routine may declare */
/* doubles of one PS_OP_USER instruction's cache: what it holds (0 nothing, 1 the value,
 * 2 also the first partials), the value, then the inputs (with time), partials, how each
 * partial was found (0 differences, 1 flat, 2 given by the routine), and last the inputs
 * whose given partials were checked in this run (bit i for input i) */
#define PS_USER_CACHE 54 /* 3 + 3 (PS_USER_MAXIN + 1) */

/* Status codes returned by kernel functions. */
#define PS_OK 0
#define PS_ERR_NONFINITE 1 /* an expression or force evaluated to NaN or infinity */
#define PS_ERR_SINGULAR 2  /* a matrix to solve with is singular */
#define PS_ERR_ASSEMBLY 3  /* the position constraints cannot be held (ps_restart_consistent) */
/* A LoadControl update's own failures (ps_control_update): its measured load, its target load
 * or the law's velocity is not finite, or its log is full. */
#define PS_CTRL_LOAD 10
#define PS_CTRL_TARGET 11
#define PS_CTRL_VELOCITY 12
#define PS_CTRL_LOG 13
/* Fields of one LoadControl update's log row (pysolver/solve/loadlaw.py, FIELDS): time, target,
 * measured, filtered, displacement, A, e, Ie, De, velocity, clamped (1 or 0). */
#define PS_LAW_FIELDS 11

struct psModel;

/* One function of a deck's generated C (pysolver/build/codegen): residual rows, iteration
 * matrix triplet values, sensor expressions or request channels at (t, y, yp) into out, reading
 * the sweep parameters from m's arrays and stored Sensor_Evaluate values from sv; cj is the
 * iteration matrix's coefficient (read by the Jacobian only). */
struct psData;
typedef void (*psGenFn)(const struct psModel* m, struct psData* d, double t, const double* y,
                        const double* yp, double cj, double* out);

/* Version of the psGen layout; a generated library with another one is not used. */
#define PS_GEN_VERSION 2

/* The table a generated library exports as ps_gen_table: straight-line C for one compiled scene
 * (same results as its tapes to rounding), the iteration matrix as ntrip (row, col) triplets
 * sorted by column then row, each entry once. */
typedef struct psGen {
  int version;            /* PS_GEN_VERSION                                     */
  int ny;                 /* states of the scene it was generated for           */
  int ntrip;              /* structural nonzeros of the iteration matrix        */
  int nsensor;            /* sensor expressions                                 */
  int nout;               /* request channels                                   */
  const int* trow;        /* (ntrip x 1) row of each nonzero                    */
  const int* tcol;        /* (ntrip x 1) column of each nonzero                 */
  psGenFn residual;       /* out: ny residual rows                              */
  psGenFn jacobian;       /* out: ntrip values of dF/dy + cj dF/dyp             */
  psGenFn sensors;        /* out: nsensor expression values                     */
  psGenFn outputs;        /* out: nout channel values (NaN for NULL channels)   */
} psGen;

typedef struct psModel {
  /* sizes */
  int ny;                 /* number of states                                  */
  int nbody;              /* number of moving bodies (ground excluded)          */
  int nmarker;            /* number of markers                                  */
  int ntape;              /* number of expression tapes                         */
  int nout;               /* number of output channels (requests, flattened)    */
  int nsensor;            /* number of Sensor_Event elements                    */
  int hd_stride;          /* doubles per hyper-dual slot (largest tape, order 2) */
  int max_slots;          /* largest tape length, in instructions              */
  int max_bslots;         /* largest number of bodies one tape touches          */

  /* scene constants */
  double gravity[3];      /* gravitational acceleration, model units            */
  double force_scale;     /* model force unit in mass*length/time^2             */

  /* bodies */
  int* body_type;         /* (nbody x 1) PS_BODY_*                              */
  int* body_qadr;         /* (nbody x 1) index of the body's first q in y       */
  int* body_uadr;         /* (nbody x 1) index of the body's first u in y       */
  double* body_mass;      /* (nbody x 1)                                        */
  double* body_inertia;   /* (nbody x 9) inertia tensor in the body frame; of a  */
                          /* planar body, in global axes at rz = 0 (zz used)    */
  double* body_plane;     /* (nbody x 10) a planar body's A0 (row-major), z     */

  /* markers */
  int* marker_body;       /* (nmarker x 1) body index, -1 for ground            */
  double* marker_pos;     /* (nmarker x 3) origin in the body frame             */
  double* marker_rot;     /* (nmarker x 9) axes in the body frame, row-major,
                             columns are the marker's x, y, z axes              */

  /* tapes */
  int* tape_code_adr;     /* (ntape x 1) first instruction in code              */
  int* tape_len;          /* (ntape x 1) number of instructions                 */
  int* tape_basis_adr;    /* (ntape x 1) first basis entry in basis_*           */
  int* tape_nbasis;       /* (ntape x 1) basis size, time included              */
  int* tape_nh;           /* (ntape x 1) leading basis entries with second
                             derivatives: all positions, then time (at nh-1)    */
  int* tape_body_adr;     /* (ntape x 1) first body slot in tbody_*             */
  int* tape_nbody;        /* (ntape x 1) number of bodies the tape touches      */
  int* tape_order;        /* (ntape x 1) least derivative order it must run at  */
  int* tape_nstate;       /* (ntape x 1) extra state entries (PS_OP_STATE) at the
                             end of its basis                                   */
  int* code;              /* (ncode x PS_INSTR_WIDTH) instructions              */
  double* consts;         /* (nconst x 1)                                       */
  int* basis_kind;        /* (nbasis x 1) PS_BASIS_*                            */
  int* basis_idx;         /* (nbasis x 1) index into y or yp                    */
  int* tbody_body;        /* (ntbody x 1) body index                            */
  int* tbody_q;           /* (ntbody x 1) basis position of first q, -1 if none */
  int* tbody_u;           /* (ntbody x 1) basis position of first u, -1 if none */
  int* tbody_a;           /* (ntbody x 1) basis position of first u' (yp), -1   */
  int* tbody_w;           /* (ntbody x 1) 1 when a measure needs the global
                             angular velocity                                   */

  /* the force elements and constraints, in the compiler's order: kind (PS_EL_*), the tape
   * that computes its values, and its ints (el_adr: the first in el_int) in the layout of its
   * kind (csrc/elements/<kind>.c and pysolver/catalogue.py) */
  int nel;                /* number of elements                                 */
  int* el_kind;           /* (nel x 1) PS_EL_*                                  */
  int* el_tape;           /* (nel x 1)                                          */
  int* el_adr;            /* (nel x 1) its first int in el_int                  */
  int* el_int;            /* tape slots, flags, markers, body slots and states  */
  int* state_alg;         /* (ny x 1) 1 for a reaction, 2 for a tracked angle:
                             algebraic, left out of IDA's error test            */
  double* compliance;     /* (ny x 1) c_i of a reaction's row: the row holds
                             g' + c_i lam or g + c_i mu (docs/numerics.md,
                             "Constraints"); 0 elsewhere                        */

  /* Sensor_Event: expression f in a tape slot, compared with value */
  int* sensor_tape;       /* (nsensor x 1)                                      */
  int* sensor_slot;       /* (nsensor x 1)                                      */
  int* sensor_compare;    /* (nsensor x 1) PS_CMP_*                             */
  double* sensor_value;   /* (nsensor x 1) threshold                            */
  double* sensor_tol;     /* (nsensor x 1) error_tol                            */

  /* outputs (request channels): a tape and a slot, or tape -1 for NULL */
  int* out_tape;          /* (nout x 1)                                         */
  int* out_slot;          /* (nout x 1)                                         */

  /* user subroutines called from tapes (PS_OP_USER) */
  int nuser;              /* number of routines                                 */
  int nusercache;         /* number of PS_OP_USER instructions (cache entries)  */
  void** user_fn;         /* (nuser x 1) the routine (C calling convention)     */
  int* user_form;         /* (nuser x 1) PS_USER_*: its argument list           */
  int* user_id;           /* (nuser x 1) element id passed as *id               */
  int* user_par_adr;      /* (nuser x 1) first parameter in user_par            */
  int* user_npar;         /* (nuser x 1) number of USER(...) parameters         */
  double* user_par;       /* (npar total x 1)                                   */
  int* user_key_adr;      /* (nuser x 1) first declared input in user_key_*     */
  int* user_nkey;         /* (nuser x 1) number of declared inputs              */
  int* user_timeless;     /* (nuser x 1) 1: never reads its time argument, 2: a
                             MOTSUB that gives its velocity and acceleration (iord) */
  int* user_python;       /* (nuser x 1) 1: a Python routine (py_syspar, ...)   */
  char** user_name;       /* (nuser x 1) the routine as the deck names it       */
  int* user_key_fn;       /* (nkey total x 1) function code (ps_user_fn_code)   */
  int* user_key_n;        /* (nkey total x 1) number of ids                     */
  int* user_key_ids;      /* (nkey total x 4) the ids                           */
  int* user_in;           /* (slots of PS_OP_USER inputs, in declaration order) */

  /* generated C for this scene, or NULL: the tapes above are interpreted. The tapes stay the
   * reference: the diagnosis of a non-finite value and ps_penalty_loads run them. */
  const psGen* gen;
} psModel;

typedef struct psData {
  double* slots;          /* (max_slots x hd_stride) tape registers             */
  double* bcache;         /* (max_bslots x 32 x hd_stride) body kinematics      */
  double* tmp;            /* (PS_TMP_TOTAL x hd_stride) scratch numbers         */
  double* res;            /* (2 ny x 1) residual scratch for the Jacobian        */
  double* trip;           /* (ntrip x 1) Jacobian triplet values (sparse mode)  */
  long nres;              /* residual evaluations                               */
  long njac;              /* Jacobian evaluations                               */
  double* senval;         /* (nevaluate x 1) stored Sensor_Evaluate values      */
  int* sensor_armed;      /* (nsensor x 1) 1 armed (watching for its event),
                             0 fired and waiting to re-arm                      */
  double* sensor_f;       /* (nsensor x 1) sensor expressions at the last
                             ps_roots call                                      */
  double* sensor_side;    /* (nsensor x 1) EQ sensors: +1 when armed above the
                             value, -1 below                                    */
  long nroots;            /* root-function evaluations                          */
  long ntimes;            /* step attempts: residual evaluations at a new time  */
  long nfail;             /* failed step attempts (a new time below the last)   */
  double last_t;          /* time of the last residual evaluation              */
  int user_error;         /* 1 after a user subroutine reported an error        */
  double user_t;          /* the time argument of the call that reported it (a
                             trial step's or a difference's); NaN when user_error
                             is another stop (held state, interrupt, steps)     */
  int user_coarse;        /* 1: user routines' first partials by second-order
                             central differences (runs at loose tolerances, half
                             the calls), 0: fourth-order (ps_user_point)        */
  double* trig;           /* (ny x 3) generated C's cosine and sine of a state entry
                             (a planar body's rz): the angle they are of, then
                             them; a NaN angle forgets (psg_trig)              */
  double* user_cache;     /* (nusercache x PS_USER_CACHE) the last evaluation of
                             each PS_OP_USER instruction, reused by the Jacobian
                             at the same state; zero it to forget               */
  int bad_kind;           /* what the last non-finite value was in (PS_BAD_*),
                             0 none; set only on that failure path               */
  int bad_index;          /* which one: element table row, sensor, state index,
                             or residual row / Jacobian entry row * ny + column   */
  double bad_t;           /* the time of that evaluation                        */
  int bad_partial;        /* 1 if it was a first partial of the element's value  */
  double bad_value;       /* the non-finite value itself                        */
  double* bad_y;          /* (ny x 1) the state at that evaluation              */
  long step_limit;        /* > 0: a residual that would start step number
                             step_limit + 1 (ntimes - nfail) ends the run, with
                             steps_exceeded and user_error set; 0: no limit     */
  int steps_exceeded;     /* 1 after step_limit stopped a run                   */
  int out_nonfinite;      /* 1 once ps_outputs gave a request channel with an
                             expression a non-finite value; zero it to forget   */
  const struct psRestart* rows; /* non-NULL: output rows take their accelerations
                             and reactions from it (ps_row_exact); a scene with
                             reactions                                          */
  char msg[256];          /* message of the last error                          */
} psData;

/* Where a non-finite value was found (psData.bad_kind): the state or its rate, an element's
 * values (bad_index its row in the element table), a Sensor_Event expression, an element
 * whose load has no direction (PS_BAD_DIRECTION: bad_index its row, bad_value its value; a
 * translational force whose markers coincide), or, when none is, a residual row or a
 * Jacobian entry (a derivative overflowed). */
enum {
  PS_BAD_NONE = 0, PS_BAD_STATE, PS_BAD_RATE, PS_BAD_ELEMENT, PS_BAD_SENSOR, PS_BAD_RESIDUAL,
  PS_BAD_JACOBIAN, PS_BAD_DIRECTION
};

/* The layout of element kind `kind` (PS_EL_*): its number of ints, how many leading ones are
 * tape slots of its values, and the least derivative order its tape runs at. Returns PS_OK,
 * or -1 for an unknown kind. */
int ps_element_layout(int kind, int* nint, int* nvalue, int* order);

/* Evaluate the DAE residual res = F(t, y, yp).
 * All arrays have length m->ny. Returns PS_OK, or PS_ERR_NONFINITE with a message in d->msg
 * (a non-finite value, an interrupt, a user subroutine's error, or a step past
 * d->step_limit). */
int ps_residual(const psModel* m, psData* d, double t, const double* y, const double* yp,
                double* res);

/* Consistent rates at (t, y): yp with F(t, y, yp) = 0 by Newton's method on yp from yp = 0 (F is
 * linear in yp unless expressions read accelerations, so one step usually converges), with
 * dF/dyp = J(cj = 1) - J(cj = 0) factored by dense LU with partial pivoting. work holds
 * 2 ny^2 + ny doubles and piv ny ints (allocated by the caller). At most iters steps; stops when
 * the update is below 1e-14 (1 + |yp|). Returns PS_OK, PS_ERR_NONFINITE (diagnosed as by
 * ps_residual) or PS_ERR_SINGULAR. */
int ps_consistent_yp(const psModel* m, psData* d, double t, const double* y, double* yp,
                     double* work, int* piv, int iters);

/* A sparse LU factorization (csrc/sparselu.c, below). */
typedef struct psLU psLU;

/* How a scene with motions and joints is made consistent again at a restart (csrc/control.c;
 * pysolver/build/consistent.py's consistent() away from the initial state): the state
 * indices it works on and its workspace, all allocated by the caller. Dense (J0, J1 and the
 * saddle-point matrix full), or sparse: J0 and J1 then hold the values of the kernel's CSC
 * pattern and the saddle-point system is factored by psLU. */
typedef struct psRestart {
  int nlam;               /* reactions: motions first, then constraint equations  */
  const int* lam;         /* (nlam) each reaction's state                         */
  const int* mu;          /* (nlam) its position multiplier's state, -1 if none   */
  const int* rate;        /* (nlam) an acceleration motion's driven velocity, -1  */
  int ndisp;              /* equations held at the position level (mu >= 0)      */
  const int* disp;        /* (ndisp) their indices into lam                       */
  int nturn;              /* tracked angles                                       */
  const int* turns;       /* (nturn) their states                                 */
  int nu;                 /* the bodies' velocities                               */
  const int* uidx;        /* (nu) their states                                    */
  int nrow;               /* the force rows: states that are not algebraic        */
  const int* row;         /* (nrow) their indices                                 */
  double* J0;             /* (ny x ny; sparse: jnnz) workspace from here on       */
  double* J1;             /* (ny x ny; sparse: jnnz)                              */
  double* res;            /* (ny)                                                 */
  double* res2;           /* (ny)                                                 */
  double* dx;             /* (ny)                                                 */
  double* g;              /* (nlam)                                               */
  double* z;              /* (nlam)                                               */
  double* z2;             /* (nlam)                                               */
  double* lamv;           /* (nlam)                                               */
  double* cc;             /* (nlam x nlam)                                        */
  double* saddle;         /* ((nrow + nlam)^2; sparse: unused)                    */
  double* rhs;            /* (nrow + nlam)                                        */
  int row_timed;          /* ps_row_exact: 1 when a rate row reads time (motions,
                             general constraints)                               */
  int row_linear;         /* 1 when no force reads an acceleration or a force:
                             one Newton step solves the row                     */
  double* ybak;           /* (ny) ps_row_exact's copy of the row                  */
  double* ypbak;          /* (ny)                                                 */
  int* rows;              /* (nlam)                                               */
  double* y0;             /* (ny) the assembly's start (step 1)                   */
  double* wt;             /* (ny) each velocity's inverse weight in its metric    */
  double* chg;            /* (ny) the change from y0 in it (build/icmetric.py)    */
  double* pull;           /* (2 ny) the pull toward the least change, the last one */
  /* a sparse scene (from SPARSE_THRESHOLD states) */
  int sparse;             /* 1: the fields below are used                         */
  int ntrip, jnnz;        /* the kernel's Jacobian triplets, the pattern's entries */
  const int* jmap;        /* (ntrip) triplet -> value (ps_jacobian_csc)           */
  const int* jcolptr;     /* (ny + 1) the pattern's columns                       */
  const int* jrowind;     /* (jnnz) and rows                                      */
  const int* lrow_ptr;    /* (nlam + 1) each reaction's row in the pattern:       */
  const int* lrow_at;     /* its entries' value indices                           */
  const int* lrow_col;    /* and columns                                          */
  const int* is_u;        /* (ny) 1: a body's velocity                            */
  const int* rowpos;      /* (ny) a force row's index in row, -1                  */
  double* w;              /* (ny) zero between uses                               */
  double* qr;             /* (nrow x nlam) ps_motion_reactions' least squares     */
  psLU* slu;              /* the saddle-point matrix's LU on the pattern below    */
  int snnz;               /* its entries: each J1's value s_one (-1: none) plus   */
  const int* s_one;       /* (snnz) s_sign times J0's value s_zero                */
  const int* s_zero;      /* (snnz)                                               */
  const double* s_sign;   /* (snnz)                                               */
  double* sval;           /* (snnz) its values                                    */
} psRestart;

/* Make (t, y, yp) consistent in place: the reactions zeroed, the tracked angles on their
 * measured angles, the positions moved onto the position constraints (the least change in the
 * mass metric, pysolver/build/icmetric.py) and the velocities onto the rate rows (the least
 * change), then the accelerations and the reactions solved for.
 * Its residual evaluations are not step attempts (d->ntimes, nfail, last_t and step_limit are
 * left as they were).
 * Returns PS_OK, PS_ERR_NONFINITE (a kernel evaluation failed, as ps_residual),
 * PS_ERR_SINGULAR or PS_ERR_ASSEMBLY. */
int ps_restart_consistent(const psModel* m, psData* d, const psRestart* r, double t, double* y,
                          double* yp);

/* Make an output row's accelerations and reactions exact at its positions and velocities, in
 * place: IDA's error test leaves the reactions out and holds the accelerations (yp) only to
 * about the tolerance over the step, so a reaction carried percents of noise at
 * integr_tol 1e-3 (a driven rod's torque: 2 %). The saddle-point system of step 3 above is
 * solved at (t, y) with the position multipliers and the reactions' rates at their exact
 * zero: one Newton step when r->row_linear (or the force rows' residual falls to rounding
 * after it), more when a force reads an acceleration; the rate rows' time derivative only
 * when r->row_timed. Its evaluations are not step attempts (as ps_restart_consistent's). On
 * failure (a singular pivot, a non-finite value, a user routine's error, or reactions a
 * thousand times IDA's largest: an ill-conditioned system near a singular configuration) the row,
 * the error flags and the message are left as they were and the code is returned. */
int ps_row_exact(const psModel* m, psData* d, const psRestart* r, double t, double* y,
                 double* yp);

/* The motions' and constraints' reactions (nlam, into lam) that balance the force rows at
 * (t, y, yp), by least squares: what a LoadControl task with load="motion" measures. Returns
 * PS_OK, PS_ERR_NONFINITE or PS_ERR_SINGULAR. */
int ps_motion_reactions(const psModel* m, psData* d, const psRestart* r, double t,
                        const double* y, const double* yp, double* lam);

/* The LoadControl law (seed 002) between updates: its parameters, then its state. loads and
 * sorted hold window doubles each (allocated by the caller). */
typedef struct psLaw {
  double velocity0;       /* the starting velocity                                */
  double max_velocity;    /* MaxVelocity                                          */
  double kp, ki;          /* gains                                                */
  double smooth;          /* a, in (0, 1)                                         */
  int window;             /* median filter samples (1: off)                       */
  int has_A;              /* 1 once the load/displacement ratio A is known        */
  double A, e, ie, e2;    /* the ratio, the smoothed error, its integral, e's
                             second smoothing                                     */
  double velocity;        /* the velocity of the current interval                 */
  double x_onset;         /* displacement at the onset of load                    */
  int nloads;             /* loads kept for the median                            */
  double* loads;          /* (window) the last loads, oldest first                */
  double* sorted;         /* (window) scratch                                     */
} psLaw;

/* Put the law's state back to its start (its parameters stay). */
void ps_law_reset(psLaw* w);

/* One update at time t with displacement x from the start, measured load and target load;
 * writes the PS_LAW_FIELDS fields of its log row into row and returns the velocity for the
 * next interval (the law of pysolver/solve/loadlaw.py, operation for operation). */
double ps_law_update(psLaw* w, double t, double x, double load, double target, double* row);

/* One LoadControl task: its law, where it reads and writes in the state, its schedule and
 * its log (cap rows of PS_LAW_FIELDS, allocated by the caller). */
typedef struct psControl {
  psLaw law;
  int contact;            /* 1: the load is the penalties' force on the body along
                             the axis; 0: minus the driving motion's reaction     */
  int q, u;               /* state indices of the body's coordinate and velocity
                             along the axis                                       */
  int lam;                /* the driving motion's index among the reactions       */
  int value;              /* its velocity's slot in d->senval                      */
  int tape, slot;         /* the target load's expression                         */
  double dt;              /* UpdateTime                                           */
  double t0, x0;          /* the start's time and coordinate                      */
  long n;                 /* the number of the next update                        */
  double* log;            /* (cap x PS_LAW_FIELDS) one row per update             */
  long nlog, cap;         /* rows written, rows allocated                         */
  double bad[3];          /* load, target and velocity of the last update         */
} psControl;

/* Start a task at (t, y): its schedule, its law's state and log, the starting velocity, and
 * (t, y, yp) made consistent with it (ps_restart_consistent's codes). */
int ps_control_start(const psModel* m, psData* d, const psRestart* r, psControl* c, double t,
                     double* y, double* yp);

/* The time of the task's next update: t0 + n dt. */
double ps_control_next(const psControl* c);

/* Run the task's update at (t, y, yp): the load, the target, the law (a log row), the new
 * velocity into d->senval and the state made consistent with it (in place). Returns PS_OK, a
 * PS_CTRL_* code (c->bad holds the values) or ps_restart_consistent's codes. */
int ps_control_update(const psModel* m, psData* d, const psRestart* r, psControl* c, double t,
                      double* y, double* yp);

/* Sensor_Event elements decided in C (csrc/events.c): those whose actions need no Python
 * (store a Sensor_Evaluate no force reads, halt, restart, print, return, dt, verbose, hmax,
 * stepsize). Per
 * sensor (index k in id order)
 * its actions, then the state of the run's instants, the events recorded (cap of them,
 * allocated by the caller) and scratch. */
#define PS_SE_CHATTER 20 /* sensor events chatter (sensors.py, CHATTER_LIMIT) */
#define PS_SE_BUDGET 21  /* a sensor's print interval passes the output budget */
#define PS_SE_USER 22    /* a user subroutine failed in an action */
#define PS_SE_RESTART 23 /* a restart could not make the state consistent (S->restart_rc) */
typedef struct psSensors {
  int n;                  /* sensors (m->nsensor)                                 */
  const int* evaluate;    /* (n) the d->senval slot of its Sensor_Evaluate, -1    */
  const int* eval_tape;   /* (n) that Sensor_Evaluate's tape                      */
  const int* eval_slot;   /* (n) and slot                                         */
  const int* halts;       /* (n) 1: halt                                          */
  const int* restarts;    /* (n) 1: restart                                       */
  const int* prints;      /* (n) 1: write a row at the event                      */
  const int* rets;        /* (n) 1: end the Simulate command                      */
  const double* dts;      /* (n) a new print interval, 0 none                     */
  const int* verboses;    /* (n) 1: log every output row while active             */
  const double* hmaxs;    /* (n) a new largest step, 0 none                       */
  const double* stepsizes; /* (n) the first step of a restart, 0 none             */
  int* verbose_on;        /* (n) 1: a verbose sensor fired and not re-armed       */
  int nverbose;           /* verbose sensors                                      */
  int consistent;         /* 1: forces read SENVAL, so an action that restarts
                             makes yp consistent again (ps_consistent_yp)         */
  double* cwork;          /* (2 ny^2 + ny) its workspace, NULL without           */
  int* cpiv;              /* (ny)                                                 */
  const psRestart* whole; /* or, with motions, joints, tracked angles or a sparse
                             scene, the whole consistent restart (positions too)  */
  int restart_rc;         /* the code of a restart that failed (PS_SE_RESTART)    */
  int batch_restart;      /* scratch: a restart among the sensors firing together */
  int* holds;             /* (n) scratch from here on                             */
  int* rearms;            /* (n)                                                  */
  int* fired;             /* (n) fired at this instant                            */
  int* rearmed;           /* (n) re-armed at this instant                         */
  int* now;               /* (n)                                                  */
  int* roots;             /* (n) IDA's root flags                                 */
  double* f;              /* (n) the sensors' expressions at the instant          */
  double recent[100];     /* the times of the last 100 firings and re-armings     */
  int first, nrecent;     /* where the oldest of them is, how many there are      */
  long nrearms;           /* re-armings in the run                                */
  int restart;            /* 1: the last instant's actions asked for a restart    */
  int emit;               /* 1: they asked for a row                              */
  int emitted;            /* the row: 0 none, 1 added, 2 replacing one            */
  int halt;               /* the sensor that halted the run at it, -1 none        */
  int ret;                /* the sensor that ended the command at it, -1 none     */
  double dt;              /* the print interval it set, 0 none                    */
  double hmax;            /* the largest step it set, 0 none                      */
  double first_step;      /* the first step it asked for (the smallest), 0 none   */
  int over;               /* the sensor whose print interval passed the budget    */
  long instant_nev;       /* the first event of the last instant                  */
  long rows;              /* output rows of the run before the instant            */
  double tend;            /* the current command's end (NaN: before the first)    */
  double row_bytes;       /* bytes per output row (outputs.over_budget)           */
  double budget;          /* the output budget in bytes                           */
  double* ev_time;        /* (cap) each event's time                              */
  double* ev_value;       /* (cap) its sensor's expression                        */
  int* ev_sensor;         /* (cap) its sensor: k an event, -1 - k a verbose line,
                             -1 - n - k a zero-crossing line (ev_value: the hmax) */
  long nev, cap;          /* events recorded, room for them                       */
  long drained;           /* records handed over before ev_time[0]                */
  long undo;              /* after a restore, the records of the run to keep when
                             it is fewer than drained (-1: none to take back)     */
  double interval;        /* the print interval in force (Printer.dt)             */
  double anchor;          /* and where its grid began                             */
  /* zero_crossing (sensors.py, _restore_and_shrink) */
  const double* zcs;      /* (n) its zero_crossing factor, 0 none                 */
  int nzc;                /* sensors with one: IDA steps one step at a time       */
  int* zc_pending;        /* (n) 1: a search for its crossing is under way        */
  int saved;              /* 1: the step bounds before the searches are kept      */
  double saved_hmax, saved_hmin;
  int back;               /* the instant ended the searches: restart with         */
  double back_hmax, back_hmin; /* these bounds (unless an hmax action set one)    */
  int restore;            /* the instant goes back to the last converged step     */
  double restore_zc;      /* and shrinks the bounds by this factor                */
  /* the converged steps the run can go back to (Run.steps_seen), a ring of PS_SNAPS:
   * time, state, the sensors' state, records, largest step and print interval */
  int nsnap, snap_first, nsenval;
  double* snap_t;         /* (PS_SNAPS)                                           */
  double* snap_hmax;      /* (PS_SNAPS)                                           */
  double* snap_interval;  /* (PS_SNAPS)                                           */
  double* snap_anchor;    /* (PS_SNAPS)                                           */
  long* snap_nrearms;     /* (PS_SNAPS)                                           */
  long* snap_records;     /* (PS_SNAPS) records of the run (drained counted)      */
  double* snap_y;         /* (PS_SNAPS x ny)                                      */
  double* snap_yp;        /* (PS_SNAPS x ny)                                      */
  int* snap_armed;        /* (PS_SNAPS x n)                                       */
  double* snap_side;      /* (PS_SNAPS x n)                                       */
  int* snap_verbose;      /* (PS_SNAPS x n)                                       */
  double* snap_senval;    /* (PS_SNAPS x nsenval)                                 */
  int nctl;               /* the run's LoadControl tasks (ps_ida_controlled's)    */
  psControl* const* ctl;  /* (nctl) set by ps_ida_controlled                      */
  psControl* snap_ctl;    /* (PS_SNAPS x nctl) each task as it was                */
  double* snap_loads;     /* (PS_SNAPS x the tasks' windows) and its last loads   */
  int nloads;             /* the tasks' windows together                          */
} psSensors;

/* The converged steps a zero-crossing search can go back to (sensors.py keeps three). */
#define PS_SNAPS 3

/* The sensors at the start of a run at (t, y, yp): every sensor armed (an EQ sensor on the
 * side it starts on), then those whose condition holds fire (the event iteration). Sets what
 * the instant asks (S->restart, emit, halt, ret, dt, hmax, first_step). Where forces read
 * SENVAL, sensors firing together that restart make (y, yp) consistent at the end of their
 * batch: yp by ps_consistent_yp (NaN when it fails), or with S->whole the whole state by
 * ps_restart_consistent. Returns PS_OK, PS_SE_CHATTER, PS_SE_USER or PS_SE_RESTART
 * (S->restart_rc: ps_restart_consistent's code). */
int ps_sensors_start(const psModel* m, psData* d, psSensors* S, double t, double* y,
                     double* yp);

/* Record a log line (an event record of sensor -1 - k) for every verbose sensor k that is
 * active, with its expression at (t, y, yp): an output row was written there. Returns the
 * number of records written (none past S->cap). */
int ps_sensors_verbose(const psModel* m, psData* d, psSensors* S, double t, const double* y,
                       const double* yp);

/* The sensors at a root of theirs at (t, y, yp), found IDA's root flags: those crossed fire
 * (armed) or re-arm (fired before), then the event iteration; but when a zero_crossing
 * sensor fires for the first time (and a converged step before t is remembered) nothing
 * happens but S->restore = 1 (S->restore_zc the smallest factor, S->now those sensors): the
 * caller goes back to that step. Sets what the instant asks (S->restart, emit, halt, ret, dt,
 * hmax, first_step; S->back with the bounds a finished search gives back); (y, yp) made
 * consistent as ps_sensors_start does. Returns PS_OK, PS_SE_CHATTER, PS_SE_USER,
 * PS_SE_RESTART or PS_SE_BUDGET (a print interval would make the run's rows, S->rows before
 * the instant and those to S->tend, pass S->budget: S->over is the sensor, and the instant
 * stops at it). */
int ps_sensors_roots(const psModel* m, psData* d, psSensors* S, const int* found, double t,
                     double* y, double* yp);

/* Ctrl-C during a run: ps_interrupt_arm installs a SIGINT handler (saving the previous one)
 * whose first signal makes every later ps_residual fail at once until ps_interrupt_disarm,
 * not recoverably, with the message "interrupted", and whose second ends the process;
 * ps_interrupt_disarm puts the previous handler back; ps_interrupted says whether the signal
 * came during the last armed run (until the next ps_interrupt_arm). */
void ps_interrupt_arm(void);
void ps_interrupt_disarm(void);
int ps_interrupted(void);

/* How far rounding carries a result (pysolver/solve/precision.py): the largest ratio, over
 * the moving bodies, of the change the rounding of the state can make in a body's
 * translational force rows (sum over j of |dF_r/dy_j| u |y_j|, reactions left out) to the
 * forces the body carries (its mass times the larger of |gravity| and its acceleration, and
 * the net applied force without reactions), or carried[b] where that is larger
 * (carried: the largest sum of the magnitudes of the forces on each body over the run,
 * ps_carried, or NULL: so that a body that comes to rest with balanced or no loads is not
 * measured against nothing; without gravity, a body on which no force acted at the deck's
 * start, at_start[b] == 0, and none above its rounding change since has no load to resolve
 * and is left out). trow and tcol (ntrip entries) are the kernel's
 * Jacobian triplet pattern (ps_jacobian_pattern; ignored with a generated library, which has
 * its own); work holds 4 ny doubles. *body is the worst body's
 * index, or -1 when no body carries a force (the ratio is then 0; NaN when a value is not
 * finite; infinite, without carried, for a body that carries exactly nothing but whose
 * forces rounding would move). The run's call counters are left as they were. */
double ps_precision(const psModel* m, psData* d, double t, const double* y,
                    const double* yp, const int* trow, const int* tcol, int ntrip,
                    const double* carried, const double* at_start, double* work, int* body);

/* The forces on each body at (t, y) without reactions, each force's magnitude summed over
 * its translational force rows (the tapes' assembly), into carried (nbody); work holds 3 ny
 * doubles. The run's call counters are left as they were. */
void ps_carried(const psModel* m, psData* d, double t, const double* y, double* work,
                double* carried);

/* Write into q (length m->ny) the generalized forces of all Force_Penalty elements at
 * (t, y, yp), in model force units, on the velocity rows (zero elsewhere): the contact load a
 * LoadControl task with load="contact" reads. Returns PS_OK or PS_ERR_NONFINITE. */
int ps_penalty_loads(const psModel* m, psData* d, double t, const double* y, const double* yp,
                     double* q);

/* A sparse LU factorization of square matrices in compressed sparse columns whose pattern
 * stays fixed (csrc/sparselu.c): IDA's sparse linear solver on the C driver, and the sparse
 * restart's (psRestart). Opaque (psLU, declared above); made by ps_lu_new, freed by
 * ps_lu_free. */

/* Return a factorization object for n x n matrices with the pattern colptr (n + 1), rowind
 * (colptr[n]), which must outlive it, factored in the column order colorder (n entries, a
 * permutation: step k factors column colorder[k]; NULL: natural order), or NULL when out of
 * memory or n <= 0. */
psLU* ps_lu_new(int n, const int* colptr, const int* rowind, const int* colorder);

/* Free a factorization object. NULL is allowed. */
void ps_lu_free(psLU* f);

/* Factor the matrix with values values (in the pattern's order) with threshold partial
 * pivoting that prefers the diagonal. Entries that are zero now and were zero in every
 * factorization since the last ps_lu_forget are left out. Returns 0; k + 1 when step k finds
 * no nonzero finite pivot (the matrix is singular to working precision, or not finite); -1
 * when out of memory. */
int ps_lu_factor(psLU* f, const double* values);

/* Factor new values with the pivots and the patterns of L and U of the last successful
 * ps_lu_factor. Returns 0; 1 when a pivot is no longer acceptable (zero, not finite, or below
 * 1e-3 of the largest entry under it) or an entry that factorization left out is nonzero:
 * call ps_lu_factor; -1 when there is no factorization to replay. */
int ps_lu_refactor(psLU* f, const double* values);

/* Forget the pivots and which entries were nonzero: the next ps_lu_refactor returns -1, so a
 * run that restarts factors as a fresh one would, and gives the same answer. */
void ps_lu_forget(psLU* f);

/* Solve A x = b in place (b: n entries) with the last successful factorization. */
void ps_lu_solve(const psLU* f, double* b);

/* Entries of L and U of the last factorization (0 if none). */
long ps_lu_nnz(const psLU* f);

/* Write the factorization's counts: full factorizations, replays (ps_lu_refactor), and
 * replays that fell back (a stale pivot, or a nonzero entry left out; out: 3 entries). */
void ps_lu_counts(const psLU* f, long* out);

/* SUNDIALS IDA opened at run time from shared libraries, and one integration with it
 * (csrc/ida.c). Opaque: made by ps_ida_load (the libraries, once per process) and ps_ida_new
 * (one integration object sharing them), freed by ps_ida_delete. */
typedef struct psIDA psIDA;

/* A CSV file written row by row while a run makes its rows (ps_stream_*). */
typedef struct psStream psStream;

/* Open the nine SUNDIALS 7 shared libraries whose paths are given in this order: core,
 * nvecserial, sunmatrixdense, sunlinsoldense, ida, sunmatrixband, sunlinsolband, and the
 * optional sunmatrixsparse and sunlinsolsuperlumt (NULL paths, or libraries that do not open,
 * leave the sparse solver out), and look up the functions used. Returns the loaded table (its
 * libraries stay open for the process's life), or NULL with a message in msg (msglen bytes). */
psIDA* ps_ida_load(const char* const* paths, char* msg, int msglen);

/* Whether a table from ps_ida_load has the sparse matrix and can give IDA pysolver's own
 * sparse LU (ps_ida_init's mu = PS_IDA_SPARSE). */
int ps_ida_has_sparse(const psIDA* s);

/* Whether a table from ps_ida_load has the sparse matrix and SuperLU_MT (ps_ida_init's
 * mu = PS_IDA_SUPERLU_MT). */
int ps_ida_has_superlumt(const psIDA* s);

/* ps_ida_init's mu selecting a sparse solver: pysolver's sparse LU (csrc/sparselu.c), or
 * SUNDIALS' SuperLU_MT on one thread (kept for comparison); or SUNDIALS' dense solver for a
 * dense matrix (kept for comparison; pysolver's own dense LU otherwise). */
enum { PS_IDA_SPARSE = -2, PS_IDA_SUPERLU_MT = -3, PS_IDA_SUNDIALS_DENSE = -4 };

/* Return a new integration object using the functions of a table from ps_ida_load (not
 * started; see ps_ida_init), or NULL when out of memory. Free it with ps_ida_delete. */
psIDA* ps_ida_new(const psIDA* loaded);

/* Free an integration object and its current integration. NULL is allowed. */
void ps_ida_delete(psIDA* s);

/* IDA's interpolant over its last step at t (at or before its current time, after its last
 * step's start) into y and yp, as IDASolve gives a requested time it has passed, without
 * stepping, stopping or looking for roots. Returns 0 or IDA's flag (< 0). */
int ps_ida_interpolate(psIDA* s, double t, double* y, double* yp);

/* Write every output row ps_ida_outputs makes to st as soon as it is made (NULL: stop),
 * flushed row by row when the model calls user subroutines (the code that may crash the
 * process), else at the end of each ps_ida_outputs call. The stream is not owned: close it
 * after the integration object no longer uses it. */
void ps_ida_set_stream(psIDA* s, psStream* st);

/* Return the message of the last failed ps_ida_init or ps_ida_tune ("" if none). */
const char* ps_ida_message(const psIDA* s);

/* Start an integration of (m, d) at (t0, y0, yp0) with the kernel's Jacobian and, if the model
 * has sensors, its root functions with directions rootdir (length m->nsensor). hmax, hmin,
 * h0 <= 0 mean IDA's defaults. mu, ml >= 0 select a band solver with those bandwidths, whose
 * matrix is filled from the kernel's triplets (ps_jacobian_pattern order) at the band storage
 * indices map (ntrip entries); mu = PS_IDA_SPARSE or PS_IDA_SUPERLU_MT selects a
 * compressed-sparse-column matrix with the fixed pattern colptr (ny + 1) and rowind (nnz),
 * filled from the triplets at the value indices map, factored by pysolver's sparse LU in the
 * column order colorder (ny entries; NULL: natural order) or by SuperLU_MT on one thread;
 * otherwise dense: factored by pysolver's own LU (by SUNDIALS' dense solver with
 * mu = PS_IDA_SUNDIALS_DENSE). map, colptr, rowind and colorder must outlive the integration. Returns
 * PS_OK, or -1 with a message (ps_ida_message); a failed set-up frees what it built. */
int ps_ida_init(psIDA* s, const psModel* m, psData* d, double t0, const double* y0,
                const double* yp0, double rtol, double atol, double hmax, double hmin, double h0,
                long mxsteps, const int* rootdir, int mu, int ml, const int* map, int ntrip,
                const int* colptr, const int* rowind, int nnz, const int* colorder);

/* Tune IDA's step control for stiff penalties. eta_max > 0 limits how fast IDA may grow its
 * step (IDA's default 2); nlconv > 0 sets the Newton convergence coefficient (IDA's default
 * 0.33); auto_eta > 0 (with eta_max <= 0) switches the limit auto_eta on by itself once IDA's
 * error test has failed in more than half of 50 consecutive steps while the step size stayed
 * within a factor 4, the signature of a stiff penalty mode (docs/stiff-penalties.md).
 * Call right after ps_ida_init. Returns PS_OK, or -1 with a message (ps_ida_message). */
int ps_ida_tune(psIDA* s, double eta_max, double nlconv, double auto_eta);

/* Name the states a scene may hold at their start values (ascending indices; none: nhold
 * 0), for the next ps_ida_init: a point body's coordinate that nothing moves, and its
 * velocity (pysolver/build/held.py). An integration with a dense matrix that starts with
 * every one of them at rest (its rate zero in yp0, its equation exactly satisfied at the
 * start, and some other state left to integrate) leaves them out of IDA's vectors, error
 * test and matrix; the kernel and every state this object returns are still full, the held
 * entries at their values of the last (re)start. Each residual checks that their equations
 * hold exactly (else the run ends with a message). Returns 0, or -1 when out of memory. */
int ps_ida_hold(psIDA* s, const int* hold, int nhold);

/* The number of states the current integration holds (0: IDA integrates all of them). */
int ps_ida_held(const psIDA* s);

/* The number of dense solves s has made by a product with the matrix's inverse (small,
 * well-conditioned systems; docs/numerics.md, "The dense solve") since it was loaded. */
long ps_ida_inverse_solves(const psIDA* s);

/* The ascending times (n of them, after the run's start) where a function of time alone has a
 * kink or jump (pysolver/solve/breaks.py): ps_ida_controlled stops IDA at each and restarts
 * it there with the rates of ps_consistent_yp at t + 1e-12 max(1, |t|) (work and piv
 * its workspace, kept by the caller), as the general driver's TimeBreaks actor does (a scene
 * without motions, constraints or tracked angles, dense); ps_ida_rerun and ps_ida_init start
 * from the first break after their t0. The times are copied; n = 0 clears them. Returns 0,
 * or -1 when out of memory. */
int ps_ida_breaks(psIDA* s, const double* times, int n, double* work, int* piv);

/* ps_ida_reinit's return when the integration holds states and the restart's yp0 moves one
 * (ps_ida_hold): call ps_ida_init, which then integrates every state. */
#define PS_IDA_HELD -2006

/* Cold-restart the current integration at (t0, y0, yp0); the counters of ps_ida_stats keep
 * counting. Returns IDA's flag, or PS_IDA_HELD. */
int ps_ida_reinit(psIDA* s, double t0, const double* y0, const double* yp0);

/* One IDASolve call toward tout (one internal step if onestep) never passing tstop; copies the
 * state into y, yp; on a root return (2) fills rootsfound. Returns IDA's flag. */
int ps_ida_solve(psIDA* s, double tout, double tstop, int onestep, double* tret, double* y,
                 double* yp, int* rootsfound);

/* Advance through the nout output times, writing states (nout x ny) and request outputs
 * (nout x m->nout); stops early on a root (flag 2, rootsfound filled, tret the root time) or a
 * failure (< 0). *nreached is the number of outputs written. With fresh (right after a
 * (re)start) the first call is one internal step toward tstop, so that IDA sizes the first step
 * from the stop rather than from the first output time; the output times it passes are
 * interpolated. Returns the last IDA flag. */
int ps_ida_outputs(psIDA* s, const double* tout, int nout, double tstop, int fresh,
                   double* y_out, double* yp_out, double* req_out, int* nreached, double* tret,
                   int* rootsfound);

/* Start a new run of the integration set up by ps_ida_init at (t0, y0, yp0), keeping its IDA
 * object and linear solver: IDA's state and the counters of ps_ida_stats start from zero.
 * Returns 1 when the object cannot be reused as it is (never set up, its step-growth limit
 * switched on by ps_ida_tune's auto_eta, SuperLU_MT, whose factorization is kept between
 * runs, or a start that can hold states this integration does not, or the other way round):
 * call ps_ida_init instead; else IDA's flag. The step bounds go back to
 * ps_ida_init's. */
int ps_ida_rerun(psIDA* s, double t0, const double* y0, const double* yp0);

/* ps_ida_controlled's returns other than IDA's flags: a LoadControl update failed, the
 * sensors chatter, a sensor halted the run, a sensor ended the command, a sensor set a new
 * print interval (call again with its print times), the event records or the rows are full
 * (drain or grow them and call again). After the last four the state is that of the top of
 * the loop. */
#define PS_IDA_CONTROL_FAILED -2000
#define PS_IDA_CHATTER -2001
#define PS_IDA_HALTED 3
#define PS_IDA_DRAIN 4
#define PS_IDA_RETURN 5
#define PS_IDA_REGRID 6
#define PS_IDA_BUDGET -2002
#define PS_IDA_BOUNDS -2003
#define PS_IDA_USER -2004
#define PS_IDA_RESTORED 7
#define PS_IDA_SENSOR_RESTART -2005

/* Advance through the rest of a Simulate command's output times tout (ending at tend) with the run's actors deciding in C, exactly as the general driver does
 * (pysolver/solve/driver.py, Run.integrate_command and Run.apply): the LoadControl tasks c
 * (nctl, in id order) at their update times (ps_control_update, then a cold restart; IDA stops
 * exactly there) and the sensors S (NULL: none) at their roots (ps_sensors_roots, then a
 * restart if asked, a row at the instant for print, halt and return, which replaces a row at
 * the same time); one internal step toward the stop after a restart; at the command's
 * end the updates due there. (*t, y, yp) is the current state and *fresh
 * whether IDA was just (re)started, both carried from call to call. Rows go to t_out, y_out,
 * yp_out, req_out (cap rows of room, which the caller keeps at least one more than the output
 * times left): *nreached rows written, *nused output times used; *nrestarts counts the
 * restarts. The rows are streamed (ps_ida_set_stream) all but the last, which a row at an
 * event may replace: held says how many rows before t_out[0] are not streamed yet (0 or 1),
 * and the rows before index *nstreamed (from -held) are streamed on return; the caller streams the rest at
 * the end of the run. Returns 0, IDA's flag (< 0) of a failed step with *tret its time,
 * PS_IDA_CONTROL_FAILED (ctl: the task's index and ps_control_update's code), PS_IDA_CHATTER,
 * PS_IDA_BUDGET (S->over's print interval passes the output budget; S->rows are the rows of
 * the run before its call plus those it wrote, as the caller sets S->rows at each call),
 * PS_IDA_BOUNDS (new step bounds could not be set: ps_ida_message), PS_IDA_USER (a user
 * subroutine failed in a sensor's action: the kernel's message), PS_IDA_SENSOR_RESTART (a
 * sensors' restart could not make the state consistent: S->restart_rc), PS_IDA_HALTED,
 * PS_IDA_RETURN, PS_IDA_REGRID, PS_IDA_DRAIN or PS_IDA_RESTORED. Returns early, with 0, after
 * Ctrl-C (ps_interrupted).
 *
 * With zero_crossing sensors (S->nzc) IDA takes one step at a time and every converged step
 * is remembered (S's snapshots, as the general loop's Run.steps_seen); a zero_crossing sensor
 * seen firing for the first time takes the run back to the last one (the state, the sensors,
 * the records, the rows after it: *nreached may then be negative, down to -row0, where row0
 * rows of the run lie before t_out[0]), shrinks the step bounds and returns PS_IDA_RESTORED:
 * call again with the print times after *t of the grid of S->interval from S->anchor (the
 * caller sets both at each command's start, and S->nsnap = 0: a restore goes back no
 * further than the command's start). Rows are then
 * streamed only before the oldest snapshot, and held counts the rows before t_out[0] not
 * streamed yet. */
int ps_ida_controlled(psIDA* s, const psRestart* r, psControl* const* c, int nctl, psSensors* S,
                      const double* tout, int nout, double tend, double* t, double* y,
                      double* yp, int* fresh, int cap, int row0, int held, double* t_out,
                      double* y_out,
                      double* yp_out, double* req_out, int* nreached, int* nused, int* nstreamed,
                      double* tret, long* nrestarts, int* ctl);

/* New step bounds for the current integration, from its next (re)start on: the largest and
 * smallest step and the first step (0: IDA's default for each). As with a new IDA object, a
 * step-growth limit that ps_ida_tune's auto_eta switched on is lifted. Returns 0, or -1 with
 * a message (ps_ida_message). */
int ps_ida_bounds(psIDA* s, double hmax, double hmin, double h0);

/* IDA's counters over the whole run, restarts included: steps, residual evaluations, Jacobian
 * evaluations, error-test failures, nonlinear convergence failures, root-function evaluations,
 * and the step at which the automatic step-growth limit came on, 0 if it did not (out has 7
 * entries). */
void ps_ida_stats(psIDA* s, long* out);


/* Fill the dense iteration matrix J = dF/dy + cj * dF/dyp, row-major (ny x ny), exactly.
 * Returns PS_OK or an error code with a message in d->msg. */
int ps_jacobian(const psModel* m, psData* d, double t, const double* y, const double* yp,
                double cj, double* jac);

/* Count the structural nonzeros of the iteration matrix as (row, col) triplets, in the order
 * ps_jacobian_csc produces their values. rows and cols may be NULL (count only); a triplet may
 * repeat an entry (values are summed). d->res must hold 2 ny doubles. Returns the count. */
int ps_jacobian_pattern(const psModel* m, psData* d, int* rows, int* cols);

/* Fill the CSC data array (length nnz) of the iteration matrix: triplet k is added to
 * data[map[k]]. d->trip must hold ntrip doubles. Returns PS_OK or an error code. */
int ps_jacobian_csc(const psModel* m, psData* d, double t, const double* y, const double* yp,
                    double cj, const int* map, int ntrip, double* data, int nnz);

/* Evaluate the root function of every sensor into g (length m->nsensor): an event is a
 * crossing of g from negative to positive. Armed GE: f - value; armed LT: value - f; armed
 * EQ entering the band |f - value| <= tol from its side s: s (value + s tol - f) (one crossing,
 * so a fast pass through a narrow band is not missed). A fired sensor watches for re-arming
 * instead: GE (value - tol) - f, LT f - (value + tol), EQ |f - value| - 2 tol. Writes f into
 * d->sensor_f. Returns PS_OK, or PS_ERR_NONFINITE (d->bad_kind = PS_BAD_SENSOR) when a sensor's
 * expression is not finite. */
int ps_roots(const psModel* m, psData* d, double t, const double* y, const double* yp,
             double* g);

/* The sensors' rules at one point, for the driver's event iteration: evaluate every sensor
 * expression into d->sensor_f and set holds[k] = 1 where sensor k's condition holds (GE:
 * f >= value; LT: f < value; EQ: |f - value| <= tol) and rearms[k] = 1 where a fired sensor
 * may re-arm (GE: f < value - tol; LT: f > value + tol; EQ: |f - value| > 2 tol). These are
 * the same rules whose crossings ps_roots reports; this call is not counted in d->nroots.
 * holds and rearms have m->nsensor entries. Returns PS_OK. */
int ps_sensor_status(const psModel* m, psData* d, double t, const double* y, const double* yp,
                     int* holds, int* rearms);

/* Open the generated library at path (RTLD_LOCAL; it stays open for the process's life) and
 * return its ps_gen_table, checked against its record of the scene it was generated for
 * (ps_gen_scene, equal to scene) and against m (version and sizes), or NULL with a message in
 * msg (msglen bytes), the library closed again. */
const psGen* ps_gen_open(const char* path, const char* scene, const psModel* m, char* msg,
                         int msglen);

/* Open the shared library at path and return its function name, or NULL with a message in msg
 * (msglen bytes). The kernel's own symbols (c_sysfnc, c_sysary, c_errmes) are made global
 * first, so that a library built without linking against pysolver finds them. */
void* ps_user_open(const char* path, const char* name, char* msg, int msglen);

/* Evaluate the routine of PS_OP_USER instruction cache_index (routine k, result channel chan)
 * at its nin inputs and time, z (nin + 1 values), with its partials in them to order `order`
 * (0, 1 or 2) by central differences: out[0] the value, out[1 + i] the first partials,
 * out[1 + n + i n + j] the second (n = nin + 1; out holds 1 + n + n n doubles). The value and
 * first partials at the same inputs are reused from d->user_cache. Returns 0, or -1 after the
 * routine reported an error (d->user_error and d->msg set, out[0] NaN). Tapes (csrc/tape.c)
 * and generated C call it. */
int ps_user_point(const psModel* m, psData* d, int cache_index, int k, int chan,
                  const double* z, int nin, int order, double* out);

/* Call user routine fn (argument list form, PS_USER_*; python 1 for a Python routine, whose
 * messages name py_sysfnc) once with iflag = 1, as Adams does to learn its dependencies: each
 * c_sysfnc / c_sysary call it makes is recorded as a canonical key ("DX(9,1)"; arrays as their
 * entries) into keys (maxkeys x PS_USER_KEY) and returns 0. Returns the number of keys
 * (maxkeys + 1 if there were more), or -1 with a message in msg when the routine reported an
 * error (c_errmes) or called an unknown function. */
int ps_user_declare(void* fn, int form, int python, int id, const double* par, int npar,
                    char* keys, int maxkeys, char* msg, int msglen);

/* Call a MOTSUB fn (python 1 for a Python routine) once at time t with iflag = 0 and iord
 * (0: the value, 1: its velocity, 2: its acceleration) into *value. Returns 0, or -1 with a
 * message in msg when it reported an error or read a value. */
int ps_user_motion(void* fn, int python, int id, const double* par, int npar, double t,
                   int iord, double* value, char* msg, int msglen);

/* Return the code c_sysfnc uses for an expression-language function name (case and spaces
 * ignored), or -1 when it is not one c_sysfnc answers. */
int ps_user_fn_code(const char* name);

/* Report an error from inside a user subroutine call (a Python routine's exception): the
 * current evaluation yields NaN and d->msg says why, in this message, which names the routine
 * (other errors are prefixed with user_name). Outside a call it does nothing. */
void ps_user_fail(const char* message);

/* Return the values of the system values the routine being called declared, in declaration
 * order (what c_sysfnc answers from), or NULL outside an evaluating call. A Python routine
 * reads them from here instead of calling c_sysfnc for each. */
const double* ps_user_values(void);

/* Give the partial of the routine being called in its declared input `key` (py_syspar for one
 * value the routine read, found by its key without c_syspar's parsing). Returns 0, or 1 when
 * no partials are wanted now (outside an evaluating call, or a call for the value alone) or
 * `key` is not one of its inputs; nothing is written then. */
int ps_user_give(int key, double partial);

/* Return the rate of change of the kinetic energy, sum of m v.v' + w.(I w') over bodies, in
 * model units (the root function of MKEAM's kinetic-energy peaks). */
double ps_power(const psModel* m, const double* y, const double* yp);

/* Evaluate every output channel into out (length m->nout); a NULL channel gives NaN, and a
 * channel with an expression that is not finite sets d->out_nonfinite. Returns PS_OK. */
int ps_outputs(const psModel* m, psData* d, double t, const double* y, const double* yp,
               double* out);

/* Evaluate one tape at derivative order 0 and return its slot's value (for tests and tools). */
double ps_eval_tape(const psModel* m, psData* d, int tape, int slot, double t, const double* y,
                    const double* yp);

/* Write f into out as Python's repr(float) writes it (the shortest digits that read back to
 * the same double), NUL-terminated; out holds at least 26 characters. Returns the length. */
int ps_format_double(double f, char* out);

/* Write a CSV file: open path with fopen mode ("w" or "a"), write header (already a complete
 * line, or ""), then nrows rows of ncols numbers from data (row-major), each as
 * ps_format_double writes it, separated by commas, each row ended by CR LF (the csv module's
 * default dialect). Returns 0, or an errno value if the file could not be opened or written. */
int ps_write_csv(const char* path, const char* mode, const char* header, const double* data,
                 long nrows, int ncols);

/* Create the file at path, write header (a complete line) and return a stream writing the
 * time and then the request channels cols (ncols entries; the array must outlive the stream)
 * of each row, or NULL with an errno value in *err. */
psStream* ps_stream_open(const char* path, const char* header, const int* cols, int ncols,
                         int* err);

/* Append nrows rows: the time t[r] and req[r * nout + cols[c]], formatted as ps_write_csv
 * does, and with flush != 0 hand them to the operating system (a crash of the process then
 * loses none). A NULL stream writes nothing. Returns 0 or an errno value. */
int ps_stream_rows(psStream* st, const double* t, const double* req, long nrows, int nout,
                   int flush);

/* Hand the rows written so far to the operating system. Returns 0 or an errno value. */
int ps_stream_flush(psStream* st);

/* Close a stream (NULL is allowed). */
void ps_stream_close(psStream* st);

#ifdef __cplusplus
}
#endif
#endif
