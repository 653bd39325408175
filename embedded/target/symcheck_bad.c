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

int symcheck_bad_cxx(void); /* symcheck_bad_cxx.cpp: operator new and delete */

/* What libstdc++'s abort path needs from an operating system; stubs let the bad image link. */
void _exit(int status);
void _exit(int status) {
  (void)status;
  for (;;) {
  }
}
int _kill(int pid, int sig);
int _kill(int pid, int sig) {
  (void)pid;
  (void)sig;
  return -1;
}
int _getpid(void);
int _getpid(void) { return 1; }
void* __dso_handle = 0; /* normally from crtbegin.o, which -nostartfiles leaves out */

int tdo_demo_run(tdo_demo_info* info) {
  char* p = (char*)malloc(16);
  info->arena_bytes = p != NULL ? 16u : 0u;
  info->footprint = (size_t)symcheck_bad_cxx();
  free(p);
  return 1;
}

void tdo_demo_print_platform(const char* key, uint32_t value) {
  (void)key;
  (void)value;
}
