/**
 * @file answer_watch.h
 * @brief Trajectories a follower was promised and has not received yet.
 *
 * A request for the follower's vehicle seen on TDO_PLAN_REQUEST, or a feasibility report on
 * TDO_FEASIBILITY (the planner sends it right after the trajectory of the same request), promises
 * a trajectory. When none with that request_id arrives within the timeout, expire() reports it
 * once. Bounded: at most kMaxPending promises are watched (the oldest is dropped and reported as
 * missing), and the last kMaxArrived arrivals are remembered (a report arriving after its
 * trajectory promises nothing).
 */
#ifndef TDO_AVOID_ANSWER_WATCH_H
#define TDO_AVOID_ANSWER_WATCH_H

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>

namespace tdo_lcm {

class AnswerWatch {
 public:
  using Time = std::chrono::steady_clock::time_point;
  static constexpr std::size_t kMaxPending = 64;
  static constexpr std::size_t kMaxArrived = 64;

  explicit AnswerWatch(std::chrono::steady_clock::duration timeout) : timeout_(timeout) {}

  /** A trajectory for `request_id` is due by now + timeout (the earlier deadline stays). */
  void promise(int64_t request_id, Time now) {
    for (int64_t id : arrived_)
      if (id == request_id) return;
    if (pending_.count(request_id) != 0) return;
    if (pending_.size() >= kMaxPending) {  // the oldest promise (smallest deadline) is given up
      auto oldest = pending_.begin();
      for (auto it = pending_.begin(); it != pending_.end(); ++it)
        if (it->second < oldest->second) oldest = it;
      pending_.erase(oldest);
      ++overflowed_;
    }
    pending_[request_id] = now + timeout_;
  }

  /** The trajectory for `request_id` arrived. */
  void arrived(int64_t request_id) {
    pending_.erase(request_id);
    arrived_.push_back(request_id);
    if (arrived_.size() > kMaxArrived) arrived_.pop_front();
  }

  /** @return promises past their deadline at `now` (forgotten), plus those dropped for room. */
  int64_t expire(Time now) {
    int64_t n = overflowed_;
    overflowed_ = 0;
    for (auto it = pending_.begin(); it != pending_.end();) {
      if (it->second <= now) {
        it = pending_.erase(it);
        ++n;
      } else {
        ++it;
      }
    }
    return n;
  }

  /** @return the earliest deadline, or Time::max() when nothing is pending. */
  Time next_deadline() const {
    Time t = Time::max();
    for (const auto& kv : pending_)
      if (kv.second < t) t = kv.second;
    return t;
  }

  std::size_t pending() const { return pending_.size(); }

 private:
  std::chrono::steady_clock::duration timeout_;
  std::map<int64_t, Time> pending_;
  std::deque<int64_t> arrived_;
  int64_t overflowed_ = 0;
};

}  // namespace tdo_lcm

#endif  // TDO_AVOID_ANSWER_WATCH_H
