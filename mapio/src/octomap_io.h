// OctoMap reader of tdo_io (internal): see load_map in tdo_io/map_io.h.
#ifndef TDO_IO_OCTOMAP_IO_H
#define TDO_IO_OCTOMAP_IO_H

#include <string>

#include "tdo_io/map_io.h"

namespace tdo_io {
namespace detail {

/**
 * @brief Read an OcTree (.bt binary or .ot full format, by the file's first line) and voxelize it.
 * @param[out] out filled: kind OctoMap, desc, voxels (path already set by the caller)
 * @param[out] error "FILE: message" on failure
 * @return true on success.
 */
bool load_octomap(const std::string& path, const LoadOptions& options, Map* out,
                  std::string* error);

}  // namespace detail
}  // namespace tdo_io

#endif  // TDO_IO_OCTOMAP_IO_H
