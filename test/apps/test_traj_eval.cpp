// The compact trajectory message and its header-only evaluator (lcmtypes/include/tdo_traj_eval.h)
// against the library's own samples: tdo-planner's node on Map1-5 over memq://, each request with
// SAMPLES_ON so one answer carries both forms; the evaluator at every sample time must give the
// library's sample to 1e-9 m. Also the size of Map5's answer without samples (issue goal: 16 kB).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "planner_node.h"
#include "tdo/tdo.h"
#include "tdo_lcm/adapters.h"
#include "tdo_lcm/bus.h"
#include "tdo_lcm/compact.h"
#include "tdo_lcm/map_file.h"
#include "tdo_lcm/wire.h"
#include "tdo_traj_eval.h"

namespace {

struct Answer {
  tdo::trajectory_t traj{};
  std::size_t bytes = 0;  // encoded size on the wire
};

class TrajEval : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(bus_.good());
    tdo_lcm::PlannerConfig cfg;
    cfg.max_nx = 50;
    cfg.max_ny = 50;
    cfg.max_nz = 20;
    cfg.max_nodes = 500000;
    cfg.max_boxes = 512;
    planner_ = std::make_unique<tdo_lcm::PlannerNode>(&bus_, cfg);
    std::string error;
    ASSERT_TRUE(planner_->start(&error)) << error;
    bus_.subscribe(tdo_lcm::kChannelTrajectory,
                   [this](const void* d, std::size_t n, const std::string&) {
                     Answer a;
                     ASSERT_TRUE(tdo_lcm::decode(d, n, &a.traj).ok());
                     a.bytes = n;
                     answers_.push_back(a);
                   });
  }

  void pump() {
    for (int i = 0; i < 10000 && bus_.handle_timeout(0) > 0; ++i) {
    }
  }

  /** Plan the map's own query with `smoothing`; the answer (with or without samples). */
  Answer plan(const std::string& map_name, int8_t smoothing, bool samples) {
    tdo::map_t map{};
    tdo_lcm::MapFileInfo info;
    std::string error;
    EXPECT_TRUE(tdo_lcm::map_msg_from_file(TDO_MAPS_DIR "/" + map_name, 0.5, &map, &info, &error))
        << error;
    map.map_id = ++map_id_;
    EXPECT_TRUE(bus_.publish(tdo_lcm::kChannelMap, map));
    pump();
    tdo::plan_request_t r{};
    r.request_id = map_id_;
    r.map_id = -1;
    r.start[0] = info.start.x;
    r.start[1] = info.start.y;
    r.start[2] = info.start.z;
    r.goal[0] = info.goal.x;
    r.goal[1] = info.goal.y;
    r.goal[2] = info.goal.z;
    r.use_defaults =
        tdo::plan_request_t::USE_DEFAULT_ALL & ~tdo::plan_request_t::USE_DEFAULT_SMOOTHING;
    r.smoothing = smoothing;
    r.samples = samples ? tdo::plan_request_t::SAMPLES_ON : tdo::plan_request_t::SAMPLES_OFF;
    answers_.clear();
    EXPECT_TRUE(bus_.publish(tdo_lcm::kChannelPlanRequest, r));
    pump();
    EXPECT_EQ(answers_.size(), 1u);
    return answers_.empty() ? Answer{} : answers_.back();
  }

  /** Largest deviations of the evaluator from the library's samples of one answer. */
  void compare(const std::string& label, const tdo::trajectory_t& m) {
    ASSERT_EQ(m.status, "ok") << label << ": " << m.detail;
    ASSERT_GT(m.n_samples, 1) << label;
    ASSERT_EQ(m.sample_count, m.n_samples) << label;
    tdo_traj_view v{};
    const tdo_lcm::Check c = tdo_lcm::compact_view(m, &v);
    ASSERT_TRUE(c.ok()) << label << ": " << c.detail;
    double dp = 0.0, dv = 0.0, da = 0.0;
    for (int32_t i = 0; i < m.n_samples; ++i) {
      const std::vector<double>& row = m.samples[static_cast<std::size_t>(i)];
      tdo_traj_state st;
      tdo_traj_eval(&v, row[0], &st);
      for (int a = 0; a < 3; ++a) {
        dp = std::max(dp, std::fabs(st.p[a] - row[1 + a]));
        dv = std::max(dv, std::fabs(st.v[a] - row[4 + a]));
        da = std::max(da, std::fabs(st.a[a] - row[7 + a]));
      }
    }
    std::printf(
        "%-22s %4d segments %4d pieces %6d samples: max |dp| %.3g m, |dv| %.3g m/s, "
        "|da| %.3g m/s^2\n",
        label.c_str(), m.n_segments, m.n_pieces, m.n_samples, dp, dv, da);
    EXPECT_LE(dp, 1e-9) << label;
    EXPECT_LE(dv, 1e-9) << label;
    EXPECT_LE(da, 1e-8) << label;
  }

  /** The jerk output is the derivative of the acceleration output (central differences). */
  void check_jerk(const std::string& label, const tdo::trajectory_t& m) {
    tdo_traj_view v{};
    ASSERT_TRUE(tdo_lcm::compact_view(m, &v).ok());
    const double h = 1e-5;  // s
    double worst = 0.0;
    int checked = 0;
    for (int32_t k = 0; k < m.n_pieces; ++k) {
      const double t0 = m.piece_t0[static_cast<std::size_t>(k)];
      const double dur = m.piece_dur[static_cast<std::size_t>(k)];
      if (!(dur > 10.0 * h)) continue;
      for (double f : {0.25, 0.5, 0.75}) {
        const double t = t0 + f * dur;
        tdo_traj_state lo, mid, hi;
        tdo_traj_eval(&v, t - h, &lo);
        tdo_traj_eval(&v, t, &mid);
        tdo_traj_eval(&v, t + h, &hi);
        if (lo.segment != hi.segment) continue;  // a curvature jump between segments
        for (int a = 0; a < 3; ++a) {
          const double fd = (hi.a[a] - lo.a[a]) / (2.0 * h);
          worst = std::max(worst, std::fabs(fd - mid.j[a]));
        }
        ++checked;
      }
    }
    EXPECT_GT(checked, 10) << label;
    EXPECT_LE(worst, 1e-3) << label;  // central differences of a at h = 1e-5 s: O(h^2) + rounding
  }

  tdo_lcm::Bus bus_{"memq://"};
  std::unique_ptr<tdo_lcm::PlannerNode> planner_;
  std::vector<Answer> answers_;
  int64_t map_id_ = 0;
};

TEST_F(TrajEval, GivenMap1To5WhenSampledAtTheLibrarysTimesThenMatchesItsSamplesTo1em9) {
  for (int k = 1; k <= 5; ++k) {
    const std::string name = "map" + std::to_string(k) + ".tdomap";
    const Answer a = plan(name, tdo::plan_request_t::SMOOTHING_G2, true);
    compare(name + " g2", a.traj);
    check_jerk(name + " g2", a.traj);
  }
}

TEST_F(TrajEval, GivenArcCornersWhenSampledThenMatchesTheLibrarysSamples) {
  for (int k : {1, 4}) {
    const std::string name = "map" + std::to_string(k) + ".tdomap";
    const Answer a = plan(name, tdo::plan_request_t::SMOOTHING_ARC, true);
    int arcs = 0;
    for (int8_t kind : a.traj.segment_kind) arcs += kind == tdo::trajectory_t::SEGMENT_ARC;
    EXPECT_GT(arcs, 0) << name;
    compare(name + " arc", a.traj);
    check_jerk(name + " arc", a.traj);
  }
}

TEST_F(TrajEval, GivenMap5WithoutSamplesThenTheAnswerIsAtMost16kB) {
  const Answer with = plan("map5.tdomap", tdo::plan_request_t::SMOOTHING_G2, true);
  const Answer compact = plan("map5.tdomap", tdo::plan_request_t::SMOOTHING_G2, false);
  ASSERT_EQ(compact.traj.status, "ok");
  EXPECT_EQ(compact.traj.n_samples, 0);
  EXPECT_GT(compact.traj.n_pieces, 0);
  std::printf(
      "Map5 trajectory_t: %zu bytes compact (%d segments, %d pieces), %zu bytes with %d "
      "samples\n",
      compact.bytes, compact.traj.n_segments, compact.traj.n_pieces, with.bytes,
      with.traj.n_samples);
  EXPECT_LE(compact.bytes, 16u * 1024u);
  // The compact answer regenerates the same samples as the sampled one carries.
  std::vector<tdo_sample> regen;
  ASSERT_TRUE(tdo_lcm::samples_from_compact(compact.traj, 100000, &regen).ok());
  ASSERT_EQ(regen.size(), with.traj.samples.size());
  double dp = 0.0;
  for (std::size_t i = 0; i < regen.size(); ++i) {
    EXPECT_EQ(regen[i].t, with.traj.samples[i][0]);
    dp = std::max({dp, std::fabs(regen[i].p.x - with.traj.samples[i][1]),
                   std::fabs(regen[i].p.y - with.traj.samples[i][2]),
                   std::fabs(regen[i].p.z - with.traj.samples[i][3])});
  }
  EXPECT_LE(dp, 1e-9);
}

TEST_F(TrajEval, GivenBadCompactFormsThenTheViewNamesTheReason) {
  const Answer a = plan("map1.tdomap", tdo::plan_request_t::SMOOTHING_G2, false);
  ASSERT_EQ(a.traj.status, "ok");
  tdo_traj_view v{};
  tdo::trajectory_t m = a.traj;
  m.piece_dur[0] = 0.0;
  EXPECT_EQ(tdo_lcm::compact_view(m, &v).reason, tdo_lcm::Reason::out_of_range);
  m = a.traj;
  m.segment_kind[0] = 7;
  EXPECT_EQ(tdo_lcm::compact_view(m, &v).reason, tdo_lcm::Reason::bad_enum);
  m = a.traj;
  m.segment_points[3] = std::nan("");
  EXPECT_EQ(tdo_lcm::compact_view(m, &v).reason, tdo_lcm::Reason::non_finite);
  m = a.traj;
  m.n_pieces += 1;
  EXPECT_EQ(tdo_lcm::compact_view(m, &v).reason, tdo_lcm::Reason::count_mismatch);
  m = a.traj;
  m.piece_t0[1] = m.piece_t0[0] - 1.0;  // knots decreasing
  EXPECT_EQ(tdo_lcm::compact_view(m, &v).reason, tdo_lcm::Reason::out_of_range);
  tdo::trajectory_t empty{};
  EXPECT_EQ(tdo_lcm::compact_view(empty, &v).reason, tdo_lcm::Reason::no_plan);
  // Before 0 and after the end: at rest at the start and at the goal.
  ASSERT_TRUE(tdo_lcm::compact_view(a.traj, &v).ok());
  tdo_traj_state st;
  tdo_traj_eval(&v, -5.0, &st);
  EXPECT_EQ(st.p[0], a.traj.segment_points[0]);
  EXPECT_EQ(st.v[0], 0.0);
  tdo_traj_eval(&v, a.traj.duration_s + 100.0, &st);
  const std::size_t last = a.traj.segment_points.size() - 12u;
  const int8_t kind = a.traj.segment_kind.back();
  const std::size_t end = kind == tdo::trajectory_t::SEGMENT_BEZIER ? 9u : 3u;
  for (int k = 0; k < 3; ++k) EXPECT_EQ(st.p[k], a.traj.segment_points[last + end + k]);
  EXPECT_EQ(st.v[0], 0.0);
  EXPECT_EQ(st.a[0], 0.0);
}

}  // namespace
