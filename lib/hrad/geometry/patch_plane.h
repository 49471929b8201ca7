// The plane a probe or a sample on a patch is put on: the patch's unit normal through the mean of
// its vertices (a patch may leave its plane by 1e-7 of its size, io/obj_reader.h).
#pragma once

#include "hrad/core/scene.h"

namespace hrad::detail {

/// normal . x for every x on the plane of `p`.
inline double plane_offset(const Patch& p) {
  Vec3 mean = Vec3::Zero();
  for (const Vec3& v : p.vertices) mean += v;
  return p.normal.dot(mean / static_cast<double>(p.vertices.size()));
}

}  // namespace hrad::detail
