/*
 * Bare-metal start-up and platform layer of the demo firmware (Cortex-M7, QEMU mps2-an500).
 *
 * - Vector table and reset handler of our own (no CMSIS, no newlib crt0): paint the stack, enable
 *   the FPU (SystemInit), copy .data, clear .bss, run constructors (none expected), run the demo.
 * - Output through ARM semihosting SYS_WRITE0 (one NUL-terminated line per call) and the exit code
 *   through SYS_EXIT, so the image references no stdio, no syscalls and no heap.
 * - Stack high-water mark: the reset handler fills the stack with a pattern before any C code
 *   runs; after planning, the lowest overwritten word gives the deepest stack use.
 * - Any fault prints its name and exits with a failure instead of hanging the emulator.
 */
#include <stdint.h>
#include <string.h>

#include "tdo_demo.h"

/* Linker script symbols (mps2_an500.ld). */
extern uint32_t __data_start[], __data_end[], __data_load[];
extern uint32_t __bss_start[], __bss_end[];
extern uint32_t __stack_limit[], __stack_top[];
extern void (*__preinit_array_start[])(void), (*__preinit_array_end[])(void);
extern void (*__init_array_start[])(void), (*__init_array_end[])(void);

#define STACK_PAINT 0xC5A5C5A5u

/* ---- Semihosting ---------------------------------------------------------------------------- */

enum { SYS_WRITE0 = 0x04, SYS_EXIT = 0x18 };
enum { ADP_STOPPED_APPLICATION_EXIT = 0x20026, ADP_STOPPED_RUNTIME_ERROR = 0x20023 };

static int semihost(int op, const void* arg) {
  register int r0 __asm__("r0") = op;
  register const void* r1 __asm__("r1") = arg;
  __asm__ volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
  return r0;
}

void tdo_demo_write(const char* text) { (void)semihost(SYS_WRITE0, text); }

static void __attribute__((noreturn)) semihost_exit(int ok) {
  /* AArch32: r1 holds the reason itself; QEMU exits 0 for ApplicationExit, 1 otherwise. */
  (void)semihost(SYS_EXIT, (const void*)(uintptr_t)(ok ? ADP_STOPPED_APPLICATION_EXIT
                                                       : ADP_STOPPED_RUNTIME_ERROR));
  for (;;) {
  }
}

/* ---- Start-up ------------------------------------------------------------------------------- */

/* Enable CP10/CP11 (the FPU) in CPACR before the first floating-point instruction. */
void SystemInit(void) {
  volatile uint32_t* const cpacr = (volatile uint32_t*)0xE000ED88u;
  *cpacr |= 0xFu << 20;
  __asm__ volatile("dsb\n\tisb" ::: "memory");
}

int main(void);

void __attribute__((noreturn, used)) reset_c(void) {
  SystemInit();
  for (uint32_t *src = __data_load, *dst = __data_start; dst < __data_end;) *dst++ = *src++;
  for (uint32_t* dst = __bss_start; dst < __bss_end;) *dst++ = 0u;
  for (void (**f)(void) = __preinit_array_start; f < __preinit_array_end; ++f) (*f)();
  for (void (**f)(void) = __init_array_start; f < __init_array_end; ++f) (*f)();
  semihost_exit(main() == 0);
}

/* Paint [__stack_limit, sp) with STACK_PAINT, then continue in C. No stack is used before. */
void __attribute__((naked, noreturn)) Reset_Handler(void) {
  __asm__ volatile(
      "ldr r0, =__stack_limit\n\t"
      "mov r1, sp\n\t"
      "ldr r2, =0xC5A5C5A5\n\t"
      "1:\n\t"
      "cmp r0, r1\n\t"
      "bhs 2f\n\t"
      "str r2, [r0], #4\n\t"
      "b 1b\n\t"
      "2:\n\t"
      "b reset_c\n\t"
      ".ltorg");
}

static void __attribute__((noreturn)) fault(const char* name) {
  tdo_demo_write("FAULT ");
  tdo_demo_write(name);
  tdo_demo_write("\n");
  semihost_exit(0);
}
static void NMI_Handler(void) { fault("nmi"); }
static void HardFault_Handler(void) { fault("hardfault"); }
static void MemManage_Handler(void) { fault("memmanage"); }
static void BusFault_Handler(void) { fault("busfault"); }
static void UsageFault_Handler(void) { fault("usagefault"); }
static void Default_Handler(void) { fault("unexpected interrupt"); }

typedef void (*vector)(void);
/* The Cortex-M vector table: initial stack pointer, then the 15 system exception handlers. */
typedef struct vector_table {
  uint32_t* initial_sp;
  vector handler[15];
} vector_table;
__attribute__((section(".isr_vector"), used)) static const vector_table vectors = {
    __stack_top,
    {
        Reset_Handler, NMI_Handler, HardFault_Handler, MemManage_Handler, BusFault_Handler,
        UsageFault_Handler, 0, 0, 0, 0, Default_Handler, /* SVCall */
        Default_Handler,                                 /* DebugMonitor */
        0, Default_Handler,                              /* PendSV */
        Default_Handler,                                 /* SysTick */
    }};

/* ---- The firmware --------------------------------------------------------------------------- */

/* Bytes of stack ever used: from the top down to the lowest word that lost the paint. */
static uint32_t stack_high_water(void) {
  const uint32_t* p = __stack_limit;
  while (p < __stack_top && *p == STACK_PAINT) ++p;
  return (uint32_t)((uintptr_t)__stack_top - (uintptr_t)p);
}

int main(void) {
  tdo_demo_info info;
  const int rc = tdo_demo_run(&info);
  tdo_demo_print_platform("platform_cortex_m7", 1u);
  tdo_demo_print_platform("arena_bytes", (uint32_t)info.arena_bytes);
  tdo_demo_print_platform("arena_footprint", (uint32_t)info.footprint);
  tdo_demo_print_platform("arena_used", (uint32_t)info.arena_used);
  tdo_demo_print_platform("stack_bytes",
                          (uint32_t)((uintptr_t)__stack_top - (uintptr_t)__stack_limit));
  tdo_demo_print_platform("stack_high_water_bytes", stack_high_water());
  return rc;
}
