/**
 * @file arena.h
 * @brief A bump allocator over caller-owned memory. Every libtdo buffer is carved from one.
 */
#ifndef TDO_ARENA_H
#define TDO_ARENA_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Caller-owned memory handed to libtdo once; carved at init, never grown. */
typedef struct tdo_arena {
  unsigned char* base; /**< start of the caller's memory */
  size_t size;         /**< bytes available */
  size_t used;         /**< bytes carved so far */
} tdo_arena;

/** Alignment every carve honours (bytes). */
#define TDO_ARENA_ALIGN 16u

/** Bytes a carve of `bytes` takes, alignment padding included; footprints add these up. */
size_t tdo_arena_round(size_t bytes);

/** Point the arena at caller memory. */
void tdo_arena_init(tdo_arena* arena, void* memory, size_t size);

/**
 * @brief Carve `bytes` (aligned to TDO_ARENA_ALIGN) from the arena.
 * @return the memory, or NULL when the arena has no room left.
 */
void* tdo_arena_alloc(tdo_arena* arena, size_t bytes);

#ifdef __cplusplus
}
#endif

#endif /* TDO_ARENA_H */
