// Map and scenario readers for the host tools. See tdo_io/map_io.h.
#include "tdo_io/map_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <new>
#include <sstream>
#include <string_view>
#include <system_error>

#include "octomap_io.h"
#include "tdo_io/text.h"

namespace tdo_io {
namespace {

// ---------------------------------------------------------------- small helpers

/** Whole file into `text`; false with a message when it cannot be opened, read or is too big. */
bool read_file(const std::string& path, uint64_t max_bytes, std::string* text, std::string* why) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  const std::streamoff size = in ? static_cast<std::streamoff>(in.tellg()) : -1;
  if (size < 0) {
    *why = path + ": cannot open";
    return false;
  }
  if (static_cast<uint64_t>(size) > max_bytes) {
    *why = path + ": file of " + std::to_string(size) + " bytes exceeds the limit of " +
           std::to_string(max_bytes);
    return false;
  }
  text->resize(static_cast<std::size_t>(size));
  in.seekg(0);
  if (size > 0 && !in.read(&(*text)[0], size)) {
    *why = path + ": cannot read";
    return false;
  }
  return true;
}

/** A directory given as a file: its own message rather than "empty file" or "cannot read". */
bool is_directory(const std::string& path, std::string* why) {
  std::error_code ec;
  if (!std::filesystem::is_directory(path, ec)) return false;
  *why = path + ": is a directory, not a map file";
  return true;
}

/** `tok` quoted in a message: escaped and capped (text.h). */
std::string q(std::string_view tok) { return "'" + printable(tok) + "'"; }

void set_error(std::string* error, const std::string& msg) {
  if (error != nullptr) *error = msg;
}

std::string lower_extension(const std::string& path) {
  const std::size_t slash = path.find_last_of("/\\");
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

/** Thrown inside the parsers, turned into `false` + message at the API boundary. */
struct ParseError {
  std::string message;
};

/** Line-by-line tokenizer that knows its file name and line number for messages. */
class LineReader {
 public:
  LineReader(const std::string& path, const std::string& text, bool hash_comments)
      : path_(path), text_(text), comments_(hash_comments) {}

  /** Next line with at least one token (comments removed); false at the end of the file. */
  bool next() {
    while (pos_ < text_.size()) {
      std::size_t end = text_.find('\n', pos_);
      if (end == std::string::npos) end = text_.size();
      std::string_view line(text_.data() + pos_, end - pos_);
      pos_ = end + 1;
      ++line_;
      if (comments_) {
        const std::size_t hash = line.find('#');
        if (hash != std::string_view::npos) line = line.substr(0, hash);
      }
      tokens_.clear();
      std::size_t i = 0;
      while (i < line.size()) {
        while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i])) != 0) ++i;
        const std::size_t start = i;
        while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i])) == 0) ++i;
        if (i > start) tokens_.push_back(line.substr(start, i - start));
      }
      if (!tokens_.empty()) return true;
    }
    tokens_.clear();
    return false;
  }

  int line() const { return line_ == 0 ? 1 : line_; }
  /** Offset of the first byte not read yet (past the end after the last line). */
  std::size_t offset() const { return pos_; }
  /** Lines read so far. */
  int lines_read() const { return line_; }
  /** Go on from byte `pos` (a line's start) as if `lines` lines had been read before it. */
  void seek(std::size_t pos, int lines) {
    pos_ = pos;
    line_ = lines;
  }
  const std::vector<std::string_view>& tokens() const { return tokens_; }

  [[noreturn]] void fail(const std::string& msg) const {
    throw ParseError{path_ + ":" + std::to_string(line()) + ": " + msg};
  }

  /** Exactly `count` tokens after the keyword (token 0). */
  void expect_count(std::size_t count, const char* what) const {
    const std::size_t have = tokens_.size() - 1;
    if (have < count) {
      fail(q(tokens_[0]) + " needs " + std::to_string(count) + " numbers (" + what + "), got " +
           std::to_string(have));
    }
    if (have > count) {
      fail("unexpected " + q(tokens_[count + 1]) + " after " + std::to_string(count) +
           " numbers of " + q(tokens_[0]));
    }
  }

  /** Token `i` as a finite double. */
  double number(std::size_t i) const {
    const std::string tok(tokens_[i]);
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(tok.c_str(), &end);
    if (end == tok.c_str() || *end != '\0') fail("expected a number, got " + q(tok));
    if (!std::isfinite(v)) fail("non-finite number " + q(tok));
    return v;
  }

  /** Token `i` as an integer in [lo, hi]. */
  long long integer(std::size_t i, long long lo, long long hi, const char* what) const {
    const std::string tok(tokens_[i]);
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(tok.c_str(), &end, 10);
    if (end == tok.c_str() || *end != '\0')
      fail(std::string("expected an integer ") + what + ", got " + q(tok));
    if (errno == ERANGE || v < lo || v > hi) {
      fail(std::string(what) + " " + printable(tok) + " is outside [" + std::to_string(lo) + ", " +
           std::to_string(hi) + "]");
    }
    return v;
  }

  tdo_vec3 vec3(std::size_t first) const {
    return tdo_vec3{number(first), number(first + 1), number(first + 2)};
  }

 private:
  const std::string& path_;
  const std::string& text_;
  bool comments_;
  std::size_t pos_ = 0;
  int line_ = 0;
  std::vector<std::string_view> tokens_;
};

const char* axis_name(int a) { return a == 0 ? "x" : (a == 1 ? "y" : "z"); }

double axis(const tdo_vec3& v, int a) { return a == 0 ? v.x : (a == 1 ? v.y : v.z); }

// ---------------------------------------------------------------- .tdomap

void parse_tdomap(const std::string& path, const std::string& text, Map* map) {
  LineReader r(path, text, true);
  if (!r.next()) r.fail("missing header 'tdomap 1' (empty file)");
  if (r.tokens()[0] != "tdomap") {
    r.fail("missing header 'tdomap 1' (found " + q(r.tokens()[0]) + ")");
  }
  if (r.tokens().size() != 2 || r.tokens()[1] != "1") {
    r.fail("unsupported header: expected 'tdomap 1'");
  }
  bool have_bounds = false;
  bool have_res = false;
  tdo_vec3 bmin{};
  tdo_vec3 bmax{};
  double res = 0.0;
  while (r.next()) {
    const std::string_view kw = r.tokens()[0];
    if (kw == "bounds") {
      if (have_bounds) r.fail("duplicate 'bounds'");
      r.expect_count(6, "XMIN YMIN ZMIN XMAX YMAX ZMAX");
      bmin = r.vec3(1);
      bmax = r.vec3(4);
      for (int a = 0; a < 3; ++a) {
        if (!(axis(bmax, a) > axis(bmin, a))) {
          r.fail(std::string("bounds inverted: max <= min on the ") + axis_name(a) + " axis");
        }
      }
      have_bounds = true;
    } else if (kw == "resolution") {
      if (have_res) r.fail("duplicate 'resolution'");
      r.expect_count(1, "R");
      res = r.number(1);
      if (!(res > 0.0)) r.fail("resolution must be > 0, got " + printable(r.tokens()[1]));
      have_res = true;
    } else if (kw == "box") {
      r.expect_count(6, "X0 Y0 Z0 X1 Y1 Z1");
      const tdo_box b{r.vec3(1), r.vec3(4)};
      for (int a = 0; a < 3; ++a) {
        if (!(axis(b.max, a) > axis(b.min, a))) {
          r.fail(std::string("inverted box: max <= min on the ") + axis_name(a) + " axis");
        }
      }
      map->boxes.push_back(b);
    } else if (kw == "start") {
      if (map->has_start) r.fail("duplicate 'start'");
      r.expect_count(3, "X Y Z");
      map->start = r.vec3(1);
      map->has_start = true;
    } else if (kw == "goal") {
      if (map->has_goal) r.fail("duplicate 'goal'");
      r.expect_count(3, "X Y Z");
      map->goal = r.vec3(1);
      map->has_goal = true;
    } else if (kw == "mover") {
      r.expect_count(8, "ID X Y Z VX VY VZ RADIUS");
      Mover m{};
      m.id = static_cast<int>(r.integer(1, 0, std::numeric_limits<int>::max(), "mover id"));
      m.pos = r.vec3(2);
      m.vel = r.vec3(5);
      m.radius = r.number(8);
      if (!(m.radius > 0.0)) r.fail("mover radius must be > 0, got " + printable(r.tokens()[8]));
      map->movers.push_back(m);
    } else if (kw == "tdomap") {
      r.fail("duplicate header 'tdomap'");
    } else {
      r.fail("unknown keyword " + q(kw));
    }
  }
  if (!have_bounds) r.fail("missing 'bounds'");
  if (!have_res) r.fail("missing 'resolution'");
  int32_t n[3];
  for (int a = 0; a < 3; ++a) {
    const double cells = std::ceil((axis(bmax, a) - axis(bmin, a)) / res - 1e-9);
    if (!(cells <= static_cast<double>(std::numeric_limits<int32_t>::max()))) {
      throw ParseError{path + ": grid too large: " + std::string(axis_name(a)) +
                       " extent / resolution exceeds 2^31-1 voxels"};
    }
    n[a] = std::max<int32_t>(1, static_cast<int32_t>(cells));
  }
  map->desc.nx = n[0];
  map->desc.ny = n[1];
  map->desc.nz = n[2];
  map->desc.res = res;
  map->desc.origin = bmin;
}

// ---------------------------------------------------------------- .3dmap

/** What std::isspace takes in the "C" locale, less the line break. */
inline bool blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/**
 * Fast path of one voxel coordinate at `p`: 1 to 9 decimal digits (no sign) whose value is below
 * `n`, followed by a blank, the line break or the end. The position after the digits, the value
 * in *v; nullptr for anything else (the tokenizer then reads the line). Nine digits never
 * overflow int32, and such a token reads the same through strtoll.
 */
const char* fast_coord(const char* p, const char* end, int32_t n, int32_t* v) {
  const char* const start = p;
  int32_t x = 0;
  while (p < end && p - start < 9 && static_cast<unsigned>(*p - '0') < 10u) {
    x = 10 * x + (*p - '0');
    ++p;
  }
  if (p == start || x >= n) return nullptr;
  if (p < end && *p != '\n' && !blank(*p)) return nullptr;  // a tenth digit too
  *v = x;
  return p;
}

/**
 * Fast path of one voxel line starting at `p`: three coordinates (fast_coord) of the declared
 * size among blanks. The position of its line break (or the end), the voxel in *out; nullptr for
 * any other line (blank, signed, malformed, out of range), which the tokenizer then reads, so
 * every line gets the tokenizer's result and error.
 */
const char* fast_voxel(const char* p, const char* end, const int32_t n[3], tdo_voxel* out) {
  int32_t c[3];
  for (int a = 0; a < 3; ++a) {
    while (p < end && blank(*p)) ++p;
    p = fast_coord(p, end, n[a], &c[a]);
    if (p == nullptr) return nullptr;
  }
  while (p < end && blank(*p)) ++p;
  if (p < end && *p != '\n') return nullptr;
  *out = tdo_voxel{c[0], c[1], c[2]};
  return p;
}

/** A voxel line through the tokenizer: the checks and messages of the format, in their order. */
void voxel_line(const LineReader& r, const int32_t n[3], Map* map) {
  if (r.tokens().size() != 3) {
    r.fail("expected a voxel 'x y z', got " + std::to_string(r.tokens().size()) + " fields");
  }
  const long long imin = std::numeric_limits<int32_t>::min();
  const long long imax = std::numeric_limits<int32_t>::max();
  const long long x = r.integer(0, imin, imax, "x");
  const long long y = r.integer(1, imin, imax, "y");
  const long long z = r.integer(2, imin, imax, "z");
  if (x < 0 || x >= n[0] || y < 0 || y >= n[1] || z < 0 || z >= n[2]) {
    r.fail("voxel " + std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z) +
           " outside the declared size " + std::to_string(n[0]) + " x " + std::to_string(n[1]) +
           " x " + std::to_string(n[2]));
  }
  map->voxels.push_back(
      tdo_voxel{static_cast<int32_t>(x), static_cast<int32_t>(y), static_cast<int32_t>(z)});
}

// The header through the tokenizer, then the voxel lines straight from the buffer (fast_voxel)
// until one is not plain: that one, and the blank lines after it, go through the tokenizer
// (voxel_line), and the fast path resumes at the next line.
void parse_3dmap(const std::string& path, const std::string& text, Map* map) {
  LineReader r(path, text, false);
  if (!r.next() || r.tokens()[0] != "voxel") r.fail("missing header 'voxel X Y Z'");
  if (r.tokens().size() != 4) r.fail("header needs 'voxel X Y Z'");
  const long long imax = std::numeric_limits<int32_t>::max();
  const int32_t nx = static_cast<int32_t>(r.integer(1, 1, imax, "size X"));
  const int32_t ny = static_cast<int32_t>(r.integer(2, 1, imax, "size Y"));
  const int32_t nz = static_cast<int32_t>(r.integer(3, 1, imax, "size Z"));
  map->desc.nx = nx;
  map->desc.ny = ny;
  map->desc.nz = nz;
  map->desc.res = 1.0;
  map->desc.origin = tdo_vec3{-0.5, -0.5, -0.5};
  const int32_t n[3] = {nx, ny, nz};
  const char* const begin = text.data();
  const char* const end = begin + text.size();
  // Every round takes at least one line (the fast path's or the tokenizer's), so the loop ends.
  for (;;) {
    std::size_t pos = r.offset();
    int line = r.lines_read();
    tdo_voxel v{};
    for (const char* e = nullptr;
         pos < text.size() && (e = fast_voxel(begin + pos, end, n, &v)) != nullptr;
         pos = static_cast<std::size_t>(e - begin) + 1) {
      map->voxels.push_back(v);
      ++line;
    }
    r.seek(pos, line);
    if (!r.next()) break;
    voxel_line(r, n, map);
  }
}

// ---------------------------------------------------------------- .3dscen

void parse_3dscen(const std::string& path, const std::string& text, std::vector<ScenQuery>* out) {
  LineReader r(path, text, false);
  if (!r.next() || r.tokens()[0] != "version") r.fail("missing header 'version 1'");
  if (r.tokens().size() != 2 || r.tokens()[1] != "1")
    r.fail("unsupported header: expected 'version 1'");
  if (!r.next()) r.fail("missing map name line");
  while (r.next()) {
    const std::size_t n = r.tokens().size();
    if (n < 7 || n > 8) {
      r.fail("expected 'sx sy sz gx gy gz cost ratio', got " + std::to_string(n) + " fields");
    }
    ScenQuery q{};
    q.start = r.vec3(0);
    q.goal = r.vec3(3);
    q.cost = r.number(6);
    if (n == 8) (void)r.number(7);
    q.line = r.line();
    out->push_back(q);
  }
}

}  // namespace

// ---------------------------------------------------------------- API

bool load_map(const std::string& path, Map* out, std::string* error) {
  return load_map(path, LoadOptions{}, out, error);
}

bool load_map(const std::string& path, const LoadOptions& options, Map* out, std::string* error) {
  if (out == nullptr) {
    set_error(error, path + ": no output map given");
    return false;
  }
  *out = Map{};
  out->path = path;
  std::string why;
  if (is_directory(path, &why)) {
    set_error(error, why);
    return false;
  }
  const std::string ext = lower_extension(path);
  if (ext == "bt" || ext == "ot") {
    std::string msg;
    bool ok = false;
    try {
      ok = detail::load_octomap(path, options, out, &msg);
    } catch (const std::bad_alloc&) {
      msg = path + ": out of memory while voxelizing the OcTree (try a coarser resolution)";
    } catch (const std::exception& e) {
      msg = path + ": " + e.what();
    }
    if (!ok) set_error(error, msg);
    return ok;
  }
  if (ext != "tdomap" && ext != "3dmap") {
    set_error(error, path + ": unknown map format '" + (ext.empty() ? std::string() : "." + ext) +
                         "' (expected .tdomap, .3dmap, .bt or .ot)");
    return false;
  }
  std::string text;
  if (!read_file(path, options.max_file_bytes, &text, &why)) {
    set_error(error, why);
    return false;
  }
  try {
    if (ext == "tdomap") {
      out->kind = MapKind::TdoMap;
      parse_tdomap(path, text, out);
    } else {
      out->kind = MapKind::MovingAI;
      parse_3dmap(path, text, out);
    }
  } catch (const ParseError& e) {
    set_error(error, e.message);
    return false;
  } catch (const std::exception& e) {
    set_error(error, path + ": " + e.what());
    return false;
  }
  return true;
}

bool load_scen(const std::string& path, std::vector<ScenQuery>* out, std::string* error) {
  if (out == nullptr) {
    set_error(error, path + ": no output given");
    return false;
  }
  out->clear();
  std::string text;
  std::string why;
  if (is_directory(path, &why) || !read_file(path, LoadOptions{}.max_file_bytes, &text, &why)) {
    set_error(error, why);
    return false;
  }
  try {
    parse_3dscen(path, text, out);
  } catch (const ParseError& e) {
    set_error(error, e.message);
    return false;
  } catch (const std::exception& e) {
    set_error(error, path + ": " + e.what());
    return false;
  }
  return true;
}

tdo_capacity capacity_for(const Map& map, double clearance, uint32_t headings, uint32_t node_cap) {
  tdo_capacity cap{};
  const double ratio = map.desc.res > 0.0 ? clearance / map.desc.res : 0.0;
  tdo_capacity_for_grid(&cap, map.desc.nx, map.desc.ny, map.desc.nz, ratio, headings, node_cap);
  const std::size_t boxes = std::max<std::size_t>(map.boxes.size(), 1u);
  cap.max_boxes = static_cast<uint32_t>(std::min<std::size_t>(boxes, 0xFFFFFFF0u));
  return cap;
}

tdo_status load_into(const Map& map, tdo_grid* grid, double clearance) {
  tdo_status st = tdo_grid_reset(grid, &map.desc);
  if (st != TDO_OK) return st;
  for (const tdo_box& b : map.boxes) {
    st = tdo_grid_add_box(grid, &b);
    if (st != TDO_OK) return st;
  }
  for (const tdo_voxel& v : map.voxels) {
    st = tdo_grid_add_voxel(grid, v.i, v.j, v.k);
    if (st != TDO_OK) return st;
  }
  return tdo_grid_finish(grid, clearance);
}

}  // namespace tdo_io
