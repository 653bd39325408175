// Vehicle messages <-> libtdo structs, with every check named (vehicle.h).
#include "tdo_lcm/vehicle.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "tdo/status.h"
#include "tdo_lcm/adapters.h"

namespace tdo_lcm {
namespace {

std::string idx(const char* name, std::size_t i) {
  return std::string(name) + "[" + std::to_string(i) + "]";
}

Check need_finite3(const std::string& name, const double* v) {
  for (std::size_t i = 0; i < 3; ++i)
    if (!std::isfinite(v[i]))
      return fail(Reason::non_finite, name + "[" + std::to_string(i) + "] = " + exact_num(v[i]));
  return {};
}

Check need_finite(const char* name, double v) {
  if (std::isfinite(v)) return {};
  return fail(Reason::non_finite, std::string(name) + " = " + exact_num(v));
}

void put3(tdo_vec3 v, double* out) {
  out[0] = v.x;
  out[1] = v.y;
  out[2] = v.z;
}

tdo_vec3 get3(const double* v) { return tdo_vec3{v[0], v[1], v[2]}; }

Check other_vehicle(const char* what, int32_t got, int32_t mine) {
  return fail(Reason::other_vehicle, std::string(what) + " for vehicle " + std::to_string(got) +
                                         ", this program serves vehicle " + std::to_string(mine));
}

}  // namespace

double seconds_since(int64_t utime, int64_t utime_ref) {
  // Both near 1.7e15: the difference is exact in int64 (saturated, never overflowing).
  int64_t d = 0;
  if (__builtin_sub_overflow(utime, utime_ref, &d))
    d = utime > utime_ref ? std::numeric_limits<int64_t>::max()
                          : std::numeric_limits<int64_t>::min();
  return static_cast<double>(d) * 1e-6;
}

int64_t utime_at(int64_t utime_ref, double t) {
  const double us = std::round(t * 1e6);
  if (!(us > -9.0e18 && us < 9.0e18)) return utime_ref;  // NaN or absurd: no shift
  int64_t out = 0;
  if (__builtin_add_overflow(utime_ref, static_cast<int64_t>(us), &out)) return utime_ref;
  return out;
}

namespace {

// A vehicle_state_t or setpoint_t (`kind` in the messages) into out's t, p, v and a: the message
// is for this vehicle and every number finite.
template <typename Msg, typename Motion>
Check motion_from_msg(const char* kind, const Msg& m, int32_t vehicle_id, int64_t utime_ref,
                      Motion* out) {
  if (m.vehicle_id != vehicle_id) return other_vehicle(kind, m.vehicle_id, vehicle_id);
  Check c = need_finite3("position", m.position);
  if (c.ok()) c = need_finite3("velocity", m.velocity);
  if (c.ok()) c = need_finite3("acceleration", m.acceleration);
  if (c.ok()) c = need_finite("yaw", m.yaw);
  if (!c.ok()) return c;
  out->t = seconds_since(m.utime, utime_ref);
  out->p = get3(m.position);
  out->v = get3(m.velocity);
  out->a = get3(m.acceleration);
  return {};
}

// s's p, v, a and `yaw` into the message being built, then every one of them checked finite.
template <typename Msg, typename Motion>
Check put_motion(const Motion& s, double yaw, Msg* m) {
  put3(s.p, m->position);
  put3(s.v, m->velocity);
  put3(s.a, m->acceleration);
  m->yaw = yaw;
  Check c = need_finite3("position", m->position);
  if (c.ok()) c = need_finite3("velocity", m->velocity);
  if (c.ok()) c = need_finite3("acceleration", m->acceleration);
  if (c.ok()) c = need_finite("yaw", yaw);
  return c;
}

}  // namespace

Check vehicle_state_from_msg(const tdo::vehicle_state_t& m, int32_t vehicle_id, int64_t utime_ref,
                             tdo_vehicle_state* out) {
  return motion_from_msg("state", m, vehicle_id, utime_ref, out);
}

Check vehicle_state_to_msg(const tdo_vehicle_state& s, int64_t utime_ref, int32_t vehicle_id,
                           int64_t seq, double yaw, tdo::vehicle_state_t* out) {
  tdo::vehicle_state_t m{};
  m.utime = utime_at(utime_ref, s.t);
  m.seq = seq;
  m.vehicle_id = vehicle_id;
  const Check motion = put_motion(s, yaw, &m);
  Check c = need_finite("t", s.t);
  if (c.ok()) c = motion;
  if (!c.ok()) return c;
  *out = m;
  return {};
}

Check setpoint_from_msg(const tdo::setpoint_t& m, int32_t vehicle_id, int64_t utime_ref,
                        tdo_setpoint* out) {
  return motion_from_msg("setpoint", m, vehicle_id, utime_ref, out);
}

Check setpoint_to_msg(const tdo_setpoint& s, int64_t utime, int32_t vehicle_id, int64_t seq,
                      int64_t request_id, double yaw, tdo_status status, tdo::setpoint_t* out) {
  tdo::setpoint_t m{};
  m.utime = utime;
  m.seq = seq;
  m.vehicle_id = vehicle_id;
  m.request_id = request_id;
  m.status_code = static_cast<int32_t>(status);
  m.status = tdo_status_str(status);
  const Check c = put_motion(s, yaw, &m);
  if (!c.ok()) return c;
  *out = std::move(m);
  return {};
}

Check movers_from_msg(const tdo::obstacles_t& m, int32_t vehicle_id, uint32_t max_movers,
                      std::vector<tdo_mover>* out) {
  if (m.vehicle_id != -1 && m.vehicle_id != vehicle_id)
    return other_vehicle("obstacles", m.vehicle_id, vehicle_id);
  Check c = check_counts(m);
  if (!c.ok()) return c;
  if (static_cast<uint64_t>(m.n) > max_movers)
    return fail(Reason::over_capacity, std::to_string(m.n) +
                                           " obstacles, more than the capacity of " +
                                           std::to_string(max_movers));
  std::vector<tdo_mover> movers(static_cast<std::size_t>(m.n));
  for (std::size_t i = 0; i < movers.size(); ++i) {
    c = need_finite3(idx("position", i), m.position[i].data());
    if (c.ok()) c = need_finite3(idx("velocity", i), m.velocity[i].data());
    if (c.ok() && !std::isfinite(m.radius[i]))
      c = fail(Reason::non_finite, idx("radius", i) + " = " + exact_num(m.radius[i]));
    if (!c.ok()) return c;
    if (!(m.radius[i] > 0.0))
      return fail(Reason::out_of_range,
                  idx("radius", i) + " = " + exact_num(m.radius[i]) + " <= 0");
    if (m.id[i] < 0)
      return fail(Reason::out_of_range, idx("id", i) + " = " + std::to_string(m.id[i]) + " < 0");
    movers[i].id = static_cast<uint32_t>(m.id[i]);
    movers[i].p = get3(m.position[i].data());
    movers[i].v = get3(m.velocity[i].data());
    movers[i].radius = m.radius[i];
  }
  *out = std::move(movers);
  return {};
}

Check movers_to_msg(const tdo_mover* movers, uint32_t n, int64_t utime, int32_t vehicle_id,
                    int64_t seq, tdo::obstacles_t* out) {
  if (n > 0 && movers == nullptr)
    return fail(Reason::count_mismatch, "movers: no array for " + std::to_string(n));
  if (n > static_cast<uint32_t>(std::numeric_limits<int32_t>::max()))
    return fail(Reason::too_large, "movers: " + std::to_string(n) + " > INT32_MAX");
  tdo::obstacles_t m{};
  m.utime = utime;
  m.seq = seq;
  m.vehicle_id = vehicle_id;
  m.n = static_cast<int32_t>(n);
  for (uint32_t i = 0; i < n; ++i) {
    const tdo_mover& v = movers[i];
    if (v.id > static_cast<uint32_t>(std::numeric_limits<int32_t>::max()))
      return fail(Reason::too_large, idx("id", i) + " = " + std::to_string(v.id) + " > INT32_MAX");
    std::vector<double> p(3), u(3);
    put3(v.p, p.data());
    put3(v.v, u.data());
    Check c = need_finite3(idx("position", i), p.data());
    if (c.ok()) c = need_finite3(idx("velocity", i), u.data());
    if (!c.ok()) return c;
    if (!(v.radius > 0.0) || !std::isfinite(v.radius))
      return fail(std::isfinite(v.radius) ? Reason::out_of_range : Reason::non_finite,
                  idx("radius", i) + " = " + exact_num(v.radius));
    m.id.push_back(static_cast<int32_t>(v.id));
    m.position.push_back(std::move(p));
    m.velocity.push_back(std::move(u));
    m.radius.push_back(v.radius);
  }
  *out = std::move(m);
  return {};
}

void movers_advance(std::vector<tdo_mover>* movers, double t_obs, double t, double max_shift_s) {
  double dt = t - t_obs;
  if (!(dt > 0.0)) return;
  if (dt > max_shift_s) dt = max_shift_s;
  for (tdo_mover& m : *movers) {
    m.p.x += m.v.x * dt;
    m.p.y += m.v.y * dt;
    m.p.z += m.v.z * dt;
  }
}

double heading_of(tdo_vec3 v, double previous) {
  if (!(std::hypot(v.x, v.y) >= 0.1)) return previous;
  return std::atan2(v.y, v.x);
}

}  // namespace tdo_lcm
