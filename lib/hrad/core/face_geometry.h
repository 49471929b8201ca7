// Small geometric helpers on the polygons of a Solution (area, centroid, normal).
#pragma once

#include <cstddef>

#include "hrad/core/solution.h"
#include "hrad/core/types.h"

namespace hrad {

/// Vector area of polygon `f` (Newell's method): its direction is the CCW normal, its length the area.
Vec3 face_vector_area(const Solution& solution, std::size_t f);
inline double face_area(const Solution& solution, std::size_t f) { return face_vector_area(solution, f).norm(); }
/// Mean of the polygon's vertices.
Vec3 face_centroid(const Solution& solution, std::size_t f);

}  // namespace hrad
