/* pysolver user subroutines: the data access functions a routine may call.
 *
 * Build a routine library without linking against pysolver:
 *   cc -shared -fPIC -I$(python -c "import pysolver; print(pysolver.get_include())") sub.c -o sub.so
 * pysolver resolves these functions when it loads the library.
 *
 * Calling conventions (Adams/MotionSolve): the routine writes its result into value.
 *   void PFOSUB(int *id, double *time, double *par, int *npar, int *dflag, int *iflag,
 *               double *value);                    constraint value g of a Force_Penalty
 *   void VARSUB(...same as PFOSUB...);              value of a Reference_Variable
 *   void SFOSUB(...same as PFOSUB...);              magnitude of a Force_Scalar_TwoBody
 *   void SENSUB(int *id, double *time, double *par, int *npar, int *iflag, double *value);
 *   void SEVSUB(...same as SENSUB...);              value stored by a Sensor_Evaluate
 *   void REQSUB(...same as SENSUB..., double *result);   result[8]: a Post_Request's channels
 *   void MOTSUB(int *id, double *time, double *par, int *npar, int *iord, int *iflag,
 *               double *value);   a Motion_Marker's / Motion_Joint's driven value (iord 0),
 *                                 its velocity (iord 1) and acceleration (iord 2)
 *   void GCOSUB(...same as PFOSUB...);              the g a Constraint_General holds at 0
 * par holds the numbers of USER(p1, ..., pn); npar their count. iflag is 1 on the first call,
 * which pysolver makes once to learn which system values the routine reads (c_sysfnc then
 * returns 0): a routine must ask for every value it may use on that call. dflag is 1 while
 * pysolver differences the routine for its partial derivatives. A routine that knows its
 * partials gives them with c_syspar, and is then called far less often.
 */
#ifndef PYSOLVER_USERSUB_H
#define PYSOLVER_USERSUB_H

#include <stddef.h> /* NULL, for c_syspar("TIME", NULL, 0, ...) */

#ifdef __cplusplus
extern "C" {
#endif

/* One system value: fnc is a function of the expression language that takes ids (DX, DY, DZ,
 * DM, VX, VY, VZ, VM, VR, ACCX, ACCY, ACCZ, WX, WY, WZ, AX, AY, AZ, VARVAL, PFORCE, SFORCE,
 * SENVAL), ipar its nsize integer arguments. Writes the value into *state and 0 into *errflg,
 * or 0 and 1 on an error (unknown function, or a value not asked for on the iflag call). */
void c_sysfnc(const char *fnc, const int *ipar, int nsize, double *state, int *errflg);

/* An array of system values: TDISP (DX, DY, DZ), TVEL (VX, VY, VZ), RVEL (WX, WY, WZ),
 * VEL (VX, VY, VZ, WX, WY, WZ) or TACC (ACCX, ACCY, ACCZ) of the ids in ipar; writes *nstates
 * values into states. */
void c_sysary(const char *fnc, const int *ipar, int nsize, double *states, int *nstates,
              int *errflg);

/* Give the partial derivatives of the routine's result in values it read (Adams' SYSPAR):
 * fnc, ipar and nsize as in the c_sysfnc or c_sysary call, states the partials of the result
 * in each of the nstates values that call returned. pysolver then uses them instead of
 * differencing the routine in those values (it still differences the rest). fnc "TIME" with
 * nsize 0 and one partial gives the partial in the time argument (a pysolver extension:
 * without it, every evaluation that needs partials calls the routine once more, a step in
 * time). pysolver checks each partial against differences of the value the first time it is
 * given in a run, and ends the run naming the value when they disagree. Ignored on the iflag
 * call and when no partials are wanted; *errflg is 1 (and the run ends) for a value the iflag
 * call did not ask for or a wrong nstates. */
void c_syspar(const char *fnc, const int *ipar, int nsize, const double *states, int nstates,
              int *errflg);

/* Set *eval_jac to 1 when the call in progress wants the routine's partials (c_syspar), else
 * 0 (Adams' ADAMS_NEEDS_PARTIALS): a routine may skip computing them then. */
void c_adams_needs_partials(int *eval_jac);

/* Report an error when errflg is nonzero: the evaluation fails and the run ends with
 * success=False and this message. */
void c_errmes(int errflg, const char *message, int id, const char *endflag);

#ifdef __cplusplus
}
#endif
#endif
