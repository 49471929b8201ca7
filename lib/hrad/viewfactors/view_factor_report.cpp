#include "hrad/viewfactors/view_factor_report.h"

#include <algorithm>
#include <cmath>

namespace hrad {

nlohmann::json view_factor_report(const ViewFactorMatrix& m, const SurfaceUnits& units,
                                  const ViewFactorOptions& options, const ClosureReport* closure) {
  nlohmann::json surfaces = nlohmann::json::array();
  double min_sum = m.n > 0 ? INFINITY : 0.0, max_sum = 0.0, max_error = 0.0, max_skipped = 0.0, max_capped = 0.0,
         sky = 0.0;
  for (int u = 0; u < m.n; ++u) {
    const auto i = static_cast<std::size_t>(u);
    const double s = m.row_sum(u);
    min_sum = std::min(min_sum, s);
    max_sum = std::max(max_sum, s);
    max_error = std::max(max_error, m.sampling_error[i]);
    max_skipped = std::max(max_skipped, m.skipped_bound[i]);
    max_capped = std::max(max_capped, m.capped[i]);
    sky += m.area[i] * std::max(0.0, 1.0 - s);
    surfaces.push_back({{"name", units.names[i]},
                        {"area", m.area[i]},
                        {"emissivity", units.emissivity[i]},
                        {"row_sum", s},
                        {"sky", 1.0 - s},
                        {"sampling_error", m.sampling_error[i]},
                        {"skipped_bound", m.skipped_bound[i]},
                        {"capped", m.capped[i]}});
  }
  const ViewFactorCounters& c = m.counters;
  nlohmann::json r = {
      {"surfaces", m.n},
      {"nonzeros", m.nonzeros()},
      {"max_reciprocity_error", max_reciprocity_error(m)},
      {"min_row_sum", min_sum},
      {"max_row_sum", max_sum},
      {"max_closure_error", m.n > 0 ? std::max(std::abs(1.0 - min_sum), std::abs(1.0 - max_sum)) : 0.0},
      {"sky_exchange_area", sky},
      {"max_sampling_error", max_error},
      {"threshold", options.threshold},
      {"sample_below", options.sample_below},
      {"far_rays", options.pair.far_rays},
      {"max_skipped_bound", max_skipped},
      {"capped_rows", c.capped_rows},
      {"max_capped", max_capped},
      {"partial_visibility", options.pair.partial == PartialVisibility::kExactRegion ? "exact_region" : "sampled"},
      {"fraction_error_target", options.pair.fraction_error},
      {"row_error_target", options.row_error},
      {"work",
       {{"patch_pairs", c.patch_pairs},
        {"skipped_pairs", c.skipped_pairs},
        {"dropped_by_closed_form", c.dropped_by_closed_form},
        {"shaft_skipped", c.shaft_skipped},
        {"facing_away", c.facing_away},
        {"fully_visible", c.fully_visible},
        {"fully_hidden", c.fully_hidden},
        {"partial", c.partial},
        {"closed_forms", c.closed_forms},
        {"rays", c.rays},
        {"visible_regions", c.regions},
        {"matrix_bytes", m.bytes()},
        {"classify_seconds", c.classify_seconds},
        {"seconds", c.seconds}}},
      {"per_surface", surfaces}};
  if (closure != nullptr)
    r["closure_adjustment"] = {
        {"max_row_error_before", closure->max_row_error_before}, {"max_row_error_after", closure->max_row_error_after},
        {"max_factor_change", closure->max_factor_change},       {"relative_change", closure->relative_change},
        {"rows_not_closable", closure->rows_not_closable},       {"clamped", closure->clamped}};
  return r;
}

}  // namespace hrad
