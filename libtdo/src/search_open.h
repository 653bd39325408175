// The open lists of the search (docs/design.md s.1, "Memory and work"): a 4-ary heap ordered by
// (f, h, state) as one 128-bit integer, and the buckets of unidirectional plain A*. Internal to
// libtdo.
#ifndef TDO_SRC_SEARCH_OPEN_H
#define TDO_SRC_SEARCH_OPEN_H

#include <stdint.h>
#include <string.h>

#include "search_state.h"

namespace tdo_internal {
inline namespace TDO_SEARCH_NS {
namespace {  // one copy per translation unit, as the search's hot paths were

// Open-list order: smaller f, then smaller h, then smaller node index. f >= 0 and h >= 0 (finite or
// +inf), so their bit patterns order as unsigned integers: the order is that of the 128-bit integer
// (f bits, h bits, node), compared without a data-dependent branch.
struct Key {
  uint64_t hi;  // bits of f
  uint64_t lo;  // bits of h << 32 | node
};

inline Key key_of(const OpenItem& a) {
  Key k;
  memcpy(&k.hi, &a.f, sizeof(k.hi));
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
  // node then h in memory, h last: one load of the 8 bytes ending with h gives h << 32 | node
  // (32-bit Index) or h << 32 | node << 16 | two bytes of f (16-bit Index), shifted out.
  constexpr size_t kLoAt = offsetof(OpenItem, h) + sizeof(float) - sizeof(uint64_t);
  static_assert(offsetof(OpenItem, h) == offsetof(OpenItem, node) + sizeof(Index) &&
                    offsetof(OpenItem, node) == sizeof(double),
                "OpenItem layout");
  memcpy(&k.lo, reinterpret_cast<const unsigned char*>(&a) + kLoAt, sizeof(k.lo));
  k.lo >>= 8u * (offsetof(OpenItem, node) - kLoAt);
#else
  uint32_t h;
  memcpy(&h, &a.h, sizeof(h));
  k.lo = (static_cast<uint64_t>(h) << (8u * sizeof(Index))) | a.node;
#endif
  return k;
}

inline bool less(const Key& a, const Key& b) {
#if defined(__SIZEOF_INT128__)
  __extension__ typedef unsigned __int128 U128;
  return ((static_cast<U128>(a.hi) << 64) | a.lo) < ((static_cast<U128>(b.hi) << 64) | b.lo);
#else
  return (a.hi < b.hi) | ((a.hi == b.hi) & (a.lo < b.lo));
#endif
}

inline bool before(const OpenItem& a, const OpenItem& b) { return less(key_of(a), key_of(b)); }

inline void place(Side& s, uint32_t i, const OpenItem& it) {
  s.open[i] = it;
  if ((it.node & kDeferItem) == 0) s.nodes[it.node].heap = static_cast<Index>(i);
}

// Put item `it` at position i (a hole, or its old place) and move it up to where it belongs. The
// item comes in registers: storing its fields and reading them back as one key would stall on
// store-to-load forwarding.
void sift_up(Side& s, uint32_t i, const OpenItem& it) {
  const Key k = key_of(it);
  while (i > 0) {
    const uint32_t p = (i - 1u) / kArity;
    if (!less(k, key_of(s.open[p]))) break;
    place(s, i, s.open[p]);
    i = p;
  }
  place(s, i, it);
}

// Index of the smallest of the kArity items from `first` (all present), chosen by selects.
inline uint32_t min_of_four(const OpenItem* open, uint32_t first) {
  const uint32_t a =
      first + static_cast<uint32_t>(less(key_of(open[first + 1u]), key_of(open[first])));
  const uint32_t b =
      first + 2u + static_cast<uint32_t>(less(key_of(open[first + 3u]), key_of(open[first + 2u])));
  const uint32_t m = 0u - static_cast<uint32_t>(less(key_of(open[b]), key_of(open[a])));
  return a ^ ((a ^ b) & m);
}

// Remove the smallest item: the hole it leaves goes down to a leaf along the smaller children
// (no comparison with the item that fills it), then the last item fills the hole and sifts up,
// which it rarely does far (it came from the bottom).
uint32_t pop(Side& s) {
  static_assert(kArity == 4, "min_of_four");
  const uint32_t top = s.open[0].node;
  const uint32_t n = --s.n_open;
  if (n > 0) {
    uint32_t i = 0;
    for (;;) {
      const uint32_t first = kArity * i + 1u;
      if (first >= n) break;
      uint32_t c;
      if (first + kArity <= n) {
        c = min_of_four(s.open, first);
      } else {
        c = first;
        for (uint32_t j = first + 1u; j < n; ++j)
          if (before(s.open[j], s.open[c])) c = j;
      }
      place(s, i, s.open[c]);
      i = c;
    }
    const OpenItem last = s.open[n];
    sift_up(s, i, last);
  }
  if ((top & kDeferItem) == 0) s.nodes[top].heap = kNil;
  return top;
}

inline uint64_t bucket_of(const Side& s, double f) {
  return static_cast<uint64_t>(f * s.inv_width);
}

// Queue item `it` (not queued yet): into the heap when its bucket is not above the current one,
// else at the head of its bucket's list.
inline void enqueue(Side& s, const OpenItem& it) {
  if (!s.bucketed) {
    sift_up(s, s.n_open++, it);
    return;
  }
  const uint64_t b = bucket_of(s, it.f);
  // b - cur < kRing always holds (see kRing); the heap keeps the order if it ever did not.
  if (b <= s.cur || b - s.cur >= kRing) {
    sift_up(s, s.n_open++, it);
    return;
  }
  const uint32_t r = static_cast<uint32_t>(b & (kRing - 1u));
  const uint32_t h = s.head[r];
  s.nodes[it.node].next = static_cast<Index>(h);
  s.nodes[it.node].heap = static_cast<Index>(kBucketBit | (kBucketHeadBase + r));
  if (h != kNil) s.nodes[h].heap = static_cast<Index>(kBucketBit | it.node);
  s.head[r] = it.node;
  ++s.n_future;
}

// Take item i out of its bucket list.
inline void unlink(Side& s, uint32_t i) {
  const uint32_t p = s.nodes[i].heap & ~kBucketBit, n = s.nodes[i].next;
  if (p >= kBucketHeadBase)
    s.head[p - kBucketHeadBase] = n;
  else
    s.nodes[p].next = static_cast<Index>(n);
  if (n != kNil) s.nodes[n].heap = static_cast<Index>(kBucketBit | p);
  --s.n_future;
}

// The heap is empty: make the next non-empty bucket current and build its heap (f and h computed
// as push() computes them, so the same bits). Bounded: the later buckets lie within kRing.
template <typename Prio>
void advance(Side& s, Prio prio) {
  for (uint32_t k = 0; k < kRing && s.n_future > 0; ++k) {
    ++s.cur;
    const uint32_t r = static_cast<uint32_t>(s.cur & (kRing - 1u));
    uint32_t i = s.head[r];
    if (i == kNil) continue;
    s.head[r] = kNil;
    while (i != kNil) {  // bounded by the items queued
      const uint32_t after = s.nodes[i].next;
      OpenItem it;
      float h;
      it.node = static_cast<Index>(i);
      it.f = prio(s.nodes[i], &h);
      it.h = h;
      sift_up(s, s.n_open++, it);
      --s.n_future;
      i = after;
    }
    return;
  }
}

}  // namespace
}  // namespace TDO_SEARCH_NS
}  // namespace tdo_internal

#endif  // TDO_SRC_SEARCH_OPEN_H
