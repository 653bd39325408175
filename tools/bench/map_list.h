// The map options the bench tools share: --maps-dir DIR and --map NAME (repeatable).
#ifndef TDO_TOOLS_BENCH_MAP_LIST_H
#define TDO_TOOLS_BENCH_MAP_LIST_H

#include <string>
#include <vector>

namespace tdo_bench {

/** Maps chosen on the command line; Map1-Map5 of the maps directory when none is named. */
struct MapList {
  std::string dir;                 // directory of the named .tdomap files
  std::vector<std::string> names;  // as given, in order

  /** Takes option `a` with value `v` when it is --maps-dir or --map; false for any other. */
  bool take(const std::string& a, const std::string& v) {
    if (a == "--maps-dir") {
      dir = v;
    } else if (a == "--map") {
      names.push_back(v);
    } else {
      return false;
    }
    return true;
  }

  /** The named maps, or Map1-Map5 when none was named. */
  std::vector<std::string> chosen() const {
    if (!names.empty()) return names;
    return {"map1", "map2", "map3", "map4", "map5"};
  }
};

}  // namespace tdo_bench

#endif  // TDO_TOOLS_BENCH_MAP_LIST_H
