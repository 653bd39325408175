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

  /**
   * Reads argv[1..] as OPTION VALUE pairs in order: the map options here, every other one through
   * `other(option, value)`, which returns "" when it took the pair or the error. Returns "" or the
   * first error (also "missing value after OPTION").
   */
  template <typename Other>
  std::string parse(int argc, char** argv, Other other) {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (i + 1 >= argc) return "missing value after " + a;
      const std::string v = argv[++i];
      if (take(a, v)) continue;
      const std::string err = other(a, v);
      if (!err.empty()) return err;
    }
    return "";
  }

  /** The named maps, or Map1-Map5 when none was named. */
  std::vector<std::string> chosen() const {
    if (!names.empty()) return names;
    return {"map1", "map2", "map3", "map4", "map5"};
  }
};

}  // namespace tdo_bench

#endif  // TDO_TOOLS_BENCH_MAP_LIST_H
