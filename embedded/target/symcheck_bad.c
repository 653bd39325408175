/* Linked into tdo-fw-symcheck-bad only: a firmware that uses the heap, which the symbol check of
 * scripts/embedded.sh must reject, naming malloc and this object. Never run. */
#include <stdlib.h>

#include "tdo_demo.h"

/* newlib's malloc grows its pool through _sbrk; a stub lets the bad image link. */
void* _sbrk(ptrdiff_t increment);
void* _sbrk(ptrdiff_t increment) {
  (void)increment;
  return (void*)-1;
}

int tdo_demo_run(tdo_demo_info* info) {
  char* p = (char*)malloc(16);
  info->arena_bytes = p != NULL ? 16u : 0u;
  free(p);
  return 1;
}

void tdo_demo_print_platform(const char* key, uint32_t value) {
  (void)key;
  (void)value;
}
