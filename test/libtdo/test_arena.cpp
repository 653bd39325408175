// tdo_arena: a bump allocator over caller memory (arena.h).
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "tdo/arena.h"

namespace {

uintptr_t addr(const void* p) { return reinterpret_cast<uintptr_t>(p); }

TEST(Arena, GivenAnyByteCount_WhenRounded_ThenNextMultipleOfTheAlignment) {
  static_assert((TDO_ARENA_ALIGN & (TDO_ARENA_ALIGN - 1u)) == 0u, "alignment is a power of two");
  for (size_t b = 1; b <= 4096; ++b) {
    const size_t r = tdo_arena_round(b);
    ASSERT_EQ(r % TDO_ARENA_ALIGN, 0u) << "bytes " << b;
    ASSERT_GE(r, b) << "bytes " << b;
    ASSERT_LT(r - b, static_cast<size_t>(TDO_ARENA_ALIGN)) << "bytes " << b;
  }
  EXPECT_EQ(tdo_arena_round(TDO_ARENA_ALIGN), static_cast<size_t>(TDO_ARENA_ALIGN));
  EXPECT_EQ(tdo_arena_round(TDO_ARENA_ALIGN + 1u), 2u * TDO_ARENA_ALIGN);
  EXPECT_EQ(tdo_arena_round(1000u * TDO_ARENA_ALIGN), 1000u * TDO_ARENA_ALIGN);
}

TEST(Arena, GivenAlignedMemory_WhenCarving_ThenBlocksAreAlignedDisjointAndInside) {
  alignas(64) static unsigned char mem[1024];
  tdo_arena a;
  tdo_arena_init(&a, mem, sizeof mem);
  const size_t sizes[] = {1, 3, 16, 17, 40, 7, 100};
  uintptr_t prev_end = addr(mem);
  for (size_t s : sizes) {
    const size_t used_before = a.used;
    void* p = tdo_arena_alloc(&a, s);
    ASSERT_NE(p, nullptr) << "size " << s;
    EXPECT_EQ(addr(p) % TDO_ARENA_ALIGN, 0u) << "size " << s;
    EXPECT_GE(addr(p), prev_end) << "blocks overlap";
    EXPECT_LE(addr(p) + s, addr(mem) + sizeof mem);
    EXPECT_EQ(a.used - used_before, tdo_arena_round(s)) << "a carve takes tdo_arena_round bytes";
    prev_end = addr(p) + s;
  }
  EXPECT_LE(a.used, a.size);
}

TEST(Arena, GivenMisalignedMemory_WhenCarving_ThenBlocksAreStillAlignedAndInside) {
  alignas(64) static unsigned char mem[512];
  for (size_t off = 0; off < TDO_ARENA_ALIGN; ++off) {
    tdo_arena a;
    tdo_arena_init(&a, mem + off, 256);
    uintptr_t prev_end = addr(mem + off);
    for (int n = 0; n < 4; ++n) {
      void* p = tdo_arena_alloc(&a, 24);
      ASSERT_NE(p, nullptr) << "offset " << off << " carve " << n;
      EXPECT_EQ(addr(p) % TDO_ARENA_ALIGN, 0u) << "offset " << off;
      EXPECT_GE(addr(p), prev_end) << "offset " << off;
      EXPECT_LE(addr(p) + 24, addr(mem + off) + 256) << "offset " << off;
      prev_end = addr(p) + 24;
    }
  }
}

TEST(Arena, GivenAFullArena_WhenCarvingMore_ThenNullAndNothingIsConsumed) {
  alignas(64) static unsigned char mem[128];
  tdo_arena a;
  tdo_arena_init(&a, mem, sizeof mem);
  ASSERT_NE(tdo_arena_alloc(&a, 64), nullptr);
  const size_t used = a.used;
  EXPECT_EQ(tdo_arena_alloc(&a, 65), nullptr) << "65 bytes cannot fit in the 64 left";
  EXPECT_EQ(a.used, used) << "a failed carve must not consume memory";
  EXPECT_NE(tdo_arena_alloc(&a, 64), nullptr) << "exactly the rest fits";
  EXPECT_EQ(a.used, a.size);
  EXPECT_EQ(tdo_arena_alloc(&a, 1), nullptr);
  EXPECT_EQ(a.used, a.size);
}

TEST(Arena, GivenARequestWhoseRoundingOverflows_WhenCarving_ThenNull) {
  alignas(64) static unsigned char mem[128];
  tdo_arena a;
  tdo_arena_init(&a, mem, sizeof mem);
  EXPECT_EQ(tdo_arena_alloc(&a, SIZE_MAX), nullptr);
  EXPECT_EQ(tdo_arena_alloc(&a, SIZE_MAX - TDO_ARENA_ALIGN / 2u), nullptr);
  EXPECT_EQ(tdo_arena_alloc(&a, SIZE_MAX / 2u), nullptr);
  EXPECT_NE(tdo_arena_alloc(&a, 128), nullptr) << "failed huge carves consumed memory";
}

TEST(Arena, GivenNullArenaOrMemory_WhenCarving_ThenNull) {
  EXPECT_EQ(tdo_arena_alloc(nullptr, 16), nullptr);
  tdo_arena a;
  tdo_arena_init(&a, nullptr, 1024);
  EXPECT_EQ(tdo_arena_alloc(&a, 16), nullptr);
}

TEST(Arena, GivenASequenceOfCarves_WhenFilled_ThenWritesStayInsideTheirBlocks) {
  // Fill every block with its own byte and check none was overwritten by a later carve.
  std::vector<unsigned char> mem(4096 + 15);
  tdo_arena a;
  tdo_arena_init(&a, mem.data() + 5, 4096);
  std::vector<std::pair<unsigned char*, size_t>> blocks;
  for (size_t s = 1;; s = s * 3 + 1) {
    auto* p = static_cast<unsigned char*>(tdo_arena_alloc(&a, s));
    if (p == nullptr) break;
    for (size_t n = 0; n < s; ++n) p[n] = static_cast<unsigned char>(blocks.size() + 1);
    blocks.emplace_back(p, s);
  }
  ASSERT_GE(blocks.size(), 5u);
  for (size_t b = 0; b < blocks.size(); ++b)
    for (size_t n = 0; n < blocks[b].second; ++n)
      ASSERT_EQ(blocks[b].first[n], static_cast<unsigned char>(b + 1)) << "block " << b;
}

}  // namespace
