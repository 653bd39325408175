/* The host twin of the demo firmware: the same demo source, lines written to stdout. */
#include <stdio.h>

#include "tdo_demo.h"

void tdo_demo_write(const char* text) { fputs(text, stdout); }

int main(void) {
  tdo_demo_info info;
  const int rc = tdo_demo_run(&info);
  tdo_demo_print_platform("platform_host", 1u);
  tdo_demo_print_platform("arena_bytes", (uint32_t)info.arena_bytes);
  tdo_demo_print_platform("arena_footprint", (uint32_t)info.footprint);
  tdo_demo_print_platform("arena_used", (uint32_t)info.arena_used);
  return fflush(stdout) == 0 ? rc : 1;
}
