// The final gather of a solution read from a file (`hrad render --final-gather`, `hrad probe`):
// through the links the file carries (a hierarchical solve's: link_gather.h, with stored_links.h
// rebuilding them on the scene), so a point costs the links on its leaf's path, or over every
// patch (leaf_gather.h) when the file has none (full matrix, substructuring, files written before
// links were stored) or when asked to. Points in space (probes off every surface) have no leaf and
// are gathered over every patch either way.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "hrad/gather/leaf_gather.h"
#include "hrad/gather/link_gather.h"
#include "hrad/io/solution_ply.h"
#include "hrad/solvers/solved_hierarchy.h"

namespace hrad {

/// What a solution's gather runs over: the stored links when there are any (automatic), the links
/// (an error when the file has none), or every patch.
enum class GatherSources { automatic, links, all };

/// "links" or "all"; hrad::Error naming --gather-sources otherwise.
GatherSources parse_gather_sources(const std::string& text);

/// The gather through the links that matches the all-patches gather `o`: the same tolerance,
/// partial-visibility mode, samples, per-point classification and seed.
LinkGatherOptions matching_link_options(const LeafGatherOptions& o);

class SolutionGather {
 public:
  /// `scene` and `solution` (read from `path` with `links`) must outlive the gather. Through the
  /// links with matching_link_options(options); exact visibility (VisibilityMode::exact) gathers
  /// over all patches. Errors name `path` (links that do not fit the scene or the solution) or
  /// --gather-sources.
  SolutionGather(const Scene& scene, const Solution& solution, const std::optional<SolutionLinks>& links,
                 const std::string& path, GatherSources sources, const LeafGatherOptions& options);
  ~SolutionGather();

  const FinalGather& gather() const;
  bool through_links() const { return links_ != nullptr; }
  /// "through the links" or "over all patches", for summaries.
  const char* description() const { return through_links() ? "through the links" : "over all patches"; }

 private:
  SolvedHierarchy solved_;
  std::unique_ptr<LeafGather> all_;
  std::unique_ptr<LinkGather> links_;
};

}  // namespace hrad
