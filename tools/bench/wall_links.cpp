// The walls bound of tdo-turn-bound (wall_links.h).
#include "wall_links.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

namespace tdo_bench {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Slack of the feasibility test: a system counts as feasible when its worst violation is at most
// this (m). Erring towards feasible can only lower the bound.
constexpr double kSlack = 1e-6;
// Slopes dv/du tried beyond every breakpoint (the convex gap function is piecewise linear).
constexpr double kFarSlope = 1e6;
// Share of the map's width a group of full-height pieces must block to count as a wall.
constexpr double kMinCover = 0.5;

double coord(const tdo_vec3& p, int axis) { return axis == 0 ? p.x : axis == 1 ? p.y : p.z; }

/** lo <= p + q u <= hi (lo may be -inf, hi +inf). */
struct Cons {
  double u;
  double lo;
  double hi;
};

/**
 * Is there a line v = p + q u meeting every constraint? For a fixed slope q the feasible p form
 * the interval [max(lo - q u), min(hi - q u)]; its emptiness gap(q) = max - min is convex and
 * piecewise linear in q, so its minimum lies at a crossing of two of the lines or beyond all of
 * them.
 */
bool feasible(const std::vector<Cons>& cs) {
  std::vector<std::pair<double, double>> low, high;  // (u, bound)
  for (const Cons& c : cs) {
    if (std::isfinite(c.lo)) low.emplace_back(c.u, c.lo);
    if (std::isfinite(c.hi)) high.emplace_back(c.u, c.hi);
  }
  if (low.empty() || high.empty()) return true;
  const auto gap = [&](double q) {
    double mx = -kInf, mn = kInf;
    for (const auto& l : low) mx = std::max(mx, l.second - q * l.first);
    for (const auto& h : high) mn = std::min(mn, h.second - q * h.first);
    return mx - mn;
  };
  if (gap(kFarSlope) <= kSlack || gap(-kFarSlope) <= kSlack) return true;
  std::vector<std::pair<double, double>> all = low;
  all.insert(all.end(), high.begin(), high.end());
  for (size_t a = 0; a < all.size(); ++a)
    for (size_t b = a + 1; b < all.size(); ++b) {
      const double du = all[a].first - all[b].first;
      if (!(du < 0.0 || du > 0.0)) continue;  // parallel lines: no crossing
      const double q = (all[a].second - all[b].second) / du;
      if (gap(q) <= kSlack) return true;
    }
  return false;
}

/** Items of the chain: 0 = start point, 1..n = bands, n + 1 = goal point. */
struct Problem {
  double us, vs, ug, vg;  // m, start and goal in the (u, v) frame
  std::vector<WallBand> bands;
  int items() const { return static_cast<int>(bands.size()) + 2; }
};

/** The alternatives of one item: each a set of constraints, any one of which may hold. */
std::vector<std::vector<Cons>> options(const Problem& pr, int k, bool partial) {
  if (k == 0) return {{{pr.us, pr.vs, pr.vs}}};
  if (k == pr.items() - 1) return {{{pr.ug, pr.vg, pr.vg}}};
  const WallBand& b = pr.bands[static_cast<size_t>(k - 1)];
  std::vector<std::vector<Cons>> out;
  for (const WallWindow& w : b.windows) {
    if (!partial) {  // crossed whole: inside the window at both band edges
      out.push_back({{b.u_lo, w.lo, w.hi}, {b.u_hi, w.lo, w.hi}});
      continue;
    }
    // Meets the window somewhere in the band: at one of its edges, or crossing it from one side
    // to the other in between (a linear function that is out on the same side at both edges
    // stays out).
    out.push_back({{b.u_lo, w.lo, w.hi}});
    out.push_back({{b.u_hi, w.lo, w.hi}});
    if (std::isfinite(w.lo) && std::isfinite(w.hi)) {
      out.push_back({{b.u_lo, -kInf, w.lo}, {b.u_hi, w.hi, kInf}});
      out.push_back({{b.u_lo, w.hi, kInf}, {b.u_hi, -kInf, w.lo}});
    }
  }
  return out;
}

/** Depth-first over the items' alternatives. A span whose alternatives outnumber the budget
 *  counts as possible (which only weakens the bound). */
bool any_line(const std::vector<std::vector<std::vector<Cons>>>& opts, size_t k,
              std::vector<Cons>* acc) {
  if (k == opts.size()) return feasible(*acc);
  for (const std::vector<Cons>& o : opts[k]) {
    const size_t mark = acc->size();
    acc->insert(acc->end(), o.begin(), o.end());
    const bool ok = any_line(opts, k + 1, acc);
    acc->resize(mark);
    if (ok) return true;
  }
  return false;
}

constexpr double kMaxAlternatives = 1e5;  // line systems tried per span at most

/** Can one segment touch items i..j, with partial (1) or whole (0) crossings at the ends? */
bool span(const Problem& pr, int i, int j, int pi, int pj) {
  if (i == j) return true;
  std::vector<std::vector<std::vector<Cons>>> opts;
  double count = 1.0;
  for (int k = i; k <= j; ++k) {
    opts.push_back(options(pr, k, (k == i && pi == 1) || (k == j && pj == 1)));
    count *= static_cast<double>(opts.back().size());
  }
  if (count > kMaxAlternatives) return true;
  std::vector<Cons> acc;
  return any_line(opts, 0, &acc);
}

int fewest_segments(const Problem& pr) {
  const int n = pr.items();
  // ok[i][j][pi][pj]; a span is only tried when its two sub-spans one item shorter are possible
  // (the inner item then is crossed whole, which is the stronger condition).
  std::vector<int> ok(static_cast<size_t>(n * n * 4), 0);
  const auto at = [n](int i, int j, int pi, int pj) {
    return static_cast<size_t>(((i * n + j) * 2 + pi) * 2 + pj);
  };
  for (int len = 0; len < n; ++len)
    for (int i = 0; i + len < n; ++i) {
      const int j = i + len;
      for (int pi = 0; pi < 2; ++pi)
        for (int pj = 0; pj < 2; ++pj) {
          const bool sub = len < 2 || (ok[at(i, j - 1, pi, 0)] && ok[at(i + 1, j, 0, pj)]);
          ok[at(i, j, pi, pj)] = sub && span(pr, i, j, pi, pj) ? 1 : 0;
        }
    }
  // best[j][p]: fewest segments of a chain from the start whose last run ends at item j, with
  // the vertex inside band j (p = 1) or beyond it (p = 0). The next run starts at j (p = 1,
  // sharing the vertex) or at j + 1 crossed whole (p = 0).
  const int kBig = 1 << 20;
  std::vector<int> best(static_cast<size_t>(n * 2), kBig);
  for (int j = 0; j < n; ++j)
    for (int p = 1; p >= 0; --p) {
      int b = kBig;
      for (int i = 0; i <= j; ++i)
        for (int q = 0; q < 2; ++q) {
          if (!ok[at(i, j, q, p)]) continue;
          int prev;
          if (i == 0) {
            prev = 0;
          } else if (q == 0) {
            prev = best[static_cast<size_t>((i - 1) * 2)];
          } else if (i < j || p == 0) {  // i == j, p == 0: out of band j after reaching it
            prev = best[static_cast<size_t>(i * 2 + 1)];
          } else {
            continue;
          }
          b = std::min(b, prev + 1);
        }
      best[static_cast<size_t>(j * 2 + p)] = b;
    }
  return std::min(best[static_cast<size_t>((n - 1) * 2)],
                  best[static_cast<size_t>((n - 1) * 2 + 1)]);
}

/** The bands crossing `axis` (0 = x, 1 = y) between start and goal. */
Problem bands_across(const tdo_io::Map& map, int axis, double clearance) {
  const tdo_grid_desc& d = map.desc;
  const int across = 1 - axis;
  const double z_lo = d.origin.z, z_hi = d.origin.z + d.nz * d.res;
  const double v_lo = coord(d.origin, across);
  const double v_hi = v_lo + (across == 0 ? d.nx : d.ny) * d.res;
  const double sa = coord(map.start, axis), ga = coord(map.goal, axis);
  const double sign = sa <= ga ? 1.0 : -1.0;
  Problem pr{sign * sa, coord(map.start, across), sign * ga, coord(map.goal, across), {}};
  // Full-height pieces grouped by their extent along the axis.
  std::map<std::pair<double, double>, std::vector<std::pair<double, double>>> groups;
  for (const tdo_box& b : map.boxes)
    if (b.min.z <= z_lo && b.max.z >= z_hi)
      groups[{coord(b.min, axis), coord(b.max, axis)}].emplace_back(coord(b.min, across),
                                                                    coord(b.max, across));
  for (auto& g : groups) {
    double u0 = sign * g.first.first, u1 = sign * g.first.second;
    if (u0 > u1) std::swap(u0, u1);
    if (!(u0 > pr.us && u1 < pr.ug)) continue;  // not strictly between start and goal
    std::vector<std::pair<double, double>>& pieces = g.second;
    std::sort(pieces.begin(), pieces.end());
    WallBand band{u0, u1, {}};
    double v = v_lo;  // free from here on, up to the next piece
    bool open_side = true;
    for (const auto& piece : pieces) {
      if (piece.first > v) {
        const WallWindow w{open_side ? -kInf : v + clearance, piece.first - clearance};
        if (w.lo <= w.hi) band.windows.push_back(w);
      }
      if (piece.second > v) {
        v = piece.second;
        open_side = false;
      }
    }
    if (v < v_hi) {
      const WallWindow w{open_side ? -kInf : v + clearance, kInf};
      band.windows.push_back(w);
    }
    if (band.windows.empty()) continue;  // closed: no path at all, not this bound's business
    // A wall, not a row of pillars: its pieces cover at least kMinCover of the map's width.
    double covered = 0.0, reach = v_lo;
    for (const auto& piece : pieces) {
      const double a = std::max(piece.first, reach), b = std::min(piece.second, v_hi);
      if (b > a) covered += b - a;
      reach = std::max(reach, piece.second);
    }
    if (covered < kMinCover * (v_hi - v_lo)) continue;
    pr.bands.push_back(band);
  }
  std::sort(pr.bands.begin(), pr.bands.end(),
            [](const WallBand& a, const WallBand& b) { return a.u_lo < b.u_lo; });
  // Keep bands disjoint (dropping a band only weakens the bound).
  std::vector<WallBand> kept;
  for (const WallBand& b : pr.bands)
    if (kept.empty() || b.u_lo > kept.back().u_hi) kept.push_back(b);
  pr.bands = kept;
  return pr;
}

}  // namespace

WallLinks wall_links(const tdo_io::Map& map, double clearance) {
  WallLinks best;
  for (int axis = 0; axis < 2; ++axis) {
    const Problem pr = bands_across(map, axis, clearance);
    if (pr.bands.empty()) continue;
    const int s = fewest_segments(pr);
    if (best.axis < 0 || s > best.segments) {
      best.axis = axis;
      best.bands = pr.bands;
      best.segments = s;
    }
  }
  return best;
}

}  // namespace tdo_bench
