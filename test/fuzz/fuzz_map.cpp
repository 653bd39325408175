// libFuzzer target of the map readers (mapio/): the input, up to 1 MB, as a map file of the
// format TDO_FUZZ_EXT names (.tdomap, .3dmap, .bt; a .bt file with the .ot header is read as .ot).
// load_map must return true or false with a one-line message; it must never crash, hang, leak or
// allocate past the caps (LoadOptions: 1e6 voxels, the OcTree check's 1e6 nodes).
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

#include "tdo_io/map_io.h"
#include "tdo_io/octree_check.h"

#ifndef TDO_FUZZ_EXT
#error "TDO_FUZZ_EXT (tdomap, 3dmap or bt) is required"
#endif

namespace {

const std::string& scratch_path() {
  static const std::string path = "/tmp/tdo_fuzz_" + std::to_string(::getpid()) + "." TDO_FUZZ_EXT;
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > (1u << 20)) return 0;
  if (std::string(TDO_FUZZ_EXT) == "bt") {
    std::string detail;
    tdo_io::OctreeInfo info;
    const tdo_io::OctreeStatus st =
        tdo_io::check_octree(data, size, tdo_io::OctreeLimits{}, &info, &detail);
    if ((st == tdo_io::OctreeStatus::ok) != detail.empty()) __builtin_trap();
  }
  std::FILE* f = std::fopen(scratch_path().c_str(), "wb");
  if (f == nullptr) return 0;
  const bool written = size == 0 || std::fwrite(data, 1, size, f) == size;
  std::fclose(f);
  if (!written) return 0;
  tdo_io::LoadOptions opt;
  opt.max_voxels = 1000000;
  tdo_io::Map map;
  std::string error;
  const bool ok = tdo_io::load_map(scratch_path(), opt, &map, &error);
  // A failure always says why, in one bounded line of printable text.
  if (!ok && (error.empty() || error.find('\n') != std::string::npos || error.size() > 4096))
    __builtin_trap();
  return 0;
}
