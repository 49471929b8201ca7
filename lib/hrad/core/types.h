// Basic value types shared by every module.
#pragma once

#include <Eigen/Dense>

namespace hrad {

using Vec3 = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;
/// Linear RGB triple (reflectance, exitance or radiosity per channel).
using Rgb = Eigen::Array3d;

}  // namespace hrad
