// tdo_samples (apps/common/samples): a plan's samples as one vector whether the library stored
// them or regenerates them (tdo_capacity.stream_samples), and its refusals.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "tdo/tdo.h"
#include "tdo_samples/samples.h"

namespace {

/** A planner on a 10 x 10 x 5 m map at 0.5 m with one wall, planning with `stream_samples`. */
struct Planned {
  std::vector<unsigned char> mem;
  tdo_planner* planner = nullptr;
  tdo_plan_result r{};
  tdo_status st = TDO_ERR_INVALID_ARGUMENT;
};

void plan(uint32_t stream_samples, Planned* p) {
  tdo_planner_config cfg{};
  tdo_capacity_for_grid(&cfg.cap, 20, 20, 10, 2.0, 27u, 400000u);
  cfg.cap.max_boxes = 8u;
  cfg.cap.stream_samples = stream_samples;
  p->mem.resize(tdo_planner_footprint(&cfg));
  ASSERT_FALSE(p->mem.empty());
  ASSERT_EQ(tdo_planner_init(&p->planner, p->mem.data(), p->mem.size(), &cfg), TDO_OK);
  tdo_grid* g = tdo_planner_grid(p->planner);
  const tdo_grid_desc d{20, 20, 10, 0.5, {0.0, 0.0, 0.0}};
  const tdo_box wall{{4.5, 0.0, 0.0}, {5.5, 7.0, 5.0}};
  ASSERT_EQ(tdo_grid_reset(g, &d), TDO_OK);
  ASSERT_EQ(tdo_grid_add_box(g, &wall), TDO_OK);
  ASSERT_EQ(tdo_grid_finish(g, 0.25), TDO_OK);
  tdo_plan_request req{};
  tdo_plan_params_default(&req.params);
  req.start = tdo_vec3{1.25, 1.25, 1.25};
  req.goal = tdo_vec3{8.75, 1.25, 1.25};
  p->st = tdo_planner_plan(p->planner, &req, &p->r);
}

bool same_bits(const std::vector<tdo_sample>& a, const std::vector<tdo_sample>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double x[10] = {a[i].t,   a[i].p.x, a[i].p.y, a[i].p.z, a[i].v.x,
                          a[i].v.y, a[i].v.z, a[i].a.x, a[i].a.y, a[i].a.z};
    const double y[10] = {b[i].t,   b[i].p.x, b[i].p.y, b[i].p.z, b[i].v.x,
                          b[i].v.y, b[i].v.z, b[i].a.x, b[i].a.y, b[i].a.z};
    if (std::memcmp(x, y, sizeof x) != 0) return false;
  }
  return true;
}

TEST(PlanSamples, GivenStoredAndStreamedPlannersThenTheSameSamplesBitForBit) {
  Planned stored, streamed;
  plan(0u, &stored);
  plan(1u, &streamed);
  ASSERT_EQ(stored.st, TDO_OK);
  ASSERT_EQ(streamed.st, TDO_OK);
  ASSERT_NE(stored.r.samples, nullptr);
  ASSERT_EQ(streamed.r.samples, nullptr);  // the mode took effect
  ASSERT_GT(stored.r.n_samples, 2u);
  std::vector<tdo_sample> a, b;
  EXPECT_EQ(tdo_samples::plan_samples(stored.planner, stored.r, &a), TDO_OK);
  EXPECT_EQ(tdo_samples::plan_samples(streamed.planner, streamed.r, &b), TDO_OK);
  EXPECT_EQ(a.size(), stored.r.n_samples);
  EXPECT_EQ(b.size(), streamed.r.n_samples);
  EXPECT_TRUE(same_bits(a, b));
  // The stored array needs no planner; the samples start at the start, at rest.
  std::vector<tdo_sample> c;
  EXPECT_EQ(tdo_samples::plan_samples(nullptr, stored.r, &c), TDO_OK);
  EXPECT_TRUE(same_bits(a, c));
  EXPECT_EQ(c.front().p.x, 1.25);
  EXPECT_EQ(c.front().v.x, 0.0);
  // The trajectory context's own samples are the same.
  const tdo_traj* traj = tdo_planner_trajectory(streamed.planner);
  tdo_traj_output o{};
  o.n_samples = streamed.r.n_samples;
  std::vector<tdo_sample> d;
  EXPECT_EQ(tdo_samples::traj_samples(traj, o, &d), TDO_OK);
  EXPECT_TRUE(same_bits(a, d));
}

TEST(PlanSamples, GivenNoWayToTheSamplesThenRefusedAndTheVectorEmpty) {
  Planned streamed;
  plan(1u, &streamed);
  ASSERT_EQ(streamed.st, TDO_OK);
  std::vector<tdo_sample> out(3);
  // samples to regenerate but no planner
  EXPECT_EQ(tdo_samples::plan_samples(nullptr, streamed.r, &out), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_TRUE(out.empty());
  // a result that is not the planner's last plan: another count
  tdo_plan_result other = streamed.r;
  other.n_samples += 1u;
  EXPECT_EQ(tdo_samples::plan_samples(streamed.planner, other, &out), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_TRUE(out.empty());
  other.n_samples -= 2u;
  EXPECT_EQ(tdo_samples::plan_samples(streamed.planner, other, &out), TDO_ERR_INVALID_ARGUMENT);
  EXPECT_TRUE(out.empty());
  // no samples: empty, ok
  other.n_samples = 0u;
  EXPECT_EQ(tdo_samples::plan_samples(streamed.planner, other, &out), TDO_OK);
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(tdo_samples::plan_samples(streamed.planner, streamed.r, nullptr),
            TDO_ERR_INVALID_ARGUMENT);
}

TEST(PlanSamples, ModeNames) {
  const char* const names[] = {"stored", "streamed", "pieces"};
  for (uint32_t i = 0; i < 3u; ++i) {
    EXPECT_STREQ(tdo_samples::mode_name(i), names[i]);
    uint32_t m = 99u;
    EXPECT_TRUE(tdo_samples::mode_parse(names[i], &m));
    EXPECT_EQ(m, i);
  }
  EXPECT_EQ(tdo_samples::mode_name(3u), nullptr);
  uint32_t m = 7u;
  EXPECT_FALSE(tdo_samples::mode_parse("Stored", &m));
  EXPECT_FALSE(tdo_samples::mode_parse(nullptr, &m));
  EXPECT_EQ(m, 7u);
}

}  // namespace
