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
#include <ctype.h>
#include <dlfcn.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "internal.h"

#define PS_EXPORT __attribute__((visibility("default")))
#define PS_USER_MAXPAR 64

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
  const double* values; /* evaluating: their current values                       */
  int error;            /* an error was reported                                  */
  char msg[200];
} UserCtx;

static __thread UserCtx* current = NULL;

/* The expression-language functions c_sysfnc answers. */
static const char* const FUNCTIONS[] = {
    "DX", "DY", "DZ", "DM", "VX", "VY", "VZ", "VM", "VR", "ACCX", "ACCY", "ACCZ",
    "WX", "WY", "WZ", "AX", "AY", "AZ", "VARVAL", "PFORCE", "SFORCE", "SENVAL"};

/* Copy a function name upper-cased and without spaces into name (16 bytes). */
static void clean_name(char* name, const char* fnc) {
  int n = 0;
  for (const char* p = fnc; *p && n < 15; p++)
    if (!isspace((unsigned char)*p)) name[n++] = (char)toupper((unsigned char)*p);
  name[n] = '\0';
}

int ps_user_fn_code(const char* fnc) {
  char name[16];
  clean_name(name, fnc);
  for (size_t i = 0; i < sizeof(FUNCTIONS) / sizeof(*FUNCTIONS); i++)
    if (!strcmp(name, FUNCTIONS[i])) return (int)i;
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

static void fail(UserCtx* ctx, const char* what, const char* detail) {
  if (ctx->error) return;
  ctx->error = 1;
  snprintf(ctx->msg, sizeof(ctx->msg), "%s%s", what, detail);
}

PS_EXPORT void c_sysfnc(const char* fnc, const int* ipar, int nsize, double* state,
                        int* errflg) {
  UserCtx* ctx = current;
  char key[PS_USER_KEY];
  *state = 0.0;
  *errflg = 1;
  if (!ctx) return;
  if (!ctx->recording) {
    /* the common case, kept fast: the name as declared (upper case) and the same ids; any
     * other spelling is normalised once */
    int code = -2;
    for (int i = 0; i < ctx->nknown; i++) {
      if (ctx->kn[i] != nsize) continue;
      if (strcmp(fnc, FUNCTIONS[ctx->kfn[i]]) != 0) {
        if (code == -2) code = ps_user_fn_code(fnc);
        if (ctx->kfn[i] != code) continue;
      }
      int same = 1;
      for (int j = 0; j < nsize && same; j++) same = ctx->kid[4 * i + j] == ipar[j];
      if (same) {
        *state = ctx->values[i];
        *errflg = 0;
        return;
      }
    }
  }
  if (make_key(key, fnc, ipar, nsize) != 0) {
    fail(ctx, "c_sysfnc: unknown function ", key);
    return;
  }
  if (ctx->recording) {
    for (int i = 0; i < ctx->nkeys && i < ctx->maxkeys; i++)
      if (!strcmp(ctx->keys + (long)i * PS_USER_KEY, key)) {
        *errflg = 0;
        return;
      }
    if (ctx->nkeys < ctx->maxkeys) memcpy(ctx->keys + (long)ctx->nkeys * PS_USER_KEY, key,
                                          PS_USER_KEY);
    ctx->nkeys++;
    *errflg = 0;
    return;
  }
  fail(ctx, "read a value its iflag call did not ask for: ", key);
}

/* SYSARY arrays: their entries as SYSFNC functions; angular ones take at most three ids. */
static const struct { const char* name; const char* parts[6]; int n; } ARRAYS[] = {
    {"TDISP", {"DX", "DY", "DZ"}, 3}, {"TVEL", {"VX", "VY", "VZ"}, 3},
    {"RVEL", {"WX", "WY", "WZ"}, 3}, {"VEL", {"VX", "VY", "VZ", "WX", "WY", "WZ"}, 6},
    {"TACC", {"ACCX", "ACCY", "ACCZ"}, 3}};

PS_EXPORT void c_sysary(const char* fnc, const int* ipar, int nsize, double* states,
                        int* nstates, int* errflg) {
  char name[16];
  clean_name(name, fnc);
  *nstates = 0;
  *errflg = 1;
  for (size_t a = 0; a < sizeof(ARRAYS) / sizeof(*ARRAYS); a++) {
    if (strcmp(name, ARRAYS[a].name)) continue;
    *errflg = 0;
    for (int i = 0; i < ARRAYS[a].n; i++) {
      int e = 0, nids = ARRAYS[a].parts[i][0] == 'W' && nsize > 3 ? 3 : nsize;
      c_sysfnc(ARRAYS[a].parts[i], ipar, nids, states + i, &e);
      *errflg |= e;
    }
    *nstates = ARRAYS[a].n;
    return;
  }
  if (current) fail(current, "c_sysary: unknown array ", name);
}

PS_EXPORT void c_errmes(int errflg, const char* message, int id, const char* endflag) {
  (void)id;
  (void)endflag;
  if (errflg && current) fail(current, "", message);
}

void ps_user_fail(const char* message) {
  if (current) fail(current, "", message);
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
  memcpy(p, par, sizeof(double) * (size_t)n);   /* the routine may not change the model */
  if (form == PS_USER_DFLAG)
    ((UserFnD)fn)(&id, &t, p, &n, &dflag, &iflag, val);
  else
    ((UserFnP)fn)(&id, &t, p, &n, &iflag, val);
  return val[chan];
}

int ps_user_declare(void* fn, int form, int id, const double* par, int npar, char* keys,
                    int maxkeys, char* msg, int msglen) {
  UserCtx ctx;
  memset(&ctx, 0, sizeof(ctx));
  ctx.recording = 1;
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

/* One evaluation of routine k at inputs z (declared values, then time). */
static double eval(const psModel* m, int k, UserCtx* ctx, const double* z, int nin, int dflag,
                   int chan) {
  ctx->values = z;
  return call(m->user_fn[k], m->user_form[k], m->user_id[k], z[nin],
              m->user_par + m->user_par_adr[k], m->user_npar[k], dflag, 0, chan);
}

void ps_user_call(const psModel* m, psData* d, const psuHD* c, double* out, const int* a,
                  double t) {
  int k = a[0], nin = a[2], chan = a[3], n = nin + 1;   /* inputs, then time */
  const int* in = m->user_in + a[1];
  const double* arg[PS_USER_MAXIN + 1];
  double z[PS_USER_MAXIN + 1], fi[PS_USER_MAXIN + 1];
  double fij[(PS_USER_MAXIN + 1) * (PS_USER_MAXIN + 1)];
  int flat[PS_USER_MAXIN + 1];   /* the routine gave exactly f0 at both +/- steps of input i */
  double* tvar = ps_tmp(m, d, PS_TMP_TAPE - 1);   /* time as a hyper-dual */
  psu_hd_var(c, tvar, t, c->order >= 1 ? c->nh - 1 : -1);
  for (int i = 0; i < nin; i++) {
    arg[i] = ps_slot(m, d, in[i]);
    z[i] = arg[i][0];
  }
  arg[nin] = tvar;
  z[nin] = t;
  UserCtx ctx;
  ctx.recording = 0;
  ctx.error = 0;
  ctx.msg[0] = '\0';
  ctx.kfn = m->user_key_fn + m->user_key_adr[k];
  ctx.kn = m->user_key_n + m->user_key_adr[k];
  ctx.kid = m->user_key_ids + 4 * m->user_key_adr[k];
  ctx.nknown = m->user_nkey[k];
  UserCtx* prev = current;
  current = &ctx;
  double f0 = eval(m, k, &ctx, z, nin, 0, chan);
  /* first partials by central differences (step ~ cbrt(eps)); the +/- values also give the
   * diagonal second partials, refined with a larger step (~ eps^(1/4)) when needed */
  for (int i = 0; c->order >= 1 && i < n; i++) {
    double zi = z[i], h = 6e-6 * fmax(1.0, fabs(zi));
    z[i] = zi + h;
    double fp = eval(m, k, &ctx, z, nin, 1, chan);
    z[i] = zi - h;
    double fm = eval(m, k, &ctx, z, nin, 1, chan);
    z[i] = zi;
    fi[i] = (fp - fm) / (2.0 * h);
    flat[i] = fp == f0 && fm == f0;
  }
  for (int i = 0; c->order >= 2 && i < n; i++)
    for (int j = i; j < n; j++) {
      if (flat[i] || flat[j]) {   /* no dependence on that input (time, usually): no calls */
        fij[i * n + j] = fij[j * n + i] = 0.0;
        continue;
      }
      double hi = 1e-4 * fmax(1.0, fabs(z[i])), hj = 1e-4 * fmax(1.0, fabs(z[j])), v;
      double zi = z[i], zj = z[j];
      if (i == j) {
        z[i] = zi + hi;
        double fp = eval(m, k, &ctx, z, nin, 1, chan);
        z[i] = zi - hi;
        double fm = eval(m, k, &ctx, z, nin, 1, chan);
        v = (fp - 2.0 * f0 + fm) / (hi * hi);
      } else {
        double s = 0.0;
        for (int q = 0; q < 4; q++) {
          double si = q & 1 ? -1.0 : 1.0, sj = q & 2 ? -1.0 : 1.0;
          z[i] = zi + si * hi;
          z[j] = zj + sj * hj;
          s += si * sj * eval(m, k, &ctx, z, nin, 1, chan);
        }
        v = s / (4.0 * hi * hj);
      }
      z[i] = zi;
      z[j] = zj;
      fij[i * n + j] = fij[j * n + i] = v;
    }
  current = prev;
  if (ctx.error) {
    d->user_error = 1;
    snprintf(d->msg, sizeof(d->msg), "user subroutine (id %d): %s", m->user_id[k], ctx.msg);
    psu_hd_const(c, out, NAN);
    return;
  }
  psu_hd_nary(c, out, arg, n, f0, fi, fij);
}
