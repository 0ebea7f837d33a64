/* User subroutines called from tapes (PS_OP_USER), and the data access functions they call.
 *
 * A routine reads the state only through c_sysfnc / c_sysary. Its dependencies are learned once,
 * Adams-style, by a call with iflag = 1 that records every system value it asks for
 * (ps_user_declare); those values become ordinary measure slots of the tape, with their exact
 * derivatives. At each evaluation the routine is called with the slots' values (c_sysfnc
 * answers from them) and its own partials in those values, and in time, are taken by central
 * differences; the chain rule through the slots' derivatives gives the result's gradient and,
 * for penalty constraints, its Hessian block. Nothing is allocated: the call context lives on
 * the stack and is found by c_sysfnc through a thread-local pointer.
 */
#define _GNU_SOURCE
/* The copies here are of a few numbers per routine call: loops, not calls to libc's memcpy. */
#pragma GCC optimize("no-tree-loop-distribute-patterns")
#include <ctype.h>
#include <dlfcn.h>
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "internal.h"

#define PS_EXPORT __attribute__((visibility("default")))
#define PS_USER_MAXPAR 64
_Static_assert(PS_USER_CACHE == 3 + 3 * (PS_USER_MAXIN + 1), "PS_USER_CACHE layout");

typedef void (*UserFnD)(int*, double*, double*, int*, int*, int*, double*);
typedef void (*UserFnP)(int*, double*, double*, int*, int*, double*);

/* The call in progress on this thread: what c_sysfnc answers from, or records into. */
typedef struct {
  int recording;        /* 1: ps_user_declare's iflag call                       */
  char* keys;           /* recording: (maxkeys x PS_USER_KEY) out                 */
  int nkeys, maxkeys;
  const int* kfn;       /* evaluating: the declared keys' function codes,         */
  const int* kn;        /* ... numbers of ids                                     */
  const int* kid;       /* ... and ids (4 per key)                                */
  int nknown;
  int next;             /* the key after the last one read: routines read in order */
  const double* values; /* evaluating: their current values                       */
  int error;            /* an error was reported                                  */
  int named;            /* ... by ps_user_fail, whose message names the routine   */
  int python;           /* a Python routine: its messages name py_sysfnc, ...     */
  double t;             /* the time argument of the call in progress              */
  double t_error;       /* ... and of the call that reported the error            */
  double* part;         /* partials wanted: c_syspar writes input i's here        */
  unsigned char* got;   /* ... and sets got[i]; NULL: c_syspar's partials unused  */
  int last;             /* the last read: array index, or NARRAYS + function code */
  int last_n, last_ids[4], last_keys[6];   /* ... its ids and the keys it found  */
  char msg[200];
} UserCtx;

/* initial-exec: a load from the thread pointer, not a __tls_get_addr call per data access */
static __thread UserCtx* current __attribute__((tls_model("initial-exec"))) = NULL;

/* The expression-language functions c_sysfnc answers, in code order: those of
 * pysolver/catalogue.py with c_sysfnc (tests/test_catalogue.py checks the two agree). */
enum { F_DX, F_DY, F_DZ, F_DM, F_VX, F_VY, F_VZ, F_VM, F_VR, F_ACCX, F_ACCY, F_ACCZ, F_WX, F_WY,
       F_WZ, F_AX, F_AY, F_AZ, F_VARVAL, F_PFORCE, F_SFORCE, F_SENVAL, F_COUNT };
static const char* const FUNCTIONS[F_COUNT] = {
    "DX", "DY", "DZ", "DM", "VX", "VY", "VZ", "VM", "VR", "ACCX", "ACCY", "ACCZ",
    "WX", "WY", "WZ", "AX", "AY", "AZ", "VARVAL", "PFORCE", "SFORCE", "SENVAL"};

/* Copy a function name upper-cased and without spaces into name (16 bytes). */
static void clean_name(char* name, const char* fnc) {
  int n = 0;
  for (const char* p = fnc; *p && n < 15; p++)
    if (!isspace((unsigned char)*p)) name[n++] = (char)toupper((unsigned char)*p);
  name[n] = '\0';
}

static int same_text(const char* a, const char* b) {
  while (*a && *a == *b) a++, b++;
  return *a == *b;
}

int ps_user_fn_code(const char* fnc) {
  char name[16];
  /* the spelling the header documents first; any other is normalised */
  for (int pass = 0; pass < 2; pass++) {
    for (int i = 0; i < F_COUNT; i++)
      if (same_text(pass ? name : fnc, FUNCTIONS[i])) return i;
    clean_name(name, fnc);
  }
  return -1;
}

/* Write the canonical key "NAME(i,j,...)" of a request; returns 0, or -1 for an unknown name. */
static int make_key(char* key, const char* fnc, const int* ipar, int nsize) {
  char name[16];
  clean_name(name, fnc);
  int known = ps_user_fn_code(name) >= 0;
  int len = snprintf(key, PS_USER_KEY, "%s(", name);
  for (int i = 0; i < nsize && len < PS_USER_KEY; i++)
    len += snprintf(key + len, (size_t)(PS_USER_KEY - len), i ? ",%d" : "%d", ipar[i]);
  if (len < PS_USER_KEY) snprintf(key + len, (size_t)(PS_USER_KEY - len), ")");
  return known ? 0 : -1;
}

/* A data access function's name as the routine calls it: py_sysfnc from Python, c_sysfnc
 * from C (a Python routine's py_sysfnc and py_syspar reach c_sysfnc and c_syspar). */
#define API(ctx, name) ((ctx)->python ? "py_" name : "c_" name)

static void fail(UserCtx* ctx, const char* format, ...) {
  if (ctx->error) return;
  ctx->error = 1;
  ctx->t_error = ctx->t;
  va_list args;
  va_start(args, format);
  vsnprintf(ctx->msg, sizeof(ctx->msg), format, args);
  va_end(args);
}

/* The declared key (function code, ids) being read, or -1; the one after the last match is
 * tried first, so a routine that reads in the order it declared finds each in one test. */
static int find_key(UserCtx* ctx, int code, const int* ipar, int nsize) {
  for (int s = 0, i = ctx->next; s < ctx->nknown; s++, i = i + 1 < ctx->nknown ? i + 1 : 0) {
    if (ctx->kfn[i] != code || ctx->kn[i] != nsize) continue;
    int j = 0;
    while (j < nsize && ctx->kid[4 * i + j] == ipar[j]) j++;
    if (j < nsize) continue;
    ctx->next = i + 1 < ctx->nknown ? i + 1 : 0;
    return i;
  }
  return -1;
}

/* Record key (recording) or report it as not declared (evaluating). */
static void unknown_read(UserCtx* ctx, const char* fnc, const int* ipar, int nsize, int* errflg) {
  char key[PS_USER_KEY];
  if (make_key(key, fnc, ipar, nsize) != 0) {
    fail(ctx, "%s: unknown function %s", API(ctx, "sysfnc"), key);
    return;
  }
  if (!ctx->recording) {
    fail(ctx, "read a value its iflag call did not ask for: %s", key);
    return;
  }
  *errflg = 0;
  for (int i = 0; i < ctx->nkeys && i < ctx->maxkeys; i++)
    if (!strcmp(ctx->keys + (long)i * PS_USER_KEY, key)) return;
  if (ctx->nkeys < ctx->maxkeys)
    memcpy(ctx->keys + (long)ctx->nkeys * PS_USER_KEY, key, PS_USER_KEY);
  ctx->nkeys++;
}

/* SYSARY arrays: their entries as SYSFNC function codes; angular ones take at most three ids. */
static const struct { const char* name; int parts[6]; int n; } ARRAYS[] = {
    {"TDISP", {F_DX, F_DY, F_DZ}, 3}, {"TVEL", {F_VX, F_VY, F_VZ}, 3},
    {"RVEL", {F_WX, F_WY, F_WZ}, 3}, {"VEL", {F_VX, F_VY, F_VZ, F_WX, F_WY, F_WZ}, 6},
    {"TACC", {F_ACCX, F_ACCY, F_ACCZ}, 3}};
#define NARRAYS ((int)(sizeof(ARRAYS) / sizeof(*ARRAYS)))

/* Note the keys of a read that found them all (what c_syspar will most likely name next). */
static void remember_read(UserCtx* ctx, int what, const int* ipar, int nsize, const int* keys) {
  int n = what < NARRAYS ? ARRAYS[what].n : 1;
  ctx->last = nsize <= 4 ? what : -1;
  ctx->last_n = nsize;
  for (int i = 0; i < nsize && i < 4; i++) ctx->last_ids[i] = ipar[i];
  for (int i = 0; i < n; i++) ctx->last_keys[i] = keys[i];
}

/* Whether ipar (nsize ids) of `what` is the last read's. */
static int same_read(const UserCtx* ctx, int what, const int* ipar, int nsize) {
  if (ctx->last != what || ctx->last_n != nsize) return 0;
  for (int i = 0; i < nsize; i++)
    if (ctx->last_ids[i] != ipar[i]) return 0;
  return 1;
}

PS_EXPORT void c_sysfnc(const char* fnc, const int* ipar, int nsize, double* state,
                        int* errflg) {
  UserCtx* ctx = current;
  *state = 0.0;
  *errflg = 1;
  if (!ctx) return;
  if (!ctx->recording) {
    /* the common case, kept fast: the name of the key expected next */
    int code = ctx->next < ctx->nknown && same_text(fnc, FUNCTIONS[ctx->kfn[ctx->next]])
                   ? ctx->kfn[ctx->next] : ps_user_fn_code(fnc);
    int i = code < 0 ? -1 : find_key(ctx, code, ipar, nsize);
    if (i >= 0) {
      *state = ctx->values[i];
      *errflg = 0;
      remember_read(ctx, NARRAYS + code, ipar, nsize, &i);
      return;
    }
  }
  unknown_read(ctx, fnc, ipar, nsize, errflg);
}

static int array_code(const char* fnc) {
  char name[16];
  for (int pass = 0; pass < 2; pass++) {
    for (int a = 0; a < NARRAYS; a++)
      if (same_text(pass ? name : fnc, ARRAYS[a].name)) return a;
    clean_name(name, fnc);
  }
  return -1;
}

PS_EXPORT void c_sysary(const char* fnc, const int* ipar, int nsize, double* states,
                        int* nstates, int* errflg) {
  UserCtx* ctx = current;
  int a = array_code(fnc);
  *nstates = 0;
  *errflg = 1;
  if (a < 0) {
    char name[16];
    clean_name(name, fnc);
    if (ctx) fail(ctx, "%s: unknown array %s", API(ctx, "sysary"), name);
    return;
  }
  *errflg = 0;
  int keys[6], found = 0;
  for (int i = 0; i < ARRAYS[a].n; i++) {
    int code = ARRAYS[a].parts[i], e = 0;
    int nids = code >= F_WX && code <= F_WZ && nsize > 3 ? 3 : nsize;
    int k = ctx && !ctx->recording ? find_key(ctx, code, ipar, nids) : -1;
    if (k >= 0) {
      states[i] = ctx->values[k];
      keys[found++] = k;
      continue;
    }
    c_sysfnc(FUNCTIONS[code], ipar, nids, states + i, &e);
    *errflg |= e;
  }
  if (found == ARRAYS[a].n) remember_read(ctx, a, ipar, nsize, keys);
  *nstates = ARRAYS[a].n;
}

PS_EXPORT void c_syspar(const char* fnc, const int* ipar, int nsize, const double* states,
                        int nstates, int* errflg) {
  UserCtx* ctx = current;
  *errflg = 0;
  /* taken only when partials are wanted (not on the iflag call, nor for a plain value) */
  if (!ctx || !ctx->got) return;
  /* the common cases, kept fast: time's partial, and the partials of the value just read */
  if (nsize == 0 && nstates == 1 && same_text(fnc, "TIME")) {
    ctx->part[ctx->nknown] = states[0];
    ctx->got[ctx->nknown] = 1;
    return;
  }
  int last = ctx->last;
  if (last >= 0 && nstates == (last < NARRAYS ? ARRAYS[last].n : 1) &&
      same_text(fnc, last < NARRAYS ? ARRAYS[last].name : FUNCTIONS[last - NARRAYS]) &&
      same_read(ctx, last, ipar, nsize)) {
    for (int i = 0; i < nstates; i++) {
      ctx->part[ctx->last_keys[i]] = states[i];
      ctx->got[ctx->last_keys[i]] = 1;
    }
    return;
  }
  int a = array_code(fnc), code = a < 0 ? ps_user_fn_code(fnc) : -1, n = a >= 0 ? ARRAYS[a].n : 1;
  char name[16];
  clean_name(name, fnc);
  *errflg = 1;
  if (a < 0 && code < 0 && !strcmp(name, "TIME")) {
    if (nsize == 0 && nstates == 1) {
      *errflg = 0;
      ctx->part[ctx->nknown] = states[0];
      ctx->got[ctx->nknown] = 1;
    } else {
      fail(ctx, "%s: TIME takes no ids and one partial, %s was given %d id%s and %d partial%s",
           API(ctx, "syspar"), API(ctx, "syspar"), nsize, nsize == 1 ? "" : "s", nstates,
           nstates == 1 ? "" : "s");
    }
    return;
  }
  if (a < 0 && code < 0) {
    fail(ctx, "%s: unknown function or array %s", API(ctx, "syspar"), name);
    return;
  }
  if (nstates != n) {
    fail(ctx, "%s: %s has %d value%s, %s was given %d partials", API(ctx, "syspar"), name, n,
         n > 1 ? "s" : "", API(ctx, "syspar"), nstates);
    return;
  }
  int keys[6];
  for (int i = 0; i < n; i++) {
    int c = a >= 0 ? ARRAYS[a].parts[i] : code;
    int nids = c >= F_WX && c <= F_WZ && nsize > 3 ? 3 : nsize;
    keys[i] = find_key(ctx, c, ipar, nids);
    if (keys[i] < 0) {
      char key[PS_USER_KEY];
      make_key(key, FUNCTIONS[c], ipar, nids);
      fail(ctx, "%s: partials in a value its iflag call did not ask for: %s",
           API(ctx, "syspar"), key);
      return;
    }
  }
  *errflg = 0;
  for (int i = 0; i < n; i++) {
    ctx->part[keys[i]] = states[i];
    ctx->got[keys[i]] = 1;
  }
}

PS_EXPORT void c_adams_needs_partials(int* eval_jac) {
  *eval_jac = current && current->got ? 1 : 0;
}

PS_EXPORT void c_errmes(int errflg, const char* message, int id, const char* endflag) {
  (void)id;
  (void)endflag;
  if (errflg && current) fail(current, "%s", message);
}

void ps_user_fail(const char* message) {
  if (!current || current->error) return;
  current->named = 1;
  fail(current, "%s", message);
}

const double* ps_user_values(void) {
  return current && !current->recording ? current->values : NULL;
}

int ps_user_give(int key, double partial) {
  UserCtx* ctx = current;
  if (!ctx || !ctx->got || key < 0 || key >= ctx->nknown) return 1;
  ctx->part[key] = partial;
  ctx->got[key] = 1;
  return 0;
}

void* ps_user_open(const char* path, const char* name, char* msg, int msglen) {
  Dl_info info;
  /* make c_sysfnc and friends visible to libraries opened from here on */
  if (dladdr((void*)&c_sysfnc, &info) && info.dli_fname)
    dlopen(info.dli_fname, RTLD_NOW | RTLD_NOLOAD | RTLD_GLOBAL);
  void* lib = dlopen(path, RTLD_NOW | RTLD_LOCAL);
  if (!lib) {
    snprintf(msg, (size_t)msglen, "%s", dlerror());
    return NULL;
  }
  void* fn = dlsym(lib, name);
  if (!fn) snprintf(msg, (size_t)msglen, "no function %s in %s", name, path);
  return fn;
}

/* Call routine fn once; returns channel chan of its result. */
static double call(void* fn, int form, int id, double t, const double* par, int npar, int dflag,
                   int iflag, int chan) {
  double p[PS_USER_MAXPAR], val[8] = {0};
  int n = npar < PS_USER_MAXPAR ? npar : PS_USER_MAXPAR;
  /* the routine may not change the model */
  for (int i = 0; i < n; i++) p[i] = par[i];
  /* a MOTSUB's iord (the time derivative asked for) comes as -dflag: a difference call's dflag
   * is 1, and asks for the value */
  int iord = dflag < 0 ? -dflag : 0;
  if (form == PS_USER_DFLAG)
    ((UserFnD)fn)(&id, &t, p, &n, &dflag, &iflag, val);
  else if (form == PS_USER_IORD)
    ((UserFnD)fn)(&id, &t, p, &n, &iord, &iflag, val);
  else
    ((UserFnP)fn)(&id, &t, p, &n, &iflag, val);
  return val[chan];
}

int ps_user_declare(void* fn, int form, int python, int id, const double* par, int npar,
                    char* keys, int maxkeys, char* msg, int msglen) {
  UserCtx ctx;
  memset(&ctx, 0, sizeof(ctx));
  ctx.recording = 1;
  ctx.python = python;
  ctx.keys = keys;
  ctx.maxkeys = maxkeys;
  UserCtx* prev = current;
  current = &ctx;
  call(fn, form, id, 0.0, par, npar, 0, 1, 0);
  current = prev;
  if (ctx.error) {
    snprintf(msg, (size_t)msglen, "%s", ctx.msg);
    return -1;
  }
  return ctx.nkeys > maxkeys ? maxkeys + 1 : ctx.nkeys;
}

int ps_user_motion(void* fn, int python, int id, const double* par, int npar, double t,
                   int iord, double* value, char* msg, int msglen) {
  UserCtx ctx;
  char key[PS_USER_KEY];
  memset(&ctx, 0, sizeof(ctx));
  ctx.recording = 1;      /* a motion reads nothing: a read is counted, not answered */
  ctx.python = python;
  ctx.keys = key;
  ctx.maxkeys = 0;
  UserCtx* prev = current;
  current = &ctx;
  *value = call(fn, PS_USER_IORD, id, t, par, npar, -iord, 0, 0);
  current = prev;
  if (ctx.error || ctx.nkeys) {
    snprintf(msg, (size_t)msglen, "%s", ctx.error ? ctx.msg : "a motion reads no values");
    return -1;
  }
  return 0;
}

/* One evaluation of routine k at inputs z (declared values, then time). */
static double eval(const psModel* m, int k, UserCtx* ctx, const double* z, int nin, int dflag,
                   int chan) {
  ctx->values = z;
  ctx->next = 0;
  ctx->last = -1;
  ctx->t = z[nin];
  return call(m->user_fn[k], m->user_form[k], m->user_id[k], z[nin],
              m->user_par + m->user_par_adr[k], m->user_npar[k], dflag, 0, chan);
}

/* A difference step near rel * max(1, |z|), a power of two: z +/- step is then exact, where a
 * rounded step would add an error of eps |z| / step to the partial (1e-10 relative for a
 * position of 100 mm), enough to cost IDA steps at tight tolerances. */
static double step(double rel, double z) {
  /* the largest power of two not above x (x normal and positive): x's exponent bits alone */
  double x = rel * fmax(1.0, fabs(z));
  unsigned long long b;
  memcpy(&b, &x, sizeof b);
  b &= 0x7ff0000000000000ULL;
  memcpy(&x, &b, sizeof b);
  return x;
}

/* Evaluate with input i moved by h (and input j by hj when j >= 0). */
static double eval_at(const psModel* m, int k, UserCtx* ctx, double* z, int nin, int chan,
                      int i, double h, int j, double hj) {
  double zi = z[i], zj = j >= 0 ? z[j] : 0.0;
  z[i] = zi + h;
  if (j >= 0) z[j] = zj + hj;
  double f = eval(m, k, ctx, z, nin, 1, chan);
  z[i] = zi;
  if (j >= 0) z[j] = zj;
  return f;
}

/* Evaluate at z with input i moved by h (none for i < 0), taking the partials the routine
 * gives with c_syspar into part (got[j] = 1 for each input j it gave; got NULL: none wanted). */
static double eval_with(const psModel* m, int k, UserCtx* ctx, double* z, int nin, int chan,
                        int dflag, int i, double h, double* part, unsigned char* got) {
  double zi = i >= 0 ? z[i] : 0.0;
  if (i >= 0) z[i] = zi + h;
  ctx->part = part;
  ctx->got = got;
  for (int j = 0; got && j <= nin; j++) got[j] = 0;
  double f = eval(m, k, ctx, z, nin, dflag, chan);
  ctx->part = NULL;
  ctx->got = NULL;
  if (i >= 0) z[i] = zi;
  return f;
}

/* Check the partial `given` in input i of a routine whose value at z is f0 against
 * differences of the value at the steps h0 / 16^s (h0 ~ 1e-3 |z_i|, s = 0..3: a smaller step
 * resolves what curves within a larger one, or stays in a domain a larger one leaves): the
 * fourth-order central one, or, at a kink, either second-order one-sided one. A match within
 * 1e-6 relative at a step where the values' rounding is below that is taken at once (most
 * routines: at the first step, four calls); without one, the difference of each kind whose
 * error estimate is least (4 times its gap to the next lower order, and, for the central one,
 * the fourth difference of the values: their noise) must match within that estimate. Returns
 * 0, or -1 with the routine's error set (the run then ends, naming the input, the partial
 * and the surest central difference). */
static int check_given(const psModel* m, int k, UserCtx* ctx, double* z, int nin, int chan,
                       int i, double f0, double given) {
  double best[3] = {NAN, NAN, NAN}, err[3] = {INFINITY, INFINITY, INFINITY};
  for (int s = 0; s < 4; s++) {
    double h = ldexp(step(1e-3, z[i]), -4 * s), f[5] = {0.0, 0.0, f0, 0.0, 0.0}, big = 0.0;
    int finite = 1;
    for (int j = 0; j < 5; j++) {
      if (j != 2) f[j] = eval_at(m, k, ctx, z, nin, chan, i, (j - 2) * h, -1, 0.0);
      finite = finite && isfinite(f[j]);
      big = fmax(big, fabs(f[j]));
    }
    if (!finite) continue;
    /* rounding leaves about eps |f| / h in a difference */
    double fl = 1e3 * DBL_EPSILON * big / h, c2 = (f[3] - f[1]) / (2.0 * h);
    double d4 = f[0] - 4.0 * f[1] + 6.0 * f[2] - 4.0 * f[3] + f[4];
    double d[3] = {(8.0 * (f[3] - f[1]) - (f[4] - f[0])) / (12.0 * h),
                   (4.0 * f[3] - f[4] - 3.0 * f[2]) / (2.0 * h),
                   (3.0 * f[2] - 4.0 * f[1] + f[0]) / (2.0 * h)};
    double e[3] = {4.0 * fabs(d[0] - c2) + fabs(d4) / h, 8.0 * fabs(d[1] - (f[3] - f[2]) / h),
                   8.0 * fabs(d[2] - (f[2] - f[1]) / h)};
    for (int q = 0; q < 3; q++) {
      double tol = 1e-6 * (fabs(given) + fabs(d[q]));
      if (fl <= tol && fabs(given - d[q]) <= tol + fl) return 0;
      if (e[q] + fl < err[q]) best[q] = d[q], err[q] = e[q] + fl;
    }
  }
  for (int q = 0; q < 3; q++)
    if (fabs(given - best[q]) <= 1e-6 * (fabs(given) + fabs(best[q])) + err[q]) return 0;
  char key[PS_USER_KEY] = "TIME";
  if (i < nin) make_key(key, FUNCTIONS[ctx->kfn[i]], ctx->kid + 4 * i, ctx->kn[i]);
  fail(ctx, "%s gave the partial in %s as %.9g, but differences of its value give %.9g",
       API(ctx, "syspar"), key, given, best[0]);
  return -1;
}

/* Second partials (n = nin + 1 inputs, time last) from central differences of the first
 * partials the routine gives in all nin inputs, and time's own from differences of the value:
 * 2 calls per input that is not flat (a routine's inputs are smooth where it gives partials).
 * Returns 0, or -1 when a call did not give every partial (value differences are then used). */
static int hessian_given(const psModel* m, int k, UserCtx* ctx, double* z, int nin, int chan,
                         double f0, const int* flat, double* fij) {
  int n = nin + 1;
  double gp[PS_USER_MAXIN + 1], gm[PS_USER_MAXIN + 1], row[(PS_USER_MAXIN + 1) * PS_USER_MAXIN];
  unsigned char okp[PS_USER_MAXIN + 1], okm[PS_USER_MAXIN + 1];
  double tt = 0.0;
  for (int i = 0; i < n; i++) {
    double* r = row + i * nin;   /* d/dz_i of the given partials */
    if (flat[i]) {
      for (int j = 0; j < nin; j++) r[j] = 0.0;
      continue;
    }
    double h = step(i == nin ? 1e-4 : 6e-6, z[i]);
    double fp = eval_with(m, k, ctx, z, nin, chan, 1, i, h, gp, okp);
    double fm = eval_with(m, k, ctx, z, nin, chan, 1, i, -h, gm, okm);
    for (int j = 0; j < nin; j++) {
      if (!okp[j] || !okm[j]) return -1;
      r[j] = (gp[j] - gm[j]) / (2.0 * h);
    }
    if (i == nin) tt = (fp - 2.0 * f0 + fm) / (h * h);
  }
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++)
      fij[i * n + j] = i < nin && j < nin ? 0.5 * (row[i * nin + j] + row[j * nin + i])
                       : i == nin && j == nin ? tt
                                              : row[nin * nin + (i == nin ? j : i)];
  return 0;
}

/* Second partials from differences of the value: the diagonal from +/- steps ~ eps^(1/4),
 * the rest from one diagonal pair of steps each and the diagonal values. */
static void hessian_differenced(const psModel* m, int k, UserCtx* ctx, double* z, int nin,
                                int chan, double f0, const int* flat, double* fij) {
  int n = nin + 1;
  double fp[PS_USER_MAXIN + 1], fm[PS_USER_MAXIN + 1], H[PS_USER_MAXIN + 1];
  for (int i = 0; i < n; i++) {
    if (flat[i]) continue;
    H[i] = step(1e-4, z[i]);
    fp[i] = eval_at(m, k, ctx, z, nin, chan, i, H[i], -1, 0.0);
    fm[i] = eval_at(m, k, ctx, z, nin, chan, i, -H[i], -1, 0.0);
  }
  for (int i = 0; i < n; i++)
    for (int j = i; j < n; j++) {
      double v = 0.0;
      if (flat[i] || flat[j]) v = 0.0;
      else if (i == j) v = (fp[i] - 2.0 * f0 + fm[i]) / (H[i] * H[i]);
      else {
        double fpp = eval_at(m, k, ctx, z, nin, chan, i, H[i], j, H[j]);
        double fmm = eval_at(m, k, ctx, z, nin, chan, i, -H[i], j, -H[j]);
        v = (fpp + fmm - fp[i] - fm[i] - fp[j] - fm[j] + 2.0 * f0) / (2.0 * H[i] * H[j]);
      }
      fij[i * n + j] = fij[j * n + i] = v;
    }
}

int ps_user_point(const psModel* m, psData* d, int cache_index, int k, int chan,
                  const double* zin, int nin, int order, double* out) {
  int n = nin + 1;   /* inputs, then time */
  double* cache = d->user_cache + (long)cache_index * PS_USER_CACHE;
  double *cz = cache + 2, *cfi = cz + n, *cflat = cfi + n, *checked = cache + PS_USER_CACHE - 1;
  double z[PS_USER_MAXIN + 1], *fi = out + 1, *fij = out + 1 + n;
  double given[PS_USER_MAXIN + 1];
  unsigned char got[PS_USER_MAXIN + 1];
  int flat[PS_USER_MAXIN + 1];   /* the routine gave exactly f0 a step away in input i */
  int sup[PS_USER_MAXIN + 1];    /* the routine gave its partial in input i (c_syspar) */
  for (int i = 0; i < n; i++) z[i] = zin[i];
  UserCtx ctx;
  ctx.recording = 0;
  ctx.error = 0;
  ctx.named = 0;
  ctx.python = m->user_python[k];
  ctx.t = ctx.t_error = z[nin];
  ctx.part = NULL;
  ctx.got = NULL;
  ctx.msg[0] = '\0';
  ctx.kfn = m->user_key_fn + m->user_key_adr[k];
  ctx.kn = m->user_key_n + m->user_key_adr[k];
  ctx.kid = m->user_key_ids + 4 * m->user_key_adr[k];
  ctx.nknown = m->user_nkey[k];
  UserCtx* prev = current;
  current = &ctx;
  /* the value and first partials of the last call at the same inputs (the residual before a
   * Jacobian) are reused; the first partials are wanted from the routine (c_syspar) */
  int need = order >= 1 ? 2 : 1, hit = cache[0] >= need;
  for (int i = 0; hit && i < n; i++) hit = cz[i] == z[i];
  double f0 = hit ? cache[1]
                  : eval_with(m, k, &ctx, z, nin, chan, 0, -1, 0.0, order >= 1 ? given : NULL,
                              order >= 1 ? got : NULL);
  int nsup = 0;   /* partials given in the inputs, time's apart */
  for (int i = 0; i < n; i++) {
    sup[i] = hit ? cflat[i] == 2.0 : order >= 1 && got[i];
    nsup += sup[i] && i < nin;
  }
  /* each partial a routine gives is checked against differences the first time it is given
   * in a run (a routine may give some only on some branches) */
  if (!hit && (nsup || sup[nin])) {
    long done = (long)*checked;
    for (int i = 0; i < n && !ctx.error; i++)
      if (sup[i] && !(done >> i & 1)) {
        check_given(m, k, &ctx, z, nin, chan, i, f0, given[i]);
        done |= 1L << i;
      }
    *checked = (double)done;
  }
  /* other first partials by fourth-order central differences (Richardson's combination of the
   * steps h and 2h, h ~ eps^(1/5) relative): truncation and rounding both near 1e-13
   * relative. Second-order differences at the step ~ cbrt(eps) that balances their errors
   * carry rounding noise of about eps |f| / h, 1e-11 of a position of 100 mm: enough to fail
   * IDA's corrector at tight tolerances (seed 3's penalties as routines at integr_tol 1e-10:
   * 1.1-2.3x the expression version's steps, 5-50x its convergence failures; fourth order:
   * its steps), and they take half the calls: runs at loose tolerances use them
   * (d->user_coarse). An input whose first step leaves the value exactly unchanged (time,
   * usually) is taken as not read; time is not stepped at all for a routine that never reads
   * its time argument (user_timeless: a Python routine, from its bytecode). */
  for (int i = 0; order >= 1 && i < n; i++) {
    if (hit) {
      fi[i] = cfi[i];
      flat[i] = cflat[i] == 1.0;
      continue;
    }
    flat[i] = i == nin && m->user_timeless[k] == 1;
    if (i == nin && m->user_timeless[k] == 2) {   /* a MOTSUB's own velocity, iord = 1 */
      fi[i] = eval(m, k, &ctx, z, nin, -1, chan);
      continue;
    }
    if (flat[i]) {
      fi[i] = 0.0;
      continue;
    }
    if (sup[i]) {
      fi[i] = given[i];
      flat[i] = 0;
      continue;
    }
    double h = step(d->user_coarse ? 6e-6 : 1e-3, z[i]);
    double f1 = eval_at(m, k, &ctx, z, nin, chan, i, h, -1, 0.0);
    flat[i] = f1 == f0;
    if (flat[i]) {
      fi[i] = 0.0;
      continue;
    }
    double fm = eval_at(m, k, &ctx, z, nin, chan, i, -h, -1, 0.0);
    fi[i] = (f1 - fm) / (2.0 * h);
    /* a value defined on one side only (a routine that returns NaN past x = 1, at x within a
     * step of 1): the side it is defined on, so that the run reaches the edge and ends there
     * as an expression's does, rather than failing every step near it */
    if (isfinite(f0) && !isfinite(fi[i])) {
      fi[i] = isfinite(f1) ? (f1 - f0) / h : (f0 - fm) / h;
      continue;
    }
    if (d->user_coarse) continue;
    double d2 = (eval_at(m, k, &ctx, z, nin, chan, i, 2.0 * h, -1, 0.0) -
                 eval_at(m, k, &ctx, z, nin, chan, i, -2.0 * h, -1, 0.0)) / (4.0 * h);
    if (isfinite(d2)) fi[i] = (4.0 * fi[i] - d2) / 3.0;
  }
  if (order >= 2 && nin == 0 && m->user_timeless[k] == 2)
    fij[0] = eval(m, k, &ctx, z, nin, -2, chan);   /* its own acceleration, iord = 2 */
  else if (order >= 2 && !(nin > 0 && nsup == nin &&
                            hessian_given(m, k, &ctx, z, nin, chan, f0, flat, fij) == 0))
    hessian_differenced(m, k, &ctx, z, nin, chan, f0, flat, fij);
  current = prev;
  if (ctx.error) {
    cache[0] = 0.0;
    out[0] = NAN;
    d->user_error = 1;
    d->user_t = ctx.t_error;
    /* the routine as the deck names it, unless its own message (a Python routine's) does */
    snprintf(d->msg, sizeof(d->msg), "user subroutine (id %d): %s%s%s", m->user_id[k],
             ctx.named ? "" : m->user_name[k], ctx.named ? "" : ": ", ctx.msg);
    out[0] = NAN;
    return -1;
  }
  if (!hit) {
    cache[0] = need;
    cache[1] = f0;
    for (int i = 0; i < n; i++) {
      cz[i] = z[i];
      if (need < 2) continue;
      cfi[i] = fi[i];
      cflat[i] = sup[i] ? 2.0 : flat[i];
    }
  }
  out[0] = f0;
  return 0;
}

void ps_user_call(const psModel* m, psData* d, const psuHD* c, double* out, const int* a,
                  double t) {
  int k = a[0], nin = a[2], chan = a[3], n = nin + 1;   /* inputs, then time */
  const int* in = m->user_in + a[1];
  const double* arg[PS_USER_MAXIN + 1];
  double z[PS_USER_MAXIN + 1], point[1 + (PS_USER_MAXIN + 1) * (PS_USER_MAXIN + 2)];
  double* tvar = ps_tmp(m, d, PS_TMP_TAPE - 1);   /* time as a hyper-dual */
  psu_hd_var(c, tvar, t, c->order >= 1 ? c->nh - 1 : -1);
  for (int i = 0; i < nin; i++) {
    arg[i] = ps_slot(m, d, in[i]);
    z[i] = arg[i][0];
  }
  arg[nin] = tvar;
  z[nin] = t;
  if (ps_user_point(m, d, a[4], k, chan, z, nin, c->order, point) != 0) {
    psu_hd_const(c, out, NAN);
    return;
  }
  psu_hd_nary(c, out, arg, n, point[0], point + 1, point + 1 + n);
}
