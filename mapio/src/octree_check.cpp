// Bounded, non-recursive check of an OcTree stream (tdo_io/octree_check.h).
#include "tdo_io/octree_check.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string_view>

#include "tdo_io/text.h"

namespace tdo_io {
namespace {

const char kBinaryHeader[] = "# Octomap OcTree binary file";  // .bt, OcTree::readBinary
const char kFullHeader[] = "# Octomap OcTree file";           // .ot, AbstractOcTree::read
constexpr std::size_t kMaxHeaderBytes = 16384;                // comments included

struct Header {
  std::string id;
  double res = 0.0;
  uint64_t size = 0;
  bool have_res = false;
  bool have_size = false;
};

/** Reads the header the way OctoMap's AbstractOcTree::readHeader does, strictly. */
class HeaderReader {
 public:
  HeaderReader(const uint8_t* data, std::size_t size, std::string* detail)
      : data_(data), end_(size < kMaxHeaderBytes ? size : kMaxHeaderBytes), detail_(detail) {}

  OctreeStatus read(Header* h, OctreeInfo* info) {
    const std::string_view first = line();
    if (first.rfind(kBinaryHeader, 0) == 0)
      info->binary = true;
    else if (first.rfind(kFullHeader, 0) != 0)
      return fail(OctreeStatus::not_octomap, std::string("the first line should start with '") +
                                                 kBinaryHeader + "' (.bt) or '" + kFullHeader +
                                                 "' (.ot), got '" + printable(first) + "'");
    while (true) {
      const std::string_view tok = token();
      if (tok.empty())
        return fail(OctreeStatus::bad_header, "header without 'data' line" + where());
      if (tok == "data") {
        (void)line();  // the binary data starts after this line
        info->data_at = pos_;
        return OctreeStatus::ok;
      }
      if (tok[0] == '#') {
        (void)line();
      } else if (tok == "id") {
        h->id = std::string(token());
      } else if (tok == "res") {
        const OctreeStatus st = number(&h->res);
        if (st != OctreeStatus::ok) return st;
        h->have_res = true;
      } else if (tok == "size") {
        const OctreeStatus st = count(&h->size);
        if (st != OctreeStatus::ok) return st;
        h->have_size = true;
      } else {
        return fail(OctreeStatus::bad_header, "unknown header keyword '" + printable(tok) + "'");
      }
    }
  }

 private:
  std::string_view line() {
    const std::size_t start = pos_;
    while (pos_ < end_ && data_[pos_] != '\n') ++pos_;
    std::size_t stop = pos_;
    if (pos_ < end_) ++pos_;
    if (stop > start && data_[stop - 1] == '\r') --stop;
    return std::string_view(reinterpret_cast<const char*>(data_) + start, stop - start);
  }

  static bool space(uint8_t c) { return c == ' ' || (c >= '\t' && c <= '\r'); }

  std::string_view token() {
    while (pos_ < end_ && space(data_[pos_])) ++pos_;
    const std::size_t start = pos_;
    while (pos_ < end_ && !space(data_[pos_])) ++pos_;
    return std::string_view(reinterpret_cast<const char*>(data_) + start, pos_ - start);
  }

  OctreeStatus number(double* v) {
    const std::string tok(token());
    char* stop = nullptr;
    errno = 0;
    *v = std::strtod(tok.c_str(), &stop);
    if (tok.empty() || stop != tok.c_str() + tok.size() || errno == ERANGE || !std::isfinite(*v))
      return fail(OctreeStatus::bad_resolution, "'res " + printable(tok) + "' is not a number");
    return OctreeStatus::ok;
  }

  OctreeStatus count(uint64_t* v) {
    const std::string tok(token());
    bool digits = !tok.empty() && tok.size() <= 10;
    for (char c : tok) digits = digits && c >= '0' && c <= '9';
    if (digits) *v = std::strtoull(tok.c_str(), nullptr, 10);
    if (!digits || *v > 0xFFFFFFFFull)  // OctoMap reads an unsigned int
      return fail(OctreeStatus::bad_header,
                  "'size " + printable(tok) + "' is not a node count (0 to 4294967295)");
    return OctreeStatus::ok;
  }

  std::string where() const {
    return end_ == kMaxHeaderBytes ? " in the first " + std::to_string(kMaxHeaderBytes) + " bytes"
                                   : "";
  }

  OctreeStatus fail(OctreeStatus st, const std::string& msg) {
    if (detail_ != nullptr) *detail_ = msg;
    return st;
  }

  const uint8_t* data_;
  std::size_t end_;
  std::string* detail_;
  std::size_t pos_ = 0;
};

/** One level of the walk: how many children of a node at `depth` are still to be read. */
struct Frame {
  int depth;
  int remaining;
};

/** Walks the tree's nodes in the stream's depth-first order without recursion. */
class TreeWalk {
 public:
  TreeWalk(const uint8_t* data, std::size_t size, std::size_t at, bool binary, uint64_t expected,
           std::string* detail)
      : data_(data), size_(size), pos_(at), binary_(binary), expected_(expected), detail_(detail) {}

  OctreeStatus run(OctreeInfo* info) {
    OctreeStatus st = node(0);
    while (st == OctreeStatus::ok && top_ > 0) {
      Frame& f = stack_[top_ - 1];
      if (f.remaining == 0) {
        --top_;
        continue;
      }
      --f.remaining;
      st = node(f.depth + 1);
    }
    if (st != OctreeStatus::ok) return st;
    if (nodes_ != expected_)
      return fail(OctreeStatus::node_count, "the header says " + std::to_string(expected_) +
                                                " nodes, the stream holds " +
                                                std::to_string(nodes_));
    if (pos_ != size_)
      return fail(OctreeStatus::trailing_bytes,
                  std::to_string(size_ - pos_) + " bytes after the tree's last node");
    info->nodes = nodes_;
    info->depth = deepest_;
    return OctreeStatus::ok;
  }

 private:
  // One node: .bt 2 bytes of 2-bit child codes (0 none, 1 and 2 leaves, 3 inner nodes that
  // follow); .ot a float log-odds and a byte with one bit per child (every child follows).
  OctreeStatus node(int depth) {
    const std::size_t need = binary_ ? 2u : 5u;
    if (size_ - pos_ < need)
      return fail(OctreeStatus::truncated, "the stream ends inside node " +
                                               std::to_string(nodes_ + 1) + " (byte " +
                                               std::to_string(size_) + ")");
    int children = 0;
    int follow = 0;
    if (binary_) {
      for (int b = 0; b < 2; ++b) {
        for (int i = 0; i < 4; ++i) {
          const int code = (data_[pos_ + b] >> (2 * i)) & 3;
          children += code != 0 ? 1 : 0;
          follow += code == 3 ? 1 : 0;
        }
      }
    } else {
      float v = 0.0f;
      std::memcpy(&v, data_ + pos_, sizeof v);
      if (!std::isfinite(v))
        return fail(OctreeStatus::bad_value,
                    "node " + std::to_string(nodes_ + 1) + " has a log-odds that is not finite");
      for (int i = 0; i < 8; ++i) children += (data_[pos_ + 4] >> i) & 1;
      follow = children;
    }
    pos_ += need;
    if (depth > deepest_) deepest_ = depth;
    // .bt: inner nodes (code 3) sit at depth 15 at the deepest, their leaves at 16; .ot: every
    // node is read, the deepest at 16.
    const int child_depth = depth + 1;
    const bool deep = binary_ ? (follow > 0 && child_depth >= kOctreeMaxDepth)
                              : (children > 0 && child_depth > kOctreeMaxDepth);
    if (deep)
      return fail(OctreeStatus::too_deep, "a node at depth " + std::to_string(depth) +
                                              " has children below OctoMap's " +
                                              std::to_string(kOctreeMaxDepth) + " levels");
    if (binary_) {
      nodes_ += (depth == 0 ? 1u : 0u) + static_cast<uint64_t>(children);
      if (children > 0 && child_depth > deepest_) deepest_ = child_depth;
    } else {
      nodes_ += 1u;
    }
    if (nodes_ > expected_)
      return fail(OctreeStatus::node_count,
                  "the stream holds more nodes than the header's " + std::to_string(expected_));
    if (follow > 0) stack_[top_++] = Frame{depth, follow};
    return OctreeStatus::ok;
  }

  OctreeStatus fail(OctreeStatus st, const std::string& msg) {
    if (detail_ != nullptr) *detail_ = msg;
    return st;
  }

  const uint8_t* data_;
  std::size_t size_;
  std::size_t pos_;
  bool binary_;
  uint64_t expected_;
  std::string* detail_;
  uint64_t nodes_ = 0;
  int deepest_ = 0;
  Frame stack_[kOctreeMaxDepth + 1] = {};
  int top_ = 0;
};

}  // namespace

const char* octree_status_str(OctreeStatus status) {
  switch (status) {
    case OctreeStatus::ok:
      return "ok";
    case OctreeStatus::not_octomap:
      return "not_octomap";
    case OctreeStatus::bad_header:
      return "bad_header";
    case OctreeStatus::wrong_tree_type:
      return "wrong_tree_type";
    case OctreeStatus::bad_resolution:
      return "bad_resolution";
    case OctreeStatus::too_many_nodes:
      return "too_many_nodes";
    case OctreeStatus::too_deep:
      return "too_deep";
    case OctreeStatus::node_count:
      return "node_count";
    case OctreeStatus::truncated:
      return "truncated";
    case OctreeStatus::trailing_bytes:
      return "trailing_bytes";
    case OctreeStatus::bad_value:
      return "bad_value";
  }
  return "unknown";
}

OctreeStatus check_octree(const uint8_t* data, std::size_t size, const OctreeLimits& limits,
                          OctreeInfo* info, std::string* detail) {
  auto fail = [&](OctreeStatus st, const std::string& msg) {
    if (detail != nullptr) *detail = msg;
    return st;
  };
  if (data == nullptr && size > 0) return fail(OctreeStatus::truncated, "no data");
  OctreeInfo got;
  Header h;
  HeaderReader header(data, size, detail);
  OctreeStatus st = header.read(&h, &got);
  if (st != OctreeStatus::ok) return st;
  if (h.id != "OcTree")
    return fail(OctreeStatus::wrong_tree_type,
                h.id.empty()
                    ? std::string("the header has no 'id'")
                    : "tree type '" + printable(h.id) + "' is not supported (only OcTree)");
  if (!h.have_res || !(h.res >= limits.min_res && h.res <= limits.max_res)) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "resolution %.6g m outside [%g, %g] m", h.res, limits.min_res,
                  limits.max_res);
    return fail(OctreeStatus::bad_resolution, h.have_res ? buf : "the header has no 'res'");
  }
  got.res = h.res;
  if (!h.have_size || h.size == 0)
    return fail(OctreeStatus::node_count, "the header gives no nodes ('size 0' or none)");
  // Constant-time bounds first: a .bt node takes 2 bytes and names at most 8 children, a .ot node
  // takes 5 bytes.
  const uint64_t body = size - got.data_at;
  const uint64_t fit = got.binary ? 1u + 4u * body : body / 5u;
  if (h.size > limits.max_nodes)
    return fail(OctreeStatus::too_many_nodes, "the header says " + std::to_string(h.size) +
                                                  " nodes, more than the limit of " +
                                                  std::to_string(limits.max_nodes));
  if (h.size > fit)
    return fail(OctreeStatus::node_count, "the header says " + std::to_string(h.size) + " nodes, " +
                                              std::to_string(body) +
                                              " bytes of data hold at most " + std::to_string(fit));
  TreeWalk walk(data, size, got.data_at, got.binary, h.size, detail);
  st = walk.run(&got);
  if (st != OctreeStatus::ok) return st;
  if (info != nullptr) *info = got;
  return OctreeStatus::ok;
}

}  // namespace tdo_io
