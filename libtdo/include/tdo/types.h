/**
 * @file types.h
 * @brief Plain geometric value types shared by every stage.
 */
#ifndef TDO_TYPES_H
#define TDO_TYPES_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** A point or vector in the world frame (z up). */
typedef struct tdo_vec3 {
  double x; /**< m, world frame */
  double y; /**< m, world frame */
  double z; /**< m, world frame */
} tdo_vec3;

/** Axis-aligned obstacle box; its interior is occupied. */
typedef struct tdo_box {
  tdo_vec3 min; /**< m, world frame, minimum corner */
  tdo_vec3 max; /**< m, world frame, maximum corner (each axis strictly greater than min) */
} tdo_box;

/** Integer voxel coordinates. */
typedef struct tdo_voxel {
  int32_t i; /**< voxel index along x */
  int32_t j; /**< voxel index along y */
  int32_t k; /**< voxel index along z */
} tdo_voxel;

#ifdef __cplusplus
}
#endif

#endif /* TDO_TYPES_H */
