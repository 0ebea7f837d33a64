/* The element kinds (csrc/assembly.h), indexed by PS_EL_*; pysolver/catalogue.py declares the
 * same layouts (tests/test_catalogue.py compares them through ps_element_layout). */
#include "../assembly.h"

#define KIND(name) void ps_el_##name(const psModel* m, psData* d, const psuHD* c, int tape, \
                                     const int* I, double t, const double* y,             \
                                     const double* yp, Assembly* as);
KIND(penalty)
KIND(sforce)
KIND(vforce)
KIND(motion)
KIND(joint)
KIND(gcon)
KIND(coupler)
KIND(turn)
int ps_el_sforce_undefined(const psModel* m, psData* d, const psuHD* c, int tape, const int* I,
                           double* value);

const psElementKind ps_element_kinds[PS_EL_COUNT] = {
  [PS_EL_PENALTY] = {ps_el_penalty, 2, 2, 1},
  [PS_EL_SFORCE] = {ps_el_sforce, 4, 1, 0, ps_el_sforce_undefined},
  [PS_EL_VFORCE] = {ps_el_vforce, 11, 6, 0},
  [PS_EL_MOTION] = {ps_el_motion, 7, 2, 1},
  [PS_EL_JOINT] = {ps_el_joint, 4, 2, 1},
  [PS_EL_GCON] = {ps_el_gcon, 4, 2, 1},
  [PS_EL_COUPLER] = {ps_el_coupler, 4, 2, 1},
  [PS_EL_TURN] = {ps_el_turn, 2, 1, 0},
};

int ps_element_layout(int kind, int* nint, int* nvalue, int* order) {
  if (kind < 0 || kind >= PS_EL_COUNT) return -1;
  *nint = ps_element_kinds[kind].nint;
  *nvalue = ps_element_kinds[kind].nvalue;
  *order = ps_element_kinds[kind].order;
  return PS_OK;
}
