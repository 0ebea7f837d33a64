/* Loading a deck's generated C (pysolver/build/codegen): the library exports one psGen table
 * whose functions residual.c calls in place of the tape interpreter, and ps_gen_scene, the
 * record of the scene (cache key) it was generated for. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <string.h>

#include "internal.h"

const psGen* ps_gen_open(const char* path, const char* scene, const psModel* m, char* msg,
                         int msglen) {
  void* lib = dlopen(path, RTLD_NOW | RTLD_LOCAL);
  if (!lib) {
    snprintf(msg, (size_t)msglen, "cannot open %s: %s", path, dlerror());
    return NULL;
  }
  const char* record = (const char*)dlsym(lib, "ps_gen_scene");
  if (!record || strcmp(record, scene) != 0) {
    snprintf(msg, (size_t)msglen, "%s was generated for another scene (%s)", path,
             record ? "its scene record differs" : "it has no scene record");
    dlclose(lib);
    return NULL;
  }
  const psGen* gen = (const psGen*)dlsym(lib, "ps_gen_table");
  if (!gen) {
    snprintf(msg, (size_t)msglen, "%s has no ps_gen_table", path);
    dlclose(lib);
    return NULL;
  }
  if (gen->version != PS_GEN_VERSION || gen->ny != m->ny || gen->nsensor != m->nsensor ||
      gen->nout != m->nout) {
    snprintf(msg, (size_t)msglen, "%s was generated for another scene or version", path);
    dlclose(lib);
    return NULL;
  }
  /* user subroutines called from the generated code go through this kernel */
  void** hook = (void**)dlsym(lib, "psg_user_point");
  if (!hook) {
    snprintf(msg, (size_t)msglen, "%s has no psg_user_point", path);
    dlclose(lib);
    return NULL;
  }
  *hook = (void*)ps_user_point;
  return gen;
}
