// Stage 5: time parameterisation, dynamic feasibility verification and refinement
// (docs/design.md s.5, paper eq. 15-19).
//
// Speed profile. Every line of positive length is a "plateau", every curved segment up to kSubMax
// equal parts (as many as the profile capacity allows, curve_parts), so the speed ceiling follows
// the curvature along a curve instead of taking its worst point for all of it. A plateau has a
// constant speed ceiling (the minimum over it of v_max, the segment's v_limit,
// sqrt(a_lat / kappa) and the lateral-jerk bounds) and its own tangential acceleration and jerk
// limits, chosen so that the total acceleration (friction circle) and the tangential and normal
// parts of the jerk (plateau_limits, plateau_at: the limits at the speed flown) stay inside
// a_max and j_max. Consecutive plateaus form moves (choose_moves): each move is flown as
// accelerate (S-curve) / cruise / decelerate (S-curve), so its acceleration is zero only at its
// two ends and runs on through the plateau boundaries inside it; it cruises below the lowest
// ceiling of its plateaus, and each S-curve takes the limits of the plateaus it covers
// (move_ramp). Moves always end at the path's ends, at stop points, at tangent kinks and at
// curvature jumps (the finite differences at dt turn a curvature jump into a jerk of about
// v^2 dkappa / dt, so the speed there is capped); elsewhere they end where that is faster.
// Forward and backward passes make the move ends' speeds mutually reachable (closed-form S-curve
// distance, bisection on the reachable speed); the peak of each move is found by bisection. The
// result is a list of constant-jerk pieces in time, so s(t) is an exact piecewise cubic.
//
// Why this passes the finite-difference checks: the second and third differences of the sampled
// positions are kernel averages (hat and quadratic B-spline kernels) of the continuous
// acceleration and jerk, so they never exceed the continuous maxima that the budgets bound;
// curvature jumps and kinks (deltas in the jerk) get their own share of the budget.
//
// Verification recomputes everything from the sampled positions only (eq. 15-17) and refinement
// lowers the plateaus around each violation (x0.8) a bounded number of times.
#include "tdo/trajectory.h"

#include <math.h>
#include <string.h>

#include "tdo/traj_profile.h"
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#include <immintrin.h>
#endif

#include "bisect_highest.h"
#include "collision_internal.h"
#include "path_clearance.h"
#include "path_segment.h"
#include "sample_energy.h"
#include "scalar.h"
#include "tdo/collision.h"
#include "vec3.h"

namespace tdo_internal {
namespace {

// Verification.
constexpr double kTolerance = 0.01;       // 1 % discretisation tolerance on v, a, j and r
constexpr double kClearanceSlack = 1e-9;  // m, clearance check slack
constexpr double kClearanceCapExtra =
    TDO_TRAJ_CLEARANCE_CAP_EXTRA;           // m, distance cap above clearance
constexpr double kLipschitzSlack = 1e-9;    // m, rounding allowance of the skipped-sample bound
constexpr uint32_t kClearanceStride = 256;  // samples between the clearance pre-pass's points
// m, the clearance pass evaluates a sample's distance capped at this much above what can still
// change its result (the minimum so far, the violation floor): a larger cap visits more obstacles
// per query, a smaller one leaves the probe's bound too low to skip the next samples (geb079
// G2 at 0.08 m: 0 -> 52 M instructions per plan, 0.05 -> 43 M, 0.15 -> 56 M, uncapped 90 M)
constexpr double kClearanceEvalMargin = 0.05;
// m, the same margin in clearance_min, at most kClearanceMinVoxels voxel edges: its queries'
// bounds prune both ways, so a larger cap pays on coarse grids (MovingAI Simple at 1 m, 200
// queries: 0.05 -> 35,741 queries, 0.2 -> 21,650), while on fine ones a larger cap reaches many
// more cubes per query (geb079 G3 at 0.08 m: 0.2 -> 1.80 M instructions per plan, 0.04 -> 0.97 M;
// forest pairs 1, 105, 205 at 0.1 m: trajectory stage 5.45 M -> 4.51 M with 0.05)
constexpr double kClearanceMinMargin = 0.2;
constexpr double kClearanceMinVoxels = 0.5;
constexpr double kRadiusNoise = 64.0 * 2.220446049250313e-16;  // FD rounding, relative to |P|
// Budgets (fractions of a_max / j_max).
constexpr double kLineShare = 0.99;    // tangential jerk on straight plateaus
constexpr double kLineAcc = 0.99;      // tangential acceleration on straight plateaus
constexpr double kAccCircle = 0.99;    // total acceleration on curved plateaus (friction circle)
constexpr double kShareFloor = 0.35;   // least tangential share of jb in speed changes on curves
constexpr double kLeftFloor = 1e-9;    // of a_max / jb: least limits of a speed change (plateau_at)
constexpr double kJerkGeo = 0.98;      // of jb: the curvature terms at the ceiling
constexpr double kCurveAccLat = 0.96;  // lateral acceleration at the ceiling (of a_max)
constexpr double kCurveJerk = 0.99;    // total jerk on curved plateaus
constexpr double kJumpJerk = 0.6;      // total smooth jerk on plateaus next to a curvature jump
constexpr double kJumpShare = 0.3;     // jerk share of the curvature jump itself
constexpr double kKinkShare = 0.05;    // a / j share of a tiny tangent kink (rounding)
constexpr double kKinkStop = 1e-3;     // rad: tangent kinks above this are stop points
constexpr double kGapTolerance = 1e-6;  // m: segment end points further apart are invalid input
// Geometry summary of a curved segment.
constexpr uint32_t kStations = 16;  // curvature stations per curved segment, shared by its parts
constexpr uint32_t kSubMax = 4;     // plateaus per curved segment, at most (TDO_TRAJ_PIECES_...)
constexpr uint32_t kPiecesPerPlateau =
    8;                                  // 7 of the accelerate/cruise/decelerate profile + a dwell
constexpr double kKappaMargin = 1.01;   // on the sampled curvature maximum
constexpr double kDKappaMargin = 1.01;  // on the sampled curvature-rate maximum
// Profile.
constexpr uint32_t kMoveWindow = 2;    // moves on either side that judge a change (choose_moves)
constexpr double kRefineFactor = 0.8;  // speed/acc/jerk factor per refinement round
constexpr double kAlignSlack = 1e-9;   // in units of dt when aligning stops to the sample grid
// Moving start (docs/design.md s.5): the entry ramp's jerk and the braking line's limits.
constexpr double kRampJerk = 0.95;  // of j_max: the ramp that brings the start acceleration to 0
// Of j_max: the steepest ramp, for one that would end above v_max at kRampJerk. Above the profile's
// 0.99 so that a state of a plan's own speed-up to v_max (at 0.99 j_max) is plannable.
constexpr double kRampJerkMax = 0.995;
constexpr double kBrakeRel = 1e-6;  // relative margin on the braking line's length
constexpr double kBrakeAbs = 1e-9;  // m, absolute margin on it
// m: the shortest braking line. A start that has almost stopped at the ramp's end (|v1| of a few
// nm/s) would otherwise get a line of about kBrakeAbs, which the smoothing merges into the next
// waypoint (points closer than 1e-9 m), leaving no line along the velocity.
constexpr double kBrakeMin = 1e-5;
constexpr double kEntryAngle = 1e-3;  // rad: the path's first line must leave along the velocity
// Relative rounding allowance on |v| <= v_max and |a| <= a_max of a start state: a state sampled
// from a trajectory at v_max has |T sd| above v_max by a rounding error (the entry then flies at
// exactly v_max).
constexpr double kStateSlack = 1e-9;
// The two-piece ramp (a start whose one-piece ramp would exceed v_max): the middle acceleration's
// grid steps per a_max, and the bisections that find a piece's speed maximum (to 2^-40 of it).
constexpr int kMidGrid = 8;
constexpr int kPeakBisections = 40;

/** A segment of positive length, or one of the equal parts of a curved segment, with its speed
 *  ceiling and tangential limits. */
struct Plateau {
  uint32_t seg;   // index of the path segment
  uint32_t head;  // first plateau of its move (filled per profile build)
  double off;     // m, arclength inside the segment where the plateau starts
  double s0;      // m, path arclength at its start
  double len;     // m
  double kappa;   // 1/m, curvature bound (0 on lines)
  // 1/m^2, bounds of the curvature rate dkappa/ds that adds to the normal jerk 3 kappa v a_t +
  // dkappa/ds v^3 while the speed rises (the largest dkappa/ds) and while it falls (the largest
  // -dkappa/ds); negative where it takes away: a corner's way out lets the speed rise faster,
  // its way in lets it fall faster. dkappa_bound is the larger, the bound of |dkappa/ds|.
  double dk_up, dk_down;
  double cap;     // m/s, min(v_max, v_limit)
  int near_jump;  // 1 when a boundary of it has a curvature jump (smaller jerk budget)
  uint32_t next;  // on the first plateau of a move: the first plateau after the move
  double scale;   // refinement factor, 1 at first
  // Filled per profile build:
  double level;  // m/s, speed ceiling
  double peak;   // m/s, on the first plateau of a move: the move's peak speed
  // Memo of the move starting here (choose_moves evaluates the same moves between the same
  // speeds many times): each entry holds for the move [this plateau, its key) only, and all are
  // cleared when the limits change (build_profile). Same results as recomputing them.
  mutable uint32_t level_key;                          // move_level
  mutable uint32_t time_key;                           // move_time
  mutable uint32_t reach_key[2];                       // move_reach, forward and backward
  mutable double level_v;                              // m/s
  mutable double reach_v0[2];                          // m/s, its start speed
  mutable double reach_v[2];                           // m/s, its result
  mutable double time_v0, time_v1, time_t, time_peak;  // m/s, m/s, s, m/s
};

/** The boundary before plateau k (k = n_plateaus is the end of the path). */
struct Boundary {
  double cap;    // m/s, geometric cap: 0 at ends, stops and kinks; jump and kink limits
  double v;      // m/s, speed of the profile (filled per build)
  double saved;  // m/s, v before a trial change of the moves (sweep_moves)
};

/** Pieces mode, per boundary: at a segment joint (else 0) |T2 - T1| of the tangents and
 *  |kn2 - kn1| (1/m) of the curvature vectors on either side, the deltas the finite differences
 *  see there. */
struct JointJump {
  double t, k;
};

/** Pieces mode, per plateau: of a Bezier the parameter at its start and end and the segment's
 *  arclength at the first, as the curve summary's cursor found them; its proven curvature parts. */
struct PlateauSpan {
  double u_start, u_end, s_start;
  uint32_t first;  // its first station in PiecesState::stations (curved plateaus)
  uint32_t np;     // its proven curvature parts in PiecesState::parts (rigor_plateau)
};

/** Pieces mode: one station of the curve summary (summarise_curve) of a Bezier, handed down to the
 *  energy integral: the curvature and its rate along s there, the cursor's parameter and
 *  arclength; and the same at the middle of the interval to the next station (station_mids), or
 *  `exact` when the cubic from the two stations misses the middle's curvature. */
struct StationK {
  double k, dk;        // 1/m, 1/m^2
  double u, s;         // -, m (segment-local)
  double sp, dsp;      // m, m: |B'(u)| and its derivative in u
  double mk, mdk, ms;  // 1/m, 1/m^2, m: at the middle parameter of the interval to the next one
  int exact;           // the interval's nodes invert the arclength instead (station_kappa)
};

struct Junction;  // a delta of the trajectory (pieces mode)
struct RigorPart;

/** Pieces mode's arrays (arena). */
struct PiecesState {
  Junction* junctions;   // plateau_cap + max_profile + 2
  JointJump* jumps;      // plateau_cap + 1
  PlateauSpan* spans;    // plateau_cap
  StationK* stations;    // (kStations + kSubMax) per path segment: the curves' summary stations
  uint32_t curve_parts;  // plateaus per curved segment in this run (curve_parts)
  RigorPart* parts;      // kRigorParts per plateau (plateau_cap of them)
  int rigor_ready;       // `parts` is set for this run
  int fine;              // `parts` has the fine bounds (kRigorParts), else the coarse ones
};
/** Pieces mode: proven curvature bounds of one part of a plateau, from path arclength s0 on. */
struct RigorPart {
  double s0;           // m
  double k, up, down;  // 1/m, 1/m^2, 1/m^2 (as Plateau's kappa, dk_up, dk_down)
};

/** One constant-jerk piece of the profile. */
struct Phase {
  double t0;   // s, start time
  double dur;  // s, duration
  double s0;   // m, path arclength at t0
  double v0;   // m/s, path speed at t0
  double a0;   // m/s^2, path acceleration at t0
  double j;    // m/s^3, path jerk
};

}  // namespace
}  // namespace tdo_internal

struct tdo_traj {
  tdo_traj_config cfg;
  tdo_sample* samples;                // max_samples; nullptr with stream_samples
  uint32_t* owner;                    // max_samples: plateau of each sample; nullptr when streamed
  tdo_violation* violations;          // max_violations
  tdo_internal::Plateau* plateaus;    // plateau_cap
  tdo_internal::Boundary* bounds;     // plateau_cap + 1
  uint8_t* hit;                       // plateau_cap: plateau flagged by a violation
  tdo_internal::Phase* phases;        // max_profile
  tdo_internal::PiecesState* pieces;  // pieces mode, else nullptr
  uint32_t plateau_cap;               // max(max_segments, (max_profile - 1) / kPiecesPerPlateau)
  uint32_t n_plateaus;
  uint32_t n_phases;
  // Moving start of the current run (tdo_traj_input.start non-zero): the state and its entry.
  int moving;
  double total;  // m, path length
  tdo_vec3 start_p;
  tdo_start_state start;
  tdo_traj_entry entry;
  // The samples of the last run (tdo_traj_each_sample): their number (0: none), path and dt.
  uint32_t n_last;
  const tdo_path_segment* last_segs;
  double last_dt;
};

namespace tdo_internal {
namespace {

// ---------------------------------------------------------------------------------------------
// Jerk-limited speed changes with zero acceleration at both ends.

/** Durations of a rest-to-rest acceleration change of the speed by dv >= 0. */
struct SCurve {
  double tj;  // s, each jerk ramp
  double ta;  // s, constant acceleration between the ramps
};

SCurve scurve(double dv, double acc, double jerk) {
  SCurve c{0.0, 0.0};
  if (!(dv > 0.0)) return c;
  if (dv * jerk >= acc * acc) {
    c.tj = acc / jerk;
    c.ta = dv / acc - c.tj;
    if (c.ta < 0.0) c.ta = 0.0;
  } else {
    c.tj = sqrt(dv / jerk);
  }
  return c;
}

/** m, distance of the S-curve between speeds a and b (symmetric: the mean speed times the time). */
double scurve_dist(double a, double b, double acc, double jerk) {
  const double lo = dmin(a, b), hi = dmax(a, b);
  const SCurve c = scurve(hi - lo, acc, jerk);
  return 0.5 * (lo + hi) * (2.0 * c.tj + c.ta);
}

// ---------------------------------------------------------------------------------------------
// Bezier cursor (sampling and curve summaries).
//
// Samples and curvature stations walk a segment forward in small steps, so a cubic Bezier is
// followed by a cursor (parameter u and its arclength) that Newton-steps from the previous point
// with 8-point Gauss-Legendre over the short stretch, instead of inverting the arclength from
// u = 0 every time as tdo_segment_eval must. Same curve and same arclength (to ~1e-13 relative).

constexpr double kGlX[4] = {0.1834346424956498049394761, 0.5255324099163289858177390,
                            0.7966664774136267395915539, 0.9602898564975362316835609};
constexpr double kGlW[4] = {0.3626837833783619829651504, 0.3137066458778872873379622,
                            0.2223810344533744705443560, 0.1012285362903762591525314};
constexpr int kCursorSteps = 24;             // Newton steps per sample, at most
constexpr double kCursorPanel = 1.0 / 64.0;  // widest Gauss-Legendre panel in u
constexpr uint32_t kCursorPanels = 64;  // panels per step, at most (covers the whole of [0, 1])
constexpr double kCursorTaylor = 1e-5;  // steps in u below this use the local arclength model

struct BezierCursor {
  tdo_vec3 p[4];  // control points
  tdo_vec3 d[3];  // P[i+1] - P[i]
  tdo_vec3 e[2];  // d[i+1] - d[i]
  tdo_vec3 d3;    // B''' = 6 (e[1] - e[0])
  tdo_vec3 h[3];  // B'(u) = h[0] + u (h[1] + u h[2]), for the arclength quadrature
  double u;       // parameter of the last sample
  double s;       // m, arclength at u
  double len;     // m, segment length (tdo_segment_length)
  uint32_t seg;   // segment index, UINT32_MAX when unset
  // B'(u), B''(u), |B'(u)| and B'.B''/|B'| at the parameter u of the last sample (valid when
  // `have`): the next evaluation starts from there, so it reuses them instead of recomputing.
  tdo_vec3 d1u, d2u;
  double spu, curvu;
  int have;
};

inline tdo_vec3 bez_d1(const BezierCursor& b, double u) {
  const double w = 1.0 - u;
  return mul(add(add(mul(b.d[0], w * w), mul(b.d[1], 2.0 * w * u)), mul(b.d[2], u * u)), 3.0);
}
inline tdo_vec3 bez_d2(const BezierCursor& b, double u) {
  return mul(add(mul(b.e[0], 1.0 - u), mul(b.e[1], u)), 6.0);
}
/** m/(unit u), |B'(u)| in the power basis (Horner): the quadrature's integrand. */
[[maybe_unused]] inline double bez_speed(const BezierCursor& b, double u) {
  return norm(add(b.h[0], mul(add(b.h[1], mul(b.h[2], u)), u)));
}

typedef double V2 __attribute__((vector_size(16)));  // two lanes of IEEE doubles

/** sqrt(q[0]) + sqrt(q[1]); both roots in one instruction where SSE2 has it (same results). */
inline double sqrt_pair_sum(V2 q) {
#if defined(__SSE2__)
  const V2 r = _mm_sqrt_pd(q);
  return r[0] + r[1];
#else
  return sqrt(q[0]) + sqrt(q[1]);
#endif
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define TDO_ARCLEN_AVX 1
typedef double V4 __attribute__((vector_size(32)));  // four lanes of IEEE doubles

/** bez_arclen's panels with AVX: two pairs of nodes side by side in a four-lane vector, the same
 *  lane-wise operations in the same order (no FMA), the same sums: the same bits, half the
 *  instructions (used where the processor has AVX). */
__attribute__((target("avx"), noinline)) double bez_arclen_avx(const BezierCursor& b, double a,
                                                               double h, uint32_t panels) {
  const V4 h0x = {b.h[0].x, b.h[0].x, b.h[0].x, b.h[0].x};
  const V4 h0y = {b.h[0].y, b.h[0].y, b.h[0].y, b.h[0].y};
  const V4 h0z = {b.h[0].z, b.h[0].z, b.h[0].z, b.h[0].z};
  const V4 h1x = {b.h[1].x, b.h[1].x, b.h[1].x, b.h[1].x};
  const V4 h1y = {b.h[1].y, b.h[1].y, b.h[1].y, b.h[1].y};
  const V4 h1z = {b.h[1].z, b.h[1].z, b.h[1].z, b.h[1].z};
  const V4 h2x = {b.h[2].x, b.h[2].x, b.h[2].x, b.h[2].x};
  const V4 h2y = {b.h[2].y, b.h[2].y, b.h[2].y, b.h[2].y};
  const V4 h2z = {b.h[2].z, b.h[2].z, b.h[2].z, b.h[2].z};
  // The nodes m -/+ dx as m + (-dx) (the same IEEE result), the offsets once per call.
  double dx[4];
  for (int i = 0; i < 4; ++i) dx[i] = 0.5 * h * kGlX[i];
  const V4 off0 = {-dx[0], dx[0], -dx[1], dx[1]}, off1 = {-dx[2], dx[2], -dx[3], dx[3]};
  // The pair sums in the order hadd leaves them (nodes 0, 2, 1, 3) and their weights.
  const V4 w = {kGlW[0], kGlW[2], kGlW[1], kGlW[3]};
  double total = 0.0;
  for (uint32_t k = 0; k < panels; ++k) {
    const double m = a + h * (k + 0.5);
    const V4 mv = {m, m, m, m};
    V4 r[2];
    for (int i = 0; i < 2; ++i) {
      const V4 u = mv + (i == 0 ? off0 : off1);
      const V4 x = h0x + (h1x + h2x * u) * u;
      const V4 y = h0y + (h1y + h2y * u) * u;
      const V4 z = h0z + (h1z + h2z * u) * u;
      r[i] = reinterpret_cast<V4>(_mm256_sqrt_pd(reinterpret_cast<__m256d>(x * x + y * y + z * z)));
    }
    // {r0[0] + r0[1], r1[0] + r1[1], r0[2] + r0[3], r1[2] + r1[3]}: the pairs of nodes 0, 2, 1, 3.
    const V4 p = w * reinterpret_cast<V4>(_mm256_hadd_pd(reinterpret_cast<__m256d>(r[0]),
                                                         reinterpret_cast<__m256d>(r[1])));
    double sum = 0.0;
    sum += p[0];
    sum += p[2];
    sum += p[1];
    sum += p[3];
    total += 0.5 * h * sum;
  }
  return total;
}
#endif

/** m, arclength between parameters a and b (signed), panels of at most kCursorPanel. */
double bez_arclen(const BezierCursor& b, double a, double e) {
  const double span = e - a;
  // One panel for the short spans of consecutive samples (ceil gives 1 there and span / 1 is span).
  uint32_t panels = 1u;
  double h = span;
  if (!(fabs(span) <= kCursorPanel)) {
    double n = ceil(fabs(span) / kCursorPanel);
    if (n > kCursorPanels) n = kCursorPanels;
    panels = static_cast<uint32_t>(n);
    h = span / panels;
  }
#if defined(TDO_ARCLEN_AVX)
  if (__builtin_cpu_supports("avx")) return bez_arclen_avx(b, a, h, panels);
#endif
  double total = 0.0;
  // Each pair of nodes m -/+ dx goes through the same operations as bez_speed, side by side in
  // a two-lane vector (lane-wise IEEE arithmetic: the same results as one at a time).
  const V2 h0x = {b.h[0].x, b.h[0].x}, h0y = {b.h[0].y, b.h[0].y}, h0z = {b.h[0].z, b.h[0].z};
  const V2 h1x = {b.h[1].x, b.h[1].x}, h1y = {b.h[1].y, b.h[1].y}, h1z = {b.h[1].z, b.h[1].z};
  const V2 h2x = {b.h[2].x, b.h[2].x}, h2y = {b.h[2].y, b.h[2].y}, h2z = {b.h[2].z, b.h[2].z};
  for (uint32_t k = 0; k < panels; ++k) {
    const double m = a + h * (k + 0.5);
    double sum = 0.0;
    for (int i = 0; i < 4; ++i) {
      const double dx = 0.5 * h * kGlX[i];
      const V2 u = {m - dx, m + dx};
      const V2 x = h0x + (h1x + h2x * u) * u;
      const V2 y = h0y + (h1y + h2y * u) * u;
      const V2 z = h0z + (h1z + h2z * u) * u;
      const V2 q = x * x + y * y + z * z;
      sum += kGlW[i] * sqrt_pair_sum(q);
    }
    total += 0.5 * h * sum;
  }
  return total;
}

void cursor_reset(BezierCursor* c, const tdo_path_segment& seg, uint32_t index) {
  for (int i = 0; i < 4; ++i) c->p[i] = seg.p[i];
  for (int i = 0; i < 3; ++i) c->d[i] = sub(c->p[i + 1], c->p[i]);
  c->h[0] = mul(c->d[0], 3.0);
  for (int i = 0; i < 2; ++i) c->e[i] = sub(c->d[i + 1], c->d[i]);
  c->d3 = mul(sub(c->e[1], c->e[0]), 6.0);
  c->h[1] = mul(c->e[0], 6.0);
  c->h[2] = mul(add(sub(c->d[0], mul(c->d[1], 2.0)), c->d[2]), 3.0);
  c->u = 0.0;
  c->s = 0.0;
  c->len = seg.length;
  c->seg = index;
  c->have = 0;
}

/** Moves the cursor to local arclength s (clamped to [0, len]) from its last position; the
 *  derivatives at the new parameter are left in the cursor. */
void cursor_seek(BezierCursor* c, double s) {
  double u = c->u, at = c->s;
  // Derivatives at u (the same expressions wherever u came from; computed once per u, right
  // where u changes, so none of them is carried across the arclength quadrature's call).
  tdo_vec3 d1 = c->d1u, d2 = c->d2u;
  double sp = c->spu, curv = c->curvu;
  const auto derivs = [&]() {
    d1 = bez_d1(*c, u);
    d2 = bez_d2(*c, u);
    sp = norm(d1);
    curv = sp > 0.0 ? dot(d1, d2) / sp : 0.0;
  };
  if (s <= 0.0) {
    u = 0.0;
    at = 0.0;
    derivs();
  } else if (s >= c->len) {
    u = 1.0;
    at = c->len;
    derivs();
  } else {
    if (c->have == 0) derivs();
    const double tol = 1e-13 * (c->len > 1.0 ? c->len : 1.0);
    double lo = 0.0, hi = 1.0;  // bracket of the solution in u
    for (int it = 0; it < kCursorSteps; ++it) {
      const double r = s - at;
      if (fabs(r) <= tol) break;
      if (r > 0.0)
        lo = u;
      else
        hi = u;
      // Second-order inversion of s(u + du) - s(u) = sp du + (d1.d2 / sp) du^2 / 2.
      double du = sp > 0.0 ? r / sp : 0.5 * (lo + hi) - u;
      if (sp > 0.0) du -= 0.5 * curv * du * du / sp;
      double un = u + du;
      if (!(un > lo && un < hi)) un = 0.5 * (lo + hi);
      if (!(un > lo && un < hi)) break;  // bracket down to adjacent doubles
      du = un - u;
      // Tiny corrections: the local second-order model is exact to ~du^3 (< 1e-15 m); larger
      // steps integrate the speed exactly (Gauss-Legendre).
      if (fabs(du) < kCursorTaylor && sp > 0.0)
        at += du * (sp + 0.5 * curv * du);
      else
        at += bez_arclen(*c, u, un);
      u = un;
      derivs();
    }
  }
  c->u = u;
  c->s = at;
  c->d1u = d1;
  c->d2u = d2;
  c->spu = sp;
  c->curvu = curv;
  c->have = 1;
}

/** Position, unit tangent and dT/ds at the cursor's parameter (after cursor_seek). */
void cursor_state(const BezierCursor& c, tdo_segment_state* st) {
  const double u = c.u, sp = c.spu;
  const tdo_vec3 a0 = lerp(c.p[0], c.p[1], u), a1 = lerp(c.p[1], c.p[2], u),
                 a2 = lerp(c.p[2], c.p[3], u);
  st->p = u <= 0.0 ? c.p[0] : (u >= 1.0 ? c.p[3] : lerp(lerp(a0, a1, u), lerp(a1, a2, u), u));
  if (!(sp > 0.0)) {
    st->t = tdo_vec3{0.0, 0.0, 0.0};
    st->kn = st->t;
    return;
  }
  const tdo_vec3 t = mul(c.d1u, 1.0 / sp);
  st->t = t;
  st->kn = mul(sub(c.d2u, mul(t, dot(c.d2u, t))), 1.0 / (sp * sp));  // dT/ds
}

/** State at local arclength s (clamped to [0, len]) from the cursor's last position. */
void cursor_eval(BezierCursor* c, double s, tdo_segment_state* st) {
  cursor_seek(c, s);
  cursor_state(*c, st);
}

/** kappa and dkappa_ds at the cursor's parameter, as tdo_segment_eval computes them. */
void cursor_curvature(const BezierCursor& c, tdo_segment_state* st) {
  st->kappa = 0.0;
  st->dkappa_ds = 0.0;
  const double u = c.u;
  // cursor_eval left the derivatives at u in the cursor.
  const tdo_vec3 d1 = c.have ? c.d1u : bez_d1(c, u), d2 = c.have ? c.d2u : bez_d2(c, u);
  const tdo_vec3 d3 = c.d3;
  const double sp = c.have ? c.spu : norm(d1);
  if (!(sp > 0.0)) return;
  const tdo_vec3 cr = cross(d1, d2);
  const double cn = norm(cr);
  const double sp3 = sp * sp * sp;
  st->kappa = cn / sp3;
  // kappa = |c| / |B'|^3 with c = B' x B'', c' = B' x B''' (B'' x B'' = 0).
  const tdo_vec3 cp = cross(d1, d3);
  double dcn;  // d|c|/du
  if (cn > 1e-12 * (norm(cp) + sp3 / (c.len > 0.0 ? c.len : 1.0)))
    dcn = dot(cr, cp) / cn;
  else
    dcn = u < 0.5 ? norm(cp) : -norm(cp);  // one-sided limit where kappa = 0
  const double dk_du = dcn / sp3 - 3.0 * cn * dot(d1, d2) / (sp3 * sp * sp);
  st->dkappa_ds = dk_du / sp;
}

// ---------------------------------------------------------------------------------------------
// Path analysis (once per run).

struct Limits {
  double v_max, a_max, j_max, a_lat, dt;
};

/** Curvature and curvature-rate bounds (p's kappa, dk_up, dk_down) of the part [a, a + len] of a
 *  curved segment from `stations` + 1 stations (the segment's kStations shared by its parts: the
 *  same evaluations as for the whole segment; what they miss, the verification finds and
 *  refinement corrects); on Beziers also *span (when not null: its cursor's parameters). */
tdo_status summarise_curve(const tdo_path_segment& seg, double a, double len, uint32_t stations,
                           Plateau* p, PlateauSpan* span, StationK* out) {
  double km = 0.0, hi = -HUGE_VAL, lo = HUGE_VAL, prev = 0.0;
  const double h = len / stations;
  // Beziers: the stations come in order, so a cursor walks them.
  const bool bez = seg.kind == TDO_SEGMENT_BEZIER;
  BezierCursor cursor;
  cursor_reset(&cursor, seg, 0u);
  for (uint32_t i = 0; i <= stations; ++i) {
    tdo_segment_state st;
    const double s = i == stations ? a + len : a + h * i;
    if (bez) {
      cursor_seek(&cursor, s);  // only the curvature is needed here
      cursor_curvature(cursor, &st);
      if (span != nullptr && i == 0u) {
        span->u_start = cursor.u;
        span->s_start = cursor.s;
      }
      if (span != nullptr && i == stations) span->u_end = cursor.u;
    } else if (!tdo_segment_eval(&seg, s, &st)) {
      return TDO_ERR_INVALID_ARGUMENT;
    }
    if (!isfinite(st.kappa) || !isfinite(st.dkappa_ds)) return TDO_ERR_INVALID_ARGUMENT;
    if (out != nullptr) {  // the cursor's numbers on Beziers only (arcs do not use them)
      out[i] = StationK{st.kappa, st.dkappa_ds, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1};
      if (bez) {
        out[i].u = cursor.u;
        out[i].s = cursor.s;
        out[i].sp = cursor.spu;
        out[i].dsp = cursor.curvu;
      }
    }
    km = dmax(km, st.kappa);
    hi = dmax(hi, st.dkappa_ds);
    lo = dmin(lo, st.dkappa_ds);
    if (i > 0 && h > 0.0) {
      hi = dmax(hi, (st.kappa - prev) / h);
      lo = dmin(lo, (st.kappa - prev) / h);
    }
    prev = st.kappa;
  }
  // The margin of the largest |dkappa/ds| widens both ends of [lo, hi].
  const double margin = (kDKappaMargin - 1.0) * dmax(fabs(hi), fabs(lo));
  p->kappa = km * kKappaMargin;
  p->dk_up = hi + margin;
  p->dk_down = margin - lo;
  return TDO_OK;
}

tdo_status validate(const tdo_traj* ctx, const tdo_traj_input* in) {
  if (!positive(in->v_max) || !positive(in->a_max) || !positive(in->j_max) ||
      !positive(in->a_lat_max) || !positive(in->dt))
    return TDO_ERR_INVALID_ARGUMENT;
  if (in->grid != nullptr && !(isfinite(in->clearance) && in->clearance >= 0.0))
    return TDO_ERR_INVALID_ARGUMENT;
  if (in->clearance_proven != 0 && in->clearance_proven != 1) return TDO_ERR_INVALID_ARGUMENT;
  const tdo_path& path = in->path;
  if (path.seg == nullptr || path.n == 0) return TDO_ERR_INVALID_ARGUMENT;
  if (path.n > ctx->cfg.max_segments) return TDO_ERR_PATH_CAPACITY;
  double total = 0.0;
  for (uint32_t i = 0; i < path.n; ++i) {
    const tdo_path_segment& s = path.seg[i];
    if (!segment_shape_ok(s)) return TDO_ERR_INVALID_ARGUMENT;
    if (isnan(s.v_limit) || !(s.v_limit > 0.0)) return TDO_ERR_INVALID_ARGUMENT;
    total += s.length;
  }
  if (!(total > 0.0) || !isfinite(total)) return TDO_ERR_INVALID_ARGUMENT;
  if (in->grid != nullptr && tdo_grid_clearance(in->grid) < 0.0) return TDO_ERR_MAP_NOT_READY;
  return TDO_OK;
}

/** A moving start (docs/design.md s.5): its entry, and a path that begins where the ramp ends
 *  with a line along the velocity at least the braking length long. */
tdo_status validate_start(tdo_traj* ctx, const tdo_traj_input* in) {
  const tdo_start_state& st = in->start;
  ctx->moving = !(zero3(st.v) && zero3(st.a));  // a NaN is not zero: tdo_traj_entry_plan names it
  if (!ctx->moving) return TDO_OK;
  const tdo_status s =
      tdo_traj_entry_plan(in->start_p, &st, in->v_max, in->a_max, in->j_max, &ctx->entry);
  if (s != TDO_OK) return s;
  ctx->start_p = in->start_p;
  ctx->start = st;
  const tdo_path_segment& first = in->path.seg[0];
  if (norm(sub(first.p[0], ctx->entry.p)) > kGapTolerance) return TDO_ERR_INVALID_ARGUMENT;
  if (!(ctx->entry.speed > 0.0)) return TDO_OK;  // the ramp ends at rest: the path starts at rest
  if (first.kind != TDO_SEGMENT_LINE || !(first.length >= ctx->entry.brake))
    return TDO_ERR_INVALID_ARGUMENT;
  const tdo_vec3 d = sub(first.p[1], first.p[0]), v = ctx->entry.v;
  const double angle = atan2(norm(cross(d, v)), dot(d, v));
  return angle <= kEntryAngle ? TDO_OK : TDO_ERR_INVALID_ARGUMENT;
}

/** Parts per curved segment: the most (kSubMax, halved as needed) whose plateaus and profile
 *  pieces fit the capacities, so a smaller max_profile gets a coarser (slower) profile. */
uint32_t curve_parts(const tdo_traj* ctx, const tdo_path& path) {
  uint32_t lines = 0, curves = 0;
  for (uint32_t i = 0; i < path.n; ++i) {
    if (!(path.seg[i].length > 0.0)) continue;
    if (path.seg[i].kind == TDO_SEGMENT_LINE)
      ++lines;
    else
      ++curves;
  }
  uint32_t m = kSubMax;
  for (; m > 1u; m /= 2u) {
    const uint64_t plateaus = lines + static_cast<uint64_t>(m) * curves;
    if (plateaus <= ctx->plateau_cap &&
        kPiecesPerPlateau * plateaus + 1u <= static_cast<uint64_t>(ctx->cfg.max_profile))
      break;
  }
  return m;
}

/** The boundary cap between the previous plateau's segment `prev` and segment `seg`, and whether
 *  the curvature jumps there; TDO_ERR_INVALID_ARGUMENT for a gap. */
tdo_status joint_cap(const tdo_path_segment& prev, const tdo_path_segment& seg, const Limits& lim,
                     int stop, double* cap, int* jump_out, JointJump* joint) {
  tdo_segment_state e, f;
  tdo_segment_eval(&prev, prev.length, &e);
  tdo_segment_eval(&seg, 0.0, &f);
  if (norm(sub(e.p, f.p)) > kGapTolerance) return TDO_ERR_INVALID_ARGUMENT;
  double b = stop ? 0.0 : HUGE_VAL;
  // Tangent kink: a velocity jump v*theta, FD acceleration v*theta/dt, FD jerk v*theta/dt^2.
  const double theta = atan2(norm(cross(e.t, f.t)), dot(e.t, f.t));
  if (theta > kKinkStop) {
    b = 0.0;
  } else if (theta > 0.0) {
    b = dmin(b, kKinkShare * dmin(lim.j_max * lim.dt * lim.dt, lim.a_max * lim.dt) / theta);
  }
  // Curvature jump: acceleration jumps by v^2 dkappa; the third difference spreads that delta
  // with a kernel whose peak is 0.75 / dt.
  const double jump = norm(sub(e.kn, f.kn));
  if (joint != nullptr) *joint = JointJump{norm(sub(f.t, e.t)), jump};
  *jump_out = 0;
  if (0.75 * lim.v_max * lim.v_max * jump / lim.dt > (1.0 - kLineShare) * lim.j_max) {
    b = dmin(b, sqrt(kJumpShare * lim.j_max * lim.dt / jump));
    *jump_out = 1;
  }
  *cap = b;
  return TDO_OK;
}

/** Plateaus (curved segments in `parts` equal parts), boundary caps and the curvature-jump flags.
 */
tdo_status analyse(tdo_traj* ctx, const tdo_traj_input* in, const Limits& lim) {
  const tdo_path& path = in->path;
  const uint32_t parts = curve_parts(ctx, path);
  if (ctx->pieces != nullptr) ctx->pieces->curve_parts = parts;
  uint32_t n = 0, stations = 0;
  double s0 = 0.0;
  int stop_pending = 0;  // a zero-length segment with stop_at_end before the next plateau
  for (uint32_t i = 0; i < path.n; ++i) {
    const tdo_path_segment& seg = path.seg[i];
    if (!(seg.length > 0.0)) {
      stop_pending |= seg.stop_at_end;
      continue;
    }
    const uint32_t m = seg.kind == TDO_SEGMENT_LINE ? 1u : parts;
    const double part = seg.length / m;
    for (uint32_t j = 0; j < m; ++j) {
      if (n >= ctx->plateau_cap) return TDO_ERR_PATH_CAPACITY;  // curve_parts prevents it
      Plateau& p = ctx->plateaus[n];
      memset(&p, 0, sizeof(p));
      p.seg = i;
      p.off = part * j;
      p.s0 = s0 + p.off;
      p.len = j + 1u == m ? seg.length - p.off : part;
      p.cap = dmin(lim.v_max, seg.v_limit);
      p.scale = 1.0;
      if (seg.kind != TDO_SEGMENT_LINE) {
        PlateauSpan* span = nullptr;
        StationK* out = nullptr;
        if (ctx->pieces != nullptr) {  // the stations' curvatures go on to the energy integral
          span = &ctx->pieces->spans[n];
          span->first = stations;
          out = ctx->pieces->stations + stations;
          stations += kStations / m + 1u;  // at most kStations + m per curve: the array's stride
        }
        const tdo_status st = summarise_curve(seg, p.off, p.len, kStations / m, &p, span, out);
        if (st != TDO_OK) return st;
      }
      Boundary& b = ctx->bounds[n];
      b.cap = HUGE_VAL;  // inside a segment: no kink, no curvature jump
      JointJump* jj = ctx->pieces != nullptr ? &ctx->pieces->jumps[n] : nullptr;
      if (jj != nullptr) *jj = JointJump{0.0, 0.0};
      if (n == 0) {
        b.cap = ctx->moving ? ctx->entry.speed : 0.0;  // start at rest, or at the entry's speed
      } else if (j == 0) {
        const tdo_path_segment& prev = path.seg[ctx->plateaus[n - 1].seg];
        int jump = 0;
        const tdo_status st =
            joint_cap(prev, seg, lim, prev.stop_at_end || stop_pending, &b.cap, &jump, jj);
        if (st != TDO_OK) return st;
        if (jump) {
          ctx->plateaus[n - 1].near_jump = 1;
          p.near_jump = 1;
        }
      }
      ++n;
    }
    stop_pending = 0;
    s0 += seg.length;
  }
  ctx->bounds[n].cap = 0.0;  // end at rest
  ctx->n_plateaus = n;
  ctx->total = s0;
  return TDO_OK;
}

// ---------------------------------------------------------------------------------------------
// Profile (per refinement round).

/** 1/m^2, the bound of |dkappa/ds| on a plateau (0 on lines). */
inline double dkappa_bound(const Plateau& p) { return dmax(p.dk_up, p.dk_down); }

/** Tangential acceleration and jerk limits of a plateau for speeds up to v (<= its ceiling) while
 *  the speed rises (falling 0) or falls (1): what the budgets leave at v, so a move whose peak is
 *  below the ceiling may change its speed faster. On a curve the jerk is
 *  (j_t - kappa^2 v^3) T + (3 kappa v a_t + dkappa/ds v^3) N; at v its normal part gets the share
 *  sn of jb that full acceleration needs (at most all but kShareFloor, at least the curvature
 *  rate's term of either sign, which the acceleration does not cancel), the tangential part the
 *  rest (squares summing to 1). Both limits fall as v grows, so the limits at a move's peak hold
 *  at every speed of the move. */
void plateau_at(const Plateau& p, const Limits& lim, double v, int falling, double* acc,
                double* jerk) {
  const double jb =
      (p.near_jump ? kJumpJerk : (p.kappa > 0.0 ? kCurveJerk : kLineShare)) * lim.j_max;
  if (!(p.kappa > 0.0)) {
    *acc = kLineAcc * lim.a_max * p.scale;
    *jerk = jb * p.scale;
    return;
  }
  // The curvature rate's part of the normal jerk in this direction (negative: it takes away).
  const double k = p.kappa, dk = falling ? p.dk_down : p.dk_up;
  const double v3 = v * v * v;
  const double lat = k * v * v;
  const double circle = kAccCircle * lim.a_max;
  const double a_cap = dmin(kLineShare * lim.a_max, sqrt(dmax(0.0, circle * circle - lat * lat)));
  const double rate = dkappa_bound(p) * v3 / jb;
  const double sn =
      dmin(sqrt(1.0 - kShareFloor * kShareFloor), (dk * v3 + 3.0 * k * v * a_cap) / jb);
  const double st = sqrt(dmax(0.0, 1.0 - dmax(sn, rate) * dmax(sn, rate)));
  // Near the ceiling little or nothing is left: a speed change there takes (almost) forever.
  *jerk = dmax(kLeftFloor * jb, st * jb - k * k * v3) * p.scale;
  double a = a_cap;
  if (v > 0.0) a = dmin(a, (sn * jb - dk * v3) / (3.0 * k * v));
  *acc = dmax(kLeftFloor * lim.a_max, a) * p.scale;
}

/** Ceiling of each plateau under its refinement scale (its tangential limits at a speed:
 *  plateau_at). Cruising on a curve, the jerk is -kappa^2 v^3 T + dkappa/ds v^3 N: at the ceiling
 *  it is at most kJerkGeo of jb, the rest is left for speed changes. The tangential acceleration
 *  shares a_max with the lateral one (a_t^2 + (kappa v^2)^2 <= (kAccCircle a_max)^2). */
void plateau_limits(Plateau* p, const Limits& lim) {
  const double jb =
      (p->near_jump ? kJumpJerk : (p->kappa > 0.0 ? kCurveJerk : kLineShare)) * lim.j_max;
  double level = p->cap;
  p->level_key = p->reach_key[0] = p->reach_key[1] = p->time_key = UINT32_MAX;
  if (p->kappa > 0.0) {
    const double k = p->kappa, dk = dkappa_bound(*p);
    // Lateral acceleration kappa v^2 <= min(a_lat, kCurveAccLat a_max).
    level = dmin(level, sqrt(dmin(lim.a_lat, kCurveAccLat * lim.a_max) / k));
    // Curvature terms of the jerk at cruise: v^3 |(kappa^2, dkappa/ds)| <= kJerkGeo jb.
    level = dmin(level, cbrt(kJerkGeo * jb / sqrt(k * k * k * k + dk * dk)));
  }
  p->level = level * p->scale;
}

/** Appends a phase; false when the profile capacity is exhausted. */
bool push_phase(tdo_traj* ctx, double t0, double dur, double s0, double v0, double a0, double j) {
  if (ctx->n_phases >= ctx->cfg.max_profile) return false;
  ctx->phases[ctx->n_phases++] = Phase{t0, dur, s0, v0, a0, j};
  return true;
}

/** Running state of the profile under construction. */
struct Cursor {
  double t, s, v, a;
};

bool advance(tdo_traj* ctx, Cursor* c, double dur, double j) {
  if (!(dur > 0.0)) return true;
  if (!push_phase(ctx, c->t, dur, c->s, c->v, c->a, j)) return false;
  c->s += dur * (c->v + dur * (0.5 * c->a + dur * j / 6.0));
  c->v += dur * (c->a + 0.5 * dur * j);
  c->a += dur * j;
  c->t += dur;
  return true;
}

/** S-curve from c->v to v1 (acceleration 0 at both ends). */
bool speed_change(tdo_traj* ctx, Cursor* c, double v1, double acc, double jerk) {
  const double sign = v1 >= c->v ? 1.0 : -1.0;
  const SCurve sc = scurve(fabs(v1 - c->v), acc, jerk);
  if (!advance(ctx, c, sc.tj, sign * jerk)) return false;
  if (!advance(ctx, c, sc.ta, 0.0)) return false;
  if (!advance(ctx, c, sc.tj, -sign * jerk)) return false;
  c->v = v1;  // remove rounding: the S-curve ends exactly at v1 with zero acceleration
  c->a = 0.0;
  return true;
}

/** Zero-speed dwell so that a stop falls exactly on a sample time. */
bool align_stop(tdo_traj* ctx, Cursor* c, double dt) {
  const double k = ceil(c->t / dt - kAlignSlack);
  const double dwell = k * dt - c->t;
  c->v = 0.0;
  c->a = 0.0;
  if (!(dwell > 0.0)) return true;
  return advance(ctx, c, dwell, 0.0);
}

/** A move: the plateaus [k, next) flown as one accelerate / cruise / decelerate profile with zero
 *  acceleration only at its ends, so the acceleration runs on through the boundaries inside it.
 *  Its cruise speed stays under every plateau's ceiling; each of its two speed changes has the
 *  lowest acceleration and jerk limits of the plateaus it covers, at its top speed (move_ramp). */
struct Ramp {
  double acc;   // m/s^2, tangential acceleration limit
  double jerk;  // m/s^3, tangential jerk limit
  double dist;  // m, length of the S-curve
};

/** m/s, the ceiling of the move starting at plateau k: the lowest of its plateaus' and of its
 *  inner boundaries' caps. */
double move_level(const tdo_traj* ctx, uint32_t k) {
  const Plateau* pl = ctx->plateaus;
  if (pl[k].level_key == pl[k].next) return pl[k].level_v;
  double level = HUGE_VAL;
  for (uint32_t i = k; i < pl[k].next; ++i) {
    level = dmin(level, pl[i].level);
    // The cap of an inner boundary (a tiny tangent kink), scaled with its plateaus.
    if (i > k) level = dmin(level, ctx->bounds[i].cap * dmin(pl[i - 1u].scale, pl[i].scale));
  }
  pl[k].level_key = pl[k].next;
  pl[k].level_v = level;
  return level;
}

/** m, length of the move starting at plateau k. */
double move_len(const tdo_traj* ctx, uint32_t k) {
  const uint32_t e = ctx->plateaus[k].next;
  return e < ctx->n_plateaus ? ctx->plateaus[e].s0 - ctx->plateaus[k].s0
                             : ctx->total - ctx->plateaus[k].s0;
}

/** The S-curve between speeds a and b at the start (from_end 0) or at the end (1) of the move
 *  starting at plateau k: plateaus are taken in from that end until they cover its length under
 *  their limits at max(a, b) (the length only grows as plateaus join; at most the move's). A
 *  length beyond the move's means the change does not fit. */
Ramp move_ramp(const tdo_traj* ctx, const Limits& lim, uint32_t k, double a, double b,
               int from_end) {
  const Plateau* pl = ctx->plateaus;
  const uint32_t e = pl[k].next;
  const double top = dmax(a, b);
  Ramp r{HUGE_VAL, HUGE_VAL, 0.0};
  double covered = 0.0;
  for (uint32_t q = 0; q < e - k; ++q) {
    const Plateau& p = pl[from_end ? e - 1u - q : k + q];
    double acc, jerk;
    plateau_at(p, lim, dmin(top, p.level), from_end, &acc, &jerk);
    r.acc = dmin(r.acc, acc);
    r.jerk = dmin(r.jerk, jerk);
    covered += p.len;
    r.dist = scurve_dist(a, b, r.acc, r.jerk);
    if (r.dist <= covered) break;
  }
  return r;
}

/** Whether a and b are the same double, bit for bit (the memo keys of the moves). */
inline bool same(double a, double b) { return memcmp(&a, &b, sizeof(double)) == 0; }

/** m/s, highest speed in [v0, ceiling] that the move starting at plateau k can reach from v0
 *  with one S-curve at its start (from_end 0: forward) or, speeds read backwards, at its end
 *  (from_end 1). The length grows with the speed, so bisection finds it. */
double move_reach(const tdo_traj* ctx, const Limits& lim, uint32_t k, double v0, int from_end) {
  const Plateau& p = ctx->plateaus[k];
  if (p.reach_key[from_end] == p.next && same(p.reach_v0[from_end], v0)) return p.reach_v[from_end];
  const double cap = move_level(ctx, k), len = move_len(ctx, k);
  double v = cap;
  const auto lhs = [&](double v1) { return move_ramp(ctx, lim, k, v0, v1, from_end).dist; };
  if (cap > v0) {
    const double at_cap = lhs(cap);
    if (!(at_cap <= len)) v = bisect_highest(v0, cap, len, at_cap, lhs);  // v0 always reachable
  }
  p.reach_key[from_end] = p.next;
  p.reach_v0[from_end] = v0;
  p.reach_v[from_end] = v;
  return v;
}

/** m/s, the highest peak in [max(v0, v1), ceiling] of the move starting at plateau k from v0 to
 *  v1: its S-curve up at the start and its S-curve down at the end fit its length. Those two
 *  S-curves at the peak into *up and *down (at the ceiling they are the ones just tested). */
double move_peak(const tdo_traj* ctx, const Limits& lim, uint32_t k, double v0, double v1, Ramp* up,
                 Ramp* down) {
  const double len = move_len(ctx, k);
  const auto lhs = [&](double vp) {
    return move_ramp(ctx, lim, k, v0, vp, 0).dist + move_ramp(ctx, lim, k, vp, v1, 1).dist;
  };
  const double hi = move_level(ctx, k);
  *up = move_ramp(ctx, lim, k, v0, hi, 0);
  *down = move_ramp(ctx, lim, k, hi, v1, 1);
  const double at_hi = up->dist + down->dist;
  if (at_hi <= len) return hi;
  const double vp = bisect_highest(dmax(v0, v1), hi, len, at_hi, lhs);
  *up = move_ramp(ctx, lim, k, v0, vp, 0);
  *down = move_ramp(ctx, lim, k, vp, v1, 1);
  return vp;
}

/** s, duration of an S-curve between speeds a and b. */
double scurve_time(double a, double b, double acc, double jerk) {
  const SCurve c = scurve(fabs(b - a), acc, jerk);
  return 2.0 * c.tj + c.ta;
}

/** m/s, the highest speed boundary k may have: its cap, scaled with the neighbouring plateaus,
 *  and the ceilings of the moves on either side. */
double boundary_top(const tdo_traj* ctx, uint32_t k) {
  const Plateau* pl = ctx->plateaus;
  double scale = 1.0, v = HUGE_VAL;
  if (k > 0) {
    scale = dmin(scale, pl[k - 1].scale);
    v = dmin(v, move_level(ctx, pl[k - 1].head));
  }
  if (k < ctx->n_plateaus) {
    scale = dmin(scale, pl[k].scale);
    v = dmin(v, move_level(ctx, pl[k].head));
  }
  return dmin(v, ctx->bounds[k].cap * scale);
}

/** s, flight time of the move starting at plateau k between its boundary speeds; its peak
 *  speed (move_peak) into *peak. */
double move_time(const tdo_traj* ctx, const Limits& lim, uint32_t k, double* peak) {
  const Boundary* bd = ctx->bounds;
  const Plateau& p = ctx->plateaus[k];
  const double v0 = bd[k].v, v1 = bd[p.next].v;
  if (p.time_key == p.next && same(p.time_v0, v0) && same(p.time_v1, v1)) {
    *peak = p.time_peak;
    return p.time_t;
  }
  Ramp up, down;
  const double vp = move_peak(ctx, lim, k, v0, v1, &up, &down);
  const double len = move_len(ctx, k), ramps = up.dist + down.dist;
  double t = scurve_time(v0, vp, up.acc, up.jerk) + scurve_time(vp, v1, down.acc, down.jerk);
  if (len > ramps && vp > 0.0) t += (len - ramps) / vp;
  p.time_key = p.next;
  p.time_v0 = v0;
  p.time_v1 = v1;
  p.time_t = t;
  p.time_peak = vp;
  *peak = vp;
  return t;
}

/** Speeds of the boundaries strictly between the moves from plateau h to plateau e (h and e are
 *  move boundaries) by forward and backward passes: every pair of neighbouring move ends is
 *  joined by one S-curve inside the move (the backward pass only lowers speeds that exceed what
 *  the next one allows, which keeps the forward condition). With `keep` the speeds at h and e
 *  stay and the result is HUGE_VAL when they do not fit; otherwise they are lowered as needed.
 *  Returns the flight time of those moves. */
double window_speeds(tdo_traj* ctx, const Limits& lim, uint32_t h, uint32_t e, int keep) {
  Plateau* pl = ctx->plateaus;
  Boundary* bd = ctx->bounds;
  for (uint32_t k = pl[h].next; k < e; k = pl[k].next) bd[k].v = boundary_top(ctx, k);
  if (keep && (bd[h].v > boundary_top(ctx, h) || bd[e].v > boundary_top(ctx, e))) return HUGE_VAL;
  for (uint32_t k = h; k < e; k = pl[k].next) {
    const uint32_t x = pl[k].next;
    const double r = move_reach(ctx, lim, k, bd[k].v, 0);
    if (keep && x == e && bd[x].v > r) return HUGE_VAL;
    bd[x].v = dmin(bd[x].v, r);
  }
  for (uint32_t x = e; x > h;) {
    const uint32_t k = pl[x - 1].head;
    const double r = move_reach(ctx, lim, k, bd[x].v, 1);
    if (keep && k == h && bd[k].v > r) return HUGE_VAL;
    bd[k].v = dmin(bd[k].v, r);
    x = k;
  }
  double total = 0.0;
  for (uint32_t k = h; k < e; k = pl[k].next) total += move_time(ctx, lim, k, &pl[k].peak);
  return total;
}

/** Boundary speeds of all moves (window_speeds over the whole path, from rest or the entry
 *  speed to rest); returns the flight time. */
double move_speeds(tdo_traj* ctx, const Limits& lim) {
  const uint32_t n = ctx->n_plateaus;
  ctx->bounds[0].v = boundary_top(ctx, 0);
  ctx->bounds[n].v = boundary_top(ctx, n);
  return window_speeds(ctx, lim, 0, n, 0);
}

/** Splits the move holding boundary k (inside it) at k; returns its first plateau. */
uint32_t split_move(Plateau* pl, uint32_t k) {
  const uint32_t h = pl[k].head, e = pl[h].next;
  pl[h].next = k;
  pl[k].next = e;
  for (uint32_t i = k; i < e; ++i) pl[i].head = k;
  return h;
}

/** Joins the move ending at boundary k with the one starting there. */
void join_moves(Plateau* pl, uint32_t k) {
  const uint32_t h = pl[k - 1u].head, e = pl[k].next;
  pl[h].next = e;
  for (uint32_t i = k; i < e; ++i) pl[i].head = h;
}

/** One sweep over the segment joints: splits a move at an inner joint (`split`) or joins two
 *  moves at a joint that allows it (`free`), only where the flight of the moves it touches and
 *  kMoveWindow moves on either side gets shorter (the speeds at the ends of that window kept);
 *  2 evaluations of that window per joint (the speeds before the change are restored from a copy).
 */
template <typename Free>
void sweep_moves(tdo_traj* ctx, const Limits& lim, int split, const Free& free) {
  const uint32_t n = ctx->n_plateaus;
  Plateau* pl = ctx->plateaus;
  for (uint32_t k = 1; k < n; ++k) {
    const bool inner = pl[k].head != k;
    if (pl[k].seg == pl[k - 1u].seg || (split ? !inner : (inner || !free(k)))) continue;
    uint32_t a = pl[k - 1u].head, b = pl[pl[k].head].next;
    for (uint32_t w = 0; w < kMoveWindow && a > 0; ++w) a = pl[a - 1u].head;
    for (uint32_t w = 0; w < kMoveWindow && b < n; ++w) b = pl[b].next;
    const double before = window_speeds(ctx, lim, a, b, 1);
    for (uint32_t i = a; i <= b; ++i) ctx->bounds[i].saved = ctx->bounds[i].v;
    if (split)
      split_move(pl, k);
    else
      join_moves(pl, k);
    if (window_speeds(ctx, lim, a, b, 1) < before) continue;
    if (split)
      join_moves(pl, k);
    else
      split_move(pl, k);
    for (uint32_t i = a; i <= b; ++i) ctx->bounds[i].v = ctx->bounds[i].saved;
  }
}

/** Moves: at first one per stretch between boundaries that need zero acceleration (stops,
 *  tangent kinks above kKinkStop, curvature jumps; a moving start's braking line keeps its own
 *  move, it must stop from the start speed), then a sweep that splits them at segment joints and
 *  one that joins them again, each change kept where it shortens the flight. Leaves the boundary
 *  speeds of the chosen moves (move_speeds). */
void choose_moves(tdo_traj* ctx, const Limits& lim) {
  const uint32_t n = ctx->n_plateaus;
  Plateau* pl = ctx->plateaus;
  const uint32_t first = ctx->moving && ctx->entry.speed > 0.0 ? 2u : 1u;
  const auto free = [&](uint32_t k) {
    return k >= first && ctx->bounds[k].cap > 0.0 && !(pl[k - 1u].near_jump && pl[k].near_jump);
  };
  uint32_t head = 0;
  for (uint32_t k = 0; k < n; ++k) {
    if (k > 0 && !free(k)) head = k;
    pl[k].head = head;
  }
  for (uint32_t k = n; k > 0; --k) pl[k - 1u].next = k == n || !free(k) ? k : pl[k].next;
  move_speeds(ctx, lim);
  sweep_moves(ctx, lim, 1, free);
  sweep_moves(ctx, lim, 0, free);
  move_speeds(ctx, lim);
}

/** Builds the constant-jerk pieces. TDO_ERR_SAMPLE_CAPACITY when they do not fit. */
tdo_status build_profile(tdo_traj* ctx, const Limits& lim) {
  const uint32_t n = ctx->n_plateaus;
  Plateau* pl = ctx->plateaus;
  Boundary* bd = ctx->bounds;
  for (uint32_t k = 0; k < n; ++k) plateau_limits(&pl[k], lim);
  choose_moves(ctx, lim);
  // A moving start keeps its speed: the braking line (tdo_traj_entry.brake) lets every later
  // boundary be reached from it, so a lower speed here means the path broke that promise.
  if (ctx->moving && n > 0 && !(bd[0].v >= ctx->entry.speed)) return TDO_ERR_INFEASIBLE;
  ctx->n_phases = 0;
  Cursor c{ctx->moving ? ctx->entry.ramp : 0.0, 0.0, 0.0, 0.0};
  for (uint32_t k = 0; k < n; k = pl[k].next) {
    Plateau& p = pl[k];
    const double v0 = bd[k].v, v1 = bd[p.next].v;
    move_time(ctx, lim, k, &p.peak);
    const Ramp up = move_ramp(ctx, lim, k, v0, p.peak, 0);
    const Ramp down = move_ramp(ctx, lim, k, p.peak, v1, 1);
    c.s = p.s0;  // anchor every move at its exact start
    c.v = v0;
    c.a = 0.0;
    if (!speed_change(ctx, &c, p.peak, up.acc, up.jerk)) return TDO_ERR_SAMPLE_CAPACITY;
    const double cruise = move_len(ctx, k) - up.dist - down.dist;
    if (cruise > 0.0 && p.peak > 0.0 && !advance(ctx, &c, cruise / p.peak, 0.0))
      return TDO_ERR_SAMPLE_CAPACITY;
    if (!speed_change(ctx, &c, v1, down.acc, down.jerk)) return TDO_ERR_SAMPLE_CAPACITY;
    if (!(v1 > 0.0) && !align_stop(ctx, &c, lim.dt)) return TDO_ERR_SAMPLE_CAPACITY;
  }
  if (ctx->n_phases == 0) return TDO_ERR_INFEASIBLE;  // cannot happen for a positive length
  return TDO_OK;
}

// ---------------------------------------------------------------------------------------------
// Sampling: Beziers by the cursor, lines and arcs by tdo_segment_eval.

/** Samples of the current profile at dt; TDO_ERR_SAMPLE_CAPACITY beyond max_samples. */
tdo_status sample_count(const tdo_traj* ctx, double dt, uint32_t* n_out) {
  const Phase& last = ctx->phases[ctx->n_phases - 1];
  const double t_end = last.t0 + last.dur;
  const double steps = ceil(t_end / dt - kAlignSlack);
  if (!(steps + 1.0 <= static_cast<double>(ctx->cfg.max_samples))) return TDO_ERR_SAMPLE_CAPACITY;
  *n_out = static_cast<uint32_t>(steps) + 1u;
  return TDO_OK;
}

/** Sample of a moving start's entry ramp at t (< ramp): its first piece from the start state,
 *  its second (if any) from the knot; sample 0 is the start state itself. */
void entry_sample(const tdo_traj* ctx, double t, uint32_t i, tdo_sample* out) {
  const tdo_traj_entry& e = ctx->entry;
  const bool first = t < e.knot;
  const tdo_vec3 p0 = first ? ctx->start_p : e.knot_p, v0 = first ? ctx->start.v : e.knot_v;
  const tdo_vec3 a0 = first ? ctx->start.a : e.knot_a, j = first ? e.jerk : e.jerk2;
  out->t = t;
  if (i == 0u) {  // exactly the caller's state
    out->p = ctx->start_p;
    out->v = ctx->start.v;
    out->a = ctx->start.a;
    return;
  }
  if (!first) t -= e.knot;
  out->p = add(p0, mul(add(v0, mul(add(mul(a0, 0.5), mul(j, t / 6.0)), t)), t));
  out->v = add(v0, mul(add(a0, mul(j, 0.5 * t)), t));
  out->a = add(a0, mul(j, t));
}

/** Generates samples 0, 1, ..., n-1 of the current profile in order (the only sampling code). */
struct Sampler {
  const tdo_traj* ctx;
  const tdo_path_segment* segs;
  double dt;
  uint32_t n;
  uint32_t i;  // next sample
  uint32_t ph, q;
  // Where the next phase and the next plateau begin (phases[ph + 1].t0, plateaus[q + 1].s0; only
  // read while there is one): the walk's tests without reloading them for every sample.
  double next_t0, next_s0;
  BezierCursor cursor;
  // The line segment of the last sample (lseg, UINT32_MAX when unset): its end points, direction
  // d, length |d| and unit tangent, as tdo_segment_eval computes them for every sample.
  uint32_t lseg;
  tdo_vec3 la, ld, lt;
  double ln;
};

/** tdo_segment_eval of line segment `index` at local arclength s in [0, length], with the
 *  per-segment quantities computed once (same expressions, same results). */
__attribute__((always_inline)) inline void line_eval(Sampler* g, uint32_t index, double s,
                                                     tdo_segment_state* st) {
  const tdo_path_segment& seg = g->segs[index];
  if (g->lseg != index) {
    g->lseg = index;
    g->la = seg.p[0];
    g->ld = sub(seg.p[1], g->la);
    g->ln = norm(g->ld);
    g->lt = g->ln > 0.0 ? mul(g->ld, 1.0 / g->ln) : tdo_vec3{0.0, 0.0, 0.0};
  }
  st->kn = tdo_vec3{0.0, 0.0, 0.0};
  st->kappa = 0.0;
  st->dkappa_ds = 0.0;
  if (s >= seg.length)
    st->p = seg.p[1];
  else if (s <= 0.0 || !(g->ln > 0.0))
    st->p = seg.p[0];
  else
    st->p = add(g->la, mul(g->ld, s / g->ln));
  st->t = g->lt;
}

void sampler_start(Sampler* g, const tdo_traj* ctx, const tdo_path_segment* segs, double dt,
                   uint32_t n) {
  g->ctx = ctx;
  g->segs = segs;
  g->dt = dt;
  g->n = n;
  g->i = 0;
  g->ph = 0;
  g->q = 0;
  g->next_t0 = ctx->n_phases > 1u ? ctx->phases[1].t0 : 0.0;
  g->next_s0 = ctx->n_plateaus > 1u ? ctx->plateaus[1].s0 : 0.0;
  memset(&g->cursor, 0, sizeof(g->cursor));
  g->cursor.seg = 0xFFFFFFFFu;
  g->lseg = 0xFFFFFFFFu;
}

/** Samples g->i, ..., g->i + count - 1 (< g->n) into out[0..count) and the plateaus they lie on
 *  into owner[0..count): the sampler's state in locals across the run (one sample per call for
 *  the streamed window, the whole run for the stored samples). */
void sampler_fill(Sampler* g, tdo_sample* out, uint32_t* owner, uint32_t count) {
  const tdo_traj* ctx = g->ctx;
  const tdo_path_segment* segs = g->segs;
  const uint32_t n = g->n, n_phases = ctx->n_phases, n_plateaus = ctx->n_plateaus;
  const double dt = g->dt;
  uint32_t ph = g->ph, qq = g->q;
  double next_t0 = g->next_t0, next_s0 = g->next_s0;
  for (uint32_t k = 0; k < count; ++k) {
    const uint32_t i = g->i + k;
    const double t = dt * i;
    if (ctx->moving && (i == 0u || t < ctx->entry.ramp) && i + 1u < n) {
      entry_sample(ctx, t, i, &out[k]);
      owner[k] = 0u;
      continue;
    }
    while (ph + 1u < n_phases && next_t0 <= t) {  // bounded by n_phases
      ++ph;
      if (ph + 1u < n_phases) next_t0 = ctx->phases[ph + 1u].t0;
    }
    const Phase& f = ctx->phases[ph];
    double tau = t - f.t0;
    if (tau < 0.0) tau = 0.0;
    if (tau > f.dur) tau = f.dur;
    double s = f.s0 + tau * (f.v0 + tau * (0.5 * f.a0 + tau * f.j / 6.0));
    double sd = f.v0 + tau * (f.a0 + 0.5 * tau * f.j);
    double sdd = f.a0 + tau * f.j;
    if (i + 1u == n) {  // exactly at the goal, at rest
      s = ctx->total;
      sd = 0.0;
      sdd = 0.0;
    }
    if (sd < 0.0) sd = 0.0;                         // rounding at the end of a deceleration
    while (qq + 1u < n_plateaus && s >= next_s0) {  // bounded by n_plateaus
      ++qq;
      if (qq + 1u < n_plateaus) next_s0 = ctx->plateaus[qq + 1u].s0;
    }
    const uint32_t q = qq;
    const Plateau& p = ctx->plateaus[q];
    double local = s - p.s0;
    if (local < 0.0) local = 0.0;
    if (local > p.len) local = p.len;
    local += p.off;
    const tdo_path_segment& seg = segs[p.seg];
    if (i + 1u == n) local = seg.length;  // exactly at the goal
    tdo_segment_state st;
    if (seg.kind == TDO_SEGMENT_BEZIER) {
      if (g->cursor.seg != p.seg) cursor_reset(&g->cursor, seg, p.seg);
      cursor_eval(&g->cursor, local, &st);
    } else if (seg.kind == TDO_SEGMENT_LINE) {
      line_eval(g, p.seg, local, &st);
    } else {
      tdo_segment_eval(&seg, local, &st);
    }
    out[k].t = t;
    out[k].p = st.p;
    out[k].v = mul(st.t, sd);
    out[k].a = add(mul(st.t, sdd), mul(st.kn, sd * sd));
    owner[k] = q;
  }
  g->i += count;
  g->ph = ph;
  g->q = qq;
  g->next_t0 = next_t0;
  g->next_s0 = next_s0;
}

/** Sample g->i (< g->n) and the plateau it lies on; then the next one. */
void sampler_next(Sampler* g, tdo_sample* out, uint32_t* owner) { sampler_fill(g, out, owner, 1u); }

/** Stored samples: all of them into the context's arrays. */
void sample(tdo_traj* ctx, const tdo_traj_input* in, const Limits& lim, uint32_t n) {
  Sampler g;
  sampler_start(&g, ctx, in->path.seg, lim.dt, n);
  sampler_fill(&g, ctx->samples, ctx->owner, n);
}

/** Sample source of the verification: the stored arrays. */
struct StoredSamples {
  static constexpr bool kRandomAccess = true;  // any sample, in any order (clearance_pass)
  const tdo_sample* samples;
  const uint32_t* owners;
  void rewind() {}
  const tdo_sample& at(uint32_t i) { return samples[i]; }
  uint32_t owner(uint32_t i) { return owners[i]; }
};

/** Sample source of the verification without storage: a generator and a window of the last kWindow
 *  samples. The verification reads samples at most 3 behind and 2 ahead of its position, so every
 *  sample is generated once per pass. */
struct StreamedSamples {
  static constexpr uint32_t kWindow = 8;        // a power of two > 3 + 1 + 2
  static constexpr bool kRandomAccess = false;  // in order only (clearance_pass)
  Sampler gen;
  const tdo_traj* ctx;
  const tdo_path_segment* segs;
  double dt;
  uint32_t n;
  tdo_sample ring[kWindow];
  uint32_t owners[kWindow];
  void rewind() { sampler_start(&gen, ctx, segs, dt, n); }
  void reach(uint32_t i) {
    while (gen.i <= i && gen.i < n) {  // bounded by n
      const uint32_t k = gen.i & (kWindow - 1u);
      sampler_next(&gen, &ring[k], &owners[k]);
    }
  }
  const tdo_sample& at(uint32_t i) {
    reach(i);
    return ring[i & (kWindow - 1u)];
  }
  uint32_t owner(uint32_t i) {
    reach(i);
    return owners[i & (kWindow - 1u)];
  }
};

// ---------------------------------------------------------------------------------------------
// Verification (eq. 15-19) on the sampled positions only.

struct Report {
  tdo_feasibility* rep;
  uint32_t cap;
  tdo_violation* list;
  uint32_t dynamic;  // dynamic violations (refinement can act on them)
};

void add_violation(Report* r, double t, tdo_quantity what, double value, double limit) {
  if (r->rep->n_violations < r->cap) {
    r->list[r->rep->n_violations++] = tdo_violation{t, what, value, limit};
  }
  ++r->rep->n_violations_total;
  if (what != TDO_QUANTITY_CLEARANCE) ++r->dynamic;
}

template <typename Src>
void mark(tdo_traj* ctx, Src& src, uint32_t n, uint32_t first, uint32_t last) {
  const uint32_t a = first > 0u ? first - 1u : 0u;
  const uint32_t b = last + 1u < n ? last + 1u : n - 1u;
  for (uint32_t i = a; i <= b; ++i) ctx->hit[src.owner(i)] = 1u;
}

/** Point distances along the samples, skipped by the 1-Lipschitz bound: a point at distance r from
 *  the last evaluated one, whose distance was `ref`, is at least ref - r from the obstacles. */
struct LipschitzProbe {
  double ref = -HUGE_VAL;      // m, distance of the last evaluated point
  tdo_vec3 at{0.0, 0.0, 0.0};  // m, world frame: that point
  PointHint hint;
  LipschitzProbe() { hint.valid = 0; }
  /** m, lower bound of the distance at p. */
  double bound(const tdo_vec3& p) const { return ref - norm(sub(p, at)) - kLipschitzSlack; }
  /** m, the distance at p (capped at cap: min(distance, cap)), evaluated. The bound kept is
   *  the query's proven lower bound, which may exceed the cap (PointHint::lower). */
  double eval(const tdo_grid* g, const tdo_vec3& p, double cap) {
    const double d = point_distance_hinted(g, p, cap, &hint);
    ref = dmax(d, hint.lower);
    at = p;
    return d;
  }
};

/** The clearance verification's state: the minimum distance of the samples so far and the
 *  queries. Only exact distances (capped) enter the minimum and the violations; a sample is skipped
 *  only with a proven lower bound (1-Lipschitz: the distance to the nearest obstacle changes by at
 *  most the distance moved) at or above both the minimum so far and the violation floor. */
struct ClearanceScan {
  const tdo_grid* grid;
  double cap;       // m, clearance + kClearanceCapExtra: the reported distances are capped here
  double floor_ok;  // m, a distance below this is a violation
  double min;       // m, minimum of the exact (capped) distances so far
  uint32_t queries;
  /** m, the exact distance of p capped just above what can still matter (kClearanceEvalMargin):
   *  a distance at or above both the minimum so far and the floor changes neither, and the
   *  capped value is still a lower bound for the probe. */
  double eval(LipschitzProbe* probe, const tdo_vec3& p, double margin) {
    ++queries;
    const double d = probe->eval(grid, p, dmin(cap, dmax(min, floor_ok) + margin));
    min = dmin(min, d);
    return d;
  }
};

/** The in-order scan (any sample source): samples whose bound from the last exact point is at or
 *  above the minimum so far and the floor are skipped, the others are queried and every one below
 *  the floor is listed, in sample order. */
template <typename Src>
void clearance_scan(ClearanceScan* cs, Src& src, uint32_t n, Report* r, double clearance) {
  LipschitzProbe probe;
  src.rewind();
  for (uint32_t i = 0; i < n; ++i) {
    const tdo_sample& si = src.at(i);
    const double lb = probe.bound(si.p);
    if (lb >= cs->min && lb >= cs->floor_ok) continue;
    const double d = cs->eval(&probe, si.p, kClearanceEvalMargin);
    if (d < cs->floor_ok) add_violation(r, si.t, TDO_QUANTITY_CLEARANCE, d, clearance);
  }
}

/** An interval of sample indices whose ends a and b carry lower bounds of their distances. */
struct ClearanceSpan {
  uint32_t a, b;
  double la, lb;  // m
};

/** The exact minimum of the stored samples' distances by branch and bound over index intervals:
 *  an interval whose interior cannot be below the minimum so far is dropped (each sample moves at
 *  most `step` from the next, so sample k is at least max(la - (k-a) step, lb - (b-k) step) away,
 *  i.e. at least their crossing); otherwise its middle sample takes the better of its Lipschitz
 *  bounds from both ends, is queried only when that is below the minimum, and both halves
 *  follow. Depth first, the halves nearer the obstacles first; at most log2(n) + 2 intervals
 *  wait, and each sample is a middle at most once. */
bool clearance_min(ClearanceScan* cs, const tdo_sample* s, uint32_t n, double step) {
  constexpr uint32_t kStack = 72;  // > 2 (log2(2^32) + 2): never full
  ClearanceSpan stack[kStack];
  LipschitzProbe probe;
  const double margin =
      dmin(kClearanceMinMargin, kClearanceMinVoxels * tdo_grid_get_desc(cs->grid).res);
  cs->eval(&probe, s[0].p, margin);
  const double l0 = probe.ref;
  if (n < 2u) return true;
  cs->eval(&probe, s[n - 1u].p, margin);
  uint32_t top = 0;
  stack[top++] = ClearanceSpan{0u, n - 1u, l0, probe.ref};
  const uint64_t pops = 2u * static_cast<uint64_t>(n);  // every pop drops or splits: < 2n
  for (uint64_t it = 0; top > 0u && it < pops; ++it) {
    if (top + 1u >= kStack) return false;
    const ClearanceSpan sp = stack[--top];
    if (sp.b - sp.a < 2u) continue;
    const double cross = 0.5 * (sp.la + sp.lb - static_cast<double>(sp.b - sp.a) * step);
    if (cross - kLipschitzSlack >= cs->min) continue;
    const uint32_t m = sp.a + (sp.b - sp.a) / 2u;
    const tdo_vec3& pm = s[m].p;
    double lm =
        dmax(sp.la - norm(sub(pm, s[sp.a].p)), sp.lb - norm(sub(pm, s[sp.b].p))) - kLipschitzSlack;
    if (!(lm >= cs->min)) {
      cs->eval(&probe, pm, margin);
      lm = probe.ref;
    }
    const ClearanceSpan lo{sp.a, m, sp.la, lm}, hi{m, sp.b, lm, sp.lb};
    const bool lo_first = sp.la <= sp.lb;  // popped first: pushed last
    stack[top++] = lo_first ? hi : lo;
    stack[top++] = lo_first ? lo : hi;
  }
  return top == 0u;
}

/** One run of consecutive stored samples on one path segment, [a, b], into the minimum. A line
 *  that keeps r = min(the minimum so far, the cap) plus a rounding allowance (one exact segment
 *  query, which stops early when it fails) is skipped: none of its samples can lower the
 *  minimum, and when r is the cap every one of them is at least the cap away, exactly the cap as
 *  a point query gives it. The samples lie on the segment up to rounding: kLipschitzSlack plus a
 *  relative allowance covers it. Every other run takes clearance_min over its samples. */
bool run_min(ClearanceScan* cs, const tdo_path_segment& seg, const tdo_sample* s, uint32_t a,
             uint32_t b, double step) {
  if (seg.kind == TDO_SEGMENT_LINE) {
    const double r = dmin(cs->cap, cs->min);
    const double slack = kLipschitzSlack + 1e-12 * (norm(seg.p[0]) + norm(seg.p[1]));
    if (tdo_collision_segment_clear(cs->grid, seg.p[0], seg.p[1], r + 2.0 * slack) != 0) {
      cs->min = dmin(cs->min, cs->cap);
      return true;
    }
  }
  return clearance_min(cs, s + a, b - a + 1u, step);
}

/** clearance_min per path segment, curves first: paths come nearest the obstacles at their
 *  corners, so the minimum falls there with point queries alone, and then a line that keeps it
 *  (one segment query) is skipped without point queries. The same minimum, bit for bit: every
 *  sample skipped has a proven bound at or above it (MovingAI Simple, 60 queries: trajectory
 *  stage 0.91 -> 0.79 M instructions per plan on average, median 0.72 -> 0.66 M). */
bool clearance_min_runs(ClearanceScan* cs, const tdo_traj* ctx, const tdo_path_segment* segs,
                        const tdo_sample* s, uint32_t n, double step) {
  // The samples' segments never decrease (the sampler walks the plateaus in order): a run's end
  // is found by bisection.
  const auto seg_of = [ctx](uint32_t i) { return ctx->plateaus[ctx->owner[i]].seg; };
  for (int lines = 0; lines < 2; ++lines) {
    for (uint32_t a = 0; a < n;) {  // every run ends at or after a: bounded by n
      const uint32_t k = seg_of(a);
      uint32_t lo = a, hi = n;  // seg_of(lo) == k; hi: n or a sample on a later segment
      while (hi - lo > 1u) {    // bisection: bounded by log2(n)
        const uint32_t mid = lo + (hi - lo) / 2u;
        (seg_of(mid) == k ? lo : hi) = mid;
      }
      const tdo_path_segment& seg = segs[k];
      if ((seg.kind == TDO_SEGMENT_LINE) == (lines == 1) && !run_min(cs, seg, s, a, lo, step))
        return false;
      a = lo + 1u;
    }
  }
  return true;
}

/** The clearance verification (eq. 18) of the samples of `src`: the minimum exact distance of the
 *  samples (capped at clearance + kClearanceCapExtra) and, in sample order, every sample below the
 *  clearance, the same as querying every sample. Stored samples: clearance_min finds the minimum,
 *  and only when it is below the floor does the in-order scan list the violations. Streamed ones:
 *  the in-order scan alone, from the minimum `start` of some of the samples (the pre-pass). */
template <typename Src>
void clearance_pass(const tdo_traj* ctx, const tdo_traj_input* in, Src& src, uint32_t n,
                    double max_speed, bool finite, double start, Report* r) {
  ClearanceScan cs{in->grid, in->clearance + kClearanceCapExtra, in->clearance - kClearanceSlack,
                   start, 0u};
  // Largest step between consecutive samples: the finite-difference speed at dt, with a relative
  // and an absolute rounding allowance (every step finite: no position is NaN or infinite).
  const double step = max_speed * in->dt * (1.0 + 1e-9) + 1e-12;
  if (Src::kRandomAccess && finite && n > 0u && isfinite(step)) {
    // Stopped early (never): the scan still finds the rest, from a minimum of real samples.
    // Stored samples on the path (no moving start's entry ramp): per segment first.
    const bool by_runs = ctx->owner != nullptr && !ctx->moving;
    const bool ok = by_runs ? clearance_min_runs(&cs, ctx, in->path.seg, &src.at(0), n, step)
                            : clearance_min(&cs, &src.at(0), n, step);
    if (!ok || cs.min < cs.floor_ok) clearance_scan(&cs, src, n, r, in->clearance);
  } else {
    clearance_scan(&cs, src, n, r, in->clearance);
  }
  r->rep->min_clearance = cs.min;
}

/** Two passes over the samples of `src` (dynamic limits and energy, then clearance), so the
 *  violations are listed in the same order whether the samples are stored or streamed. */
template <typename Src>
uint32_t verify(tdo_traj* ctx, const tdo_traj_input* in, const Limits& lim, uint32_t n, Src& src,
                tdo_feasibility* rep, double* energy) {
  memset(rep, 0, sizeof(*rep));
  rep->violations = ctx->violations;
  rep->min_turn_radius = HUGE_VAL;
  rep->min_clearance = HUGE_VAL;
  Report r{rep, ctx->cfg.max_violations, ctx->violations, 0u};
  memset(ctx->hit, 0, ctx->n_plateaus);
  const double dt = lim.dt;
  const double v_lim = lim.v_max * (1.0 + kTolerance);
  const double a_lim = lim.a_max * (1.0 + kTolerance);
  const double j_lim = lim.j_max * (1.0 + kTolerance);
  // Clearance pre-pass, inside the dynamic pass: the distance of every kClearanceStride-th sample
  // (skipped by the Lipschitz bound below when it cannot lower their minimum). That minimum is
  // the distance of a sample, so the clearance pass may start from it: it skips every sample
  // that cannot be below it, which is most of them, instead of only those that cannot be below
  // the minimum of the samples before them.
  const bool clear = in->grid != nullptr;
  const double cap = in->clearance + kClearanceCapExtra;
  double pre_min = HUGE_VAL;
  LipschitzProbe pre;
  src.rewind();
  // Running sums and extremes in locals (written to the report at the end: same values).
  double energy_sum = 0.0, max_speed = 0.0, max_acc = 0.0, max_jerk = 0.0;
  double min_radius = HUGE_VAL;
  bool finite = true;  // every position finite (a NaN or an infinity makes a step non-finite)
  const double inv_dt = 1.0 / dt, dt2 = dt * dt;
  // Rolling finite differences: v_i = (P_{i+1} - P_i)/dt, a_i = (v_{i+1} - v_i)/dt,
  // j_i = (a_{i+1} - a_i)/dt.
  tdo_vec3 v_prev{0.0, 0.0, 0.0}, a_prev{0.0, 0.0, 0.0};
  double aa0 = 0.0;  // |a|^2 of sample i (the energy's trapezoid)
  for (uint32_t i = 0; i + 1u < n; ++i) {
    const tdo_sample& s1 = src.at(i + 1u);  // generated first: the window keeps sample i
    const tdo_sample& s0 = src.at(i);
    if (clear && !Src::kRandomAccess && (i % kClearanceStride) == 0u &&
        !(pre.bound(s0.p) >= pre_min))
      pre_min = dmin(pre_min, pre.eval(in->grid, s0.p, dmin(cap, pre_min)));
    if (i == 0u) aa0 = dot(s0.a, s0.a);
    const double aa1 = dot(s1.a, s1.a);
    energy_sum += energy_step_sq(aa0, aa1, s1.t - s0.t);
    aa0 = aa1;
    const tdo_vec3 v = mul(sub(s1.p, s0.p), inv_dt);
    const double speed = norm(v);
    max_speed = dmax(max_speed, speed);
    finite = finite && isfinite(speed);
    if (speed > v_lim) {
      add_violation(&r, s0.t + 0.5 * dt, TDO_QUANTITY_SPEED, speed, lim.v_max);
      mark(ctx, src, n, i, i + 1u);
    }
    if (i >= 1u) {  // a_{i-1} from v_{i-1} and v_i: centred at sample i
      const tdo_vec3 a = mul(sub(v, v_prev), inv_dt);
      const double acc = norm(a);
      max_acc = dmax(max_acc, acc);
      if (acc > a_lim) {
        add_violation(&r, s0.t, TDO_QUANTITY_ACCELERATION, acc, lim.a_max);
        mark(ctx, src, n, i - 1u, i + 1u);
      }
      // Turn radius at sample i with the centred velocity (eq. 19).
      const tdo_vec3 vc = mul(add(v, v_prev), 0.5);
      const double vn = norm(vc);
      if (vn > 0.0) {
        const tdo_vec3 u = mul(vc, 1.0 / vn);
        const double ap = norm(sub(a, mul(u, dot(a, u))));
        // Below the rounding noise of a second difference of these positions the path is
        // straight (near rest that noise alone would give any radius).
        const double noise = kRadiusNoise * (norm(s0.p) + 1.0) / dt2;
        if (ap > noise) {
          const double radius = vn * vn / ap;
          min_radius = dmin(min_radius, radius);
          const double need = vn * vn / lim.a_max;
          if (radius * (1.0 + kTolerance) < need) {
            add_violation(&r, s0.t, TDO_QUANTITY_TURN_RADIUS, radius, need);
            mark(ctx, src, n, i - 1u, i + 1u);
          }
        }
      }
      if (i >= 2u) {  // j_{i-2} from a_{i-2} and a_{i-1}: centred between samples i-1 and i
        const double jerk = norm(mul(sub(a, a_prev), inv_dt));
        max_jerk = dmax(max_jerk, jerk);
        if (jerk > j_lim) {
          add_violation(&r, s0.t - 0.5 * dt, TDO_QUANTITY_JERK, jerk, lim.j_max);
          mark(ctx, src, n, i - 2u, i + 1u);
        }
      }
      a_prev = a;
    }
    v_prev = v;
  }
  *energy = energy_sum;
  rep->max_speed = max_speed;
  rep->max_acc = max_acc;
  rep->max_jerk = max_jerk;
  rep->min_turn_radius = min_radius;
  if (clear) clearance_pass(ctx, in, src, n, max_speed, finite, pre_min, &r);
  rep->ok = rep->n_violations_total == 0u ? 1 : 0;
  return r.dynamic;
}

// ---------------------------------------------------------------------------------------------
// Pieces mode (TDO_TRAJ_SAMPLES_PIECES): verify()'s finite-difference checks bounded in closed
// form per profile piece, without generating a sample.
//
// The sampled positions are P_i = x(i dt) of the trajectory x(t) = path(s(t)). Between the deltas
// listed below x is C^2 with a bounded x''', and the finite differences are kernel averages:
// v_i = box (width dt, height 1/dt) * x', a_i = hat (width 2 dt, peak 1/dt, slopes 1/dt^2) * x'',
// j_i = quadratic B-spline (width 3 dt, peak 0.75/dt, slopes <= 1/dt^2, second derivative in
// {1, -2, 1}/dt^3) * x'''. So |v_i|, |a_i|, |j_i| are at most the largest |x'|, |x''|, |x'''| over
// the stencil plus, for every delta inside it, a jump of x by Ds: Ds/dt, Ds/dt^2, 2 Ds/dt^3; of x'
// by Dv: -, Dv/dt, Dv/dt^2; of x'' by Da: -, -, 0.75 Da/dt. The deltas: tangent kinks
// (Dv = s'|dT|, Da = s''|dT|) and curvature jumps (Da = s'^2 |dkn|) at segment joints, and the
// profile's own jumps between pieces (rounding at S-curve ends and move anchors) and at the last
// sample. With x' = s' T, x'' = s'' T + s'^2 kappa N and, corners being planar,
// x''' = (s''' - kappa^2 s'^3) T + (3 kappa s' s'' + kappa_s s'^3) N, each is bounded on an
// interval from the exact range of the piece's s' (quadratic) and s'' (linear) and proven bounds
// of kappa and kappa_s over it (rigor_plateau: lines 0, arcs 1/r, Beziers by interval arithmetic
// per interval between the curve summary's stations, per quarter of one when a bound misses with
// those; not the summary's sampled values, which can miss a peak between its stations: test
// peaked_path);
// rounding of the
// positions (e_P) adds 2 e_P/dt, 4 e_P/dt^2, 8 e_P/dt^3. A stencil without a delta lies in pieces
// whose bounds cover it; one with deltas lies within 3 dt of its first one, whose window (the
// pieces' bounds over it and every delta in it) covers it. Turn radius: verify() flags radius
// * 1.01 < v^2 / a_max with radius = v^2 / |a_perp|, i.e. |a_perp| > 1.01 a_max, and |a_perp| <=
// |a_i|: the acceleration bound (<= 1.01 a_max) rules it out. The bounds must keep half the 1 %
// tolerance (kPieceReserve), a reserve for what the argument leaves out (the rounding of the
// bounds' own arithmetic, a plateau's first 1e-9 m: curv_over). Any bound that misses: the round
// falls back to the streamed verification.

constexpr double kPieceReserve = 0.5;  // of kTolerance: the closed form keeps limit * 1.005
constexpr uint32_t kPieceSplits = 6;   // halvings of an interval whose bound misses (64 parts)
// The same with the coarse curvature parts (kRigorCoarse); where they miss, the plateaus under
// the span's 2^kCoarseSplits parts that miss get the fine ones (pieces_dynamic). On the first 60
// Simple plans (middle third of the trajectory stage): 2 -> 256.1 K instructions, 3 -> 256.5 K,
// 4 -> 263.2 K, 5 -> 276.4 K.
constexpr uint32_t kCoarseSplits = 3;
constexpr int kCrossBisections = 64;  // the time a piece crosses a segment joint
constexpr double kPositionNoise = 64.0 * 2.220446049250313e-16;  // rounding, relative to |P|
constexpr double kInversionNoise = 4e-13;  // m per m of Bezier: the cursor's inversion tolerance
// m: the path's distance must keep clearance - this (half the slack: the samples lie on the path
// up to rounding)
constexpr double kPieceClearSlack = 0.5 * kClearanceSlack;
constexpr double kPieceClearHint = 0.05;  // m above the clearance: pieces_clearance's hint
constexpr uint32_t kRigorParts = 16;      // parameter parts per plateau of a Bezier (bezier_bounds)
// The first try's parts per plateau (pieces_verify): one per interval between the curve summary's
// stations (their arclengths known: no quadrature). Coarser bounds are looser but still proven;
// where they miss, the kRigorParts bounds decide from that span on. On the first 60 Simple plans
// (middle third of the trajectory stage, before the fine parts went only where they miss): 4 ->
// 273 K instructions, 8 -> 284 K (11 of 60 plans needed the fine parts with 8, 22 with 4).
constexpr uint32_t kRigorCoarse = 4;
constexpr double kRigorSlackU = 1e-9;  // widening of a plateau's parameter range (inversion)
constexpr double kRigorSlackS = 1e-9;  // m, widening of a part's arclength range
constexpr uint32_t kEnergyPanels = 8;  // Gauss-Legendre panels per Bezier length, at most
constexpr double kGl5X[3] = {0.0, 0.5384693101056831, 0.9061798459386640};
constexpr double kGl5W[3] = {0.5688888888888889, 0.4786286704993665, 0.2369268850561891};

/** Upper bounds of the finite-difference speed, acceleration and jerk. */
struct Bound3 {
  double v, a, j;
};
inline Bound3 bmax(const Bound3& x, const Bound3& y) {
  return Bound3{dmax(x.v, y.v), dmax(x.a, y.a), dmax(x.j, y.j)};
}
inline Bound3 bmin(const Bound3& x, const Bound3& y) {
  return Bound3{dmin(x.v, y.v), dmin(x.a, y.a), dmin(x.j, y.j)};
}
inline bool fits(const Bound3& b, const Bound3& lim) {
  return b.v <= lim.v && b.a <= lim.a && b.j <= lim.j;
}

/** A delta of the trajectory (pieces mode): a jump of x by ds, of x' by dv, of x'' by da. */
struct Junction {
  double t;      // s
  double ds;     // m
  double dv;     // m/s
  double da;     // m/s^2
  uint32_t seg;  // segment joint: the segment that begins here (energy splits); else UINT32_MAX
};

/** [lo, hi] of an interval product. */
inline void iv_mul(double a0, double a1, double b0, double b1, double* lo, double* hi) {
  const double p[4] = {a0 * b0, a0 * b1, a1 * b0, a1 * b1};
  *lo = dmin(dmin(p[0], p[1]), dmin(p[2], p[3]));
  *hi = dmax(dmax(p[0], p[1]), dmax(p[2], p[3]));
}

/** Range of the cubic r0 + r1 u + r2 u^2 + r3 u^3 over [ua, ub] (Bernstein coefficients). */
void cubic_range(const double r[4], double ua, double ub, double* lo, double* hi) {
  const double du = ub - ua;
  const double v0 = r[0] + ua * (r[1] + ua * (r[2] + ua * r[3]));
  const double d1 = (r[1] + ua * (2.0 * r[2] + 3.0 * ua * r[3])) * du;
  const double d2 = (r[2] + 3.0 * ua * r[3]) * du * du;
  const double d3 = r[3] * du * du * du;
  const double b[4] = {v0, v0 + d1 / 3.0, v0 + 2.0 * d1 / 3.0 + d2 / 3.0, v0 + d1 + d2 + d3};
  *lo = dmin(dmin(b[0], b[1]), dmin(b[2], b[3]));
  *hi = dmax(dmax(b[0], b[1]), dmax(b[2], b[3]));
}

/** bezier_bounds' polynomials of one planar Bezier (plane normal n), once per segment: with
 *  B' = h0 + u h1 + u^2 h2, c(u) = (B' x B'').n = c0 + c1 u + c2 u^2 (B' x B'' = h0 x h1 +
 *  2u h0 x h2 + u^2 h1 x h2) and r(u) = B'.B'' = h0.h1 + u (2 h0.h2 + h1.h1) + u^2 3 h1.h2 +
 *  u^3 2 h2.h2, with their rounding allowances. */
struct BezierPoly {
  tdo_vec3 h0, h1, h2;
  double c0, c1, c2, slack;
  double r[4], rs;
};

BezierPoly bezier_poly(const BezierCursor& cb, const tdo_vec3& n) {
  BezierPoly p;
  const tdo_vec3 h0 = cb.h[0], h1 = cb.h[1], h2 = cb.h[2];
  p.h0 = h0;
  p.h1 = h1;
  p.h2 = h2;
  p.c0 = dot(cross(h0, h1), n);
  p.c1 = 2.0 * dot(cross(h0, h2), n);
  p.c2 = dot(cross(h1, h2), n);
  p.slack = 1e-9 * (fabs(p.c0) + fabs(p.c1) + fabs(p.c2)) + 1e-300;
  p.r[0] = dot(h0, h1);
  p.r[1] = 2.0 * dot(h0, h2) + dot(h1, h1);
  p.r[2] = 3.0 * dot(h1, h2);
  p.r[3] = 2.0 * dot(h2, h2);
  p.rs = 1e-9 * (fabs(p.r[0]) + fabs(p.r[1]) + fabs(p.r[2]) + fabs(p.r[3])) + 1e-300;
  return p;
}

/** What bezier_bounds needs at one end of a part: B'(u), |B'(u)|, c(u) and c'(u) (an end shared
 *  by two neighbouring parts is evaluated once). */
struct BezierEnd {
  double u;
  tdo_vec3 q;
  double nq, c, dc;
};

BezierEnd bezier_end(const BezierPoly& p, double u) {
  BezierEnd e;
  e.u = u;
  e.q = add(p.h0, mul(add(p.h1, mul(p.h2, u)), u));
  e.nq = norm(e.q);
  e.c = p.c0 + u * (p.c1 + u * p.c2);
  e.dc = p.c1 + 2.0 * p.c2 * u;
  return e;
}

/** Rigorous bounds of a planar cubic Bezier (bezier_poly) over the parameters [a.u, b.u]: kappa
 *  and the range [klo, khi] of d|kappa|/ds. The signed curvature is c / |B'|^3 and its derivative
 *  along s is (c' / |B'|^3 - 3 c r / |B'|^5) / |B'|: interval arithmetic on the polynomials'
 *  ranges (Bernstein coefficients on [a.u, b.u]) and on |B'| in [m, M] (its restriction's
 *  control points: m along B' at the middle, M their largest norm). Where c keeps a sign,
 *  |kappa|'s derivative is that sign times it; elsewhere symmetric. False when |B'| may vanish
 *  there. */
bool bezier_bounds(const BezierPoly& p, const BezierEnd& a, const BezierEnd& b, double* kappa,
                   double* klo, double* khi) {
  const double ua = a.u, ub = b.u;
  const auto d1 = [&](double u) { return add(p.h0, mul(add(p.h1, mul(p.h2, u)), u)); };
  const auto d2 = [&](double u) { return add(p.h1, mul(p.h2, 2.0 * u)); };
  const double du = ub - ua;
  const tdo_vec3 q0 = a.q, q2 = b.q, q1 = add(q0, mul(d2(ua), 0.5 * du));
  const tdo_vec3 mid = d1(0.5 * (ua + ub));
  const double nm = norm(mid);
  if (!(nm > 0.0)) return false;
  const tdo_vec3 t = mul(mid, 1.0 / nm);
  const double m = dmin(dot(t, q0), dmin(dot(t, q1), dot(t, q2))) * (1.0 - 1e-9);
  const double big = dmax(a.nq, dmax(norm(q1), b.nq)) * (1.0 + 1e-9);
  if (!(m > 0.0)) return false;
  const double ca = a.c, cbv = b.c;
  const double cm = ca + 0.5 * du * a.dc;
  const double slack = p.slack;
  const double c_lo = dmin(ca, dmin(cm, cbv)) - slack, c_hi = dmax(ca, dmax(cm, cbv)) + slack;
  const double dc_a = a.dc, dc_b = b.dc;
  const double dc_lo = dmin(dc_a, dc_b) - slack, dc_hi = dmax(dc_a, dc_b) + slack;
  double r_lo, r_hi;
  cubic_range(p.r, ua, ub, &r_lo, &r_hi);
  r_lo -= p.rs;
  r_hi += p.rs;
  const double m3 = m * m * m, b3 = big * big * big;
  *kappa = dmax(fabs(c_lo), fabs(c_hi)) / m3 * (1.0 + 1e-9);
  double t1_lo, t1_hi, cr_lo, cr_hi, t2_lo, t2_hi;
  iv_mul(dc_lo, dc_hi, 1.0 / b3, 1.0 / m3, &t1_lo, &t1_hi);
  iv_mul(c_lo, c_hi, r_lo, r_hi, &cr_lo, &cr_hi);
  iv_mul(cr_lo, cr_hi, 3.0 / (b3 * big * big), 3.0 / (m3 * m * m), &t2_lo, &t2_hi);
  double lo = t1_lo - t2_hi, hi = t1_hi - t2_lo;  // d(signed kappa)/du
  iv_mul(lo, hi, 1.0 / big, 1.0 / m, &lo, &hi);   // per unit s
  lo -= 1e-9 * fabs(lo);
  hi += 1e-9 * fabs(hi);
  if (c_lo > 0.0) {
    *klo = lo;
    *khi = hi;
  } else if (c_hi < 0.0) {
    *klo = -hi;
    *khi = -lo;
  } else {
    *khi = dmax(fabs(lo), fabs(hi));
    *klo = -*khi;
  }
  return true;
}

/** Unit normal of the plane of a Bezier's control points (the largest of their cross products);
 *  false when they are not coplanar (torsion, which the jerk bound leaves out). */
bool bezier_plane(const tdo_path_segment& seg, tdo_vec3* n) {
  const tdo_vec3 a = sub(seg.p[1], seg.p[0]), b = sub(seg.p[2], seg.p[0]),
                 e = sub(seg.p[3], seg.p[0]);
  const tdo_vec3 cands[3] = {cross(a, b), cross(a, e), cross(b, e)};
  tdo_vec3 best = cands[0];
  for (int i = 1; i < 3; ++i)
    if (norm(cands[i]) > norm(best)) best = cands[i];
  const double scale = norm(a) * norm(b) * norm(e);
  if (!(fabs(dot(cross(a, b), e)) <= 1e-12 * scale)) return false;
  const double bn = norm(best);
  *n = bn > 0.0 ? mul(best, 1.0 / bn) : tdo_vec3{0.0, 0.0, 1.0};  // a straight one: c = 0
  return true;
}

/** rigor_plateau's per-segment numbers: the plane's polynomials of one Bezier (bezier_poly) and a
 *  cursor on it (its arclength quadrature), computed once per segment. */
struct RigorSeg {
  uint32_t seg;  // UINT32_MAX when unset
  bool planar;
  BezierCursor cur;
  BezierPoly poly;
};

void rigor_seg(RigorSeg* r, const tdo_path& path, uint32_t seg) {
  if (r->seg == seg) return;
  r->seg = seg;
  tdo_vec3 n{0.0, 0.0, 1.0};
  r->planar = bezier_plane(path.seg[seg], &n);
  cursor_reset(&r->cur, path.seg[seg], seg);
  if (r->planar) r->poly = bezier_poly(r->cur, n);
}

/** Parts per plateau of a Bezier for `np` asked: whole parts of each station interval (at least
 *  one), so at most kRigorParts. */
uint32_t rigor_count(const tdo_traj* ctx, uint32_t np) {
  const uint32_t st = kStations / ctx->pieces->curve_parts;
  return st * (np > st ? np / st : 1u);
}

/** Pieces mode: the rigorous curvature bounds of plateau q in about `np` parts (rigor_count).
 *  Lines and arcs: the summary's (kappa constant, within its margin), one part; planar Beziers:
 *  bezier_bounds over equal parameter parts of each interval between the curve summary's stations
 *  (whose parameters and arclengths the summary's cursor found: only the parts inside an interval
 *  integrate the arclength, from its station); a non-planar Bezier gets infinite bounds, and so a
 *  fallback. */
void rigor_plateau(tdo_traj* ctx, const tdo_path& path, uint32_t q, uint32_t np, RigorSeg* rs) {
  const Plateau& p = ctx->plateaus[q];
  PlateauSpan& sp = ctx->pieces->spans[q];
  RigorPart* part = ctx->pieces->parts + static_cast<size_t>(q) * kRigorParts;
  if (path.seg[p.seg].kind != TDO_SEGMENT_BEZIER) {
    sp.np = 1u;
    part[0] = RigorPart{p.s0, p.kappa, p.dk_up, p.dk_down};
    return;
  }
  const uint32_t st = kStations / ctx->pieces->curve_parts, n = rigor_count(ctx, np), sub = n / st;
  sp.np = n;
  for (uint32_t i = 0; i < n; ++i)
    part[i] = RigorPart{i == 0u ? p.s0 : HUGE_VAL, HUGE_VAL, HUGE_VAL, HUGE_VAL};
  rigor_seg(rs, path, p.seg);
  if (!rs->planar) return;
  const StationK* k = ctx->pieces->stations + sp.first;
  const BezierPoly& poly = rs->poly;
  bool ok = true;  // a part whose bounds fail keeps infinite ones, and so do the rest
  // The start of part i: the end of part i - 1 (the same expression), else evaluated.
  BezierEnd a{static_cast<double>(NAN), tdo_vec3{0.0, 0.0, 0.0}, 0.0, 0.0, 0.0};
  for (uint32_t j = 0; j < st && ok; ++j) {
    // The plateau's ends widened by kRigorSlackU (the inversion's rounding).
    const double u_lo = k[j].u, u_hi = k[j + 1u].u, w = u_hi - u_lo;
    const double first = j == 0u ? dmax(0.0, u_lo - kRigorSlackU) : u_lo;
    const double last = j + 1u == st ? dmin(1.0, u_hi + kRigorSlackU) : u_hi;
    double u_at = u_lo, s_local = k[j].s;  // the arclength, carried part to part
    for (uint32_t i = 0; i < sub && ok; ++i) {
      const double ua = i == 0u ? first : u_lo + w * i / sub;
      const double ub = i + 1u == sub ? last : u_lo + w * (i + 1u) / sub;
      if (!same(a.u, ua)) a = bezier_end(poly, ua);
      const BezierEnd b = bezier_end(poly, ub);
      double kk = HUGE_VAL, lo = -HUGE_VAL, hi = HUGE_VAL;
      ok = bezier_bounds(poly, a, b, &kk, &lo, &hi);
      a = b;
      // Where the part begins along the path (the cursor's arclength), less a rounding allowance.
      if (i > 0u) {
        s_local += bez_arclen(rs->cur, u_at, ua);
        u_at = ua;
      }
      const double s_at = i + j == 0u ? p.s0 : p.s0 - p.off + s_local - kRigorSlackS;
      part[j * sub + i] = RigorPart{s_at, kk, hi, -lo};
    }
  }
}

/** Pieces mode: the rigorous curvature bounds of every plateau in about `np` parts. */
void rigorous_curvature(tdo_traj* ctx, const tdo_path& path, uint32_t np, RigorSeg* rs) {
  ctx->pieces->fine = np >= kRigorParts;
  for (uint32_t q = 0; q < ctx->n_plateaus; ++q) rigor_plateau(ctx, path, q, np, rs);
}

/** Curvature bounds of the plateaus that overlap [sa, sb]. */
struct Curv {
  double k, up, down;  // 1/m, 1/m^2, 1/m^2 (as Plateau)
};

/** Last plateau whose start is at or before s (the first when none). */
uint32_t plateau_of(const tdo_traj* ctx, double s) {
  uint32_t lo = 0, hi = ctx->n_plateaus;
  while (hi - lo > 1u) {  // bisection: bounded by log2(n_plateaus)
    const uint32_t mid = lo + (hi - lo) / 2u;
    (ctx->plateaus[mid].s0 <= s ? lo : hi) = mid;
  }
  return lo;
}

Curv curv_over(const tdo_traj* ctx, double sa, double sb) {
  Curv c{0.0, -HUGE_VAL, -HUGE_VAL};
  for (uint32_t q = plateau_of(ctx, sa); q < ctx->n_plateaus; ++q) {  // bounded by n_plateaus
    const Plateau& p = ctx->plateaus[q];
    // A plateau that begins at the interval's end (within kRigorSlackS: rounding of the anchors)
    // holds none of it: the third derivative differs there on a time set of ~1e-9 m / s', which
    // the kernels' integrals do not see (the joint's own deltas are the junctions').
    if (!(p.s0 < sb - kRigorSlackS) && c.up > -HUGE_VAL) break;
    // The parts of the plateau that overlap [sa, sb]: part i covers [s0_i, s0_{i+1} + slack].
    const RigorPart* part = ctx->pieces->parts + static_cast<size_t>(q) * kRigorParts;
    const uint32_t np = ctx->pieces->spans[q].np;
    for (uint32_t i = 0; i < np; ++i) {
      if (i > 0u && !(part[i].s0 <= sb)) break;  // unused parts (lines, arcs) start at HUGE_VAL
      const double end = i + 1u < np && part[i + 1u].s0 < HUGE_VAL
                             ? part[i + 1u].s0 + 2.0 * kRigorSlackS
                             : HUGE_VAL;
      if (end < sa && i + 1u < np) continue;
      c.k = dmax(c.k, part[i].k);
      c.up = dmax(c.up, part[i].up);
      c.down = dmax(c.down, part[i].down);
    }
  }
  return c;
}

/** Gives the fine curvature parts (kRigorParts) to the Bezier plateaus with coarse ones that
 *  curv_over may read for [sa, sb]. */
void refine_over(tdo_traj* ctx, const tdo_path& path, double sa, double sb, RigorSeg* rs) {
  const uint32_t fine = rigor_count(ctx, kRigorParts), q0 = plateau_of(ctx, sa);
  for (uint32_t q = q0; q < ctx->n_plateaus; ++q) {  // bounded by n_plateaus
    const Plateau& p = ctx->plateaus[q];
    if (q > q0 && !(p.s0 < sb)) break;  // curv_over stops there or before
    if (path.seg[p.seg].kind == TDO_SEGMENT_BEZIER && ctx->pieces->spans[q].np < fine)
      rigor_plateau(ctx, path, q, kRigorParts, rs);
  }
}

/** Path speed, acceleration and arclength of piece f at tau, as the sampler evaluates them. */
inline double ph_v(const Phase& f, double t) { return f.v0 + t * (f.a0 + 0.5 * t * f.j); }
inline double ph_a(const Phase& f, double t) { return f.a0 + t * f.j; }
inline double ph_s(const Phase& f, double t) {
  return f.s0 + t * (f.v0 + t * (0.5 * f.a0 + t * f.j / 6.0));
}

/** Range [lo, hi] of s' over [ta, tb] of piece f (a quadratic: its ends and its vertex). */
void speed_range(const Phase& f, double ta, double tb, double* lo, double* hi) {
  *hi = dmax(ph_v(f, ta), ph_v(f, tb));
  *lo = dmin(ph_v(f, ta), ph_v(f, tb));
  if (fabs(f.j) > 0.0) {
    const double tv = -f.a0 / f.j;
    if (tv > ta && tv < tb) {
      *hi = dmax(*hi, ph_v(f, tv));
      *lo = dmin(*lo, ph_v(f, tv));
    }
  }
}

/** Bounds of |x'|, |x''|, |x'''| over [ta, tb] of piece f. */
Bound3 sub_bound(const tdo_traj* ctx, const Phase& f, double ta, double tb) {
  double v_lo, v_hi;
  speed_range(f, ta, tb, &v_lo, &v_hi);
  const double v = dmax(fabs(v_hi), fabs(v_lo)), v_pos = dmax(v_lo, 0.0);
  const double a_hi = dmax(ph_a(f, ta), ph_a(f, tb)), a_lo = dmin(ph_a(f, ta), ph_a(f, tb));
  const double a = dmax(fabs(a_hi), fabs(a_lo));
  const double sa = ph_s(f, ta), sb = ph_s(f, tb);
  const Curv c = curv_over(ctx, dmin(sa, sb), dmax(sa, sb));
  const double k = c.k, v2 = v * v, v3 = v2 * v, vp3 = v_pos * v_pos * v_pos;
  Bound3 b;
  b.v = v;
  b.a = sqrt(a * a + k * k * v2 * v2);
  // Tangential: s''' - kappa^2 s'^3 with kappa^2 s'^3 in [0, kappa^2 v^3].
  const double jt = dmax(fabs(f.j), fabs(f.j - k * k * v3));
  // Normal: 3 kappa s' s'' + kappa_s s'^3 with kappa_s in [-down, up].
  const double up = 3.0 * k * v * dmax(a_hi, 0.0) + (c.up >= 0.0 ? c.up * v3 : c.up * vp3);
  const double dn = 3.0 * k * v * dmin(a_lo, 0.0) - (c.down >= 0.0 ? c.down * v3 : c.down * vp3);
  const double jn = dmax(fabs(up), fabs(dn));
  b.j = sqrt(jt * jt + jn * jn);
  return b;
}

/** sub_bound over [ta, tb], in 2, 4, ..., 2^splits parts while it misses `allowed` (each a
 *  bound: the least of them per quantity is one). */
Bound3 span_bound(const tdo_traj* ctx, const Phase& f, double ta, double tb, const Bound3& allowed,
                  uint32_t splits) {
  Bound3 b = sub_bound(ctx, f, ta, tb);
  for (uint32_t d = 1; d <= splits && !fits(b, allowed); ++d) {
    const uint32_t parts = 1u << d;
    const double h = (tb - ta) / parts;
    Bound3 m{0.0, 0.0, 0.0};
    for (uint32_t i = 0; i < parts; ++i)
      m = bmax(m, sub_bound(ctx, f, ta + h * i, i + 1u == parts ? tb : ta + h * (i + 1u)));
    b = bmin(b, m);
  }
  return b;
}

/** Index of the first piece that ends after t (the last when none). */
uint32_t piece_after(const tdo_traj* ctx, double t) {
  uint32_t lo = 0, hi = ctx->n_phases;  // answer in [lo, hi)
  while (hi - lo > 1u) {                // bisection: bounded by log2(n_phases)
    const uint32_t mid = lo + (hi - lo) / 2u;
    const Phase& f = ctx->phases[mid - 1u];
    (f.t0 + f.dur <= t ? lo : hi) = mid;
  }
  return lo;
}

/** The jump of the profile from the end of piece e to the start of piece f, as deltas of x. */
bool profile_jump(const tdo_traj* ctx, const Phase& e, const Phase& f, Junction* out) {
  const double es = ph_s(e, e.dur), ev = ph_v(e, e.dur), ea = ph_a(e, e.dur);
  const double ds = fabs(f.s0 - es), dv = fabs(f.v0 - ev), da = fabs(f.a0 - ea);
  if (!(ds > 0.0 || dv > 0.0 || da > 0.0)) return false;
  const Curv c = curv_over(ctx, dmin(es, f.s0), dmax(es, f.s0));
  const double v = dmax(fabs(ev), fabs(f.v0)), a = dmax(fabs(ea), fabs(f.a0));
  const double ks = dmax(fabs(c.up), fabs(c.down)) + c.k * c.k;  // |d(kappa N)/ds|
  // x' = s' T: |dT| <= kappa ds; x'' = s'' T + s'^2 kappa N.
  *out =
      Junction{f.t0, ds, dv + v * c.k * ds,
               da + a * c.k * ds + c.k * (2.0 * v * dv + dv * dv) + (v + dv) * (v + dv) * ks * ds,
               UINT32_MAX};
  return true;
}

/** The joint at the start of plateau q, crossed by piece k (s0 of q at most its end): its time
 *  (the piece's start, or bisection inside it) and its deltas from s', s'' there. */
Junction joint_at(const tdo_traj* ctx, uint32_t k, uint32_t q) {
  const Phase& f = ctx->phases[k];
  const JointJump& b = ctx->pieces->jumps[q];
  const double sj = ctx->plateaus[q].s0;
  double t, v, a;
  if (!(ph_s(f, 0.0) < sj)) {  // at the piece's start: both sides of it
    t = f.t0;
    v = fabs(f.v0);
    a = fabs(f.a0);
    if (k > 0u) {
      const Phase& e = ctx->phases[k - 1u];
      v = dmax(v, fabs(ph_v(e, e.dur)));
      a = dmax(a, fabs(ph_a(e, e.dur)));
    }
  } else {
    double lo = 0.0, hi = f.dur;  // s(lo) < sj <= s(hi) (or the piece's end)
    for (int it = 0; it < kCrossBisections && hi - lo > 0.0; ++it) {
      const double mid = 0.5 * (lo + hi);
      if (!(mid > lo && mid < hi)) break;
      (ph_s(f, mid) < sj ? lo : hi) = mid;
    }
    double v_lo, v_hi;
    speed_range(f, lo, hi, &v_lo, &v_hi);
    v = dmax(fabs(v_lo), fabs(v_hi));
    a = dmax(fabs(ph_a(f, lo)), fabs(ph_a(f, hi)));
    t = f.t0 + lo;
  }
  return Junction{t, 0.0, v * b.t, a * b.t + v * v * b.k, ctx->plateaus[q].seg};
}

/** The deltas of the trajectory in time order into ctx->pieces->junctions; their number. */
uint32_t junctions(tdo_traj* ctx, uint32_t n, double dt) {
  const Phase* ph = ctx->phases;
  const Plateau* pl = ctx->plateaus;
  const uint32_t np = ctx->n_phases, npl = ctx->n_plateaus;
  Junction* out = ctx->pieces->junctions;
  uint32_t m = 0, q = 1;
  for (uint32_t k = 0; k < np; ++k) {
    if (k > 0u && profile_jump(ctx, ph[k - 1u], ph[k], &out[m])) ++m;
    const double end = ph_s(ph[k], ph[k].dur);
    for (; q < npl && (pl[q].s0 <= end || k + 1u == np); ++q) {  // bounded by npl
      if (pl[q].seg == pl[q - 1u].seg) continue;                 // inside a curved segment: smooth
      out[m++] = joint_at(ctx, k, q);
    }
  }
  // The end: the last piece's state held until the last sample, which is exactly the goal.
  const Phase& e = ph[np - 1u];
  const double es = ph_s(e, e.dur), ev = ph_v(e, e.dur), ea = ph_a(e, e.dur);
  const Curv c = curv_over(ctx, es, ctx->total);
  out[m++] = Junction{e.t0 + e.dur, 0.0, fabs(ev), fabs(ea) + ev * ev * c.k, UINT32_MAX};
  out[m++] = Junction{dt * (n - 1u), fabs(ctx->total - es), 0.0, 0.0, UINT32_MAX};
  return m;
}

/** m, e_P: rounding of the sampled positions (relative to their size) and the Beziers' inversion.
 */
double position_noise(const tdo_path& path) {
  double p_max = 0.0, l_max = 1.0;
  for (uint32_t i = 0; i < path.n; ++i) {
    const tdo_path_segment& s = path.seg[i];
    double r = 0.0;
    for (int c = 0; c < 4; ++c) r = dmax(r, norm(s.p[c]));
    if (s.kind == TDO_SEGMENT_ARC) r += norm(sub(s.p[0], s.p[2]));
    p_max = dmax(p_max, r);
    if (s.kind == TDO_SEGMENT_BEZIER) l_max = dmax(l_max, s.length);
  }
  return kPositionNoise * (p_max + 1.0) + kInversionNoise * l_max;
}

/** The closed-form dynamic check; its bounds into *worst. False when a bound misses. */
bool pieces_dynamic(tdo_traj* ctx, const tdo_traj_input* in, const Limits& lim, uint32_t n,
                    Bound3* worst, uint32_t* m_out, RigorSeg* rs) {
  const double dt = lim.dt, e = position_noise(in->path);
  const double f = 1.0 + kTolerance * kPieceReserve;
  const Bound3 noise{2.0 * e / dt, 4.0 * e / (dt * dt), 8.0 * e / (dt * dt * dt)};
  const Bound3 allowed{lim.v_max * f - noise.v, lim.a_max * f - noise.a, lim.j_max * f - noise.j};
  // span_bound with the bounds in place. Where the coarse ones miss, the plateaus under the
  // parts of the span that miss (2^kCoarseSplits) get the fine ones (refine_over); where it still
  // misses, every plateau gets them (rigorous_curvature) and they decide, as they would alone (the
  // spans before hold with the bounds they had, which are proven too).
  const auto bound = [&](const Phase& ph, double ta, double tb, const Bound3& lim3) {
    Bound3 b = span_bound(ctx, ph, ta, tb, lim3, ctx->pieces->fine ? kPieceSplits : kCoarseSplits);
    if (fits(b, lim3) || ctx->pieces->fine) return b;
    const uint32_t parts = 1u << kCoarseSplits;
    const double h = (tb - ta) / parts;
    bool local = true;  // s rises on the span: each part's plateaus are known
    for (uint32_t i = 0; i < parts && local; ++i) {
      const double t0 = ta + h * i, t1 = i + 1u == parts ? tb : ta + h * (i + 1u);
      if (fits(sub_bound(ctx, ph, t0, t1), lim3)) continue;
      double v_lo, v_hi;
      speed_range(ph, t0, t1, &v_lo, &v_hi);
      local = v_lo >= 0.0;
      if (local) refine_over(ctx, in->path, ph_s(ph, t0), ph_s(ph, t1), rs);
    }
    if (local) {
      b = span_bound(ctx, ph, ta, tb, lim3, kPieceSplits);
      if (fits(b, lim3)) return b;
    }
    rigorous_curvature(ctx, in->path, kRigorParts, rs);
    return span_bound(ctx, ph, ta, tb, lim3, kPieceSplits);
  };
  Bound3 top{0.0, 0.0, 0.0};
  for (uint32_t k = 0; k < ctx->n_phases; ++k) {
    const Phase& ph = ctx->phases[k];
    const Bound3 b = bound(ph, 0.0, ph.dur, allowed);
    if (!fits(b, allowed)) return false;
    top = bmax(top, b);
  }
  const uint32_t m = junctions(ctx, n, dt);
  *m_out = m;
  const Junction* jn = ctx->pieces->junctions;
  const double w = 3.0 * dt;
  for (uint32_t i = 0, lo = 0; i < m; ++i) {
    while (jn[lo].t < jn[i].t - w) ++lo;  // bounded by i
    double ds = 0.0, dv = 0.0, da = 0.0;
    for (uint32_t r = lo; r < m && jn[r].t <= jn[i].t + w; ++r) {
      ds += jn[r].ds;
      dv += jn[r].dv;
      da += jn[r].da;
    }
    if (!(ds > 0.0 || dv > 0.0 || da > 0.0)) continue;
    const Bound3 delta{ds / dt, dv / dt + ds / (dt * dt),
                       0.75 * da / dt + dv / (dt * dt) + 2.0 * ds / (dt * dt * dt)};
    const Bound3 left{allowed.v - delta.v, allowed.a - delta.a, allowed.j - delta.j};
    Bound3 smooth{0.0, 0.0, 0.0};
    const double ta = jn[i].t - w, tb = jn[i].t + w;
    for (uint32_t k = piece_after(ctx, ta); k < ctx->n_phases; ++k) {
      const Phase& ph = ctx->phases[k];
      if (ph.t0 >= tb) break;
      smooth = bmax(smooth, bound(ph, dmax(0.0, ta - ph.t0), dmin(ph.dur, tb - ph.t0), left));
    }
    if (!fits(smooth, left)) return false;
    top = bmax(top, Bound3{smooth.v + delta.v, smooth.a + delta.a, smooth.j + delta.j});
  }
  *worst = Bound3{top.v + noise.v, top.a + noise.a, top.j + noise.j};
  return true;
}

/** Of the larger |kappa| at an interval's ends and middle: the most the cubic Hermite of the two
 *  stations may miss the middle's curvature by for the interval to use the two half cubics
 *  (station_kappa). */
constexpr double kStationFit = 1e-3;

/** 1/m, the cubic Hermite at t in [0, 1] of (k0, d0) and (k1, d1) over width w. */
inline double hermite(double k0, double d0, double k1, double d1, double w, double t) {
  const double t2 = t * t, t3 = t2 * t;
  return (2.0 * t3 - 3.0 * t2 + 1.0) * k0 + (t3 - 2.0 * t2 + t) * w * d0 +
         (3.0 * t2 - 2.0 * t3) * k1 + (t3 - t2) * w * d1;
}

/** Pieces mode: at the middle parameter of every station interval of the Beziers' plateaus the
 *  exact curvature and its rate, and the arclength there from the stations' |B'| and its
 *  derivative (corrected trapezoid rule, error O(du^5): no inversion, no quadrature); and whether
 *  the stations' cubic Hermite fits that curvature (kStationFit). `c`: scratch cursor. */
void station_mids(const tdo_traj* ctx, const tdo_path& path, BezierCursor* c) {
  const uint32_t stations = kStations / ctx->pieces->curve_parts;
  BezierCursor& cur = *c;
  cur.seg = UINT32_MAX;
  for (uint32_t q = 0; q < ctx->n_plateaus; ++q) {
    const Plateau& p = ctx->plateaus[q];
    const tdo_path_segment& seg = path.seg[p.seg];
    if (seg.kind != TDO_SEGMENT_BEZIER) continue;
    if (cur.seg != p.seg) cursor_reset(&cur, seg, p.seg);
    StationK* st = ctx->pieces->stations + ctx->pieces->spans[q].first;
    for (uint32_t i = 0; i < stations; ++i) {
      StationK& a = st[i];
      const StationK& b = st[i + 1u];
      const double du = 0.5 * (b.u - a.u);
      cur.u = a.u + du;
      cur.d1u = bez_d1(cur, cur.u);
      cur.d2u = bez_d2(cur, cur.u);
      cur.spu = norm(cur.d1u);
      cur.curvu = cur.spu > 0.0 ? dot(cur.d1u, cur.d2u) / cur.spu : 0.0;
      cur.have = 1;
      tdo_segment_state m;
      cursor_curvature(cur, &m);
      a.mk = m.kappa;
      a.mdk = m.dkappa_ds;
      a.ms = a.s + 0.5 * du * (a.sp + cur.spu) + du * du / 12.0 * (a.dsp - cur.curvu);
      const double w = b.s - a.s, t = w > 0.0 ? (a.ms - a.s) / w : 0.0;
      const double fit = hermite(a.k, a.dk, b.k, b.dk, w, t);
      const double scale = dmax(fabs(m.kappa), dmax(fabs(a.k), fabs(b.k)));
      a.exact = !(fabs(fit - m.kappa) <= kStationFit * scale) || !(a.ms > a.s && a.ms < b.s) ||
                !isfinite(m.kappa) || !isfinite(m.dkappa_ds);
    }
  }
}

/** 1/m, |kappa| of the Bezier `seg` at its local arclength s; q0 is its first plateau. Between two
 *  stations of the curve summary (handed down, with the middle from station_mids) the two half
 *  cubic Hermites, instead of inverting the arclength at each of the energy integral's nodes;
 *  where they do not fit, the arclength inverted (cursor `cur`). */
double station_kappa(const tdo_traj* ctx, uint32_t q0, const tdo_path_segment& seg, double s,
                     BezierCursor* cur) {
  const uint32_t m = ctx->pieces->curve_parts, stations = kStations / m;
  uint32_t j = 0;
  while (j + 1u < m && ctx->plateaus[q0 + j + 1u].off <= s) ++j;  // bounded by m
  const Plateau& p = ctx->plateaus[q0 + j];
  const StationK* st = ctx->pieces->stations + ctx->pieces->spans[q0 + j].first;
  double fi = floor((s - p.off) / (p.len / stations));
  fi = fi < 0.0 ? 0.0 : (fi > stations - 1.0 ? stations - 1.0 : fi);
  const StationK& a = st[static_cast<uint32_t>(fi)];
  const StationK& b = (&a)[1];
  if (a.exact) {
    if (cur->seg != p.seg) cursor_reset(cur, seg, p.seg);
    cursor_seek(cur, s);
    tdo_segment_state e;
    cursor_curvature(*cur, &e);
    return e.kappa;
  }
  if (s <= a.ms) return hermite(a.k, a.dk, a.mk, a.mdk, a.ms - a.s, (s - a.s) / (a.ms - a.s));
  return hermite(a.mk, a.mdk, b.k, b.dk, b.s - a.ms, (s - a.ms) / (b.s - a.ms));
}

/** m^2/s^3, integral of |x''|^2 = s''^2 + s'^4 kappa^2 over [ta, tb] of piece f on the segment of
 *  plateau q0 (its first): s''^2 exactly; kappa^2 s'^4 by 5-point Gauss-Legendre, exactly on arcs,
 *  on Beziers in panels of at most 1/kEnergyPanels of the segment's length (a corner's curvature
 *  peaks) with the curvature from the summary's stations (station_kappa). */
double span_energy(const tdo_traj* ctx, const Phase& f, double ta, double tb,
                   const tdo_path_segment& seg, uint32_t q0, BezierCursor* cur) {
  const double h = tb - ta, a = ph_a(f, ta);
  const double e = h * (a * a + h * f.j * (a + f.j * h / 3.0));
  if (seg.kind == TDO_SEGMENT_LINE || !(h > 0.0)) return e;
  uint32_t panels = 1u;
  if (seg.kind == TDO_SEGMENT_BEZIER && seg.length > 0.0) {
    const double share = ceil(kEnergyPanels * fabs(ph_s(f, tb) - ph_s(f, ta)) / seg.length);
    panels =
        share >= kEnergyPanels ? kEnergyPanels : (share > 1.0 ? static_cast<uint32_t>(share) : 1u);
  }
  const double kr = 1.0 / norm(sub(seg.p[0], seg.p[2]));  // arcs: constant curvature
  const double seg_s0 = ctx->plateaus[q0].s0;
  const double w = h / panels;
  double sum = 0.0;
  for (uint32_t pn = 0; pn < panels; ++pn) {
    double part = 0.0;
    for (int i = -2; i <= 2; ++i) {
      const int g = i < 0 ? -i : i;
      const double x = i < 0 ? -kGl5X[g] : kGl5X[g];
      const double t = ta + w * (pn + 0.5 * (1.0 + x));
      const double v = ph_v(f, t), v2 = v * v;
      double k = kr;
      if (seg.kind == TDO_SEGMENT_BEZIER)
        k = station_kappa(ctx, q0, seg, dmin(seg.length, dmax(0.0, ph_s(f, t) - seg_s0)), cur);
      part += kGl5W[g] * k * k * v2 * v2;
    }
    sum += 0.5 * w * part;
  }
  return e + sum;
}

/** The energy of the profile: every piece split at the segment joints it crosses. */
double pieces_energy(const tdo_traj* ctx, const tdo_path& path, uint32_t m) {
  BezierCursor cur;  // station_mids', then the inversions' where the stations' cubics miss
  memset(&cur, 0, sizeof(cur));
  station_mids(ctx, path, &cur);
  cur.seg = UINT32_MAX;
  const Junction* jn = ctx->pieces->junctions;
  double total = 0.0;
  uint32_t r = 0;
  for (uint32_t k = 0; k < ctx->n_phases; ++k) {
    const Phase& f = ctx->phases[k];
    double ta = 0.0;
    for (uint32_t step = 0; step <= m; ++step) {  // each step but the last consumes a junction
      while (r < m && (jn[r].seg == UINT32_MAX || jn[r].t - f.t0 <= ta)) ++r;
      const double tb = r < m && jn[r].t - f.t0 < f.dur ? jn[r].t - f.t0 : f.dur;
      uint32_t q = plateau_of(ctx, ph_s(f, 0.5 * (ta + tb)));
      while (q > 0u && ctx->plateaus[q - 1u].seg == ctx->plateaus[q].seg) --q;  // its first part
      total += span_energy(ctx, f, ta, tb, path.seg[ctx->plateaus[q].seg], q, &cur);
      if (!(tb < f.dur)) break;
      ta = tb;
    }
  }
  return total;
}

/** m, the path's distance to the obstacles as tdo_metrics_compute measures it (lines exact, curves
 *  a chord lower bound), capped at `cap`. The paths keep the clearance and most touch it (the
 *  geometric stages hold them there): a hint just above it caps the queries tightly; the result is
 *  the same whatever the hint. */
double pieces_clearance(const tdo_traj_input* in, double cap) {
  return path_min_clearance(in->grid, &in->path, nullptr, 0u, cap, in->clearance + kPieceClearHint);
}

/** Pieces mode: the clearance part of the report, false when the path comes closer than the
 *  clearance. A path the caller proved (clearance_proven) is not measured again: its bound is the
 *  proof's, clearance less kClearanceSlack, which no sample of the path falls below. */
bool pieces_clear(const tdo_traj_input* in, double* clear) {
  *clear = HUGE_VAL;
  if (in->grid == nullptr) return true;
  if (in->clearance_proven) {
    *clear = dmax(0.0, in->clearance - kClearanceSlack);
    return true;
  }
  *clear = pieces_clearance(in, in->clearance + kClearanceCapExtra);
  return *clear >= in->clearance - kPieceClearSlack;
}

/** Pieces mode: the closed-form checks of the current profile; true when every one holds (the
 *  report and the energy filled), false to fall back to the samples. */
bool pieces_verify(tdo_traj* ctx, const tdo_traj_input* in, const Limits& lim, uint32_t n,
                   tdo_feasibility* rep, double* energy) {
  if (ctx->moving) return false;  // the entry ramp lies off the path: the samples check it
  PiecesState* ps = ctx->pieces;
  RigorSeg rs;
  rs.seg = UINT32_MAX;
  if (!ps->rigor_ready) rigorous_curvature(ctx, in->path, kRigorCoarse, &rs);
  ps->rigor_ready = 1;
  Bound3 worst;
  uint32_t m = 0;
  if (!pieces_dynamic(ctx, in, lim, n, &worst, &m, &rs)) return false;
  double clear;
  if (!pieces_clear(in, &clear)) return false;
  memset(rep, 0, sizeof(*rep));
  rep->ok = 1;
  rep->violations = ctx->violations;
  rep->max_speed = worst.v;
  rep->max_acc = worst.a;
  rep->max_jerk = worst.j;
  double k = 0.0;
  for (uint32_t q = 0; q < ctx->n_plateaus; ++q)
    for (uint32_t i = 0; i < ps->spans[q].np; ++i)
      k = dmax(k, ps->parts[static_cast<size_t>(q) * kRigorParts + i].k);
  rep->min_turn_radius = k > 0.0 ? 1.0 / k : HUGE_VAL;
  rep->min_clearance = clear;
  *energy = pieces_energy(ctx, in->path, m);
  return true;
}

}  // namespace
}  // namespace tdo_internal

using namespace tdo_internal;

/** Plateaus a context holds: every segment, or more when the profile capacity allows curved
 *  segments in parts (curve_parts). */
static uint32_t plateau_capacity(const tdo_traj_config* cfg) {
  const uint32_t by_profile = (cfg->max_profile - 1u) / kPiecesPerPlateau;
  return by_profile > cfg->max_segments ? by_profile : cfg->max_segments;
}

/** A ramp accelerating along v0 that would end above v_max: the shorter ramp (steeper jerk, up to
 *  kRampJerkMax j_max) that ends at exactly v_max, i.e. T / 2 the root of |v0 + a0 T / 2| = v_max;
 *  `ramp` unchanged when even the steepest ramp ends above v_max (a turn at v_max). */
static double steep_ramp(tdo_vec3 v0, tdo_vec3 a0, double v_max, double j_max, double ramp) {
  const double aa = dot(a0, a0), b = dot(v0, a0), c = dot(v0, v0) - v_max * v_max;
  const double disc = b * b - aa * c;
  if (!(aa > 0.0) || !(c <= 0.0) || !(disc >= 0.0)) return ramp;
  const double t = 2.0 * (-b + sqrt(disc)) / aa;
  return t >= sqrt(aa) / (kRampJerkMax * j_max) && t < ramp ? t : ramp;
}

/** Velocity of a constant-jerk piece at t: v0 + a0 t + j t^2 / 2. */
static tdo_vec3 piece_v(tdo_vec3 v0, tdo_vec3 a0, tdo_vec3 j, double t) {
  return add(v0, mul(add(a0, mul(j, 0.5 * t)), t));
}

/** Highest |v|^2 on the constant-jerk piece (v0, a0, j) over [0, T]: at an end, or at a maximum
 *  inside, where g(t) = v.a (half the derivative of |v|^2, a cubic) falls through zero; g is
 *  monotone between the roots of its derivative 1.5 |j|^2 t^2 + 3 (a0.j) t + |a0|^2 + v0.j, and
 *  each such interval with g falling from + to - is bisected kPeakBisections times. */
static double piece_peak_sq(tdo_vec3 v0, tdo_vec3 a0, tdo_vec3 j, double T) {
  const auto g = [&](double t) { return dot(piece_v(v0, a0, j, t), add(a0, mul(j, t))); };
  double cut[4] = {0.0, T, T, T};
  uint32_t n = 1;
  const double qa = 1.5 * dot(j, j), qb = 3.0 * dot(a0, j), qc = dot(a0, a0) + dot(v0, j);
  const double disc = qb * qb - 4.0 * qa * qc;
  if (qa > 0.0 && disc > 0.0) {
    const double r = sqrt(disc), lo = (-qb - r) / (2.0 * qa), hi = (-qb + r) / (2.0 * qa);
    if (lo > 0.0 && lo < T) cut[n++] = lo;
    if (hi > 0.0 && hi < T) cut[n++] = hi;
  }
  cut[n++] = T;
  const tdo_vec3 v_end = piece_v(v0, a0, j, T);
  double peak = dmax(dot(v0, v0), dot(v_end, v_end));
  for (uint32_t k = 0; k + 1u < n; ++k) {
    double lo = cut[k], hi = cut[k + 1u];
    if (!(g(lo) > 0.0 && g(hi) < 0.0)) continue;
    for (int it = 0; it < kPeakBisections; ++it) {
      const double mid = 0.5 * (lo + hi);
      if (g(mid) > 0.0)
        lo = mid;
      else
        hi = mid;
    }
    const tdo_vec3 v = piece_v(v0, a0, j, 0.5 * (lo + hi));
    peak = dmax(peak, dot(v, v));
  }
  return peak;
}

/** A two-piece ramp: a0 to the middle acceleration am at jerk `jerk`, then am to zero. False when
 *  its speed exceeds sqrt(v2_max) anywhere (out unchanged). */
static bool two_piece(tdo_vec3 v0, tdo_vec3 a0, tdo_vec3 am, double jerk, double v2_max,
                      tdo_traj_entry* out) {
  const tdo_vec3 d = sub(am, a0);
  const double t1 = norm(d) / jerk, t2 = norm(am) / jerk;
  if (!(t1 > 0.0)) return false;
  const tdo_vec3 j1 = mul(d, 1.0 / t1), j2 = t2 > 0.0 ? mul(am, -1.0 / t2) : tdo_vec3{0, 0, 0};
  if (piece_peak_sq(v0, a0, j1, t1) > v2_max) return false;
  const tdo_vec3 vk = piece_v(v0, a0, j1, t1);
  if (t2 > 0.0 && piece_peak_sq(vk, am, j2, t2) > v2_max) return false;
  out->ramp = t1 + t2;
  out->knot = t1;
  out->jerk = j1;
  out->jerk2 = j2;
  out->knot_v = vk;
  out->knot_a = am;
  return true;
}

/** The shortest two-piece ramp (two_piece) whose middle acceleration am = -b v^ + c n^ (v^ along
 *  v0, n^ along the part of a0 across it) lies on the grid b = a_max k / kMidGrid (k =
 * 0..kMidGrid), c = a_max l / kMidGrid (|l| <= kMidGrid), |am| <= a_max, at kRampJerk j_max, else
 * at kRampJerkMax j_max; false when none keeps the speed within sqrt(v2_max). */
static bool two_piece_ramp(tdo_vec3 v0, tdo_vec3 a0, double a_max, double j_max, double v2_max,
                           tdo_traj_entry* out) {
  const double sp = norm(v0);
  if (!(sp > 0.0)) return false;
  const tdo_vec3 vh = mul(v0, 1.0 / sp), across = sub(a0, mul(vh, dot(a0, vh)));
  const double na = norm(across);
  const tdo_vec3 nh = na > 0.0 ? mul(across, 1.0 / na) : tdo_vec3{0.0, 0.0, 0.0};
  const int lmax = na > 0.0 ? kMidGrid : 0;
  for (int f = 0; f < 2; ++f) {
    const double jerk = (f == 0 ? kRampJerk : kRampJerkMax) * j_max;
    double best = HUGE_VAL;
    for (int k = 0; k <= kMidGrid; ++k) {
      for (int l = -lmax; l <= lmax; ++l) {
        if (k * k + l * l > kMidGrid * kMidGrid) continue;
        const double step = a_max / kMidGrid;
        const tdo_vec3 am = add(mul(vh, -step * k), mul(nh, step * l));
        const double dur = (norm(sub(am, a0)) + norm(am)) / jerk;
        tdo_traj_entry e = *out;
        if (!(dur < best) || !two_piece(v0, a0, am, jerk, v2_max, &e)) continue;
        best = dur;
        *out = e;
      }
    }
    if (best < HUGE_VAL) return true;
  }
  return false;
}

/** The one-piece ramp's entry (jerk -a0 / ramp); false when its speed ends above v_max. */
static bool one_piece(tdo_vec3 p0, tdo_vec3 v0, tdo_vec3 a0, double v_max, double j_max,
                      tdo_traj_entry* out) {
  const double acc = norm(a0);
  // a(t) = a0 (1 - t / T), so v(t) runs along the segment from v0 to v0 + a0 T / 2 and its norm
  // never exceeds the larger end (the norm is convex).
  double ramp = acc > 0.0 ? acc / (kRampJerk * j_max) : 0.0;
  tdo_vec3 v1 = add(v0, mul(a0, 0.5 * ramp));
  if (norm(v1) > v_max) ramp = steep_ramp(v0, a0, v_max, j_max, ramp);
  v1 = add(v0, mul(a0, 0.5 * ramp));
  if (!(norm(v1) <= v_max * (1.0 + kStateSlack))) return false;
  out->ramp = ramp;
  out->knot = ramp;
  out->jerk = ramp > 0.0 ? mul(a0, -1.0 / ramp) : tdo_vec3{0.0, 0.0, 0.0};
  out->p = add(p0, add(mul(v0, ramp), mul(a0, ramp * ramp / 3.0)));
  out->knot_p = out->p;
  out->v = v1;
  out->knot_v = v1;
  return true;
}

extern "C" tdo_status tdo_traj_entry_plan(tdo_vec3 p0, const tdo_start_state* s, double v_max,
                                          double a_max, double j_max, tdo_traj_entry* out) {
  if (s == nullptr || out == nullptr || !finite3(p0) || !positive(v_max) || !positive(a_max) ||
      !positive(j_max))
    return TDO_ERR_INVALID_ARGUMENT;
  memset(out, 0, sizeof(*out));
  if (!finite3(s->v) || !finite3(s->a)) return TDO_ERR_STATE_NOT_FINITE;
  const tdo_vec3 v0 = s->v, a0 = s->a;
  if (norm(v0) > v_max * (1.0 + kStateSlack)) return TDO_ERR_STATE_TOO_FAST;
  if (norm(a0) > a_max * (1.0 + kStateSlack)) return TDO_ERR_STATE_OVER_LIMITS;
  if (!one_piece(p0, v0, a0, v_max, j_max, out)) {
    const double vs = v_max * (1.0 + kStateSlack);
    if (!two_piece_ramp(v0, a0, a_max, j_max, vs * vs, out)) return TDO_ERR_STATE_OVER_LIMITS;
    const double t1 = out->knot, t2 = out->ramp - out->knot;
    const tdo_vec3 ak = out->knot_a, vk = out->knot_v, j1 = out->jerk, j2 = out->jerk2;
    out->knot_p = add(p0, mul(add(v0, mul(add(mul(a0, 0.5), mul(j1, t1 / 6.0)), t1)), t1));
    out->p = add(out->knot_p, mul(add(vk, mul(add(mul(ak, 0.5), mul(j2, t2 / 6.0)), t2)), t2));
    out->v = piece_v(vk, ak, j2, t2);
  }
  double speed = norm(out->v);
  if (speed > v_max) {  // rounding only (kStateSlack): the path starts at exactly v_max
    out->v = mul(out->v, v_max / speed);
    speed = v_max;
  }
  out->speed = speed;
  out->brake = dmax(
      scurve_dist(0.0, speed, kLineAcc * a_max, kJumpJerk * j_max) * (1.0 + kBrakeRel) + kBrakeAbs,
      kBrakeMin);
  if (!(speed > 0.0)) out->brake = 0.0;
  return TDO_OK;
}

extern "C" size_t tdo_traj_footprint(const tdo_traj_config* cfg) {
  if (cfg == nullptr || cfg->max_samples < 2u || cfg->max_segments == 0u || cfg->max_profile == 0u)
    return 0;
  const size_t ns = cfg->stream_samples ? 0u : cfg->max_samples, nseg = plateau_capacity(cfg);
  const bool pieces = cfg->stream_samples == TDO_TRAJ_SAMPLES_PIECES;
  const size_t nj = pieces ? nseg + cfg->max_profile + 2u : 0u;
  const size_t np = pieces ? nseg * kRigorParts : 0u, nb = pieces ? nseg + 1u : 0u;
  const size_t nsp = pieces ? nseg : 0u;
  const size_t nst = pieces ? static_cast<size_t>(kStations + kSubMax) * cfg->max_segments : 0u;
  return tdo_arena_round(sizeof(tdo_traj)) + (pieces ? tdo_arena_round(sizeof(PiecesState)) : 0u) +
         tdo_arena_round(nsp * sizeof(PlateauSpan)) + tdo_arena_round(nst * sizeof(StationK)) +
         tdo_arena_round(nj * sizeof(Junction)) + tdo_arena_round(np * sizeof(RigorPart)) +
         tdo_arena_round(nb * sizeof(JointJump)) + tdo_arena_round(ns * sizeof(tdo_sample)) +
         tdo_arena_round(ns * sizeof(uint32_t)) +
         tdo_arena_round(static_cast<size_t>(cfg->max_violations) * sizeof(tdo_violation)) +
         tdo_arena_round(nseg * sizeof(Plateau)) + tdo_arena_round((nseg + 1u) * sizeof(Boundary)) +
         tdo_arena_round(nseg) +
         tdo_arena_round(static_cast<size_t>(cfg->max_profile) * sizeof(Phase));
}

extern "C" tdo_status tdo_traj_init(tdo_traj** out, tdo_arena* arena, const tdo_traj_config* cfg) {
  if (out == nullptr || arena == nullptr || cfg == nullptr || tdo_traj_footprint(cfg) == 0)
    return TDO_ERR_INVALID_ARGUMENT;
  *out = nullptr;
  if (cfg->max_segments >= 0xFFFFFFFFu || cfg->max_samples > 0x7FFFFFFFu ||
      cfg->stream_samples > TDO_TRAJ_SAMPLES_PIECES)
    return TDO_ERR_INVALID_ARGUMENT;
  tdo_traj* ctx = static_cast<tdo_traj*>(tdo_arena_alloc(arena, sizeof(tdo_traj)));
  if (ctx == nullptr) return TDO_ERR_ARENA_TOO_SMALL;
  memset(ctx, 0, sizeof(*ctx));
  ctx->cfg = *cfg;
  ctx->plateau_cap = plateau_capacity(cfg);
  const size_t nseg = ctx->plateau_cap;
  if (!cfg->stream_samples) {
    const size_t ns = cfg->max_samples;
    ctx->samples = static_cast<tdo_sample*>(tdo_arena_alloc(arena, ns * sizeof(tdo_sample)));
    ctx->owner = static_cast<uint32_t*>(tdo_arena_alloc(arena, ns * sizeof(uint32_t)));
    if (ctx->samples == nullptr || ctx->owner == nullptr) return TDO_ERR_ARENA_TOO_SMALL;
  }
  ctx->violations = static_cast<tdo_violation*>(
      tdo_arena_alloc(arena, static_cast<size_t>(cfg->max_violations) * sizeof(tdo_violation)));
  ctx->plateaus = static_cast<Plateau*>(tdo_arena_alloc(arena, nseg * sizeof(Plateau)));
  ctx->bounds = static_cast<Boundary*>(tdo_arena_alloc(arena, (nseg + 1u) * sizeof(Boundary)));
  ctx->hit = static_cast<uint8_t*>(tdo_arena_alloc(arena, nseg));
  ctx->phases = static_cast<Phase*>(
      tdo_arena_alloc(arena, static_cast<size_t>(cfg->max_profile) * sizeof(Phase)));
  if (ctx->violations == nullptr || ctx->plateaus == nullptr || ctx->bounds == nullptr ||
      ctx->hit == nullptr || ctx->phases == nullptr)
    return TDO_ERR_ARENA_TOO_SMALL;
  if (cfg->stream_samples == TDO_TRAJ_SAMPLES_PIECES) {
    PiecesState* ps = static_cast<PiecesState*>(tdo_arena_alloc(arena, sizeof(PiecesState)));
    if (ps == nullptr) return TDO_ERR_ARENA_TOO_SMALL;
    const size_t nj = nseg + cfg->max_profile + 2u;
    ps->junctions = static_cast<Junction*>(tdo_arena_alloc(arena, nj * sizeof(Junction)));
    ps->parts =
        static_cast<RigorPart*>(tdo_arena_alloc(arena, nseg * kRigorParts * sizeof(RigorPart)));
    ps->jumps = static_cast<JointJump*>(tdo_arena_alloc(arena, (nseg + 1u) * sizeof(JointJump)));
    ps->spans = static_cast<PlateauSpan*>(tdo_arena_alloc(arena, nseg * sizeof(PlateauSpan)));
    ps->stations = static_cast<StationK*>(tdo_arena_alloc(
        arena, static_cast<size_t>(kStations + kSubMax) * cfg->max_segments * sizeof(StationK)));
    ps->curve_parts = 1u;
    ps->rigor_ready = 0;
    ps->fine = 0;
    if (ps->junctions == nullptr || ps->parts == nullptr || ps->jumps == nullptr ||
        ps->spans == nullptr || ps->stations == nullptr)
      return TDO_ERR_ARENA_TOO_SMALL;
    ctx->pieces = ps;
  }
  *out = ctx;
  return TDO_OK;
}

extern "C" tdo_status tdo_traj_run(tdo_traj* ctx, const tdo_traj_input* in, tdo_traj_output* out) {
  if (ctx == nullptr || in == nullptr || out == nullptr) return TDO_ERR_INVALID_ARGUMENT;
  memset(out, 0, sizeof(*out));
  out->report.min_turn_radius = HUGE_VAL;
  out->report.min_clearance = HUGE_VAL;
  out->report.violations = ctx->violations;
  ctx->n_last = 0;
  ctx->moving = 0;
  if (ctx->pieces != nullptr) ctx->pieces->rigor_ready = 0;
  tdo_status st = validate(ctx, in);
  if (st == TDO_OK) st = validate_start(ctx, in);
  if (st != TDO_OK) return st;
  const Limits lim{in->v_max, in->a_max, in->j_max, in->a_lat_max, in->dt};
  st = analyse(ctx, in, lim);
  if (st != TDO_OK) return st;
  const uint32_t rounds = ctx->cfg.max_refinements;
  for (uint32_t round = 0; round <= rounds; ++round) {
    ctx->n_last = 0;  // the profile changes: the samples of a previous round are gone
    st = build_profile(ctx, lim);
    if (st != TDO_OK) return st;
    uint32_t n = 0;
    st = sample_count(ctx, lim.dt, &n);
    if (st != TDO_OK) return st;
    uint32_t dynamic;
    if (ctx->cfg.stream_samples == TDO_TRAJ_SAMPLES_PIECES &&
        pieces_verify(ctx, in, lim, n, &out->report, &out->energy)) {
      dynamic = 0u;
      out->samples = nullptr;
      out->duration = lim.dt * (n - 1u);  // as the streamed samples' last t
    } else if (ctx->cfg.stream_samples) {
      ++out->sample_passes;
      StreamedSamples src;
      src.ctx = ctx;
      src.segs = in->path.seg;
      src.dt = lim.dt;
      src.n = n;
      dynamic = verify(ctx, in, lim, n, src, &out->report, &out->energy);
      out->samples = nullptr;
      out->duration = lim.dt * (n - 1u);  // the last sample's t, as the generator computes it
    } else {
      ++out->sample_passes;
      sample(ctx, in, lim, n);
      StoredSamples src{ctx->samples, ctx->owner};
      dynamic = verify(ctx, in, lim, n, src, &out->report, &out->energy);
      out->samples = ctx->samples;
      out->duration = ctx->samples[n - 1u].t;
    }
    ctx->n_last = n;
    ctx->last_segs = in->path.seg;
    ctx->last_dt = lim.dt;
    out->n_samples = n;
    out->refinements = round;
    if (out->report.ok) return TDO_OK;
    // Clearance violations are geometry: a slower flight does not move the path.
    if (dynamic == 0u || round == rounds) break;
    // Lower the plateaus around every violation (speed, acceleration and jerk limits).
    // A moving start's braking line keeps its limits: it must stop from the start speed.
    const uint32_t first = ctx->moving && ctx->entry.speed > 0.0 ? 1u : 0u;
    for (uint32_t k = first; k < ctx->n_plateaus; ++k)
      if (ctx->hit[k]) ctx->plateaus[k].scale *= kRefineFactor;
  }
  return TDO_ERR_INFEASIBLE;
}

extern "C" tdo_status tdo_traj_each_sample(const tdo_traj* ctx, tdo_sample_fn fn, void* user) {
  if (ctx == nullptr || fn == nullptr || ctx->n_last == 0u) return TDO_ERR_INVALID_ARGUMENT;
  const uint32_t n = ctx->n_last;
  if (!ctx->cfg.stream_samples) {
    for (uint32_t i = 0; i < n; ++i) fn(user, i, &ctx->samples[i]);
    return TDO_OK;
  }
  Sampler g;
  sampler_start(&g, ctx, ctx->last_segs, ctx->last_dt, n);
  for (uint32_t i = 0; i < n; ++i) {
    tdo_sample smp;
    uint32_t owner;
    sampler_next(&g, &smp, &owner);
    fn(user, i, &smp);
  }
  return TDO_OK;
}

// ---------------------------------------------------------------------------------------------
// Read-only access to the last run's profile (traj_profile.h).

extern "C" tdo_status tdo_traj_profile(const tdo_traj* ctx, tdo_traj_profile_info* out) {
  if (ctx == nullptr || out == nullptr || ctx->n_last == 0u) return TDO_ERR_INVALID_ARGUMENT;
  out->n_pieces = ctx->n_phases;
  out->n_samples = ctx->n_last;
  out->dt = ctx->last_dt;
  out->duration = ctx->last_dt * (ctx->n_last - 1u);  // as the sampler computes the last t
  out->length = ctx->total;
  return TDO_OK;
}

extern "C" tdo_status tdo_traj_piece_at(const tdo_traj* ctx, uint32_t index, tdo_traj_piece* out) {
  if (ctx == nullptr || out == nullptr || ctx->n_last == 0u || index >= ctx->n_phases)
    return TDO_ERR_INVALID_ARGUMENT;
  const Phase& f = ctx->phases[index];
  *out = tdo_traj_piece{f.t0, f.dur, f.s0, f.v0, f.a0, f.j};
  return TDO_OK;
}
