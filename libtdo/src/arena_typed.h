// Typed allocation from a caller's arena for the stages' *_init functions (internal; docs/design.md
// s.7). The bytes taken are exactly those of tdo_arena_alloc(arena, n * sizeof(T)).
#ifndef TDO_SRC_ARENA_TYPED_H
#define TDO_SRC_ARENA_TYPED_H

#include <stddef.h>
#include <string.h>

#include "tdo/arena.h"

namespace tdo_internal {

// n objects of T, not initialised; NULL when the arena is too small.
template <typename T>
T* arena_array(tdo_arena* arena, size_t n) {
  return static_cast<T*>(tdo_arena_alloc(arena, n * sizeof(T)));
}

// A stage context: one Ctx, zero-filled, its `cfg` member a copy of `cfg`; NULL when the arena is
// too small.
template <typename Ctx, typename Cfg>
Ctx* arena_context(tdo_arena* arena, const Cfg& cfg) {
  Ctx* ctx = arena_array<Ctx>(arena, 1u);
  if (ctx == nullptr) return nullptr;
  memset(ctx, 0, sizeof(Ctx));
  ctx->cfg = cfg;
  return ctx;
}

}  // namespace tdo_internal

#endif  // TDO_SRC_ARENA_TYPED_H
