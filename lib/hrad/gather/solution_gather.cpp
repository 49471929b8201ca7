#include "hrad/gather/solution_gather.h"

#include <fmt/format.h>

#include "hrad/core/error.h"
#include "hrad/gather/stored_links.h"

namespace hrad {

GatherSources parse_gather_sources(const std::string& text) {
  if (text == "links") return GatherSources::links;
  if (text == "all") return GatherSources::all;
  throw Error(fmt::format("--gather-sources: '{}' is not links or all", text));
}

LinkGatherOptions matching_link_options(const LeafGatherOptions& o) {
  LinkGatherOptions l;
  l.tolerance = o.tolerance;
  l.partial = o.partial;
  l.visibility_samples = o.visibility_samples;
  l.classify_points = o.classify_points;
  l.seed = o.seed;
  return l;
}

SolutionGather::SolutionGather(const Scene& scene, const Solution& solution, const std::optional<SolutionLinks>& links,
                               const std::string& path, GatherSources sources, const LeafGatherOptions& options) {
  if (sources == GatherSources::links && !links)
    throw Error(
        fmt::format("--gather-sources links: {} carries no links (only a hierarchical solve writes them)", path));
  if (sources == GatherSources::links && options.visibility == VisibilityMode::exact)
    throw Error("--gather-sources links: not with exact visibility (--exact-visibility gathers over all patches)");
  all_ = std::make_unique<LeafGather>(scene, solution, options);
  if (sources == GatherSources::all || !links || options.visibility == VisibilityMode::exact) return;
  solved_ = restored_links(scene, solution, *links, path);
  links_ = std::make_unique<LinkGather>(scene, solved_, matching_link_options(options), all_.get());
}

SolutionGather::~SolutionGather() = default;

const FinalGather& SolutionGather::gather() const {
  if (links_) return *links_;
  return *all_;
}

}  // namespace hrad
