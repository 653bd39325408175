// Stage 2: multi-scale inflection correction of the grid path (docs/design.md s.2, correct.h).
//
// 1. Every input segment is verified with tdo_collision_segment_clear at the clearance; one that
//    fails makes the run TDO_ERR_NO_PATH. The segments of a collinear run (step 2's) are proven
//    together by one check of the merged segment with a margin (run_clear), else one by one.
// 2. Collinear interior points (turn below kCollinearRad) and repeated points are dropped; the
//    merged segment of a run of collinear points is verified once (known when run_clear proved
//    the run), and when it fails (rounding at the limit) the run's points stay.
// 3. MULTISCALE (TDO-MSF): passes over the scales s = 3, 5, 7 until a pass removes nothing. At
//    each scale two sweeps run left to right over the windows of s consecutive points:
//      sweep A tries only "gentle" windows, whose interior turns are all below turn_threshold
//      (staircase remnants, straightened first so the larger turns see straight neighbours);
//      sweep B tries every window.
//    A window's interior points are removed when the chord from its first to its last point is
//    clear at the clearance; the sweep then retries the window at the same start (so a clear
//    run keeps shrinking at that scale), otherwise it moves one point on. A chord that failed is
//    remembered by the input indices of its ends (the last 8 per start point; the same two input
//    points give the same chord, so skipping it is exact) and not checked again while remembered.
//    A removal that would break clearance is never made.
//    GREEDY_LOS (MSF-MTPO baseline): from the current point, the farthest later point whose chord
//    is clear becomes the next waypoint (scanning from the last point backwards).
//    NONE: step 2 only.
// Safety-critical points: interior output points whose own removal (the chord between their two
// neighbours) was checked and failed. In MULTISCALE and GREEDY_LOS every interior output point is
// one at convergence; NONE checks none and reports 0.
#include "tdo/correct.h"

#include <math.h>
#include <string.h>

#include "arena_typed.h"
#include "collision_internal.h"
#include "tdo/collision.h"
#include "vec3.h"

namespace {

using namespace tdo_internal;  // vec3.h, collision_internal.h, arena_typed.h

constexpr double kCollinearRad = 1e-9;  // rad, turns below this are "collinear"
constexpr uint32_t kMemo = 8;           // failed chords remembered per start point
constexpr uint32_t kNone = 0xFFFFFFFFu;
constexpr uint32_t kScales[3] = {3u, 5u, 7u};
// Of 1 + the clearance + the largest coordinate magnitude (m): a margin far above the rounding of
// a clearance check's verdict, a distance and the points (~1e-15 of the coordinates), far below
// any clearance that matters.
constexpr double kMarginRel = 1e-7;

bool same(const tdo_vec3& a, const tdo_vec3& b) {
  return !(a.x < b.x || a.x > b.x || a.y < b.y || a.y > b.y || a.z < b.z || a.z > b.z);
}

// Turn angle (rad) at b of the polyline a -> b -> c, in [0, pi]; 0 for a zero-length side.
double turn_angle(const tdo_vec3& a, const tdo_vec3& b, const tdo_vec3& c) {
  const tdo_vec3 u = sub(b, a), v = sub(c, b);
  const double cx = u.y * v.z - u.z * v.y, cy = u.z * v.x - u.x * v.z, cz = u.x * v.y - u.y * v.x;
  const double cross = sqrt(cx * cx + cy * cy + cz * cz);
  const double dot = u.x * v.x + u.y * v.y + u.z * v.z;
  if (!(cross > 0.0) && !(dot < 0.0)) return 0.0;
  return atan2(cross, dot);
}

size_t round16(size_t n) { return tdo_arena_round(n); }

}  // namespace

struct tdo_correct {
  tdo_correct_config cfg;
  tdo_vec3* pts;     // m, working polyline; the output after a run (max_points)
  uint32_t* orig;    // original input index of each working point (max_points)
  uint32_t* memo;    // kMemo failed chord ends (original indices) per original start point
  uint8_t* memo_at;  // next ring slot of each start point's memo
};

namespace {

struct Run {
  tdo_correct* ctx;
  const tdo_grid* grid;
  double clearance;  // m
  uint32_t checks;   // checks done
  uint32_t budget;   // checks allowed
  uint32_t hint;     // box that failed the last check (segment_clear_hinted)
  uint32_t cube;     // voxel cube that failed the last check (segment_clear_steered)
  uint32_t proven;   // input points 1 .. proven: their segments are known clear (steps_proven)
  bool bounds;       // tighten bounds its keeps (keep_bounds): clearance <= res/4, 64-bit builds
};

// Counts one check; false (nothing counted) when the budget is spent.
bool count_check(Run& r) {
  if (r.checks >= r.budget) return false;
  ++r.checks;
  return true;
}

// [a, b] at clearance c, not counted (the check it stands for is counted by the caller).
bool clear_at(Run& r, const tdo_vec3& a, const tdo_vec3& b, double c) {
  return tdo_internal::segment_clear_steered(r.grid, a, b, c, &r.hint, &r.cube) != 0;
}

// [a, b] at `clearance` (m, >= the run's): 1 clear, 0 not clear, -1 budget exhausted.
int check_at(Run& r, const tdo_vec3& a, const tdo_vec3& b, double clearance) {
  if (!count_check(r)) return -1;
  return clear_at(r, a, b, clearance) ? 1 : 0;
}

// [a, b] at the run's clearance.
int check(Run& r, const tdo_vec3& a, const tdo_vec3& b) { return check_at(r, a, b, r.clearance); }

// A check whose answer is known to be "clear", counted as check() counts it: -1 when the budget
// is spent, else 1.
int known_clear(Run& r) { return count_check(r) ? 1 : -1; }

// The point drop_collinear keeps after the kept input point s: e, the first later point that is
// neither a repeat nor collinear (turn below kCollinearRad at it, seen from s), or the last.
// *run: a collinear point lies between (drop_collinear then checks the merged segment [s, e]).
uint32_t next_kept(const tdo_vec3* p, uint32_t n, uint32_t s, bool* run) {
  *run = false;
  for (uint32_t i = s + 1u; i + 1u < n; ++i) {
    if (same(p[i], p[s]) || same(p[i], p[i + 1u])) continue;
    if (!(turn_angle(p[s], p[i], p[i + 1u]) < kCollinearRad)) return i;
    *run = true;
  }
  return n - 1u;
}

// Proof that every input segment of the collinear run s .. e, and the merged segment [s, e], is
// clear at the run's clearance c (step 1 and step 2 would find them so), from one check: [s, e]
// clear at c + h + margin, h the largest distance of the run's points from [s, e]. Each point of
// a piece [p_k, p_k+1] is a convex combination of the two, so it lies within h of the convex
// [s, e]: its distance to the obstacles is at least [s, e]'s less h, so every piece (and [s, e]
// itself) keeps c plus the margin, and their checks, whose verdicts are exact up to rounding far
// below it, say clear. A piece's end points must also pass the checks' bounds test (exact, so
// tested here by the same test, point_in_bounds). False: no claim (the pieces are checked one by
// one).
bool run_clear(Run& r, const tdo_vec3* p, uint32_t s, uint32_t e) {
  double h = 0.0, mag = 1.0 + r.clearance;
  const tdo_vec3 a = p[s], ab = sub(p[e], a);
  const double ll = dot(ab, ab);
  for (uint32_t k = s; k <= e; ++k) {
    const double v[3] = {p[k].x, p[k].y, p[k].z};
    for (double x : v) mag = fabs(x) > mag ? fabs(x) : mag;
    if (k == s || k == e) continue;
    if (!point_in_bounds(r.grid, p[k])) return false;
    const tdo_vec3 w = sub(p[k], a);
    double t = ll > 0.0 ? dot(w, ab) / ll : 0.0;
    t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
    const double dk = norm(sub(w, mul(ab, t)));
    h = dk > h ? dk : h;
  }
  const double need = r.clearance + h + kMarginRel * mag;
  return clear_at(r, p[s], p[e], need);
}

// Step 1: every input segment checked at the clearance, in order; TDO_ERR_NO_PATH at the first
// that fails. A collinear run that run_clear proves, or that lies within the caller's proven
// steps, is counted check by check, as checking each would (the same answers, the same count, so
// the same status at every budget), and marked in memo_at[s] for drop_collinear.
tdo_status verify_input(Run& r, const tdo_vec3* p, uint32_t n) {
  tdo_correct* ctx = r.ctx;
  for (uint32_t i = 0; i < n; ++i) ctx->memo_at[i] = 0;
  // Bounded: s grows every iteration.
  for (uint32_t s = 0; s + 1u < n;) {
    bool run = false;
    const uint32_t e = next_kept(p, n, s, &run);
    const bool known = (s >= 1u && e <= r.proven) || (run && run_clear(r, p, s, e));
    ctx->memo_at[s] = known ? 1u : 0u;
    for (uint32_t i = s + 1u; i <= e; ++i) {
      const int ok = known ? known_clear(r) : check(r, p[i - 1u], p[i]);
      if (ok < 0) return TDO_ERR_BUDGET;
      if (ok == 0) return TDO_ERR_NO_PATH;
    }
    s = e;
  }
  return TDO_OK;
}

bool memo_failed(const tdo_correct* ctx, uint32_t oi, uint32_t oj) {
  const uint32_t* m = ctx->memo + static_cast<size_t>(oi) * kMemo;
  for (uint32_t k = 0; k < kMemo; ++k)
    if (m[k] == oj) return true;
  return false;
}

void memo_add(tdo_correct* ctx, uint32_t oi, uint32_t oj) {
  uint8_t& at = ctx->memo_at[oi];
  ctx->memo[static_cast<size_t>(oi) * kMemo + at] = oj;
  at = static_cast<uint8_t>((at + 1u) % kMemo);
}

// Remove working points (i, j) exclusive; returns the new count.
uint32_t remove_between(tdo_correct* ctx, uint32_t m, uint32_t i, uint32_t j) {
  const uint32_t gap = j - i - 1u;
  for (uint32_t k = j; k < m; ++k) {
    ctx->pts[k - gap] = ctx->pts[k];
    ctx->orig[k - gap] = ctx->orig[k];
  }
  return m - gap;
}

// Step 2: drop repeated and collinear interior points in place. Returns TDO_OK and *m, or the
// budget status.
tdo_status drop_collinear(Run& r, uint32_t n, uint32_t* m_out) {
  tdo_correct* ctx = r.ctx;
  tdo_vec3* p = ctx->pts;
  uint32_t* o = ctx->orig;
  uint32_t w = 1;            // next write position; p[0] is kept
  uint32_t pending = kNone;  // first input index of the collinear run since the last kept point
  for (uint32_t i = 1; i < n; ++i) {
    if (i + 1u < n) {
      const tdo_vec3 a = p[w - 1u], b = p[i], c = p[i + 1u];
      if (same(b, a) || same(b, c)) continue;  // a repeated point: the segments are unchanged
      if (turn_angle(a, b, c) < kCollinearRad) {
        if (pending == kNone) pending = i;
        continue;
      }
    }
    const tdo_vec3 keep = p[i];
    const uint32_t keep_o = o[i];
    if (pending != kNone) {
      // A run verify_input proved: its merged segment is clear (run_clear).
      const int ok = r.ctx->memo_at[o[w - 1u]] != 0u ? known_clear(r) : check(r, p[w - 1u], keep);
      if (ok < 0) return TDO_ERR_BUDGET;
      if (ok == 0) {  // the merged segment fails at the limit: the run's points stay
        for (uint32_t k = pending; k < i; ++k) {
          if (same(p[k], p[w - 1u])) continue;
          p[w] = p[k];
          o[w] = o[k];
          ++w;
        }
      }
      pending = kNone;
    }
    p[w] = keep;
    o[w] = keep_o;
    ++w;
  }
  *m_out = w;
  return TDO_OK;
}

tdo_status greedy(Run& r, uint32_t* m_io, uint32_t* critical) {
  tdo_correct* ctx = r.ctx;
  const uint32_t m = *m_io;
  uint32_t w = 1;  // output written in place: w <= cur + 1 always
  uint32_t cur = 0;
  // Bounded: cur grows every iteration.
  while (cur + 1u < m) {
    uint32_t next = cur + 1u;  // always clear: a verified segment
    for (uint32_t j = m - 1u; j > cur + 1u; --j) {
      const int ok = check(r, ctx->pts[cur], ctx->pts[j]);
      if (ok < 0) return TDO_ERR_BUDGET;
      if (ok == 1) {
        next = j;
        break;
      }
    }
    // next is interior: every later point was checked from cur and failed, so removing next
    // (joining cur to the point after it) breaks clearance.
    if (next + 1u < m) ++*critical;
    // In place: w <= next, and only points from next on are read later.
    ctx->pts[w] = ctx->pts[next];
    ctx->orig[w] = ctx->orig[next];
    ++w;
    cur = next;
  }
  *m_io = w;
  return TDO_OK;
}

tdo_status multiscale(Run& r, uint32_t* m_io, double turn_threshold, uint32_t* critical) {
  tdo_correct* ctx = r.ctx;
  uint32_t m = *m_io;
  // Bounded: every pass but the last removes at least one point.
  const uint32_t max_passes = m + 1u;
  for (uint32_t pass = 0; pass < max_passes; ++pass) {
    bool changed = false;
    for (uint32_t s : kScales) {
      for (int sweep = 0; sweep < 2; ++sweep) {
        uint32_t i = 0;
        // Bounded: each iteration removes points or advances i.
        while (i + s - 1u < m) {
          const uint32_t j = i + s - 1u;
          if (sweep == 0) {
            bool gentle = true;
            for (uint32_t k = i + 1u; k < j && gentle; ++k)
              gentle = turn_angle(ctx->pts[k - 1u], ctx->pts[k], ctx->pts[k + 1u]) < turn_threshold;
            if (!gentle) {
              ++i;
              continue;
            }
          }
          if (memo_failed(ctx, ctx->orig[i], ctx->orig[j])) {
            ++i;
            continue;
          }
          const int ok = check(r, ctx->pts[i], ctx->pts[j]);
          if (ok < 0) return TDO_ERR_BUDGET;
          if (ok == 1) {
            m = remove_between(ctx, m, i, j);
            changed = true;
          } else {
            memo_add(ctx, ctx->orig[i], ctx->orig[j]);
            ++i;
          }
        }
      }
    }
    if (!changed) break;
  }
  // The last pass removed nothing, and its sweep B tried every 3-window (checked, or known to
  // have failed): the chord around every interior point fails, so every one is safety-critical.
  *critical = m >= 2u ? m - 2u : 0u;
  *m_io = m;
  return TDO_OK;
}

// Optional shortening after the scales (input `shorten`), in rounds of three sweeps:
// - partial shortcuts, forward and then backward (on the reversed polyline): from waypoint i, for
//   the farthest segment [w_j, w_j+1] (j = i+1 .. i+kShortReach) first, a point p = w_j +
//   t (w_j+1 - w_j) with t in kShortT (largest first) whose chord w_i -> p is clear replaces
//   w_i+1 .. w_j. p -> w_j+1 is part of a verified segment, so every segment stays verified; the
//   polyline gets shorter (triangle inequality) and loses j - i - 1 waypoints;
// - relocation: an interior point moves a fraction s in kRelocS of the way to the nearest point
//   of the chord between its neighbours when both new segments are clear (the sum of the two
//   distances is convex in the point, so it never grows).
// After the rounds, one tightening pass (below: small axis moves of each interior point that
// shorten the polyline without tighter corners or less room from the obstacles).
// It stops early (keeping the valid polyline it has) when the check budget is spent. Finally every
// interior point whose chord between its neighbours is clear is dropped, so the safety-critical
// count stays exact.
constexpr uint32_t kShortReach = 6u;   // segments ahead tried per start point
constexpr uint32_t kShortRounds = 3u;  // forward + backward rounds at most
constexpr double kShortT[6] = {0.9375, 0.875, 0.75, 0.5, 0.25, 0.125};
constexpr double kRelocS[3] = {0.5, 0.25, 0.125};

void reverse_pts(tdo_correct* ctx, uint32_t m) {
  for (uint32_t a = 0, b = m - 1u; a < b; ++a, --b) {
    const tdo_vec3 t = ctx->pts[a];
    ctx->pts[a] = ctx->pts[b];
    ctx->pts[b] = t;
    const uint32_t o = ctx->orig[a];
    ctx->orig[a] = ctx->orig[b];
    ctx->orig[b] = o;
  }
}

// `n` checks known to fail, counted as check() counts them: false (and the budget used up) when
// the budget runs out before the last of them, as it would checking them one by one.
bool count_failed(Run& r, uint32_t n) {
  if (r.budget - r.checks < n) {
    r.checks = r.budget;
    return false;
  }
  r.checks += n;
  return true;
}

// True when box `hint` certainly blocks [a, b] at the run's clearance (segment_blocked_by_hint).
bool blocked(const Run& r, const tdo_vec3& a, const tdo_vec3& b, uint32_t hint) {
  return tdo_internal::segment_blocked_by_hint(r.grid, a, b, r.clearance, hint) != 0;
}

// One forward sweep; returns false when the budget ran out.
// Known failures are not checked again (they are counted): the end points p whose chord from w_i
// one box certainly blocks form a convex set, so when that box blocks the chords to p(t) and to
// w_j, every smaller t of the same segment fails; when it blocks the chords to w_j+1 and w_j,
// all of segment j does. Same decisions and the same check count as checking each.
bool shortcut_sweep(Run& r, uint32_t* m_io) {
  tdo_correct* ctx = r.ctx;
  uint32_t m = *m_io;
  bool ok_budget = true;
  constexpr uint32_t kNT = sizeof(kShortT) / sizeof(kShortT[0]);
  // Bounded: i grows every iteration.
  for (uint32_t i = 0; i + 2u < m && ok_budget; ++i) {
    const uint32_t j_max = i + kShortReach < m - 2u ? i + kShortReach : m - 2u;
    bool done = false;
    uint32_t far_box = 0u;  // hint of a box certainly blocking the chord w_i -> w_j+1 (0: none)
    for (uint32_t j = j_max; j > i && !done && ok_budget; --j) {
      const tdo_vec3 a = ctx->pts[j], b = ctx->pts[j + 1u];
      if (far_box != 0u && blocked(r, ctx->pts[i], a, far_box)) {
        ok_budget = count_failed(r, kNT);  // every p(t) lies between w_j and w_j+1
        continue;
      }
      far_box = 0u;
      for (uint32_t ti = 0; ti < kNT; ++ti) {
        const double t = kShortT[ti];
        const tdo_vec3 p = lerp(a, b, t);
        const int ok = check(r, ctx->pts[i], p);
        if (ok < 0) {
          ok_budget = false;
          break;
        }
        if (ok == 0) {
          // Tried once per segment, at its first (largest) t; w_i -> w_i+1 is a verified
          // segment, never blocked.
          if (ti == 0u && j > i + 1u && blocked(r, ctx->pts[i], a, r.hint) &&
              blocked(r, ctx->pts[i], p, r.hint)) {
            far_box = r.hint;  // blocks the chord to w_j, the far end of segment j - 1
            ok_budget = count_failed(r, kNT - ti - 1u);
            break;
          }
          continue;
        }
        if (ok == 1) {
          // w_i+1 .. w_j become the single point p (at index i+1).
          ctx->pts[i + 1u] = p;
          ctx->orig[i + 1u] = kNone;
          m = remove_between(ctx, m, i + 1u, j + 1u);
          done = true;
          break;
        }
      }
    }
  }
  *m_io = m;
  return ok_budget;
}

// One relocation sweep; returns false when the budget ran out.
bool relocate_sweep(Run& r, uint32_t m) {
  tdo_vec3* p = r.ctx->pts;
  for (uint32_t k = 1; k + 1u < m; ++k) {
    const tdo_vec3 a = p[k - 1u], b = p[k], c = p[k + 1u];
    const tdo_vec3 d = sub(c, a), w = sub(b, a);
    const double dd = dot(d, d);
    if (!(dd > 0.0)) continue;
    double t = dot(w, d) / dd;
    t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
    const tdo_vec3 foot = add(a, mul(d, t));
    for (double sf : kRelocS) {
      const tdo_vec3 q = lerp(b, foot, sf);
      const int ok1 = check(r, a, q);
      if (ok1 < 0) return false;
      if (ok1 == 0) continue;
      const int ok2 = check(r, q, c);
      if (ok2 < 0) return false;
      if (ok2 == 1) {
        p[k] = q;
        r.ctx->orig[k] = kNone;
        break;
      }
    }
  }
  return true;
}

// Tightening after the shortcut rounds, one pass over the interior waypoints: a pattern search
// moves each in axis steps of res/4, res/8 and res/16 (at most kTightMoves moves per point, each
// the first direction of the largest step that passes). A move is accepted only when
// - the polyline gets shorter;
// - the turns at the point and its two neighbours do not add up to more (a move that shifts the
//   turning onto the neighbours makes the flight rougher);
// - the room cost of those three corners, the sum of turn / shorter adjacent segment, grows by
//   at most kRoomTol (relative): the smoothing fits each corner's radius into the room its
//   segments leave (smooth.cpp), and integral kappa^2 of such a corner goes as turn / radius;
// - each new segment keeps max(clearance, min(d, clearance + kRoomMargin)), d the exact
//   distance of the segment it replaces: waypoints are pulled tight only where there is room,
//   and a segment never gets closer to the obstacles than the one it replaces.
// A direction whose clearance check failed is not tried again for that point (smaller steps
// towards the same obstacle fail as well, nearly always; skipping them only keeps a point).
// Without the last three rules the search met the length goal on Map2 but hugged the clearance
// and made the smoothing's corners tighter (docs/performance.md, "Why the rest is not met").
constexpr uint32_t kTightMoves = 6u;                     // accepted moves per point at most
constexpr double kTightStep[3] = {0.25, 0.125, 0.0625};  // of res, largest first
constexpr double kRoomMargin = 0.5;  // m beyond the clearance kept where a segment had it
constexpr double kRoomTol = 0.005;   // relative growth of the room cost allowed per move
constexpr double kShorterBy = 1e-9;  // m, a move must shorten the polyline by more

double dist3(const tdo_vec3& a, const tdo_vec3& b) { return norm(sub(b, a)); }

// Turn sum (rad) and room cost (rad/m) of the corners k-1, k, k+1 with p[k] replaced by q;
// false for a zero-length segment there.
bool corner_costs(const tdo_vec3* p, uint32_t m, uint32_t k, const tdo_vec3& q, double* turns,
                  double* room) {
  *turns = 0.0;
  *room = 0.0;
  for (uint32_t j = k - 1u; j <= k + 1u; ++j) {
    if (j == 0u || j + 1u >= m) continue;
    const tdo_vec3& a = j - 1u == k ? q : p[j - 1u];
    const tdo_vec3& b = j == k ? q : p[j];
    const tdo_vec3& c = j + 1u == k ? q : p[j + 1u];
    const double l1 = dist3(a, b), l2 = dist3(b, c);
    if (!(l1 > 0.0) || !(l2 > 0.0)) return false;
    const double th = turn_angle(a, b, c);
    *turns += th;
    *room += th / (l1 < l2 ? l1 : l2);
  }
  return true;
}

// The capped distance of a waypoint (tdo_collision_point_distance), computed when first asked for.
struct EndDist {
  bool known;
  double d;  // m, min(cap, distance of the point) when known
};

double end_distance(const Run& r, EndDist* e, const tdo_vec3& p, double cap) {
  if (!e->known) {
    e->d = tdo_collision_point_distance(r.grid, p, cap);
    e->known = true;
  }
  return e->d;
}

// A margin far above the rounding of the distances of [a, b] (with cap): kMarginRel of the
// coordinates' magnitude.
double margin(const tdo_vec3& a, const tdo_vec3& b, double cap) {
  double mag = 1.0 + cap;
  const double v[6] = {a.x, a.y, a.z, b.x, b.y, b.z};
  for (double x : v) mag = fabs(x) > mag ? fabs(x) : mag;
  return kMarginRel * mag;
}

// tdo_collision_segment_distance(a, b, cap), the same value bit for bit, with a tighter cap when
// one is known to lie above it. The result of a capped distance is min(cap, M), M the minimum of
// the exact distances over the leaves of the segment's pieces (and over its box pieces): a piece
// is dropped only when its bound shows it cannot lower the minimum found, so a smaller cap changes
// which pieces are looked at but not M (cubes_min, boxes_min). So a query with cap w < cap whose
// result is below w has found M = min(cap, M). Tried in turn: w = lo (a lower bound of M, or -1)
// plus the margin, where M nearly always is; w = the smaller end-point distance plus the margin
// (a segment comes as close as its ends); cap itself.
double capped_distance(const Run& r, const tdo_vec3& a, const tdo_vec3& b, EndDist* ea, EndDist* eb,
                       double cap, double lo) {
  const double da = end_distance(r, ea, a, cap), db = end_distance(r, eb, b, cap);
  const double w[2] = {lo, da >= 0.0 && db >= 0.0 ? (da < db ? da : db) : -1.0};
  for (double x : w) {
    if (!(x >= 0.0)) continue;
    const double u = x + margin(a, b, cap);
    if (!(u < cap)) continue;
    const double d = tdo_collision_segment_distance(r.grid, a, b, u);
    if (d >= 0.0 && d < u) return d;
  }
  return tdo_collision_segment_distance(r.grid, a, b, cap);
}

// The clearance a replacement of one of tighten's two current segments must keep, its "keep":
// max(the run's clearance, the segment's capped distance). Its distance is counted as a check
// when first asked for (as the budget sees it); the value is found when a candidate needs it
// (keep_ok), at small clearances only as far as the candidate's answer needs it (keep_bounds).
struct Keep {
  bool counted;  // counted as a check
  bool known;    // v holds the keep
  double v;      // m, the keep when known
  double lo;     // m, a lower bound of the keep when >= 0 (a clearance the segment passed at)
};

// Count the check of a keep's distance; false when the budget ran out.
bool count_distance(Run& r, Keep* k) {
  if (k->counted) return true;
  if (!count_check(r)) return false;
  k->counted = true;
  return true;
}

// Whether the run bounds its keeps (keep_bounds); false where they are compiled out.
bool bounding(const Run& r) {
#if defined(TDO_KEEP_BOUNDS)
  return r.bounds;
#else
  (void)r;
  return false;
#endif
}

// One tightening candidate: the old segment [s0, s1] (keep *k, end distances *e0, *e1) and the
// new segment [n0, n1] that replaces it.
struct Swap {
  const tdo_vec3 &s0, &s1;
  EndDist *e0, *e1;
  const tdo_vec3 &n0, &n1;
};

#if defined(TDO_KEEP_BOUNDS)
// Whether the new segment keeps the keep, decided from bounds of the keep where they suffice: 1
// or 0, else -1 with *at, *ok a clearance the new segment was checked at (or -1) and its answer.
// The check answers "every leaf of the segment and every cube (box) has squared distance
// d2 >= c * c and > 0" (tdo_collision_segment_clear, exact); rounding is monotone, so the answer
// is monotone in c, and a pass at c says that the capped distance (the minimum over the same
// leaves of sqrt(d2)) is at least min(cap, c). A leaf holding an end point evaluates that point
// exactly (segment_box_d2), so the capped distance is at most each end point's capped distance,
// and the keep at most u = max(clearance, min(e0, e1)).
// - u is the clearance: so is the keep.
// - Without a lower bound, the new segment is checked at u first: clear there, clear at the keep.
// - With one, a new segment failing there fails; passing, a surface cube the old segment comes
//   no nearer than lo to (segment_cube_distance) puts the keep at lo.
int keep_bounds(Run& r, Keep* k, const Swap& s, double cap, double* at, bool* ok) {
  const double d0 = end_distance(r, s.e0, s.s0, cap), d1 = end_distance(r, s.e1, s.s1, cap);
  if (d0 >= 0.0 && d1 >= 0.0) {
    const double m = d0 < d1 ? d0 : d1;
    if (!(m > r.clearance)) {
      k->known = true;
      k->v = r.clearance;
      return clear_at(r, s.n0, s.n1, k->v) ? 1 : 0;
    }
    if (!(k->lo >= 0.0)) {
      if (clear_at(r, s.n0, s.n1, m)) return 1;
      *at = m;
      return -1;
    }
  }
  if (!(k->lo >= 0.0)) return -1;
  if (!clear_at(r, s.n0, s.n1, k->lo)) return 0;
  *at = k->lo;
  *ok = true;
  // The cube of the last failed check, nearly always the one the old segment wraps.
  const double w = k->lo + margin(s.s0, s.s1, cap);
  const double dc =
      r.cube != 0u ? tdo_internal::segment_cube_distance(r.grid, s.s0, s.s1, r.cube - 1u, w) : -1.0;
  if (!(dc >= 0.0) || dc > k->lo) return -1;
  k->known = true;
  k->v = k->lo;
  return 1;
}
#endif

// Whether the new segment keeps the keep *k of the old one: the answer of checking it at the
// keep. Where the bounds did not decide it, the keep comes from the capped distance (tried first
// with the lower bound as its cap, which nearly always holds it), and the new segment is checked
// at it unless it was checked there already.
int keep_ok(Run& r, Keep* k, const Swap& s, double cap) {
  if (!k->known) {
    double at = -1.0;  // a clearance the new segment was checked at
    bool ok = false;   // its answer there
#if defined(TDO_KEEP_BOUNDS)
    if (bounding(r)) {
      const int b = keep_bounds(r, k, s, cap, &at, &ok);
      if (b >= 0) return b;
    }
#endif
    const double lo = bounding(r) ? k->lo : -1.0;
    const double d = capped_distance(r, s.s0, s.s1, s.e0, s.e1, cap, lo);
    k->v = d > r.clearance ? d : r.clearance;
    k->known = true;
    if (at >= 0.0 && !(k->v < at) && !(k->v > at)) return ok ? 1 : 0;  // checked there already
  }
  return clear_at(r, s.n0, s.n1, k->v) ? 1 : 0;
}

// The keep of a new segment that passed at the keep v of the old one (with the bounds; else not
// asked for): at least v (the pass, v <= cap), and at most the capped distance e of the shared
// end point, so known when e <= v (then e = v: the pass bounds e from below too).
Keep keep_after(const Run& r, const EndDist& e, double v) {
  if (!bounding(r)) return Keep{false, false, 0.0, -1.0};
  return Keep{false, e.known && e.d >= 0.0 && !(e.d > v), v, v};
}

// Whether tighten bounds its keeps (keep_bounds): at clearances up to a quarter voxel edge, where
// the end points nearly always bound them; at larger ones they nearly never do, and cost.
bool bounds_pay(const tdo_correct_input* in) {
#if defined(TDO_KEEP_BOUNDS)
  return in->clearance <= 0.25 * tdo_grid_get_desc(in->grid).res;
#else
  (void)in;
  return false;
#endif
}

// The pass; returns false when the budget ran out.
bool tighten(Run& r, uint32_t m) {
  tdo_vec3* p = r.ctx->pts;
  const double res = tdo_grid_get_desc(r.grid).res;
  const double cap = r.clearance + kRoomMargin;
  constexpr Keep kNotAsked{false, false, 0.0, -1.0};
  constexpr EndDist kNoEnd{false, 0.0};
  Keep carried = kNotAsked;  // keep of [p[k-1], p[k]] when already asked for or known
  EndDist ends[3] = {kNoEnd, kNoEnd, kNoEnd};  // distances of p[k-1], p[k], p[k+1] when known
  for (uint32_t k = 1; k + 1u < m; ++k) {
    const tdo_vec3 a = p[k - 1u], c = p[k + 1u];
    Keep d1 = carried, d2 = kNotAsked;  // keeps of the current segments
    carried = kNotAsked;
    if (k > 1u) {  // the window moves on by one point
      ends[0] = ends[1];
      ends[1] = ends[2];
      ends[2] = kNoEnd;
    }
    uint32_t failed = 0u;  // bit per direction whose clearance check failed
    bool moved = true;
    // Bounded: kTightMoves moves, each of at most 3 x 6 candidates.
    for (uint32_t mv = 0; mv < kTightMoves && moved; ++mv) {
      moved = false;
      const tdo_vec3 b = p[k];
      double turns0 = 0.0, room0 = 0.0;
      if (!corner_costs(p, m, k, b, &turns0, &room0)) break;
      const double len0 = dist3(a, b) + dist3(b, c);
      for (double step : kTightStep) {
        const double h = step * res;
        for (uint32_t dir = 0; dir < 6u && !moved; ++dir) {
          if ((failed >> dir & 1u) != 0u) continue;
          tdo_vec3 q = b;
          const double dh = (dir & 1u) != 0u ? -h : h;
          if (dir < 2u)
            q.x += dh;
          else if (dir < 4u)
            q.y += dh;
          else
            q.z += dh;
          if (!(dist3(a, q) + dist3(q, c) < len0 - kShorterBy)) continue;
          double turns = 0.0, room = 0.0;
          if (!corner_costs(p, m, k, q, &turns, &room)) continue;
          if (turns > turns0 || room > room0 * (1.0 + kRoomTol)) continue;
          // The old segments' distances, only for a candidate that got this far.
          if (!count_distance(r, &d1) || !count_distance(r, &d2)) return false;
          // Counted as check_at counts them: one each, the second only after the first passed.
          if (!count_check(r)) return false;
          int ok = keep_ok(r, &d1, Swap{a, b, &ends[0], &ends[1], a, q}, cap);
          if (ok == 1) {
            if (!count_check(r)) return false;
            ok = keep_ok(r, &d2, Swap{b, c, &ends[1], &ends[2], q, c}, cap);
          }
          if (ok == 0) {
            failed |= 1u << dir;
            continue;
          }
          p[k] = q;
          r.ctx->orig[k] = kNone;
          moved = true;
          // Both segments changed; each new one keeps what it passed at.
          d1 = keep_after(r, ends[0], d1.v);
          d2 = keep_after(r, ends[2], d2.v);
          ends[1] = kNoEnd;
        }
        if (moved) break;
      }
    }
    // [p[k], p[k+1]] is the next point's first segment; its keep carries over.
    carried = d2;
  }
  return true;
}

void shorten(Run& r, uint32_t* m_io, uint32_t* critical) {
  tdo_correct* ctx = r.ctx;
  uint32_t m = *m_io;
  // Bounded: kShortRounds rounds of a forward and a backward sweep, fewer when a round changes
  // nothing or the budget runs out.
  bool budget_left = true;
  for (uint32_t round = 0; round < kShortRounds && budget_left && m >= 3u; ++round) {
    uint32_t removed = m;
    budget_left = shortcut_sweep(r, &m);
    if (budget_left && m >= 3u) {
      reverse_pts(ctx, m);
      budget_left = shortcut_sweep(r, &m);
      reverse_pts(ctx, m);
    }
    if (budget_left) budget_left = relocate_sweep(r, m);
    removed -= m;
    if (removed == 0u && round > 0u) break;
  }
  if (budget_left && m >= 3u) (void)tighten(r, m);  // out of budget: keeps what it has
  // Drop points whose neighbours see each other; count the others.
  uint32_t crit = 0;
  uint32_t k = 1;
  // Bounded: each iteration removes a point or advances k.
  while (k + 1u < m) {
    const int ok = check(r, ctx->pts[k - 1u], ctx->pts[k + 1u]);
    if (ok == 1) {
      m = remove_between(ctx, m, k - 1u, k + 1u);
      continue;
    }
    if (ok == 0) ++crit;  // not counted when the budget ran out (removal not checked)
    ++k;
  }
  *critical = crit;
  *m_io = m;
}

}  // namespace

extern "C" size_t tdo_correct_footprint(const tdo_correct_config* cfg) {
  if (cfg == nullptr || cfg->max_points == 0u) return 0;
  const size_t n = cfg->max_points;
  return round16(sizeof(tdo_correct)) + round16(n * sizeof(tdo_vec3)) +
         round16(n * sizeof(uint32_t)) + round16(n * kMemo * sizeof(uint32_t)) + round16(n);
}

extern "C" tdo_status tdo_correct_init(tdo_correct** out, tdo_arena* arena,
                                       const tdo_correct_config* cfg) {
  if (out == nullptr || arena == nullptr || tdo_correct_footprint(cfg) == 0)
    return TDO_ERR_INVALID_ARGUMENT;
  *out = nullptr;
  const size_t n = cfg->max_points;
  tdo_correct* ctx = arena_context<tdo_correct>(arena, *cfg);
  if (ctx == nullptr) return TDO_ERR_ARENA_TOO_SMALL;
  ctx->pts = arena_array<tdo_vec3>(arena, n);
  ctx->orig = arena_array<uint32_t>(arena, n);
  ctx->memo = arena_array<uint32_t>(arena, n * kMemo);
  ctx->memo_at = arena_array<uint8_t>(arena, n);
  if (ctx->pts == nullptr || ctx->orig == nullptr || ctx->memo == nullptr ||
      ctx->memo_at == nullptr)
    return TDO_ERR_ARENA_TOO_SMALL;
  *out = ctx;
  return TDO_OK;
}

extern "C" tdo_status tdo_correct_run(tdo_correct* ctx, const tdo_correct_input* in,
                                      tdo_correct_output* out) {
  if (ctx == nullptr || in == nullptr || out == nullptr) return TDO_ERR_INVALID_ARGUMENT;
  memset(out, 0, sizeof(*out));
  if (in->grid == nullptr || in->points == nullptr || in->n_points < 2u ||
      !isfinite(in->clearance) || in->clearance < 0.0 || !isfinite(in->turn_threshold) ||
      in->turn_threshold < 0.0 ||
      (in->mode != TDO_CORRECT_MULTISCALE && in->mode != TDO_CORRECT_GREEDY_LOS &&
       in->mode != TDO_CORRECT_NONE) ||
      (in->steps_proven != 0 && in->steps_proven != 1))
    return TDO_ERR_INVALID_ARGUMENT;
  if (tdo_grid_clearance(in->grid) < 0.0) return TDO_ERR_MAP_NOT_READY;
  if (in->n_points > ctx->cfg.max_points) return TDO_ERR_PATH_CAPACITY;
  const uint32_t n = in->n_points;
  for (uint32_t i = 0; i < n; ++i)
    if (!finite3(in->points[i])) return TDO_ERR_INVALID_ARGUMENT;

  // max_checks 0: no budget beyond the stage's own bound (like the search's max_expansions).
  Run r{ctx,
        in->grid,
        in->clearance,
        0u,
        ctx->cfg.max_checks != 0u ? ctx->cfg.max_checks : 0xFFFFFFFFu,
        0u,
        0u,
        in->steps_proven && n >= 3u ? n - 2u : 0u,
        bounds_pay(in)};
  // 1. The input itself must keep clearance.
  tdo_status st = verify_input(r, in->points, n);
  uint32_t m = 0, critical = 0;
  if (st == TDO_OK) {
    for (uint32_t i = 0; i < n; ++i) {
      ctx->pts[i] = in->points[i];
      ctx->orig[i] = i;
    }
    for (size_t k = 0; k < static_cast<size_t>(n) * kMemo; ++k) ctx->memo[k] = kNone;
    // 2. Collinear and repeated points.
    st = drop_collinear(r, n, &m);
    for (uint32_t i = 0; i < n; ++i) ctx->memo_at[i] = 0;  // the memo's ring positions
  }
  // 3. The variant.
  if (st == TDO_OK && in->mode == TDO_CORRECT_MULTISCALE) {
    st = multiscale(r, &m, in->turn_threshold, &critical);
    if (st == TDO_OK && in->shorten) shorten(r, &m, &critical);
  } else if (st == TDO_OK && in->mode == TDO_CORRECT_GREEDY_LOS)
    st = greedy(r, &m, &critical);
  out->checks = r.checks;
  if (st != TDO_OK) return st;
  out->waypoints = ctx->pts;
  out->n_waypoints = m;
  out->n_safety_critical = critical;
  return TDO_OK;
}
