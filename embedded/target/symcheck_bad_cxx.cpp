// Linked into tdo-fw-symcheck-bad only, with symcheck_bad.c: C++ operator new/delete, which pull in
// libstdc++'s allocation, exception (__cxa_*) and typeinfo (_ZTI*) machinery that the symbol check
// of scripts/embedded.sh must reject. Never run.
#include <new>

int* volatile symcheck_bad_kept;  // the allocation escapes, so the compiler cannot elide it

extern "C" int symcheck_bad_cxx(void) {
  symcheck_bad_kept = new int(7);
  const int v = *symcheck_bad_kept;
  delete symcheck_bad_kept;
  return v;
}
