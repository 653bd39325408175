#include "tdo/arena.h"

#include <stdint.h>

extern "C" size_t tdo_arena_round(size_t bytes) {
  return (bytes + (TDO_ARENA_ALIGN - 1u)) & ~static_cast<size_t>(TDO_ARENA_ALIGN - 1u);
}

extern "C" void tdo_arena_init(tdo_arena* arena, void* memory, size_t size) {
  if (arena == nullptr) return;
  arena->base = static_cast<unsigned char*>(memory);
  arena->size = memory != nullptr ? size : 0u;
  arena->used = 0u;
  // The first carve starts aligned: skip the misaligned head of the caller's block.
  const uintptr_t addr = reinterpret_cast<uintptr_t>(memory);
  const size_t head = (TDO_ARENA_ALIGN - (addr % TDO_ARENA_ALIGN)) % TDO_ARENA_ALIGN;
  arena->used = head <= arena->size ? head : arena->size;
}

extern "C" void* tdo_arena_alloc(tdo_arena* arena, size_t bytes) {
  if (arena == nullptr || arena->base == nullptr) return nullptr;
  const size_t need = tdo_arena_round(bytes);
  if (need < bytes || arena->used > arena->size || need > arena->size - arena->used) return nullptr;
  void* p = arena->base + arena->used;
  arena->used += need;
  return p;
}
