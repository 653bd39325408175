// Proof that libtdo never touches the heap after tdo_planner_init (docs/design.md s.7, issue 2).
//
// This executable replaces every allocation entry point (malloc family and all forms of operator
// new/delete). While `armed` is set, any call is counted and aborts with a message on stderr. The
// planner lives in a static buffer; the map is loaded and 1,000 search queries (A* and
// bidirectional, succeeding and failing) run with the trap armed; then the whole pipeline
// (tdo_planner_plan: search, correction, smoothing, trajectory, metrics) runs 1,200 times on three
// maps loaded while armed, at every depth, with every search kind, correction and smoothing mode,
// succeeding and failing (bad parameters, unreachable goal, tiny budget, infeasible limits).
// No GoogleTest here: gtest allocates.
//
// Under AddressSanitizer (or another sanitizer that owns malloc) the interposition is skipped and
// only the queries run; the un-sanitized build is the proof.
#include <errno.h>
#include <signal.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <new>

#include "rng.h"
#include "tdo/tdo.h"

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define TDO_NO_HEAP_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer) || \
    __has_feature(thread_sanitizer) || __has_feature(hwaddress_sanitizer)
#define TDO_NO_HEAP_SANITIZED 1
#endif
#endif
#ifndef TDO_NO_HEAP_SANITIZED
#define TDO_NO_HEAP_SANITIZED 0
#endif

namespace {

enum Kind { kMalloc, kCalloc, kRealloc, kFree, kAligned, kNew, kDelete, kKinds };
const char* const kKindNames[kKinds] = {"malloc",        "calloc",       "realloc",        "free",
                                        "aligned alloc", "operator new", "operator delete"};

volatile int g_armed = 0;
volatile int g_self_test = 0;  // the trap is expected to fire (--self-test children)
volatile unsigned long g_calls[kKinds] = {};

void say(const char* s) {
  size_t n = strlen(s);
  while (n > 0) {
    const ssize_t w = write(2, s, n);
    if (w <= 0) return;
    s += w;
    n -= static_cast<size_t>(w);
  }
}

// Called on entry of every replaced function.
[[maybe_unused]] void check(Kind kind) {
  if (!g_armed) return;
  g_calls[kind] = g_calls[kind] + 1u;
  if (g_self_test) {
    say("tdo_no_heap: self-test: trap fired on ");
    say(kKindNames[kind]);
    say(" (expected)\n");
  } else {
    say("tdo_no_heap: FAIL: ");
    say(kKindNames[kind]);
    say(" called after tdo_planner_init (heap use inside libtdo)\n");
  }
  abort();
}

void arm() { g_armed = 1; }
void disarm() { g_armed = 0; }

}  // namespace

#if !TDO_NO_HEAP_SANITIZED
// ---------------------------------------------------------------------------------------------
// Replacement allocator: forwards to glibc's own implementation when not armed.
extern "C" {
void* __libc_malloc(size_t size);
void* __libc_calloc(size_t n, size_t size);
void* __libc_realloc(void* p, size_t size);
void __libc_free(void* p);
void* __libc_memalign(size_t alignment, size_t size);

void* malloc(size_t size) noexcept {
  check(kMalloc);
  return __libc_malloc(size);
}
void* calloc(size_t n, size_t size) noexcept {
  check(kCalloc);
  return __libc_calloc(n, size);
}
void* realloc(void* p, size_t size) noexcept {
  check(kRealloc);
  return __libc_realloc(p, size);
}
void free(void* p) noexcept {
  check(kFree);
  __libc_free(p);
}
void* aligned_alloc(size_t alignment, size_t size) noexcept {
  check(kAligned);
  return __libc_memalign(alignment, size);
}
void* memalign(size_t alignment, size_t size) noexcept {
  check(kAligned);
  return __libc_memalign(alignment, size);
}
void* valloc(size_t size) noexcept {
  check(kAligned);
  return __libc_memalign(static_cast<size_t>(sysconf(_SC_PAGESIZE)), size);
}
int posix_memalign(void** out, size_t alignment, size_t size) noexcept {
  check(kAligned);
  if (alignment == 0 || (alignment & (alignment - 1u)) != 0 || alignment % sizeof(void*) != 0)
    return EINVAL;
  void* p = __libc_memalign(alignment, size);
  if (p == nullptr) return ENOMEM;
  *out = p;
  return 0;
}
}  // extern "C"

namespace {
void* new_impl(size_t size) {
  check(kNew);
  void* p = __libc_malloc(size == 0 ? 1 : size);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}
void* new_aligned(size_t size, std::align_val_t al) {
  check(kNew);
  void* p = __libc_memalign(static_cast<size_t>(al), size == 0 ? 1 : size);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}
void* new_nothrow(size_t size) noexcept {
  check(kNew);
  return __libc_malloc(size == 0 ? 1 : size);
}
void* new_aligned_nothrow(size_t size, std::align_val_t al) noexcept {
  check(kNew);
  return __libc_memalign(static_cast<size_t>(al), size == 0 ? 1 : size);
}
void delete_impl(void* p) noexcept {
  check(kDelete);
  __libc_free(p);
}
}  // namespace

void* operator new(size_t size) { return new_impl(size); }
void* operator new[](size_t size) { return new_impl(size); }
void* operator new(size_t size, const std::nothrow_t&) noexcept { return new_nothrow(size); }
void* operator new[](size_t size, const std::nothrow_t&) noexcept { return new_nothrow(size); }
void* operator new(size_t size, std::align_val_t al) { return new_aligned(size, al); }
void* operator new[](size_t size, std::align_val_t al) { return new_aligned(size, al); }
void* operator new(size_t size, std::align_val_t al, const std::nothrow_t&) noexcept {
  return new_aligned_nothrow(size, al);
}
void* operator new[](size_t size, std::align_val_t al, const std::nothrow_t&) noexcept {
  return new_aligned_nothrow(size, al);
}
void operator delete(void* p) noexcept { delete_impl(p); }
void operator delete[](void* p) noexcept { delete_impl(p); }
void operator delete(void* p, size_t) noexcept { delete_impl(p); }
void operator delete[](void* p, size_t) noexcept { delete_impl(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { delete_impl(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { delete_impl(p); }
void operator delete(void* p, std::align_val_t) noexcept { delete_impl(p); }
void operator delete[](void* p, std::align_val_t) noexcept { delete_impl(p); }
void operator delete(void* p, size_t, std::align_val_t) noexcept { delete_impl(p); }
void operator delete[](void* p, size_t, std::align_val_t) noexcept { delete_impl(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { delete_impl(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept {
  delete_impl(p);
}
#endif  // !TDO_NO_HEAP_SANITIZED

// ---------------------------------------------------------------------------------------------

namespace {

constexpr int32_t kNx = 16, kNy = 16, kNz = 8;
constexpr uint32_t kVoxels = static_cast<uint32_t>(kNx * kNy * kNz);
constexpr double kRes = 1.0;
constexpr double kClearance = 0.6;
constexpr int kQueries = 1000;
constexpr int kPipelineMaps = 3;
constexpr int kPlansPerMap = 400;

// The whole planner memory: static, no vector, no heap.
alignas(64) unsigned char g_arena[48u << 20];

tdo_vec3 random_point(tdo_test::Rng& rng) {
  return tdo_vec3{rng.uniform(0.0, kNx * kRes), rng.uniform(0.0, kNy * kRes),
                  rng.uniform(0.0, kNz * kRes)};
}

// A random point in a voxel the search may start from (blocked voxels are retried).
tdo_vec3 random_free_point(tdo_test::Rng& rng, const tdo_grid* grid) {
  for (;;) {
    const tdo_vec3 p = random_point(rng);
    tdo_voxel v{};
    if (tdo_grid_world_to_voxel(grid, p, &v) && !tdo_grid_is_blocked(grid, v)) return p;
  }
}

tdo_vec3 centre(int32_t i, int32_t j, int32_t k) {
  return tdo_vec3{(i + 0.5) * kRes, (j + 0.5) * kRes, (k + 0.5) * kRes};
}

// Load the map. Runs armed: loading a map is part of "after init".
tdo_status load_map(tdo_grid* grid, tdo_test::Rng& rng) {
  const tdo_grid_desc d{kNx, kNy, kNz, kRes, tdo_vec3{0.0, 0.0, 0.0}};
  tdo_status st = tdo_grid_reset(grid, &d);
  if (st != TDO_OK) return st;
  for (int b = 0; b < 12; ++b) {
    const double x = rng.uniform(0.0, 10.0), y = rng.uniform(0.0, 14.0), z = rng.uniform(0.0, 6.0);
    const tdo_box box{
        tdo_vec3{x, y, z},
        tdo_vec3{x + rng.uniform(0.3, 3.0), y + rng.uniform(0.3, 2.0), z + rng.uniform(0.3, 2.0)}};
    st = tdo_grid_add_box(grid, &box);
    if (st != TDO_OK) return st;
  }
  for (int v = 0; v < 40; ++v) {
    st = tdo_grid_add_voxel(grid, rng.range(0, 10), rng.range(0, kNy - 1), rng.range(0, kNz - 1));
    if (st != TDO_OK) return st;
  }
  // A sealed chamber: a shell of cubes around x 11..15, y 0..4, z 0..4; its centre voxel
  // (13, 2, 2) is 1.5 m from the shell, so free at clearance 0.6, and unreachable.
  for (int32_t k = 0; k <= 4; ++k)
    for (int32_t j = 0; j <= 4; ++j)
      for (int32_t i = 11; i <= 15; ++i) {
        const bool shell = i == 11 || i == 15 || j == 0 || j == 4 || k == 0 || k == 4;
        if (!shell) continue;
        st = tdo_grid_add_voxel(grid, i, j, k);
        if (st != TDO_OK) return st;
      }
  return tdo_grid_finish(grid, kClearance);
}

// One pipeline request; `q` picks depth, stage modes and the failure cases.
tdo_plan_request pipeline_request(tdo_test::Rng& rng, const tdo_grid* grid, int q) {
  tdo_plan_request r{};
  tdo_plan_params_default(&r.params);
  tdo_plan_params& p = r.params;
  r.start = random_free_point(rng, grid);
  r.goal = random_free_point(rng, grid);
  p.depth = static_cast<tdo_plan_depth>(q % 4);
  p.search = (q / 4) % 2 == 0 ? TDO_SEARCH_BIDIR : TDO_SEARCH_ASTAR;
  p.correction = static_cast<tdo_correct_mode>((q / 8) % 3);
  p.smoothing = static_cast<tdo_smoothing>((q / 24) % 3);
  p.first_meet = (q / 72) % 2;
  if ((q / 4) % 5 == 4) {  // plain search, no penalties and no direction constraint
    p.lambda = 0.0;
    p.mu = 0.0;
    p.theta_max = 0.0;
  }
  switch (q % 20) {
    case 5:  // into the sealed chamber: no path
      r.goal = centre(13, 2, 2);
      break;
    case 9:  // a tiny budget
      p.max_expansions = 3;
      break;
    case 13:  // bad parameters
      if (q % 3 == 0) p.v_max = -1.0;
      if (q % 3 == 1) p.lambda = __builtin_nan("");
      if (q % 3 == 2) p.dt = 0.0;
      break;
    case 15:  // very low dynamic limits: long, slow trajectories and many refinements
      p.j_max = 0.02;
      p.a_max = 0.05;
      p.a_lat_max = 0.05;
      break;
    case 17:  // other speeds and radius scale
      p.v_max = rng.uniform(0.5, 5.0);
      p.a_max = rng.uniform(1.0, 6.0);
      p.a_lat_max = p.a_max;
      p.v_cruise = p.v_max;
      p.k = rng.uniform(0.3, 3.0);
      break;
    case 19:  // start blocked
      r.start = centre(11, 2, 2);
      break;
    default:
      break;
  }
  return r;
}

// Bit-identical points (the pipeline's ends are the exact start and goal).
bool same_point(const tdo_vec3& a, const tdo_vec3& b) { return memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

namespace {

void* volatile g_sink = nullptr;

// Each probe calls one replaced entry point; run armed, it must die with SIGABRT.
[[maybe_unused]] void probe(int n) {
  void* p = nullptr;
  switch (n) {
    case 0:
      g_sink = malloc(16);
      break;
    case 1:
      g_sink = calloc(2, 8);
      break;
    case 2:
      g_sink = realloc(nullptr, 16);
      break;
    case 3:
      free(g_sink);
      break;
    case 4:
      g_sink = aligned_alloc(64, 64);
      break;
    case 5:
      g_sink = posix_memalign(&p, 64, 64) == 0 ? p : nullptr;
      break;
    case 6:
      g_sink = operator new(16);
      break;
    case 7:
      g_sink = operator new[](16);
      break;
    case 8:
      g_sink = operator new(16, std::nothrow);
      break;
    case 9:
      g_sink = operator new (64, std::align_val_t{64});
      break;
    case 10:
      operator delete(g_sink);
      break;
    case 11:
      operator delete[](g_sink, 16);
      break;
    default:
      break;
  }
}
constexpr int kProbes = 12;

// --self-test: prove the trap fires, one forked child per entry point.
[[maybe_unused]] int self_test() {
  int failed = 0;
  for (int n = 0; n < kProbes; ++n) {
    fflush(stdout);
    fflush(stderr);
    const pid_t pid = fork();
    if (pid < 0) return 1;
    if (pid == 0) {
      g_sink = __builtin_malloc(64);  // something valid to free/delete, taken before arming
      g_self_test = 1;
      arm();
      probe(n);
      disarm();
      _exit(0);
    }
    int status = 0;
    if (waitpid(pid, &status, 0) != pid) return 1;
    const bool trapped = WIFSIGNALED(status) && WTERMSIG(status) == SIGABRT;
    printf("probe %d: %s\n", n, trapped ? "trapped" : "NOT trapped");
    if (!trapped) failed = 1;
  }
  return failed;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Follower and simulator (apf.h, sim.h): stepped with the trap armed, from static arenas.
namespace {

alignas(64) unsigned char g_follow_arena[1u << 20];
tdo_sample g_line[1201];  // 12 s along a straight line at 0.01 s

// E-APF among movers along a straight trajectory, then the classical APF towards a goal with one
// escape allowed (it may end in TDO_ERR_LOCAL_MINIMUM). Returns the number of unexpected statuses.
int fly_follower_armed(const tdo_grid* grid) {
  tdo_arena arena;
  tdo_arena_init(&arena, g_follow_arena, sizeof g_follow_arena);
  const tdo_apf_config acfg{1201u, 4u, 200u, 0u};
  const tdo_sim_config scfg{4u};
  tdo_apf* apf = nullptr;
  tdo_sim* sim = nullptr;
  if (tdo_apf_init(&apf, &arena, &acfg) != TDO_OK) return 1;
  if (tdo_sim_init(&sim, &arena, &scfg) != TDO_OK) return 1;
  for (int i = 0; i <= 1200; ++i) {  // quintic rest-to-rest ramp; no feed-forward (v, a zero)
    const double t = i * 0.01, u = t / 12.0;
    const double s = 14.0 * (10 * u * u * u - 15 * u * u * u * u + 6 * u * u * u * u * u);
    g_line[i].t = t;
    g_line[i].p = tdo_vec3{1.0 + s, 1.0 + 0.5 * s, 7.5};
    g_line[i].v = tdo_vec3{0.0, 0.0, 0.0};
    g_line[i].a = tdo_vec3{0.0, 0.0, 0.0};
  }
  const tdo_mover movers[3] = {{1u, {8.0, 8.0, 7.5}, {-0.5, -0.8, 0.0}, 0.6},
                               {2u, {12.0, 2.0, 7.0}, {-1.0, 0.6, 0.1}, 0.8},
                               {3u, {3.0, 12.0, 7.5}, {0.7, -0.9, 0.0}, 0.5}};
  int bad = 0;
  for (int kind = 0; kind < 2; ++kind) {
    tdo_apf_params p;
    tdo_apf_params_default(&p, kind == 0 ? TDO_FOLLOWER_EAPF : TDO_FOLLOWER_APF);
    p.max_escapes = 1u;
    const tdo_apf_task task{g_line, 1201u, tdo_vec3{14.5, 14.5, 1.5}, grid, 0.0};
    if (tdo_apf_reset(apf, &p, &task) != TDO_OK) return bad + 1;
    tdo_sim_params sp;
    tdo_sim_params_default(&sp);
    sp.bounds = tdo_box{{0.0, 0.0, 0.0}, {16.0, 16.0, 8.0}};
    sp.grid = grid;
    sp.accel_noise = 0.2;
    tdo_vehicle_state s0{};
    s0.p = g_line[0].p;
    if (tdo_sim_reset(sim, &sp, &s0, movers, kind == 0 ? 3u : 0u) != TDO_OK) return bad + 1;
    tdo_sim_output so;
    if (tdo_sim_get(sim, &so) != TDO_OK) return bad + 1;
    for (int k = 0; k < 1500; ++k) {
      const tdo_apf_input in{so.state, so.movers, so.n_movers};
      tdo_apf_output out;
      const tdo_status st = tdo_apf_run(apf, &in, &out);
      if (st != TDO_OK && st != TDO_ERR_LOCAL_MINIMUM) ++bad;
      const tdo_sim_input si{out.setpoint};
      if (tdo_sim_run(sim, &si, &so) != TDO_OK) ++bad;
    }
    // Capacity overflow is a status, armed as well.
    tdo_mover many[5] = {movers[0], movers[1], movers[2], movers[0], movers[1]};
    tdo_setpoint sp_out;
    if (tdo_apf_step(apf, &so.state, many, 5u, &sp_out) != TDO_ERR_OBSTACLE_CAPACITY) ++bad;
  }
  return bad;
}

}  // namespace

int main(int argc, char** argv) {
#if TDO_NO_HEAP_SANITIZED
  printf("no-heap trap disabled under ASan\n");
  if (argc > 1 && strcmp(argv[1], "--self-test") == 0) return 0;
#else
  if (argc > 1 && strcmp(argv[1], "--self-test") == 0) return self_test();
#endif
  tdo_planner_config cfg{};
  cfg.cap.max_voxels = kVoxels;
  cfg.cap.max_boxes = 16;
  cfg.cap.max_nodes = 27u * kVoxels;
  cfg.cap.max_path = kVoxels + 1u;
  cfg.cap.max_clear_cells = 125;  // K = ceil(0.6 + 0.5) = 2
  cfg.cap.max_expansions = 1u << 22;
  // The later stages (correction, smoothing, trajectory): without these they are not configured.
  cfg.cap.max_checks = 100000;
  cfg.cap.max_shrinks = 16;
  cfg.cap.max_samples = 1u << 16;
  cfg.cap.max_profile = 8u * (3u * cfg.cap.max_path + 7u) + 1u;
  cfg.cap.max_violations = 32;
  cfg.cap.max_refinements = 8;
  const size_t need = tdo_planner_footprint(&cfg);
  if (need == 0 || need > sizeof g_arena) {
    fprintf(stderr, "tdo_no_heap: footprint %zu does not fit the %zu-byte static arena\n", need,
            sizeof g_arena);
    return 1;
  }
  tdo_planner* planner = nullptr;
  const tdo_status init = tdo_planner_init(&planner, g_arena, sizeof g_arena, &cfg);
  if (init != TDO_OK) {
    fprintf(stderr, "tdo_no_heap: init failed: %s\n", tdo_status_str(init));
    return 1;
  }
  tdo_grid* grid = tdo_planner_grid(planner);
  tdo_search* search = tdo_planner_search(planner);
  tdo_test::Rng rng(2024);
  unsigned long by_status[TDO_STATUS_COUNT] = {};
  unsigned long bad_paths = 0;
  unsigned long plan_status[TDO_STATUS_COUNT] = {};
  unsigned long plan_depth_ok[4] = {};
  unsigned long bad_plans = 0;
  tdo_status pipeline_load = TDO_OK;

  arm();  // ---- from here on, any heap call aborts ----
  const tdo_status loaded = load_map(grid, rng);
  if (loaded == TDO_OK) {
    for (int q = 0; q < kQueries; ++q) {
      tdo_search_input in{};
      in.grid = grid;
      in.kind = q % 2 == 0 ? TDO_SEARCH_ASTAR : TDO_SEARCH_BIDIR;
      in.start = random_point(rng);
      in.goal = random_point(rng);
      switch (q % 10) {
        case 6:  // into the sealed chamber: no path
          in.goal = centre(13, 2, 2);
          break;
        case 7:  // a tiny budget
          in.max_expansions = 3;
          break;
        case 8:  // turn penalty and deviation term
          in.lambda = 50.0;
          in.mu = 20.0;
          break;
        case 9:  // bad input: out of bounds, identical points, blocked shell voxel
          if (q % 3 == 0) {
            in.start = random_free_point(rng, grid);
            in.goal.x = -1.0;
          }
          if (q % 3 == 1) in.goal = in.start = random_free_point(rng, grid);
          if (q % 3 == 2) in.start = centre(11, 2, 2);
          break;
        default:
          break;
      }
      tdo_search_output out;
      const tdo_status st = tdo_search_run(search, &in, &out);
      if (static_cast<int>(st) >= 0 && st < TDO_STATUS_COUNT) ++by_status[st];
      if (st == TDO_OK) {
        tdo_voxel s{}, g{};
        if (out.n_path == 0 || out.path == nullptr ||
            !tdo_grid_world_to_voxel(grid, in.start, &s) ||
            !tdo_grid_world_to_voxel(grid, in.goal, &g) || out.path[0].i != s.i ||
            out.path[0].j != s.j || out.path[0].k != s.k || out.path[out.n_path - 1].i != g.i ||
            out.path[out.n_path - 1].j != g.j || out.path[out.n_path - 1].k != g.k)
          ++bad_paths;
      }
    }
  }
  // The follower and the simulator, on the map of the queries above.
  const int follower_bad = loaded == TDO_OK ? fly_follower_armed(grid) : 0;
  // The whole pipeline, on three maps loaded while armed.
  for (int m = 0; m < kPipelineMaps && loaded == TDO_OK; ++m) {
    pipeline_load = load_map(grid, rng);
    if (pipeline_load != TDO_OK) break;
    for (int q = 0; q < kPlansPerMap; ++q) {
      const tdo_plan_request req = pipeline_request(rng, grid, m * kPlansPerMap + q);
      tdo_plan_result res;
      const tdo_status st = tdo_planner_plan(planner, &req, &res);
      if (static_cast<int>(st) >= 0 && st < TDO_STATUS_COUNT) ++plan_status[st];
      if (st != res.status) ++bad_plans;
      if (st != TDO_OK) {
        if (res.n_samples != 0) ++bad_plans;  // never a trajectory with a failure
        continue;
      }
      ++plan_depth_ok[req.params.depth];
      if (res.n_grid_path < 2 || !same_point(res.grid_path[0], req.start) ||
          !same_point(res.grid_path[res.n_grid_path - 1], req.goal))
        ++bad_plans;
      if (req.params.depth == TDO_PLAN_TRAJECTORY &&
          (res.n_samples < 2 || !same_point(res.samples[0].p, req.start) ||
           !same_point(res.samples[res.n_samples - 1].p, req.goal) || !res.feasibility.ok))
        ++bad_plans;
    }
  }
  disarm();  // ---- heap allowed again ----

  if (loaded != TDO_OK) {
    fprintf(stderr, "tdo_no_heap: loading the map failed: %s\n", tdo_status_str(loaded));
    return 1;
  }
  if (pipeline_load != TDO_OK) {
    fprintf(stderr, "tdo_no_heap: loading a pipeline map failed: %s\n",
            tdo_status_str(pipeline_load));
    return 1;
  }
  int failed = 0;
  unsigned long heap_calls = 0;
  for (int k = 0; k < kKinds; ++k) heap_calls += g_calls[k];
  if (heap_calls != 0) {
    fprintf(stderr, "tdo_no_heap: FAIL: %lu heap calls while armed\n", heap_calls);
    failed = 1;
  }
  if (follower_bad != 0) {
    fprintf(stderr, "tdo_no_heap: FAIL: %d unexpected follower/simulator statuses\n", follower_bad);
    failed = 1;
  }
  if (bad_paths != 0) {
    fprintf(stderr, "tdo_no_heap: FAIL: %lu paths do not join start and goal\n", bad_paths);
    failed = 1;
  }
  printf("tdo_no_heap: %d queries, arena %zu of %zu bytes, blocked voxels %u\n", kQueries,
         tdo_planner_arena_used(planner), need, tdo_grid_blocked_count(grid));
  for (int s = 0; s < TDO_STATUS_COUNT; ++s)
    if (by_status[s] != 0)
      printf("  %-22s %lu\n", tdo_status_str(static_cast<tdo_status>(s)), by_status[s]);
  // Every kind of outcome the trap is meant to cover must have happened.
  const tdo_status required[] = {TDO_OK,
                                 TDO_ERR_NO_PATH,
                                 TDO_ERR_BUDGET,
                                 TDO_ERR_START_BLOCKED,
                                 TDO_ERR_GOAL_OUT_OF_BOUNDS,
                                 TDO_ERR_START_EQUALS_GOAL};
  for (tdo_status s : required) {
    if (by_status[s] == 0) {
      fprintf(stderr, "tdo_no_heap: FAIL: no query ended with %s\n", tdo_status_str(s));
      failed = 1;
    }
  }
  if (by_status[TDO_OK] < 200) {
    fprintf(stderr, "tdo_no_heap: FAIL: only %lu successful queries\n", by_status[TDO_OK]);
    failed = 1;
  }
  if (bad_plans != 0) {
    fprintf(stderr, "tdo_no_heap: FAIL: %lu plans with wrong ends, status or samples\n", bad_plans);
    failed = 1;
  }
  printf("tdo_no_heap: %d pipeline plans on %d maps\n", kPipelineMaps * kPlansPerMap,
         kPipelineMaps);
  for (int s = 0; s < TDO_STATUS_COUNT; ++s)
    if (plan_status[s] != 0)
      printf("  %-22s %lu\n", tdo_status_str(static_cast<tdo_status>(s)), plan_status[s]);
  const tdo_status plan_required[] = {TDO_OK, TDO_ERR_NO_PATH, TDO_ERR_BUDGET,
                                      TDO_ERR_INVALID_ARGUMENT, TDO_ERR_START_BLOCKED};
  for (tdo_status s : plan_required) {
    if (plan_status[s] == 0) {
      fprintf(stderr, "tdo_no_heap: FAIL: no plan ended with %s\n", tdo_status_str(s));
      failed = 1;
    }
  }
  for (int d = 0; d < 4; ++d) {
    if (plan_depth_ok[d] < 50) {
      fprintf(stderr, "tdo_no_heap: FAIL: only %lu successful plans at depth %d\n",
              plan_depth_ok[d], d);
      failed = 1;
    }
  }
  if (failed)
    fputs("tdo_no_heap: FAILED\n", stdout);
  else if (TDO_NO_HEAP_SANITIZED)
    fputs("tdo_no_heap: queries ok (trap disabled)\n", stdout);
  else
    fputs("tdo_no_heap: no heap use after init\n", stdout);
  return failed;
}
