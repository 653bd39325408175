/**
 * @file octree_check.h
 * @brief A bounded, non-recursive check of an OctoMap OcTree stream (.bt binary or .ot full
 *        format) before the OctoMap library reads it.
 *
 * The library reads a tree recursively and trusts the stream: a body of 0xff bytes makes every
 * node an inner node and recurses until the stack overflows; a header's node count is only
 * compared after everything was allocated. check_octree walks the same stream with an explicit
 * stack of at most 16 levels, one pass, constant work per byte, and refuses: a tree type other
 * than OcTree, a resolution outside the limits, a tree deeper than OctoMap's 16 levels, a node
 * count that differs from the header's or exceeds the limit, a stream cut short or followed by
 * more bytes, and (in .ot files) log-odds that are not finite numbers.
 */
#ifndef TDO_IO_OCTREE_CHECK_H
#define TDO_IO_OCTREE_CHECK_H

#include <cstddef>
#include <cstdint>
#include <string>

namespace tdo_io {

/** Outcome of check_octree; OctreeStatus::ok is the only success. */
enum class OctreeStatus {
  ok = 0,
  not_octomap,     /**< the first line is neither OctoMap header */
  bad_header,      /**< header without 'data', unknown keyword, unparsable value, too long */
  wrong_tree_type, /**< 'id' other than OcTree (ColorOcTree, ...) */
  bad_resolution,  /**< 'res' not a number within the limits */
  too_many_nodes,  /**< the header's node count exceeds the limit or what the bytes can hold */
  too_deep,        /**< a node below OctoMap's 16 levels */
  node_count,      /**< the stream holds another number of nodes than the header says */
  truncated,       /**< the stream ends inside the tree */
  trailing_bytes,  /**< bytes after the tree */
  bad_value,       /**< .ot: a node's log-odds is not a finite number */
};

/** @return the stable lower-case name of a status, e.g. "too_deep". */
const char* octree_status_str(OctreeStatus status);

/** Limits of check_octree. */
struct OctreeLimits {
  uint64_t max_nodes = 1000000; /**< nodes of one tree (OctoMap needs ~60 bytes each) */
  double min_res = 1e-4;        /**< m, smallest leaf edge accepted */
  double max_res = 1e3;         /**< m, largest leaf edge accepted */
};

/** What check_octree learnt about a good stream. */
struct OctreeInfo {
  bool binary = false;     /**< .bt ("# Octomap OcTree binary file"), else .ot */
  double res = 0.0;        /**< m, the header's resolution */
  uint64_t nodes = 0;      /**< nodes in the tree (= the header's size) */
  std::size_t data_at = 0; /**< offset of the first byte after the header */
  int depth = 0;           /**< deepest level with a node (root = 0) */
};

/** OctoMap's maximum tree depth: leaves at level 16 at the finest. */
constexpr int kOctreeMaxDepth = 16;

/**
 * @brief Check the bytes of an OcTree file or ENCODING_OCTOMAP_BT message.
 * @param[out] info filled on success (may be null)
 * @param[out] detail why not, in words, for a message (may be null)
 */
OctreeStatus check_octree(const uint8_t* data, std::size_t size, const OctreeLimits& limits,
                          OctreeInfo* info, std::string* detail);

}  // namespace tdo_io

#endif  // TDO_IO_OCTREE_CHECK_H
