// A plan's trajectory samples for host code, stored or regenerated (samples.h).
#include "tdo_samples/samples.h"

#include <cstring>

namespace tdo_samples {

namespace {

// The vector holds room for the count the plan reported; the callback never allocates (it runs
// inside the library), it only counts samples beyond that room.
struct Sink {
  std::vector<tdo_sample>* out;
  uint64_t handed;
};

void append(void* user, uint32_t /*index*/, const tdo_sample* s) {
  Sink* k = static_cast<Sink*>(user);
  if (k->out->size() < k->out->capacity()) k->out->push_back(*s);
  ++k->handed;
}

// Stored: copy. Not stored: `each` regenerates them; its count must be n.
template <typename Each>
tdo_status collect(const tdo_sample* stored, uint32_t n, Each each, std::vector<tdo_sample>* out) {
  if (out == nullptr) return TDO_ERR_INVALID_ARGUMENT;
  out->clear();
  if (n == 0u) return TDO_OK;
  if (stored != nullptr) {
    out->assign(stored, stored + n);
    return TDO_OK;
  }
  out->reserve(n);
  Sink k{out, 0u};
  const tdo_status st = each(&k);
  if (st == TDO_OK && k.handed == n && out->size() == n) return TDO_OK;
  out->clear();
  return st != TDO_OK ? st : TDO_ERR_INVALID_ARGUMENT;
}

}  // namespace

tdo_status plan_samples(const tdo_planner* planner, const tdo_plan_result& r,
                        std::vector<tdo_sample>* out) {
  return collect(
      r.samples, r.n_samples,
      [planner](Sink* k) {
        return planner == nullptr ? TDO_ERR_INVALID_ARGUMENT
                                  : tdo_planner_each_sample(planner, append, k);
      },
      out);
}

tdo_status traj_samples(const tdo_traj* traj, const tdo_traj_output& o,
                        std::vector<tdo_sample>* out) {
  return collect(
      o.samples, o.n_samples,
      [traj](Sink* k) {
        return traj == nullptr ? TDO_ERR_INVALID_ARGUMENT : tdo_traj_each_sample(traj, append, k);
      },
      out);
}

namespace {
// Indexed by tdo_capacity.stream_samples (TDO_TRAJ_SAMPLES_STORED .. _PIECES).
constexpr uint32_t kModeCount = TDO_TRAJ_SAMPLES_PIECES + 1u;
const char* const kModes[kModeCount] = {"stored", "streamed", "pieces"};
}  // namespace

const char* mode_name(uint32_t stream_samples) {
  return stream_samples < kModeCount ? kModes[stream_samples] : nullptr;
}

bool mode_parse(const char* name, uint32_t* stream_samples) {
  if (name == nullptr || stream_samples == nullptr) return false;
  for (uint32_t i = 0; i < kModeCount; ++i)
    if (std::strcmp(name, kModes[i]) == 0) {
      *stream_samples = i;
      return true;
    }
  return false;
}

}  // namespace tdo_samples
