// tdo-turn-bound: the fewest turns any path from a map's start to its goal can have while keeping
// the clearance, as far as it can be proved with 0 or 1 turn, or by the walls a path must cross. It
// answers whether issue 3's quality goal (tdo turns <= 10 % of raw A* turns) is reachable at all on
// a map; docs/performance.md.
//
//   tdo-turn-bound [--maps-dir DIR] [--map NAME]... [--clearance M] [--cell M] [--max-cells N]
//
// A 0-turn path is the segment start-goal. A 1-turn path is start-P-goal with P inside the bounds
// (then both segments lie inside the bounds, which are convex). Its clearance is
// c(P) = min(d(start, P), d(P, goal)), d = the exact segment-to-geometry distance of libtdo
// (tdo_collision_segment_distance). c is 1-Lipschitz in P: moving P by e moves every point of
// both segments by at most e. Branch and bound over boxes of turn points: a box with centre P and
// half-diagonal r holds no P' with c(P') >= clearance when c(P) + r < clearance, and is dropped;
// a centre with c(P) >= clearance is a 1-turn path (found); other boxes split in 8 down to --cell.
// Result per map: "0" (the straight segment keeps the clearance), "1" (a witness P), ">= 2"
// (every box dropped: proved), or "undecided" (boxes left at the smallest size or the cell budget
// spent). The last two columns add the walls bound of wall_links.h: a lower bound on the turns of
// any path through full-height walls with doors (Map4), which this branch and bound cannot reach
// beyond ">= 2". Exit status 0, 2 on bad arguments or unreadable maps.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "map_list.h"
#include "tdo/tdo.h"
#include "tdo_io/map_io.h"
#include "wall_links.h"

namespace {

int usage(const char* msg) {
  std::fprintf(stderr, "tdo-turn-bound: error: %s\n", msg);
  std::fprintf(stderr,
               "usage: tdo-turn-bound [--maps-dir DIR] [--map NAME]... [--clearance M] "
               "[--cell M] [--max-cells N]\n");
  return 2;
}

struct Cell {
  tdo_vec3 c;     // m, centre
  tdo_vec3 half;  // m, half-extent per axis
};

enum class Verdict { Zero, One, AtLeastTwo, Undecided };

struct Result {
  Verdict verdict = Verdict::Undecided;
  tdo_vec3 witness{};      // m, the turn point of a 1-turn path
  double best = 0.0;       // m, largest clearance of a 1-turn path seen at a box centre
  uint64_t cells = 0;      // boxes evaluated
  uint64_t undecided = 0;  // boxes left at the smallest size
};

double norm(const tdo_vec3& v) { return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }

Result bound(const tdo_grid* grid, const tdo_grid_desc& d, tdo_vec3 s, tdo_vec3 g, double clearance,
             double cell, uint64_t max_cells) {
  Result r;
  if (tdo_collision_segment_distance(grid, s, g, clearance) >= clearance) {
    r.verdict = Verdict::Zero;
    return r;
  }
  std::vector<Cell> stack;
  const tdo_vec3 half{0.5 * d.nx * d.res, 0.5 * d.ny * d.res, 0.5 * d.nz * d.res};
  stack.push_back({{d.origin.x + half.x, d.origin.y + half.y, d.origin.z + half.z}, half});
  while (!stack.empty()) {
    if (r.cells >= max_cells) return r;  // undecided: budget spent
    const Cell b = stack.back();
    stack.pop_back();
    ++r.cells;
    const double rad = norm(b.half);
    const double cap = clearance + rad;
    const double c = std::fmin(tdo_collision_segment_distance(grid, s, b.c, cap),
                               tdo_collision_segment_distance(grid, b.c, g, cap));
    if (c > r.best) r.best = c;
    // A witness must also pass the exact clearance test (bounds included).
    if (c >= clearance && tdo_collision_segment_clear(grid, s, b.c, clearance) &&
        tdo_collision_segment_clear(grid, b.c, g, clearance)) {
      r.verdict = Verdict::One;
      r.witness = b.c;
      return r;
    }
    if (c + rad < clearance) continue;  // no turn point in this box keeps the clearance
    if (2.0 * std::fmax(b.half.x, std::fmax(b.half.y, b.half.z)) <= cell) {
      ++r.undecided;
      continue;
    }
    const tdo_vec3 q{0.5 * b.half.x, 0.5 * b.half.y, 0.5 * b.half.z};
    for (int k = 0; k < 8; ++k) {
      const tdo_vec3 c8{b.c.x + ((k & 1) ? q.x : -q.x), b.c.y + ((k & 2) ? q.y : -q.y),
                        b.c.z + ((k & 4) ? q.z : -q.z)};
      stack.push_back({c8, q});
    }
  }
  r.verdict = r.undecided == 0 ? Verdict::AtLeastTwo : Verdict::Undecided;
  return r;
}

bool parse_double(const std::string& v, double lo, double hi, double* out) {
  char* end = nullptr;
  const double x = std::strtod(v.c_str(), &end);
  if (end == v.c_str() || *end != '\0' || !std::isfinite(x) || x < lo || x > hi) return false;
  *out = x;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  tdo_bench::MapList maps{TDO_BENCH_PIPELINE_MAPS_DIR, {}};
  double clearance = 0.5;
  double cell = 0.01;
  double max_cells = 2e7;
  const std::string bad =
      maps.parse(argc, argv, [&](const std::string& a, const std::string& v) -> std::string {
        if (a == "--clearance")
          return parse_double(v, 0.0, 1e3, &clearance) ? "" : "--clearance needs a number >= 0";
        if (a == "--cell")
          return parse_double(v, 1e-6, 1e3, &cell) ? "" : "--cell needs a number > 0 (m)";
        if (a == "--max-cells")
          return parse_double(v, 1.0, 1e12, &max_cells) ? "" : "--max-cells needs a count >= 1";
        return "unknown option " + a;
      });
  if (!bad.empty()) return usage(bad.c_str());
  const std::vector<std::string> names = maps.chosen();
  const std::string& dir = maps.dir;

  std::printf("clearance %.3f m, smallest box %.4f m, budget %.0f boxes per map\n\n", clearance,
              cell, max_cells);
  std::printf(
      "| map | fewest turns | boxes | best 1-turn clearance at a box centre m | witness | walls "
      "crossed | walls bound |\n");
  std::printf("|---|---|---:|---:|---|---:|---|\n");
  for (const std::string& name : names) {
    const std::string path =
        name.find('/') != std::string::npos ? name : dir + "/" + name + ".tdomap";
    tdo_io::Map map;
    std::string err;
    if (!tdo_io::load_map(path, &map, &err)) return usage(err.c_str());
    if (!map.has_start || !map.has_goal) return usage((path + ": no start/goal").c_str());
    tdo_planner_config cfg{};
    cfg.cap = tdo_io::capacity_for(map, clearance, 1u, 1u);
    const size_t bytes = tdo_planner_footprint(&cfg);
    std::unique_ptr<unsigned char[]> arena(new unsigned char[bytes]);
    tdo_planner* pl = nullptr;
    if (tdo_planner_init(&pl, arena.get(), bytes, &cfg) != TDO_OK ||
        tdo_io::load_into(map, tdo_planner_grid(pl), clearance) != TDO_OK)
      return usage((path + ": planner set-up failed").c_str());
    const Result r = bound(tdo_planner_grid(pl), map.desc, map.start, map.goal, clearance, cell,
                           static_cast<uint64_t>(max_cells));
    const char* verdict = r.verdict == Verdict::Zero         ? "0"
                          : r.verdict == Verdict::One        ? "1"
                          : r.verdict == Verdict::AtLeastTwo ? ">= 2 (proved)"
                                                             : "undecided";
    char witness[96] = "-";
    if (r.verdict == Verdict::One)
      std::snprintf(witness, sizeof witness, "(%.3f, %.3f, %.3f)", r.witness.x, r.witness.y,
                    r.witness.z);
    char best[32] = "-";
    if (r.verdict != Verdict::Zero) std::snprintf(best, sizeof best, "%.3f", r.best);
    const tdo_bench::WallLinks wl = tdo_bench::wall_links(map, clearance);
    char walls[48] = "-";
    if (wl.axis >= 0) std::snprintf(walls, sizeof walls, ">= %d turns", wl.segments - 1);
    std::printf("| %s | %s | %llu | %s | %s | %zu | %s |\n", name.c_str(), verdict,
                static_cast<unsigned long long>(r.cells), best, witness, wl.bands.size(), walls);
  }
  return 0;
}
