#include "hrad/gather/final_gather.h"

namespace hrad {

GatherWork& GatherWork::operator+=(const GatherWork& o) {
  points += o.points;
  patch_visits += o.patch_visits;
  node_visits += o.node_visits;
  nodes_gathered += o.nodes_gathered;
  leaves_covered += o.leaves_covered;
  classifications += o.classifications;
  rays += o.rays;
  exact_regions += o.exact_regions;
  uncovered += o.uncovered;
  return *this;
}

GatherWork operator-(GatherWork a, const GatherWork& b) {
  a.points -= b.points;
  a.patch_visits -= b.patch_visits;
  a.node_visits -= b.node_visits;
  a.nodes_gathered -= b.nodes_gathered;
  a.leaves_covered -= b.leaves_covered;
  a.classifications -= b.classifications;
  a.rays -= b.rays;
  a.exact_regions -= b.exact_regions;
  a.uncovered -= b.uncovered;
  return a;
}

Rgb FinalGather::radiosity(int patch, const Rgb& irradiance) const {
  const Material& m = scene().material_of(scene().patches[static_cast<std::size_t>(patch)]);
  return m.emission + m.reflectance * irradiance;
}

}  // namespace hrad
