#include "hrad/solvers/work_estimate.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "hrad/core/error.h"
#include "hrad/core/memory.h"
#include "hrad/solvers/hierarchical.h"
#include "hrad/solvers/substructuring.h"

namespace hrad {

double uniform_elements(const Scene& scene, double max_area) {
  double n = 0.0;
  for (const Patch& p : scene.patches)
    n += std::pow(4.0, std::max(0.0, std::ceil(std::log(p.area / max_area) / std::log(4.0))));
  return n;
}

std::string_view smaller_work(Method method) {
  switch (method) {
    case Method::kFull:
      return "raise --max-area";
    case Method::kSubstructure:
      return "raise --max-area (or --patch-area)";
    case Method::kHierarchical:
      return "raise --aeps";
  }
  return "make the scene smaller";
}

WorkEstimate estimate_work(const Scene& scene, const SolveOptions& o) {
  WorkEstimate w;
  const double samples = static_cast<double>(o.visibility_samples);
  switch (o.method) {
    case Method::kFull: {
      const double max_area = o.max_area > 0.0 ? o.max_area : scene.total_area() / kAutoElements;
      const double n = uniform_elements(scene, max_area);
      w.elements = n;
      w.interactions = n * n;
      w.form_factors = 0.5 * n * n;
      w.bytes = 2.0 * n * n * sizeof(double) + n * kBytesPerElement;
      w.option = "--max-area";
      w.option_value = max_area;
      w.remedy = smaller_work(o.method);
      break;
    }
    case Method::kSubstructure: {
      const double max_area = o.max_area > 0.0 ? o.max_area : scene.total_area() / kAutoElements;
      const double patch_area = o.patch_area > 0.0 ? o.patch_area : kAutoPatchAreaFraction * scene.total_area();
      const double big_n = uniform_elements(scene, patch_area);
      const double n = std::max(uniform_elements(scene, std::min(max_area, patch_area)), big_n);
      w.elements = n;
      w.interactions = n * big_n;
      w.form_factors = n * big_n;
      w.bytes = n * big_n * sizeof(double) + n * kBytesPerElement;
      w.option = "--max-area";
      w.option_value = max_area;
      w.remedy = smaller_work(o.method);
      break;
    }
    case Method::kHierarchical: {
      const double aeps = o.aeps > 0.0 ? o.aeps : kAutoAepsFraction * scene.total_area();
      // Leaves are never split below aeps, and no fewer than the patches themselves.
      const double leaves = std::max(static_cast<double>(scene.patches.size()), scene.total_area() / aeps);
      w.elements = leaves;
      w.interactions = kLinksPerElement * leaves;
      w.form_factors = kEvaluationsPerLink * w.interactions;
      w.bytes = 4.0 / 3.0 * leaves * kBytesPerElement + w.interactions * kBytesPerLink;
      w.option = "--aeps";
      w.option_value = aeps;
      w.remedy = smaller_work(o.method);
      break;
    }
  }
  w.segment_queries = w.form_factors * kPartlyVisibleShare * samples;
  return w;
}

void check_work(const WorkEstimate& w, std::string_view method, double available_bytes) {
  const std::string change = fmt::format("{} (now {:g})", w.remedy, w.option_value);
  if (available_bytes > 0.0 && !(w.bytes <= 0.8 * available_bytes))
    throw Error(fmt::format("{}: about {:.3g} elements need {} and this machine has {}: {}", method, w.elements,
                            format_bytes(w.bytes), format_bytes(available_bytes), change));
  if (!(w.form_factors <= kMaxFormFactors))
    throw Error(fmt::format("{}: about {:.3g} elements need {:.3g} form factors (more than {:.0e}: days of work): {}",
                            method, w.elements, w.form_factors, kMaxFormFactors, change));
  if (!(w.segment_queries <= kMaxSegmentQueries))
    throw Error(
        fmt::format("{}: about {:.3g} visibility queries (more than {:.0e}: days of work): lower "
                    "--visibility-samples or {}",
                    method, w.segment_queries, kMaxSegmentQueries, change));
}

}  // namespace hrad
