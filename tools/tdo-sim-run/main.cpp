// tdo-sim-run: plan with tdo_planner_plan, fly the dynamic episode in the libtdo simulator with the
// E-APF or classical APF follower, write an episode JSON; or bench many seeded random episodes
// with both followers side by side. Exit 0 done, 1 an episode failed its goal (--check), 2 bad
// input.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "episode.h"
#include "mapgen.h"
#include "online.h"
#include "tdo_samples/samples.h"
#include "tool_cli.h"

namespace {

using tdo_tool::BadInput;
using tdo_tool::kExitBadInput;
using tdo_tool::kExitFailed;
using tdo_tool::kExitOk;

struct RandomSpec {
  std::vector<int> size{20, 20, 10};
  int columns = 25;
  int movers = 6;
  std::vector<double> speed{0.5, 1.5};
  std::vector<double> radius{0.5, 1.0};
};

std::string scratch_dir() {
  const auto d = std::filesystem::temp_directory_path() /
                 ("tdo-sim-run-" + std::to_string(static_cast<long>(::getpid())));
  std::filesystem::create_directories(d);
  return d.string();
}

// Generate the random map of `seed` with tdo_mapgen (movers timed to cross the route) and load it.
tdo_io::Map random_map(const RandomSpec& r, uint64_t seed, const std::string& dir) {
  tdo_mapgen::Params p;
  p.layout = tdo_mapgen::Layout::Columns;
  for (int a = 0; a < 3; ++a) p.size[a] = r.size[static_cast<std::size_t>(a)];
  p.columns = static_cast<uint32_t>(r.columns);
  p.seed = seed;
  p.movers = static_cast<uint32_t>(r.movers);
  for (int i = 0; i < 2; ++i) {
    p.mover_speed_mm[i] =
        static_cast<int32_t>(std::lround(r.speed[static_cast<std::size_t>(i)] * 1000));
    p.mover_radius_mm[i] =
        static_cast<int32_t>(std::lround(r.radius[static_cast<std::size_t>(i)] * 1000));
  }
  const int64_t kM = 10000;  // 0.1 mm per m
  const int64_t s[3] = {2 * kM, 2 * kM, 3 * kM};
  const int64_t g[3] = {(r.size[0] - 1) * kM, (r.size[1] - 1) * kM, (r.size[2] / 2) * kM};
  std::copy(s, s + 3, p.start);
  std::copy(g, g + 3, p.goal);
  const std::string bad = tdo_mapgen::validate(p);
  if (!bad.empty()) throw BadInput{bad};
  tdo_mapgen::Result res;
  std::string err;
  const std::string scratch = dir + "/scratch.tdomap";
  if (!tdo_mapgen::generate(p, scratch, &res, &err)) throw BadInput{"random map: " + err};
  const std::string path = dir + "/episode_" + std::to_string(seed) + ".tdomap";
  {
    std::ofstream f(path);
    f << res.text;
    if (!f) throw BadInput{path + ": cannot write"};
  }
  tdo_io::Map map;
  if (!tdo_io::load_map(path, &map, &err)) throw BadInput{err};
  std::filesystem::remove(path);
  return map;
}

tdo_follower_kind parse_follower(const std::string& s) {
  if (s == "eapf") return TDO_FOLLOWER_EAPF;
  if (s == "apf") return TDO_FOLLOWER_APF;
  throw BadInput{"--follower must be eapf or apf, got '" + s + "'"};
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The outcome counts both tables share; M is tdo_episode::Metrics or tdo_online::Metrics.
struct Outcomes {
  int episodes = 0, planned = 0, success = 0, collisions = 0, coll_mover = 0, coll_static = 0;
  // Count one episode; @return whether it was planned (the caller adds its own figures then).
  template <class M>
  bool count(const M& m) {
    ++episodes;
    if (!m.planned) return false;
    ++planned;
    success += m.success;
    collisions += m.collision;
    coll_mover += m.collision_mover;
    coll_static += m.collision_static;
    return true;
  }
};

struct Agg : Outcomes {
  int lm_episodes = 0, failed = 0;
  long lm_events = 0;
  double min_sep = HUGE_VAL, max_dev = 0.0, max_v = 0.0, max_a = 0.0, max_j = 0.0;
  double min_static = HUGE_VAL;  // m, smallest distance to the static geometry of any episode
  double clearance = 0.0;        // m, the planner's clearance (set by the caller)
  int inside_clearance = 0;      // episodes that came closer than the planner's clearance
  int over_limits = 0;
  long safety_steps = 0, evade_steps = 0;
  int safety_episodes = 0,
      evade_episodes = 0;  // episodes whose executed v, a or j exceeds its limit by more than 1 %
  std::vector<double> mean_dev, max_devs, overhead, seps;
  void add(const tdo_episode::Metrics& m) {
    if (!count(m)) return;
    lm_events += m.lm_events;
    lm_episodes += m.lm_events > 0;
    failed += m.escape_failed;
    min_sep = std::min(min_sep, m.min_mover_sep);
    min_static = std::min(min_static, m.min_static_dist);
    inside_clearance += m.min_static_dist < clearance;
    if (std::isfinite(m.min_mover_sep)) seps.push_back(m.min_mover_sep);
    max_dev = std::max(max_dev, m.max_deviation);
    mean_dev.push_back(m.mean_deviation);
    max_devs.push_back(m.max_deviation);
    if (m.success) overhead.push_back(m.time_overhead);
    max_v = std::max(max_v, m.max_speed);
    max_a = std::max(max_a, m.max_acc);
    max_j = std::max(max_j, m.max_jerk);
    safety_steps += m.safety_steps;
    evade_steps += m.evade_steps;
    safety_episodes += m.safety_steps > 0;
    evade_episodes += m.evade_steps > 0;
    // 1 % for the finite differences, as the feasibility check (docs/design.md s.5).
    over_limits += m.max_speed > 1.01 * m.v_limit || m.max_acc > 1.01 * m.a_limit ||
                   m.max_jerk > 1.01 * m.j_limit;
  }
};

double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

// x printed with printf format `fm`.
std::string num(double x, const char* fm = "%.3f") {
  char b[64];
  std::snprintf(b, sizeof b, fm, x);
  return std::string(b);
}

// One table row: `name`, then f(aggregate) of each column right-aligned in `width` characters.
template <class Cols, class F>
void print_row(const char* name, const Cols& cols, int width, F f) {
  std::printf("%-34s", name);
  for (const auto& c : cols) std::printf(" %*s", width, f(c.second).c_str());
  std::printf("\n");
}

void print_table(const std::vector<std::pair<std::string, Agg>>& cols) {
  auto row = [&](const char* name, auto f) { print_row(name, cols, 14, f); };
  std::printf("%-34s", "");
  for (const auto& c : cols) std::printf(" %14s", c.first.c_str());
  std::printf("\n");
  row("episodes (planned)", [&](const Agg& a) {
    return std::to_string(a.episodes) + " (" + std::to_string(a.planned) + ")";
  });
  row("success rate %",
      [&](const Agg& a) { return num(100.0 * a.success / std::max(a.planned, 1), "%.2f"); });
  row("collisions (mover / static)", [&](const Agg& a) {
    return std::to_string(a.collisions) + " (" + std::to_string(a.coll_mover) + "/" +
           std::to_string(a.coll_static) + ")";
  });
  row("min static distance m", [&](const Agg& a) { return num(a.min_static); });
  row("episodes inside planner clearance",
      [&](const Agg& a) { return std::to_string(a.inside_clearance); });
  row("min mover separation m",
      [&](const Agg& a) { return a.seps.empty() ? std::string("-") : num(a.min_sep); });
  row("median min separation m",
      [&](const Agg& a) { return a.seps.empty() ? std::string("-") : num(median(a.seps)); });
  row("mean deviation m (mean)", [&](const Agg& a) { return num(mean(a.mean_dev)); });
  row("max deviation m (median)", [&](const Agg& a) { return num(median(a.max_devs)); });
  row("max deviation m (max)", [&](const Agg& a) { return num(a.max_dev); });
  row("time overhead s (median)", [&](const Agg& a) { return num(median(a.overhead), "%.2f"); });
  row("local-minimum events", [&](const Agg& a) { return std::to_string(a.lm_events); });
  row("episodes with a local minimum", [&](const Agg& a) { return std::to_string(a.lm_episodes); });
  row("escape failed (named status)", [&](const Agg& a) { return std::to_string(a.failed); });
  row("safety-filter steps (episodes)", [&](const Agg& a) {
    return std::to_string(a.safety_steps) + " (" + std::to_string(a.safety_episodes) + ")";
  });
  row("evasion steps (episodes)", [&](const Agg& a) {
    return std::to_string(a.evade_steps) + " (" + std::to_string(a.evade_episodes) + ")";
  });
  row("executed max speed m/s", [&](const Agg& a) { return num(a.max_v); });
  row("executed max acc m/s^2", [&](const Agg& a) { return num(a.max_a); });
  row("executed max jerk m/s^3", [&](const Agg& a) { return num(a.max_j); });
  row("episodes over a v/a/j limit (1 %)",
      [&](const Agg& a) { return std::to_string(a.over_limits); });
}

// ---- Online episodes (--unknown): hidden columns, sensing, replanning (issue 20) ----

struct OnlineAgg : Outcomes {
  int over_limits = 0, escape_failed = 0;
  long replans = 0, failures = 0, blocked = 0, stuck = 0, mover_conflicts = 0, switches = 0,
       stale = 0, hidden = 0, revealed = 0, mover_replans = 0, mover_skipped = 0;
  double min_static = HUGE_VAL, min_gap = HUGE_VAL, max_v = 0.0, max_a = 0.0, max_j = 0.0;
  std::vector<double> ms, cpu, times;
  std::map<std::string, int> failed;  // failed plans by "takeover:" / "vehicle:" status
  void add(const tdo_online::Metrics& m) {
    for (const std::string& f : m.failure_statuses) ++failed[f];
    hidden += m.hidden;
    if (!count(m)) return;
    escape_failed += m.escape_failed;
    replans += m.replans;
    failures += m.replan_failures;
    blocked += m.triggers_blocked;
    stuck += m.triggers_stuck;
    mover_conflicts += m.mover_conflicts;
    mover_replans += m.mover_replans;
    mover_skipped += m.mover_skipped;
    switches += m.switches;
    stale += m.stale_switches;
    revealed += m.revealed;
    min_static = std::min(min_static, m.min_true_static);
    min_gap = std::min(min_gap, m.min_mover_gap);
    max_v = std::max(max_v, m.max_speed);
    max_a = std::max(max_a, m.max_acc);
    max_j = std::max(max_j, m.max_jerk);
    ms.insert(ms.end(), m.replan_ms.begin(), m.replan_ms.end());
    cpu.insert(cpu.end(), m.replan_cpu_ms.begin(), m.replan_cpu_ms.end());
    if (m.success) times.push_back(m.time);
    over_limits += m.max_speed > 1.01 * m.v_limit || m.max_acc > 1.01 * m.a_limit ||
                   m.max_jerk > 1.01 * m.j_limit;
  }
};

// The q-quantile (nearest rank) of v; 0 for none.
double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const auto r = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
  return v[std::min(v.size() - 1, r > 0 ? r - 1 : 0)];
}

void print_online_table(const std::vector<std::pair<std::string, OnlineAgg>>& cols) {
  auto row = [&](const char* name, auto f) { print_row(name, cols, 16, f); };
  auto n = [](long x) { return std::to_string(x); };
  std::printf("%-34s", "");
  for (const auto& c : cols) std::printf(" %16s", c.first.c_str());
  std::printf("\n");
  row("episodes (first plan ok)",
      [&](const OnlineAgg& a) { return n(a.episodes) + " (" + n(a.planned) + ")"; });
  row("success", [&](const OnlineAgg& a) {
    return n(a.success) + " (" + num(100.0 * a.success / std::max(a.episodes, 1), "%.1f") + " %)";
  });
  row("collisions (mover / static)", [&](const OnlineAgg& a) {
    return n(a.collisions) + " (" + n(a.coll_mover) + "/" + n(a.coll_static) + ")";
  });
  row("min true static distance m", [&](const OnlineAgg& a) { return num(a.min_static); });
  row("min mover gap m", [&](const OnlineAgg& a) {
    return std::isfinite(a.min_gap) ? num(a.min_gap) : std::string("-");
  });
  row("hidden / revealed columns",
      [&](const OnlineAgg& a) { return n(a.hidden) + " / " + n(a.revealed); });
  row("blocked checks / stuck reports",
      [&](const OnlineAgg& a) { return n(a.blocked) + " / " + n(a.stuck); });
  row("mover conflicts / replans (skipped)", [&](const OnlineAgg& a) {
    return n(a.mover_conflicts) + " / " + n(a.mover_replans) + " (" + n(a.mover_skipped) + ")";
  });
  row("replans (failed attempts)",
      [&](const OnlineAgg& a) { return n(a.replans) + " (" + n(a.failures) + ")"; });
  row("plan switches (stale, replaced)",
      [&](const OnlineAgg& a) { return n(a.switches) + " (" + n(a.stale) + ")"; });
  row("replan wall ms p50 / p99", [&](const OnlineAgg& a) {
    return num(quantile(a.ms, 0.5), "%.2f") + " / " + num(quantile(a.ms, 0.99), "%.2f");
  });
  row("replan wall ms max", [&](const OnlineAgg& a) { return num(quantile(a.ms, 1.0), "%.2f"); });
  row("replan CPU ms p50 / p99", [&](const OnlineAgg& a) {
    return num(quantile(a.cpu, 0.5), "%.2f") + " / " + num(quantile(a.cpu, 0.99), "%.2f");
  });
  row("flight time s (median, arrived)",
      [&](const OnlineAgg& a) { return num(quantile(a.times, 0.5), "%.2f"); });
  row("escape failed (named status)", [&](const OnlineAgg& a) { return n(a.escape_failed); });
  row("executed max v / a / j", [&](const OnlineAgg& a) {
    return num(a.max_v, "%.2f") + "/" + num(a.max_a, "%.2f") + "/" + num(a.max_j, "%.1f");
  });
  row("episodes over a v/a/j limit (1 %)", [&](const OnlineAgg& a) { return n(a.over_limits); });
}

int online_bench(int bench, uint64_t seed, const RandomSpec& r, const tdo_online::Options& base) {
  const std::string dir = scratch_dir();
  using tdo_online::Replanner;
  const Replanner kinds[3] = {Replanner::Tdo, Replanner::None, Replanner::MsfMtpo};
  OnlineAgg agg[3];
  for (int i = 0; i < bench; ++i) {
    const uint64_t sd = seed + static_cast<uint64_t>(i);
    const tdo_io::Map map = random_map(r, sd, dir);
    for (int v = 0; v < 3; ++v) {
      tdo_online::Options o = base;
      o.replanner = kinds[v];
      o.hide_seed = sd;
      tdo_online::Metrics m;
      std::string err;
      if (!tdo_online::run(map, o, &m, &err)) throw BadInput{err};
      agg[v].add(m);
    }
  }
  std::filesystem::remove_all(dir);
  std::printf(
      "tdo-sim-run --bench %d: random %dx%dx%d m maps, %d columns (%.0f %% hidden, sensor range "
      "%.3g m), %d movers, seeds %llu..%llu\n",
      bench, r.size[0], r.size[1], r.size[2], r.columns, 100.0 * base.unknown, base.sensor_range,
      r.movers, static_cast<unsigned long long>(seed),
      static_cast<unsigned long long>(seed + static_cast<uint64_t>(bench) - 1));
  if (base.mover_window > 0.0)
    std::printf("movers blocking the plan are replanned round (--mover-replan %.3g s)\n",
                base.mover_window);
  else
    std::printf("movers blocking the plan are left to the E-APF (--mover-replan 0)\n");
  print_online_table({{"tdo replan", agg[0]}, {"E-APF only", agg[1]}, {"MSF-MTPO replan", agg[2]}});
  for (int v = 0; v < 3; v += 2) {
    std::printf("failed plans (%s):", tdo_online::replanner_name(kinds[v]));
    for (const auto& kv : agg[v].failed) std::printf(" %s %d;", kv.first.c_str(), kv.second);
    std::printf("%s\n", agg[v].failed.empty() ? " none" : "");
  }
  const OnlineAgg& t = agg[0];
  std::printf(
      "online: episodes=%d success=%d collisions=%d replans=%ld replan_p99_ms=%.2f "
      "over_limits=%d\n",
      t.episodes, t.success, t.collisions, t.replans, quantile(t.ms, 0.99), t.over_limits);
  return kExitOk;
}

int online_single(const tdo_io::Map& map, const tdo_online::Options& o, bool check) {
  tdo_online::Metrics m;
  std::string err;
  if (!tdo_online::run(map, o, &m, &err)) throw BadInput{err};
  std::string fails;
  for (const std::string& f : m.failure_statuses) fails += (fails.empty() ? "" : ",") + f;
  std::printf(
      "online %s: plan %s, hidden %u revealed %u, success %s, collision %s (static %s, mover %s), "
      "min true static distance %.3f m, replans %u (failed %u%s%s), switches %u, time %.2f s, "
      "max v %.3f a %.3f j %.3f\n",
      tdo_online::replanner_name(o.replanner),
      tdo_status_str(static_cast<tdo_status>(m.plan_status)), m.hidden, m.revealed,
      m.success ? "yes" : "no", m.collision ? "yes" : "no", m.collision_static ? "yes" : "no",
      m.collision_mover ? "yes" : "no", m.min_true_static, m.replans, m.replan_failures,
      fails.empty() ? "" : ": ", fails.c_str(), m.switches, m.time, m.max_speed, m.max_acc,
      m.max_jerk);
  if (check && (!m.planned || !m.success || m.collision)) return kExitFailed;
  return kExitOk;
}

tdo_online::Replanner parse_replanner(const std::string& s) {
  if (s == "tdo") return tdo_online::Replanner::Tdo;
  if (s == "none") return tdo_online::Replanner::None;
  if (s == "msf-mtpo") return tdo_online::Replanner::MsfMtpo;
  throw BadInput{"--replanner must be tdo, none or msf-mtpo, got '" + s + "'"};
}

// The followers' bench: N random episodes with E-APF and APF, with and without movers.
int follower_bench(int bench, uint64_t seed, const RandomSpec& r, const tdo_episode::Options& o) {
  const std::string dir = scratch_dir();
  Agg eapf, apf, eapf_free, apf_free;
  for (Agg* a : {&eapf, &apf, &eapf_free, &apf_free}) a->clearance = o.clearance;
  for (int i = 0; i < bench; ++i) {
    const uint64_t sd = seed + static_cast<uint64_t>(i);
    const tdo_io::Map map = random_map(r, sd, dir);
    std::string err;
    for (int variant = 0; variant < 4; ++variant) {
      tdo_episode::Options vo = o;
      vo.keep_samples = false;
      vo.seed = sd;
      vo.follower = (variant % 2 == 0) ? TDO_FOLLOWER_EAPF : TDO_FOLLOWER_APF;
      vo.movers = variant < 2;
      tdo_episode::Episode e;
      if (!tdo_episode::run(map, vo, &e, &err)) throw BadInput{err};
      Agg* a = variant == 0 ? &eapf : variant == 1 ? &apf : variant == 2 ? &eapf_free : &apf_free;
      a->add(e.m);
    }
  }
  std::filesystem::remove_all(dir);
  std::printf(
      "tdo-sim-run --bench %d: random %dx%dx%d m maps, %d columns, %d movers "
      "(%.2g-%.2g m/s, radius %.2g-%.2g m), seeds %llu..%llu\n",
      bench, r.size[0], r.size[1], r.size[2], r.columns, r.movers, r.speed[0], r.speed[1],
      r.radius[0], r.radius[1], static_cast<unsigned long long>(seed),
      static_cast<unsigned long long>(seed + static_cast<uint64_t>(bench) - 1));
  print_table(
      {{"E-APF", eapf}, {"APF", apf}, {"E-APF no mover", eapf_free}, {"APF no mover", apf_free}});
  tdo_plan_params lim;
  tdo_plan_params_default(&lim);
  std::printf("limits v %.3g m/s, a %.3g m/s^2, j %.3g m/s^3 (1 %% tolerance):", lim.v_max,
              lim.a_max, lim.j_max);
  for (const auto& c :
       {std::make_pair("E-APF", &eapf), std::make_pair("APF", &apf),
        std::make_pair("E-APF no mover", &eapf_free), std::make_pair("APF no mover", &apf_free)})
    std::printf(" %s %s;", c.first, c.second->over_limits == 0 ? "met" : "NOT met");
  std::printf("\n");
  return kExitOk;
}

CLI::Option* add_online_options(CLI::App* app, tdo_online::Options* online,
                                std::string* replanner) {
  CLI::Option* unknown = app->add_option(
      "--unknown", online->unknown,
      "F in [0, 1]: online mode. A fraction F of the columns (seeded) stays hidden until the range "
      "sensor sees it; revealed columns update the known map; the plan is checked and replanned. "
      "--bench then compares tdo replanning, E-APF only and MSF-MTPO replanning");
  app->add_option("--sensor-range", online->sensor_range, "m, range sensor reach (default 5)");
  app->add_option("--replanner", *replanner,
                  "online single episode: tdo (default), none (E-APF only) or msf-mtpo");
  app->add_option("--latency", online->latency,
                  "s, the new plan takes over this long after the trigger (default 0.1)");
  app->add_option("--replan-horizon", online->horizon,
                  "s, the active trajectory is checked this far ahead (default 5)");
  app->add_option("--mover-replan", online->mover_window,
                  "s, W > 0 (default 1): a mover blocking the trajectory within the horizon "
                  "triggers a replan round the region it sweeps over W s around the conflict "
                  "(temporary voxels, removed after planning); 0: movers are left to the E-APF");
  return unknown;
}

// The online mode: its options checked, then the bench or one episode (random or a map file).
int online_main(const tdo_online::Options& online, int bench, uint64_t seed, const RandomSpec& r,
                bool random, const std::string& map_path, bool check) {
  if (!(online.unknown >= 0.0 && online.unknown <= 1.0))
    throw BadInput{"--unknown must be in [0, 1]"};
  if (!std::isfinite(online.sensor_range) || online.sensor_range <= 0.0)
    throw BadInput{"--sensor-range must be finite and > 0"};
  if (!std::isfinite(online.latency) || online.latency < 0.0 || online.latency > 10.0)
    throw BadInput{"--latency must be in [0, 10]"};
  if (!std::isfinite(online.horizon) || online.horizon < 0.0)
    throw BadInput{"--replan-horizon must be finite and >= 0"};
  if (!(online.mover_window >= 0.0 && online.mover_window <= 10.0))
    throw BadInput{"--mover-replan must be in [0, 10]"};
  if (bench > 0) return online_bench(bench, seed, r, online);
  tdo_io::Map map;
  if (random) {
    const std::string dir = scratch_dir();
    map = random_map(r, seed, dir);
    std::filesystem::remove_all(dir);
  } else {
    std::string err;
    if (!tdo_io::load_map(map_path, &map, &err)) throw BadInput{err};
  }
  return online_single(map, online, check);
}

int run(int argc, char** argv) {
  CLI::App app{
      "Plan a map's query with tdo_planner_plan, fly it in the libtdo simulator with the E-APF "
      "or classical APF follower among the map's moving spheres, write the episode as JSON; or "
      "(--bench N) fly N seeded random episodes with both followers and print the metrics side "
      "by side.\nExit status: 0 done, 1 a --check goal missed, 2 bad input."};
  std::string map_path, output, follower = "eapf";
  bool random = false, no_movers = false, check = false;
  int bench = 0;
  uint64_t seed = 1;
  double noise = 0.0;
  RandomSpec r;
  tdo_episode::Options o;
  app.add_option("--map", map_path, "a .tdomap with start, goal and optional movers");
  app.add_flag("--random", random, "a seeded random episode (--size --columns --movers --seed)");
  app.add_option("--bench", bench,
                 "fly N random episodes (seeds --seed .. --seed+N-1), both "
                 "followers, and the no-mover case; print a table");
  app.add_option("--follower", follower, "eapf (default) or apf");
  app.add_option("-o,--output", output, "episode JSON file");
  app.add_flag("--no-movers", no_movers, "ignore the movers");
  app.add_option("--seed", seed, "random map seed (also the simulator's disturbance seed)");
  app.add_option("--noise", noise, "simulator disturbance, m/s^2 standard deviation (default 0)");
  app.add_option("--size", r.size, "X Y Z of random maps, whole metres (default 20 20 10)")
      ->expected(3);
  app.add_option("--columns", r.columns, "columns of random maps (default 25)");
  app.add_option("--movers", r.movers, "movers of random maps (default 6)");
  app.add_option("--mover-speed", r.speed, "MIN MAX m/s (default 0.5 1.5)")->expected(2);
  app.add_option("--mover-radius", r.radius, "MIN MAX m (default 0.5 1)")->expected(2);
  app.add_option("--time-factor", o.time_factor, "time limit = F * planned duration + 20 s (2)");
  std::vector<std::string> overrides;
  app.add_option("--param", overrides,
                 "NAME=VALUE follower parameter override (tdo_apf_params field, e.g. k_r=2); "
                 "applies to both followers in --bench");
  app.add_flag("--check", check, "exit 1 unless success and no collision (single episode)");
  std::string samples;
  app.add_option("--samples", samples,
                 "stored | streamed | pieces: the planner's trajectory samples kept in its arena, "
                 "or regenerated on demand (tdo_capacity.stream_samples; the same samples, so the "
                 "same episodes). Default: as tdo_capacity_for_grid sets it")
      ->check(CLI::IsMember({"stored", "streamed", "pieces"}));
  tdo_online::Options online;
  std::string replanner = "tdo";
  CLI::Option* unknown_opt = add_online_options(&app, &online, &replanner);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitBadInput;
  }
  if (!std::isfinite(noise) || noise < 0.0) throw BadInput{"--noise must be finite and >= 0"};
  if (!std::isfinite(o.time_factor) || o.time_factor <= 0.0)
    throw BadInput{"--time-factor must be finite and > 0"};
  if (bench < 0 || bench > 100000) throw BadInput{"--bench must be in [0, 100000]"};
  if (r.movers < 0 || r.movers > 1000) throw BadInput{"--movers must be in [0, 1000]"};
  if (r.columns < 0 || r.columns > 100000) throw BadInput{"--columns must be in [0, 100000]"};
  for (double v : r.speed)
    if (!std::isfinite(v) || v <= 0.0 || v > 100.0) throw BadInput{"--mover-speed out of range"};
  for (double v : r.radius)
    if (!std::isfinite(v) || v <= 0.0 || v > 100.0) throw BadInput{"--mover-radius out of range"};
  o.follower = parse_follower(follower);
  for (const std::string& kv : overrides) {
    const auto eq = kv.find('=');
    if (eq == std::string::npos) throw BadInput{"--param needs NAME=VALUE, got '" + kv + "'"};
    double v = 0.0;
    try {
      std::size_t used = 0;
      v = std::stod(kv.substr(eq + 1), &used);
      if (used != kv.size() - eq - 1) throw std::invalid_argument("trailing");
    } catch (const std::exception&) {
      throw BadInput{"--param " + kv + ": not a number"};
    }
    tdo_apf_params probe;
    tdo_apf_params_default(&probe, TDO_FOLLOWER_EAPF);
    if (!tdo_episode::set_param(&probe, kv.substr(0, eq), v))
      throw BadInput{"--param: unknown follower parameter '" + kv.substr(0, eq) + "'"};
    o.params.emplace_back(kv.substr(0, eq), v);
  }
  uint32_t mode = 0;
  if (!samples.empty() && tdo_samples::mode_parse(samples.c_str(), &mode)) {
    o.stream_samples = static_cast<int32_t>(mode);
    online.stream_samples = static_cast<int32_t>(mode);
  }
  o.movers = !no_movers;
  o.seed = seed;
  o.accel_noise = noise;
  const int sources = (map_path.empty() ? 0 : 1) + (random ? 1 : 0) + (bench > 0 ? 1 : 0);
  if (sources != 1) throw BadInput{"give exactly one of --map FILE, --random, --bench N"};
  if (unknown_opt->count() > 0) {
    if (noise > 0.0 || !o.params.empty() || o.follower != TDO_FOLLOWER_EAPF)
      throw BadInput{"--unknown flies E-APF without --noise or --param"};
    online.replanner = parse_replanner(replanner);
    online.movers = !no_movers;
    online.time_factor = o.time_factor;
    online.hide_seed = seed;
    return online_main(online, bench, seed, r, random, map_path, check);
  }

  if (bench > 0) return follower_bench(bench, seed, r, o);

  tdo_io::Map map;
  std::string dir;
  if (random) {
    dir = scratch_dir();
    map = random_map(r, seed, dir);
  } else {
    std::string err;
    if (!tdo_io::load_map(map_path, &map, &err)) throw BadInput{err};
  }
  tdo_episode::Episode e;
  std::string err;
  const bool ok = tdo_episode::run(map, o, &e, &err);
  if (!dir.empty()) std::filesystem::remove_all(dir);
  if (!ok) throw BadInput{err};
  const tdo_episode::Metrics& m = e.m;
  if (!output.empty()) {
    std::ofstream f(output);
    f << tdo_episode::to_json(e, map, o) << "\n";
    if (!f) throw BadInput{output + ": cannot write"};
  }
  std::printf(
      "%s: plan %s, %u movers, success %s, collision %s, min mover separation %.3f m, "
      "deviation max %.3f mean %.3f m, time %.2f s (plan %.2f s), local minima %u, "
      "max v %.3f a %.3f j %.3f\n",
      tdo_episode::follower_name(o.follower),
      tdo_status_str(static_cast<tdo_status>(m.plan_status)), m.movers, m.success ? "yes" : "no",
      m.collision ? "yes" : "no", m.min_mover_sep, m.max_deviation, m.mean_deviation, m.time,
      m.plan_duration, m.lm_events, m.max_speed, m.max_acc, m.max_jerk);
  if (check && (!m.planned || !m.success || m.collision)) return kExitFailed;
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) { return tdo_tool::guarded_main("tdo-sim-run", run, argc, argv); }
