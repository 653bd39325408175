/**
 * @file tdo_demo.h
 * @brief The embedded demo: plan one map with the full static pipeline from a static arena and
 *        print the result as text. The same source runs on the host and in the firmware.
 *
 * The demo never calls printf: it formats numbers itself (fixed decimals, integer arithmetic) and
 * hands finished lines to tdo_demo_write, which each platform provides (host: stdout; firmware:
 * semihosting SYS_WRITE0). So the firmware image needs no stdio and no heap, and both platforms
 * print the same bytes for the same doubles.
 */
#ifndef TDO_DEMO_H
#define TDO_DEMO_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Platform hook: write one NUL-terminated line (it ends with '\n'). */
void tdo_demo_write(const char* text);

/** What the demo learned about its memory; platform-dependent, so printed on '@' lines only. */
typedef struct tdo_demo_info {
  size_t arena_bytes; /**< bytes of the static arena (TDO_DEMO_ARENA_BYTES) */
  size_t footprint;   /**< bytes tdo_planner_footprint asks for on this platform */
  size_t arena_used;  /**< bytes the planner carved at init */
} tdo_demo_info;

/**
 * @brief Build the planner in the static arena, load the compiled-in map, plan start -> goal with
 *        the default TDO-MSF parameters and print status, waypoints, metrics and checksums.
 * @return 0 when the plan succeeded (status ok), 1 otherwise.
 */
int tdo_demo_run(tdo_demo_info* info);

/**
 * @brief Print a platform line "@<key> <value>\n". Lines starting with '@' carry what differs
 *        between platforms (sizes, stack use) and are left out when host and firmware are compared.
 */
void tdo_demo_print_platform(const char* key, uint32_t value);

#ifdef __cplusplus
}
#endif

#endif /* TDO_DEMO_H */
