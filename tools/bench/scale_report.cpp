// Tables and goals of tdo-bench-scale. See scale_report.h.
#include "scale_report.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>

namespace tdo_bench {
namespace {

constexpr double kCostTolerance = 1e-6;  // m, A* against textbook A* costs

// Median (mean of the middle two) and nearest-rank p90 of a non-empty list.
double median_of(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
double p90_of(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t r = static_cast<size_t>(std::ceil(0.9 * static_cast<double>(v.size())));
  return v[r > 0 ? r - 1 : 0];
}

// Queries every path planner that ran (tdo, astar, rrtconnect-simplify) solved.
std::vector<bool> common_queries(const WorkloadRecord& w) {
  std::vector<bool> c(w.labels.size(), true);
  for (size_t i = 0; i < c.size(); ++i)
    for (int p = kScaleTdo; p <= kScaleRrt; ++p)
      if (w.p[p].q[i].ran && !w.p[p].q[i].ok) c[i] = false;
  return c;
}

const WorkloadRecord* find(const std::vector<WorkloadRecord>& ws, const std::string& name) {
  for (const WorkloadRecord& w : ws)
    if (w.name == name) return &w;
  return nullptr;
}

const char* verdict(bool met) { return met ? "met" : "NOT met"; }

void goal_movingai(const WorkloadRecord& w) {
  const Summary t = summarize(w, kScaleTdo);
  const Summary a = summarize(w, kScaleAstar);
  const std::string note =
      t.n == 1000 ? "" : " (" + std::to_string(t.n) + " queries; the goal is stated for 1000)";
  std::printf("goal %s: tdo median %.3f ms <= 3 x astar median %.3f ms (ratio %.2f): %s%s\n",
              w.name.c_str(), t.median, a.median, t.median / a.median,
              verdict(t.median <= 3.0 * a.median), note.c_str());
  std::printf("goal %s: tdo mean %.3f ms <= 3 x astar mean %.3f ms (ratio %.2f): %s%s\n",
              w.name.c_str(), t.mean, a.mean, t.mean / a.mean, verdict(t.mean <= 3.0 * a.mean),
              note.c_str());
  const double ta = static_cast<double>(w.p[kScaleTdo].setup.arena_bytes);
  const double aa = static_cast<double>(w.p[kScaleAstar].setup.arena_bytes);
  std::printf("goal %s: tdo arena %.0f bytes <= 1.25 x astar arena %.0f bytes (ratio %.2f): %s\n",
              w.name.c_str(), ta, aa, ta / aa, verdict(ta <= 1.25 * aa));
}

void goal_geb079(const WorkloadRecord& w) {
  const Summary t = summarize(w, kScaleTdo);
  const bool all = t.ratio_n == t.n && t.n > 0;  // every query has a ratio
  const std::string of = " over " + std::to_string(t.ratio_n) + " of " + std::to_string(t.n) +
                         " queries" + (all ? "" : ", tdo or astar failed the others");
  std::printf("goal geb079: median per-query time ratio tdo/astar %.2f <= 1%s: %s\n",
              t.ratio_median, of.c_str(), verdict(all && t.ratio_median <= 1.0));
  std::printf("goal geb079: max per-query time ratio tdo/astar %.2f <= 2%s: %s\n", t.ratio_max,
              of.c_str(), verdict(all && t.ratio_max <= 2.0));
  bool met = true;
  std::string per;
  for (size_t i = 0; i < w.labels.size(); ++i) {
    const ScaleOutcome& a = w.p[kScaleAstar].q[i];
    const ScaleOutcome& d = w.p[kScaleTdo].q[i];
    char buf[96];
    if (!a.ok || !d.ok) {
      std::snprintf(buf, sizeof buf, " %s failed,", w.labels[i].c_str());
      met = false;
    } else {
      std::snprintf(buf, sizeof buf, " %s %.3f/%.3f,", w.labels[i].c_str(), d.length, a.length);
      met = met && d.length <= a.length;
    }
    per += buf;
  }
  if (!per.empty()) per.pop_back();
  std::printf("goal geb079: tdo length <= astar grid length on every query (tdo/astar m:%s): %s\n",
              per.c_str(), verdict(met && !w.labels.empty()));
}

void goal_forest(const WorkloadRecord& w) {
  const Summary t = summarize(w, kScaleTdo);
  const Summary a = summarize(w, kScaleAstar);
  const Summary r = summarize(w, kScaleRrt);
  if (!r.ran) {
    std::printf("goal forest: not evaluated, rrtconnect-simplify did not run\n");
    return;
  }
  std::printf("goal forest: tdo median %.3f ms <= rrtconnect-simplify median %.3f ms: %s\n",
              t.median, r.median, verdict(t.median <= r.median));
  std::printf("goal forest: tdo p90 %.3f ms <= rrtconnect-simplify p90 %.3f ms: %s\n", t.p90, r.p90,
              verdict(t.p90 <= r.p90));
  std::printf(
      "goal forest: tdo total turns %llu <= 0.7 x rrtconnect-simplify's %llu (ratio %.3f, %zu "
      "common queries): %s\n",
      t.turns_total, r.turns_total,
      r.turns_total > 0 ? static_cast<double>(t.turns_total) / static_cast<double>(r.turns_total)
                        : 0.0,
      t.common, verdict(10ull * t.turns_total <= 7ull * r.turns_total));
  std::printf(
      "goal forest: tdo total length %.3f m <= astar total length %.3f m (ratio %.4f): %s\n",
      t.length_total, a.length_total, t.length_total / a.length_total,
      verdict(t.length_total <= a.length_total));
}

// Map1-5 against today's tdo row of docs/results.md (Table 6/7, tdo-bench at clearance 0.5 m):
// turns and length no worse, plan time at most today's. Lengths there are rounded to 0.01 m; the
// time is from another tool and run, so its verdict is context, not a same-run ratio.
void goal_map(const WorkloadRecord& w) {
  struct Today {
    const char* map;
    uint32_t turns;
    double length_m;
    double time_ms;
  };
  static const Today kToday[] = {{"map1", 3, 32.98, 1.8},
                                 {"map2", 4, 32.64, 1.7},
                                 {"map3", 7, 33.64, 2.1},
                                 {"map4", 19, 111.57, 6.3},
                                 {"map5", 5, 76.51, 2.1}};
  for (const Today& t : kToday) {
    if (w.name != t.map || w.labels.empty()) continue;
    const ScaleOutcome& o = w.p[kScaleTdo].q[0];
    if (!o.ok) {
      std::printf("goal %s: tdo failed (%s): NOT met\n", t.map, o.status.c_str());
      return;
    }
    std::printf(
        "goal %s: tdo turns %u <= %u and length %.3f m <= %.2f m (docs/results.md): %s; plan "
        "time %.3f ms <= %.1f ms (absolute, other run): %s\n",
        t.map, o.turns, t.turns, o.length, t.length_m,
        verdict(o.turns <= t.turns && o.length <= t.length_m + 0.005), o.ms, t.time_ms,
        verdict(o.ms <= t.time_ms));
  }
}

// Completeness and the textbook check on one workload; false when either fails.
bool checks(const WorkloadRecord& w) {
  bool good = true;
  for (int p : {kScaleTdo, kScaleRrt}) {
    const Summary s = summarize(w, p);
    if (!s.ran) continue;
    const Summary a = summarize(w, kScaleAstar);
    if (s.missed == 0)
      std::printf("check %s %s: solved every query astar solved (%zu)\n", w.name.c_str(),
                  scale_planner_name(p), a.ok);
    else
      std::printf("check %s %s: MISSED %zu of the %zu queries astar solved\n", w.name.c_str(),
                  scale_planner_name(p), s.missed, a.ok);
    if (p == kScaleTdo && s.missed > 0) good = false;
  }
  size_t both = 0, differ = 0, one = 0;
  for (size_t i = 0; i < w.labels.size(); ++i) {
    const ScaleOutcome& a = w.p[kScaleAstar].q[i];
    const ScaleOutcome& t = w.p[kScaleTextbook].q[i];
    if (a.ok != t.ok) ++one;
    if (!a.ok || !t.ok) continue;
    ++both;
    if (std::fabs(a.cost - t.cost) > kCostTolerance) ++differ;
  }
  std::printf("check %s astar: cost equals textbook-astar's on %zu of %zu queries both solved%s\n",
              w.name.c_str(), both - differ, both,
              one > 0 ? (", " + std::to_string(one) + " solved by one of them only").c_str() : "");
  return good && differ == 0;
}

// Why planners failed: per workload and planner, each status with its count and first queries.
void print_failures(const std::vector<WorkloadRecord>& ws) {
  constexpr size_t kShown = 3;  // query labels listed per status
  std::printf("\n");
  size_t lines = 0;
  for (const WorkloadRecord& w : ws)
    for (int p = 0; p < kScalePlanners; ++p) {
      std::map<std::string, std::pair<size_t, std::string>> by_status;
      for (size_t i = 0; i < w.labels.size(); ++i) {
        const ScaleOutcome& o = w.p[p].q[i];
        if (!o.ran || o.ok) continue;
        auto& e = by_status[o.status];
        if (++e.first <= kShown) e.second += (e.first > 1 ? ", " : "") + w.labels[i];
      }
      for (const auto& kv : by_status) {
        std::printf("failures %s %s: %s on %zu queries (%s%s)\n", w.name.c_str(),
                    scale_planner_name(p), kv.first.c_str(), kv.second.first,
                    kv.second.second.c_str(), kv.second.first > kShown ? ", ..." : "");
        ++lines;
      }
    }
  if (lines == 0) std::printf("failures: none\n");
}

// Per-query rows of the workloads with few queries (geb079, Map1-5).
void print_per_query(const std::vector<WorkloadRecord>& ws) {
  constexpr size_t kMaxRows = 10;
  std::printf(
      "\n| workload | query | tdo ms | astar ms | tdo/astar | rrtconnect-simplify ms | turns "
      "tdo/astar/rrt | length m tdo/astar/rrt |\n|---|---|---:|---:|---:|---:|---|---|\n");
  for (const WorkloadRecord& w : ws) {
    if (w.labels.size() > kMaxRows) continue;
    for (size_t i = 0; i < w.labels.size(); ++i) {
      const ScaleOutcome& t = w.p[kScaleTdo].q[i];
      const ScaleOutcome& a = w.p[kScaleAstar].q[i];
      const ScaleOutcome& r = w.p[kScaleRrt].q[i];
      char rms[32] = "-", rturns[32] = "-", rlen[32] = "-";
      if (r.ran) std::snprintf(rms, sizeof rms, "%.3f", r.ms);
      if (r.ok) std::snprintf(rturns, sizeof rturns, "%u", r.turns);
      if (r.ok) std::snprintf(rlen, sizeof rlen, "%.3f", r.length);
      std::printf("| %s | %s | %.3f%s | %.3f%s | %.2f | %s%s | %u/%u/%s | %.3f/%.3f/%s |\n",
                  w.name.c_str(), w.labels[i].c_str(), t.ms, t.ok ? "" : " (failed)", a.ms,
                  a.ok ? "" : " (failed)", a.ms > 0.0 ? t.ms / a.ms : 0.0, rms,
                  r.ran && !r.ok ? " (failed)" : "", t.turns, a.turns, rturns, t.length, a.length,
                  rlen);
    }
  }
}

}  // namespace

Summary summarize(const WorkloadRecord& w, int p) {
  Summary s;
  const std::vector<bool> common = common_queries(w);
  std::vector<double> ms, ratios, turns;
  for (size_t i = 0; i < w.labels.size(); ++i) {
    const ScaleOutcome& o = w.p[p].q[i];
    const ScaleOutcome& a = w.p[kScaleAstar].q[i];
    if (!o.ran) continue;
    ms.push_back(o.ms);
    if (o.ok) ++s.ok;
    if (o.status == "ok_infeasible") ++s.infeasible;
    if (a.ok && !o.ok) ++s.missed;
    if (a.ok && o.ok && a.ms > 0.0) ratios.push_back(o.ms / a.ms);
    if (common[i] && p != kScaleTextbook) {
      ++s.common;
      s.turns_total += o.turns;
      s.length_total += o.length;
      turns.push_back(o.turns);
    }
  }
  s.n = ms.size();
  s.ran = s.n > 0;
  if (!s.ran) return s;
  s.median = median_of(ms);
  s.p90 = p90_of(ms);
  for (double x : ms) s.mean += x;
  s.mean /= static_cast<double>(ms.size());
  s.ratio_n = ratios.size();
  if (!ratios.empty()) {
    s.ratio_median = median_of(ratios);
    s.ratio_max = *std::max_element(ratios.begin(), ratios.end());
  }
  if (!turns.empty()) s.turns_median = median_of(turns);
  return s;
}

void print_tables(const std::vector<WorkloadRecord>& ws) {
  std::printf(
      "| workload | planner | ok | median ms | mean ms | p90 ms | ratio to astar median | "
      "ratio max | turns total | turns median | length total m | arena bytes | setup RSS MB "
      "|\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const WorkloadRecord& w : ws)
    for (int p = 0; p < kScalePlanners; ++p) {
      const Summary s = summarize(w, p);
      const PlannerRecord& r = w.p[p];
      if (!s.ran) {
        std::printf("| %s | %s | - | - | - | - | - | - | - | - | - | - | - |\n", w.name.c_str(),
                    scale_planner_name(p));
        continue;
      }
      char arena[32] = "-";
      if (r.setup.arena_bytes > 0) std::snprintf(arena, sizeof arena, "%zu", r.setup.arena_bytes);
      if (p == kScaleTextbook) {
        std::printf(
            "| %s | %s | %zu/%zu | %.3f | %.3f | %.3f | %.2f | %.2f | - | - | - | - "
            "| %.1f |\n",
            w.name.c_str(), scale_planner_name(p), s.ok, s.n, s.median, s.mean, s.p90,
            s.ratio_median, s.ratio_max, r.setup.rss_mb);
        continue;
      }
      char rss[32] = "-";  // RRTConnect has no set-up of its own (astar's Environment)
      if (p != kScaleRrt) std::snprintf(rss, sizeof rss, "%.1f", r.setup.rss_mb);
      std::printf(
          "| %s | %s | %zu/%zu | %.3f | %.3f | %.3f | %.2f | %.2f | %llu | %.1f | %.3f | %s | %s "
          "|\n",
          w.name.c_str(), scale_planner_name(p), s.ok, s.n, s.median, s.mean, s.p90, s.ratio_median,
          s.ratio_max, s.turns_total, s.turns_median, s.length_total, arena, rss);
    }
  std::printf(
      "\n| workload | queries | common | tdo ok_infeasible | load_map ms | tdo set-up ms | astar "
      "set-up ms | RSS at start MB | peak RSS MB "
      "|\n|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const WorkloadRecord& w : ws) {
    const Summary t = summarize(w, kScaleTdo);
    std::printf("| %s | %zu | %zu | %zu | %.1f | %.1f | %.1f | %.1f | %.1f%s |\n", w.name.c_str(),
                w.labels.size(), t.common, t.infeasible, w.load_ms, w.p[kScaleTdo].setup.ms,
                w.p[kScaleAstar].setup.ms, w.start_rss_mb, w.peak_rss_mb,
                w.peak_reset ? "" : " (process)");
  }
  print_per_query(ws);
  print_failures(ws);
}

bool print_goals(const std::vector<WorkloadRecord>& ws) {
  std::printf("\ngoals\n");
  for (const char* name : {"simple", "complex"})
    if (const WorkloadRecord* w = find(ws, name)) goal_movingai(*w);
  if (const WorkloadRecord* w = find(ws, "geb079")) goal_geb079(*w);
  if (const WorkloadRecord* w = find(ws, "forest")) goal_forest(*w);
  for (const WorkloadRecord& w : ws) goal_map(w);
  bool good = true;
  for (const WorkloadRecord& w : ws) good = checks(w) && good;
  return good;
}

}  // namespace tdo_bench
