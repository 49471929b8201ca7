// Which patch a probe point lies on: a lighting designer's point is given with a few printed
// digits, so "on the floor" means within a tolerance of the floor's plane, inside it, and facing the
// way its front does. A point found on a patch gets that patch's radiosity B = E + rho H and is
// lit only from in front of it; any other point is a point in space (irradiance only).
#pragma once

#include "hrad/core/scene.h"
#include "hrad/core/types.h"

namespace hrad {

/// Whether `x` lies on patch `p`: within `tolerance` of its plane and inside its outline (counter-clockwise
/// about its normal) to the same tolerance.
bool on_patch(const Patch& p, const Vec3& x, double tolerance);

/// The patch whose front `x` lies on: within `tolerance` of its plane, inside it (to the same
/// tolerance), and `normal` within ~1.4 mrad of its front normal (cos >= 1 - 1e-6); the first such
/// patch in scene order, or -1.
int front_patch_at(const Scene& scene, const Vec3& x, const Vec3& normal, double tolerance);

/// How far from a patch a probe point may be and still count as on it: 1e-6 of the scene's size
/// (the larger of its bounding box's diagonal and its largest coordinate), so that coordinates
/// printed with 7 significant digits stay on their patch.
double probe_tolerance(const Scene& scene);

}  // namespace hrad
