#include "hrad/gather/photometry.h"

namespace hrad {

double luminous_efficacy(EmissionUnits units) { return units == EmissionUnits::lumens_per_m2 ? 1.0 : 179.0; }

double luminance_weighted(const Rgb& v) { return 0.265074126 * v[0] + 0.670114631 * v[1] + 0.064811243 * v[2]; }

}  // namespace hrad
