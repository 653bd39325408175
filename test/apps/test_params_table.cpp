// Every row of libtdo's parameter table (tdo/params.h) travels through LCM (plan_request_t encoded,
// decoded and adapted, request_fields.h), and every out-of-range value of every row is refused by
// the library's validation and by the adapters, naming the field.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "tdo/tdo.h"
#include "tdo_lcm/adapters.h"
#include "tdo_lcm/request_fields.h"
#include "tdo_lcm/wire.h"

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

const tdo_param_info& row(uint32_t i) { return *tdo_param_at(i); }

/** A valid value of row i other than its default (so a round trip that drops it fails). */
double other_valid(uint32_t i) {
  const tdo_param_info& r = row(i);
  double v = 0.0;
  if (r.type != TDO_PARAM_REAL)
    v = r.def > r.min ? r.def - 1.0 : r.def + 1.0;  // enums and flags have two values or more
  else if (std::isinf(r.max))
    v = r.def * 1.5 + 0.25;
  else
    v = r.min + (r.max - r.min) * (r.def > 0.5 * (r.min + r.max) ? 0.25 : 0.75);
  if (r.type == TDO_PARAM_UINT) v = 12345.0;
  return v;
}

/** Values row i refuses that a tdo_plan_params field can hold. */
std::vector<double> out_of_range(uint32_t i) {
  const tdo_param_info& r = row(i);
  std::vector<double> v;
  if (r.type == TDO_PARAM_REAL) {
    v.push_back(kNaN);
    v.push_back(r.min_open ? r.min : r.min - 0.5);
    if (!std::isinf(r.max)) v.push_back(r.max_open ? r.max : r.max + 0.5);
  } else if (r.type != TDO_PARAM_UINT) {
    v.push_back(r.min - 1.0);
    v.push_back(static_cast<double>(r.n_values));
  }
  return v;
}

/** Write `v` into row i's storage as it is (tdo_param_set refuses values enums cannot hold). */
void write_raw(tdo_plan_params* p, uint32_t i, double v) {
  unsigned char* at = reinterpret_cast<unsigned char*>(p) + row(i).offset;
  if (row(i).type == TDO_PARAM_REAL) {
    std::memcpy(at, &v, sizeof v);
  } else {  // enums and flags: little-endian, the low bytes of an int32 (1 byte: short enums)
    const int32_t n = static_cast<int32_t>(v);
    ASSERT_LE(row(i).size, sizeof n);
    std::memcpy(at, &n, row(i).size);
  }
}

tdo_plan_request base_request() {
  tdo_plan_request r{};
  r.start = tdo_vec3{1.0, 2.0, 3.0};
  r.goal = tdo_vec3{4.0, 5.0, 6.5};
  tdo_plan_params_default(&r.params);
  return r;
}

const tdo_lcm::RequestField* field_of(uint32_t i) {
  for (const tdo_lcm::RequestField& f : tdo_lcm::request_fields())
    if (f.param == static_cast<int32_t>(i)) return &f;
  return nullptr;
}

TEST(ParamsTable, GivenTheTable_ThenEveryRowHasOneLcmFieldAndAValidDefault) {
  ASSERT_GT(tdo_param_count(), 0u);
  std::set<int32_t> bound;
  for (const tdo_lcm::RequestField& f : tdo_lcm::request_fields())
    if (f.param >= 0) {
      EXPECT_TRUE(bound.insert(f.param).second) << f.name << " bound twice";
    }
  tdo_plan_params d{};
  tdo_plan_params_default(&d);
  for (uint32_t i = 0; i < tdo_param_count(); ++i) {
    SCOPED_TRACE(row(i).name);
    EXPECT_EQ(bound.count(static_cast<int32_t>(i)), 1u) << "no plan_request_t field";
    EXPECT_EQ(tdo_param_find(row(i).name), static_cast<int32_t>(i));
    EXPECT_EQ(tdo_param_valid(i, row(i).def), 1);
    EXPECT_EQ(tdo_param_get(&d, i), row(i).def);
    EXPECT_NE(other_valid(i), row(i).def);
    EXPECT_EQ(tdo_param_valid(i, other_valid(i)), 1);
  }
  // The rows cover the struct: no field is left out of the table (their sizes add up, padding
  // aside; tdo_plan_params has no padding beyond 8 bytes).
  std::size_t bytes = 0;
  for (uint32_t i = 0; i < tdo_param_count(); ++i) bytes += row(i).size;
  EXPECT_LE(bytes, sizeof(tdo_plan_params));
  EXPECT_GT(bytes + 8u, sizeof(tdo_plan_params));
}

TEST(ParamsTable, GivenEveryRowChanged_WhenSentThroughLcm_ThenThePlannerReceivesIt) {
  for (uint32_t i = 0; i < tdo_param_count(); ++i) {
    SCOPED_TRACE(row(i).name);
    tdo_plan_request in = base_request();
    ASSERT_EQ(tdo_param_set(&in.params, i, other_valid(i)), TDO_OK);
    tdo::plan_request_t m{};
    m.vehicle_id = 3;
    m.map_id = -1;
    tdo_lcm::plan_request_to_msg(in, 0.4, &m);
    std::vector<uint8_t> buf(static_cast<std::size_t>(m.getEncodedSize()));
    ASSERT_EQ(m.encode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
    tdo::plan_request_t wire{};
    ASSERT_TRUE(tdo_lcm::decode(buf.data(), buf.size(), &wire).ok());
    tdo_plan_request out{};
    double clearance = 0.0;
    const tdo_lcm::Check c = tdo_lcm::plan_request_from_msg(wire, 3, &out, &clearance);
    ASSERT_TRUE(c.ok()) << c.detail;
    for (uint32_t j = 0; j < tdo_param_count(); ++j)
      EXPECT_EQ(tdo_param_get(&out.params, j), tdo_param_get(&in.params, j)) << row(j).name;
    EXPECT_EQ(tdo_param_get(&out.params, i), other_valid(i));
  }
}

TEST(ParamsTable, GivenAnOutOfRangeValueOfEveryRow_ThenTheLibraryAndTheAdaptersRefuseNamingIt) {
  for (uint32_t i = 0; i < tdo_param_count(); ++i) {
    const tdo_lcm::RequestField* f = field_of(i);
    ASSERT_NE(f, nullptr) << row(i).name;
    for (double bad : out_of_range(i)) {
      SCOPED_TRACE(std::string(row(i).name) + " = " + std::to_string(bad));
      // The library: tdo_plan_params_check names the row; tdo_param_valid refuses the value.
      tdo_plan_request r = base_request();
      write_raw(&r.params, i, bad);
      uint32_t which = 999u;
      EXPECT_EQ(tdo_plan_params_check(&r.params, &which), TDO_ERR_INVALID_ARGUMENT);
      EXPECT_EQ(which, i);
      EXPECT_EQ(tdo_param_valid(i, bad), 0);
      // The adapters: the LCM field carrying it is named.
      tdo::plan_request_t m{};
      m.vehicle_id = 3;
      m.map_id = -1;
      tdo_lcm::plan_request_to_msg(base_request(), 0.4, &m);
      f->set(m, bad);
      tdo_plan_request out{};
      const tdo_lcm::Check c = tdo_lcm::plan_request_from_msg(m, 3, &out, nullptr);
      EXPECT_FALSE(c.ok());
      EXPECT_EQ(c.field, f->name) << c.detail;
    }
  }
  // max_expansions (UINT) holds no invalid value in the library; over LCM a negative one is.
  const tdo_lcm::RequestField* f = tdo_lcm::find_request_field("max_expansions");
  ASSERT_NE(f, nullptr);
  tdo::plan_request_t m{};
  m.vehicle_id = 3;
  tdo_lcm::plan_request_to_msg(base_request(), 0.4, &m);
  f->set(m, -1.0);
  tdo_plan_request out{};
  EXPECT_EQ(tdo_lcm::plan_request_from_msg(m, 3, &out, nullptr).field, "max_expansions");
}

TEST(ParamsTable, GivenThePlainPreset_ThenOnlyTheTurnDeviationRowsChange) {
  tdo_plan_params d{};
  tdo_plan_params_default(&d);
  tdo_plan_params p = d;
  tdo_plan_params_plain(&p);
  for (uint32_t i = 0; i < tdo_param_count(); ++i) {
    SCOPED_TRACE(row(i).name);
    EXPECT_EQ(tdo_param_get(&p, i), row(i).has_plain ? row(i).plain : tdo_param_get(&d, i));
  }
  EXPECT_EQ(p.lambda, 0.0);
  EXPECT_EQ(p.first_meet, 0);
}

}  // namespace
