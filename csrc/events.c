/* Sensor_Event at an instant, in C: arming, firing and re-arming, the event iteration, the
 * chatter guard and the start of a zero-crossing search of pysolver/solve/sensors.py, for
 * sensors whose actions need no Python (where a force reads SENVAL, none that restarts in a
 * scene with joints or motions). The batched path decides such sensors' instants here
 * (ps_ida_controlled, which also goes back to the last converged step); the general loop runs
 * sensors.py, and tests/test_fast.py holds the two to the same rows, events and counters. */
#include <math.h>
#include <string.h>

#include "internal.h"

/* sensors.py's CHATTER_LIMIT (the length of psSensors.recent) and CHATTER_WINDOW. */
#define PS_CHATTER_LIMIT 100
#define PS_CHATTER_WINDOW 1e-9

/* A fired or re-armed sensor at t: ends the run as chattering when PS_CHATTER_LIMIT events lie
 * within PS_CHATTER_WINDOW * max(1, |t|) (sensors.py's CHATTER_LIMIT and CHATTER_WINDOW). */
static int chatter(psSensors* S, double t) {
  S->recent[(S->first + S->nrecent) % PS_CHATTER_LIMIT] = t;
  if (S->nrecent < PS_CHATTER_LIMIT)
    S->nrecent++;
  else
    S->first = (S->first + 1) % PS_CHATTER_LIMIT;
  if (S->nrecent < PS_CHATTER_LIMIT) return 0;
  double oldest = S->recent[S->first];
  return t - oldest <= PS_CHATTER_WINDOW * fmax(1.0, fabs(t));
}

/* Arm sensor k; an EQ sensor remembers from which side of its value it approaches. */
static void arm(const psModel* m, psData* d, int k, double f) {
  d->sensor_armed[k] = 1;
  d->sensor_side[k] = f >= m->sensor_value[k] ? 1.0 : -1.0;
}

/* Fire sensor k (its expression f): disarm it, store its Sensor_Evaluate, note what it asks
 * of the instant (restart, row, halt, return, print interval, verbose, largest step, first
 * step), record the event. Returns 1
 * when its print interval would pass the output budget (S->over = k): the instant stops there,
 * its event unrecorded, as the general loop stops inside that sensor's action. */
static int fire(const psModel* m, psData* d, psSensors* S, int k, double f, double t,
                const double* y, const double* yp) {
  d->sensor_armed[k] = 0;
  /* its search is over; the last one over brings the bounds before the searches back */
  if (S->zc_pending[k]) {
    S->zc_pending[k] = 0;
    int left = 0;
    for (int j = 0; j < S->n; j++) left |= S->zc_pending[j];
    if (!left && S->saved) {
      S->saved = 0;
      S->back = 1;
      S->back_hmax = S->saved_hmax;
      S->back_hmin = S->saved_hmin;
      S->restart = S->batch_restart = 1;
    }
  }
  if (S->evaluate[k] >= 0)
    d->senval[S->evaluate[k]] = ps_eval_tape(m, d, S->eval_tape[k], S->eval_slot[k], t, y, yp);
  /* outputs.over_budget of the rows so far and those of the new interval to the end */
  if (S->dts[k] > 0 && isfinite(S->tend) &&
      ((double)S->rows + ((S->tend - t) / S->dts[k] + 1.0)) * S->row_bytes > S->budget) {
    S->over = k;
    return 1;
  }
  /* a restart: asked for, or new step bounds, or a stored value a force reads */
  int again = S->restarts[k] || S->hmaxs[k] > 0 || S->stepsizes[k] > 0 ||
              (S->evaluate[k] >= 0 && S->consistent);
  S->restart |= S->restarts[k] || (S->evaluate[k] >= 0 && S->consistent);
  S->batch_restart |= again;
  S->emit |= S->prints[k] || S->halts[k];
  if (S->halts[k]) S->halt = k;
  if (S->rets[k]) S->ret = k;
  if (S->dts[k] > 0) {
    S->dt = S->interval = S->dts[k];
    S->anchor = t;   /* the new grid begins at the instant (Printer.set_interval) */
  }
  if (S->verboses[k]) S->verbose_on[k] = 1;
  if (S->hmaxs[k] > 0) {
    S->hmax = S->hmaxs[k];
    if (S->saved) S->saved_hmax = S->hmaxs[k];   /* the bound a search gives back */
  }
  if (S->stepsizes[k] > 0)
    S->first_step = S->first_step > 0 ? fmin(S->first_step, S->stepsizes[k]) : S->stepsizes[k];
  /* room: the loop hands the records over whenever an instant could fill them */
  if (S->nev >= S->cap) return 0;
  S->ev_time[S->nev] = t;
  S->ev_value[S->nev] = f;
  S->ev_sensor[S->nev] = k;
  S->nev++;
  return 0;
}

int ps_sensors_verbose(const psModel* m, psData* d, psSensors* S, double t, const double* y,
                       const double* yp) {
  int any = 0;
  for (int k = 0; k < S->n && !any; k++) any = S->verbose_on[k];
  if (!any) return 0;
  ps_sensor_status(m, d, t, y, yp, S->holds, S->rearms);
  int wrote = 0;
  for (int k = 0; k < S->n; k++) {
    if (!S->verbose_on[k] || S->nev >= S->cap) continue;
    /* a record of sensor -1 - k: a line of the log, not an event */
    S->ev_time[S->nev] = t;
    S->ev_value[S->nev] = d->sensor_f[k];
    S->ev_sensor[S->nev] = -1 - k;
    S->nev++;
    wrote++;
  }
  return wrote;
}

/* Fire the sensors marked in `marks` (in id order): one call of sensors.py's _fire. Where
 * forces read SENVAL and one of them restarts, yp is made consistent again at its end
 * (ps_consistent_yp, as kernel.consistent_yp: NaN when it fails). Returns PS_OK,
 * PS_SE_BUDGET or PS_SE_USER (a user subroutine failed there). */
static int fire_batch(const psModel* m, psData* d, psSensors* S, const int* marks, double t,
                      double* y, double* yp) {
  S->batch_restart = 0;
  for (int k = 0; k < S->n; k++)
    if (marks[k] && fire(m, d, S, k, S->f[k], t, y, yp)) return PS_SE_BUDGET;
  if (!(S->batch_restart && S->consistent)) return PS_OK;
  if (S->whole) {
    /* motions, joints, tracked angles or a sparse scene: the whole restart (y too) */
    int rc = ps_restart_consistent(m, d, S->whole, t, y, yp);
    if (rc == PS_OK) return PS_OK;
    if (d->user_error) return PS_SE_USER;
    S->restart_rc = rc;
    return PS_SE_RESTART;
  }
  if (ps_consistent_yp(m, d, t, y, yp, S->cwork, S->cpiv, 4) != PS_OK) {
    if (d->user_error) return PS_SE_USER;
    for (int i = 0; i < m->ny; i++) yp[i] = NAN;
  }
  return PS_OK;
}

/* The sensors' status at (t, y, yp) into S->holds, S->rearms and S->f. */
static void status(const psModel* m, psData* d, psSensors* S, double t, const double* y,
                   const double* yp) {
  ps_sensor_status(m, d, t, y, yp, S->holds, S->rearms);
  memcpy(S->f, d->sensor_f, sizeof(double) * (size_t)S->n);
}

/* The event iteration at one instant (sensors.py, Sensors._settle): re-arm and fire until
 * nothing changes, each sensor firing and re-arming at most once. */
static int settle(const psModel* m, psData* d, psSensors* S, double t, double* y,
                  double* yp) {
  for (;;) {
    status(m, d, S, t, y, yp);
    int up = 0, now = 0;
    for (int k = 0; k < S->n; k++)
      if (!d->sensor_armed[k] && !S->rearmed[k] && S->rearms[k]) {
        arm(m, d, k, S->f[k]);
        S->nrearms++;
        S->verbose_on[k] = 0;
        S->rearmed[k] = 1;
        up = 1;
        if (chatter(S, t)) return PS_SE_CHATTER;
      }
    for (int k = 0; k < S->n; k++) {
      S->now[k] = d->sensor_armed[k] && !S->fired[k] && S->holds[k];
      now |= S->now[k];
    }
    if (now) {
      if (chatter(S, t)) return PS_SE_CHATTER;
      for (int k = 0; k < S->n; k++) S->fired[k] |= S->now[k];
      int rc = fire_batch(m, d, S, S->now, t, y, yp);
      if (rc != PS_OK) return rc;
    }
    if (!up && !now) return PS_OK;
  }
}

/* A new instant: nothing asked yet. */
static void begin(psSensors* S) {
  S->restart = S->emit = 0;
  S->halt = S->ret = -1;
  S->dt = S->hmax = S->first_step = 0.0;
  S->over = -1;
  S->instant_nev = S->nev;
  S->back = S->restore = 0;
}

int ps_sensors_start(const psModel* m, psData* d, psSensors* S, double t, double* y,
                     double* yp) {
  begin(S);
  S->tend = NAN; /* before the first command a print interval is not checked (Printer) */
  if (!S->n) return PS_OK;
  status(m, d, S, t, y, yp);
  for (int k = 0; k < S->n; k++) {
    arm(m, d, k, S->f[k]);
    S->fired[k] = S->rearmed[k] = S->verbose_on[k] = S->zc_pending[k] = 0;
  }
  S->saved = 0;
  return settle(m, d, S, t, y, yp);
}

int ps_sensors_roots(const psModel* m, psData* d, psSensors* S, const int* found, double t,
                     double* y, double* yp) {
  begin(S);
  for (int k = 0; k < S->n; k++) {
    S->fired[k] = found[k] != 0 && d->sensor_armed[k];
    S->rearmed[k] = found[k] != 0 && !d->sensor_armed[k];
  }
  if (chatter(S, t)) return PS_SE_CHATTER;
  /* zero_crossing sensors seen firing for the first time (S->now) send the run back to the
   * last converged step before t, which the caller does (nothing else happens here) */
  double zc = 0.0;
  for (int k = 0; k < S->n; k++) {
    S->now[k] = S->fired[k] && S->zcs[k] > 0 && !S->zc_pending[k];
    if (S->now[k]) zc = zc > 0 ? fmin(zc, S->zcs[k]) : S->zcs[k];
  }
  if (zc > 0 && S->nsnap > 0 &&
      S->snap_t[(S->snap_first + S->nsnap - 1) % PS_SNAPS] < t) {
    S->restore = 1;
    S->restore_zc = zc;
    return PS_OK;
  }
  /* IDA saw these crossings: take them as they are, then settle the rest */
  status(m, d, S, t, y, yp);
  for (int k = 0; k < S->n; k++)
    if (S->rearmed[k]) {
      arm(m, d, k, S->f[k]);
      S->nrearms++;
      S->verbose_on[k] = 0;
    }
  int any = 0;
  for (int k = 0; k < S->n; k++) any |= S->fired[k];
  if (any) {
    int rc = fire_batch(m, d, S, S->fired, t, y, yp);
    if (rc != PS_OK) return rc;
  }
  return settle(m, d, S, t, y, yp);
}
