#include "hrad/solvers/clustered_hierarchical.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "hrad/geometry/polygon.h"
#include "hrad/solvers/cluster_transfer.h"
#include "hrad/solvers/cluster_tree.h"
#include "hrad/solvers/hierarchical.h"
#include "hrad/solvers/hierarchical_leaf_factors.h"
#include "hrad/solvers/hierarchical_refine.h"
#include "hrad/solvers/solver_context.h"

namespace hrad {
namespace {

enum class Action : std::uint8_t { kDrop, kLink, kSplitP, kSplitQ, kSelf, kElements };

struct Candidate {
  NodeRef p = kNoNode;
  NodeRef q = kNoNode;
  Action action = Action::kDrop;
  FormFactorEstimate estimate;  ///< receiver p, source q
};

/// A stored interaction, gathered both ways: p gathers f_pq * B(q), q gathers f_qp * B(p).
struct PairLink {
  NodeRef p, q;
  float f_pq, f_qp;
};
static_assert(sizeof(PairLink) == 16);

/// One directed link in the gather layout, grouped by receiver: 8 bytes.
struct DirectedLink {
  std::int32_t source;  ///< dense node index
  float factor;         ///< F(receiver -> source); float: 6e-8 relative, far below any tolerance here
};
static_assert(sizeof(DirectedLink) == 8);

/// A directed link with a cluster at one end: 20 bytes (the direction picks which of the cluster's
/// surfaces send and receive).
struct ClusterLink {
  std::int32_t source;                ///< dense node index
  float factor;                       ///< F(receiver -> source)
  std::array<float, 3> to_source;     ///< unit direction from the receiver's centre to the source's
};
static_assert(sizeof(ClusterLink) == 20);

/// Per signed axis (+x, +y, +z, -x, -y, -z): a cluster's gathered irradiance for surfaces facing
/// that way, or its radiosity shown that way.
using Bins = std::array<Rgb, 6>;

/// Pairs farther apart than this many times the sum of their bounding radii use the far-field
/// transfer when its error is within the tolerance. 3, not 2: on the generated 1k-polygon office
/// (hrad scene generate) the clustered solve absorbs 0.979-0.982 of the emitted power with 3 and
/// 0.943-0.953 with 2 (plain HSA: 1.004), for 1.6x the links and 2x the time: the falloff term
/// alone underestimates the far-field error of near perpendicular pairs (cluster_transfer.h).
constexpr double kSeparation = 3.0;

double brightest(const Rgb& b, int channels) { return channels == 1 ? b[0] : b.maxCoeff(); }

class ClusteredSolver {
 public:
  ClusteredSolver(SolverContext& ctx, ElementHierarchy& h, const ClusterTree& tree, const HierarchicalTolerances& tol)
      : ctx_(ctx),
        scene_(ctx.scene()),
        h_(h),
        tree_(tree),
        tol_(tol),
        channels_(ctx.channels()),
        transfer_(ctx.scene(), h, tree, ctx.visibility(), ctx.effects().visibility, ctx.options().visibility_samples),
        cluster_radiosity_(tree.size(), Rgb::Zero()),
        refine_tol_{tol.feps, tol.bfeps, tol.aeps, detail::source_weights(ctx.scene(), ctx.channels())} {
    // A cluster's weight in the feps test is its brightest patch's (solve_hierarchical's weights).
    cluster_weight_.assign(tree.size(), 1.0);
    if (!refine_tol_.source_weight.empty()) {
      for (std::size_t c = 0; c < tree.size(); ++c) {
        double w = 0.0;
        for (const int patch : tree.patches(static_cast<int>(c)))
          w = std::max(w, refine_tol_.source_weight[static_cast<std::size_t>(patch)]);
        cluster_weight_[c] = w;
      }
    }
  }

  /// Refines from the root self-link; returns the number of new element nodes.
  std::size_t refine() {
    auto phase = ctx_.phase("refine");
    const std::size_t before = h_.size();
    pairs_.clear();
    recorded_element_pairs_ = false;
    cluster_pairs_ = 0;
    std::vector<detail::RefineCandidate> element_work;
    std::vector<Candidate> work{{tree_.root(), tree_.root(), Action::kDrop, {}}}, next;
    while (!work.empty()) {
      // Decide every candidate of this level in parallel (reads only), then split in order.
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, work.size(), 16),
                        [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t i = range.begin(); i != range.end(); ++i) decide(work[i]);
                        });
      next.clear();
      for (const Candidate& c : work) {
        switch (c.action) {
          case Action::kDrop:
            break;
          case Action::kElements:
            element_work.push_back(detail::candidate(c.p, c.q));
            break;
          case Action::kLink:
            pairs_.push_back({c.p, c.q, static_cast<float>(c.estimate.value), static_cast<float>(c.estimate.reverse)});
            cluster_pairs_ += (is_cluster(c.p) || is_cluster(c.q)) ? 1 : 0;
            break;
          case Action::kSelf: {
            const Cluster& k = tree_.cluster(cluster_index(c.p));
            next.push_back({k.children[0], k.children[0], Action::kDrop, {}});
            next.push_back({k.children[1], k.children[1], Action::kDrop, {}});
            next.push_back({k.children[0], k.children[1], Action::kDrop, {}});
            break;
          }
          case Action::kSplitP:
            for (const NodeRef child : split(c.p)) next.push_back({child, c.q, Action::kDrop, {}});
            break;
          case Action::kSplitQ:
            for (const NodeRef child : split(c.q)) next.push_back({c.p, child, Action::kDrop, {}});
            break;
        }
      }
      std::swap(work, next);
    }
    // Pairs of elements that are not far apart: plain HSA with solve_hierarchical()'s oracle and
    // its leaf-exact links (hierarchical_leaf_factors.h), so that near interactions are computed
    // exactly as without clustering.
    detail::RefineResult refined = detail::refine_pairs(h_, ctx_.evaluator(), std::move(element_work), refine_tol_, channels_);
    element_pairs_ = refined.links.size();
    element_directed_ = detail::directed_link_count(refined.links);
    leaf_links_ = detail::leaf_links(h_, refined.links);
    if (ctx_.options().record_links) {
      for (const detail::LinkPair& l : refined.links)
        pairs_.push_back({l.p, l.q, static_cast<float>(l.estimate.value), static_cast<float>(l.estimate.reverse)});
      recorded_element_pairs_ = true;
    }
    return h_.size() - before;
  }

  /// Builds the gather layout from the link pairs.
  void build_links() {
    auto phase = ctx_.phase("links");
    const std::size_t n = dense_size();
    offsets_.assign(n + 1, 0);
    cluster_offsets_.assign(n + 1, 0);
    const std::size_t own = pairs_.size() - (recorded_element_pairs_ ? element_pairs_ : 0);
    auto with_cluster = [](const PairLink& l) { return is_cluster(l.p) || is_cluster(l.q); };
    for (std::size_t i = 0; i < own; ++i) {
      const PairLink& l = pairs_[i];
      auto& off = with_cluster(l) ? cluster_offsets_ : offsets_;
      if (l.f_pq > 0.0f) ++off[dense(l.p) + 1];
      if (l.f_qp > 0.0f) ++off[dense(l.q) + 1];
    }
    for (std::size_t i = 0; i < n; ++i) {
      offsets_[i + 1] += offsets_[i];
      cluster_offsets_[i + 1] += cluster_offsets_[i];
    }
    links_.assign(offsets_[n], {});
    cluster_links_.assign(cluster_offsets_[n], {});
    std::vector<std::uint64_t> cursor(offsets_.begin(), offsets_.end() - 1);
    std::vector<std::uint64_t> cluster_cursor(cluster_offsets_.begin(), cluster_offsets_.end() - 1);
    for (std::size_t i = 0; i < own; ++i) {
      const PairLink& l = pairs_[i];
      const std::size_t dp = dense(l.p), dq = dense(l.q);
      if (!with_cluster(l)) {
        if (l.f_pq > 0.0f) links_[cursor[dp]++] = {static_cast<std::int32_t>(dq), l.f_pq};
        if (l.f_qp > 0.0f) links_[cursor[dq]++] = {static_cast<std::int32_t>(dp), l.f_qp};
        continue;
      }
      const Vec3 d = (transfer_.shape(l.q).centre - transfer_.shape(l.p).centre).normalized();  // p towards q
      const std::array<float, 3> to_q = {static_cast<float>(d.x()), static_cast<float>(d.y()), static_cast<float>(d.z())};
      const std::array<float, 3> to_p = {-to_q[0], -to_q[1], -to_q[2]};
      if (l.f_pq > 0.0f) cluster_links_[cluster_cursor[dp]++] = {static_cast<std::int32_t>(dq), l.f_pq, to_q};
      if (l.f_qp > 0.0f) cluster_links_[cluster_cursor[dq]++] = {static_cast<std::int32_t>(dp), l.f_qp, to_p};
    }
    leaf_link_count_ = leaf_links_.size();
  }

  /// Jacobi iterations of gather and push-pull; false when it stopped without converging.
  bool solve(double bound) {
    auto phase = ctx_.phase("solve");
    const std::size_t n = dense_size();
    radiosity_.assign(n, Rgb::Zero());
    gathered_.assign(n, Rgb::Zero());
    for (std::size_t i = 0; i < h_.size(); ++i) radiosity_[i] = h_.node(static_cast<NodeId>(i)).radiosity;
    pull();
    patch_change_.assign(static_cast<std::size_t>(h_.patch_count()), 0.0);
    patch_largest_.assign(static_cast<std::size_t>(h_.patch_count()), 0.0);
    const Bins zero = {Rgb::Zero(), Rgb::Zero(), Rgb::Zero(), Rgb::Zero(), Rgb::Zero(), Rgb::Zero()};
    cluster_bins_.assign(tree_.size(), zero);
    cluster_down_.assign(tree_.size(), zero);
    cluster_directional_.assign(tree_.size(), zero);
    pull_clusters();
    while (true) {
      gather();
      const double change = push_pull();
      if (ctx_.record_iteration(change)) break;
      double largest = 0.0;
      for (int p = 0; p < h_.patch_count(); ++p) largest = std::max(largest, radiosity_[static_cast<std::size_t>(p)].maxCoeff());
      if (largest > 2.0 * bound) {
        ctx_.set_failed(fmt::format("diverging: the mean radiosity of a patch ({}) passed twice the bound E_max / "
                                    "(1 - rho_max) = {} after {} iterations (try a smaller --feps or --aeps)",
                                    largest, bound, ctx_.summary().iterations));
        break;
      }
    }
    // Back into the hierarchy (output, and the B*F oracle of a next pass).
    for (std::size_t i = 0; i < h_.size(); ++i) h_.node(static_cast<NodeId>(i)).radiosity = radiosity_[i];
    for (std::size_t c = 0; c < tree_.size(); ++c) cluster_radiosity_[c] = radiosity_[h_.size() + c];
    return ctx_.summary().termination == Termination::kConverged;
  }

  /// Directed links as solve_hierarchical() counts them (element pairs before their leaf expansion).
  std::size_t directed_links() const {
    std::size_t own = 0;
    const std::size_t n = pairs_.size() - (recorded_element_pairs_ ? element_pairs_ : 0);
    for (std::size_t i = 0; i < n; ++i) own += (pairs_[i].f_pq > 0.0f) + (pairs_[i].f_qp > 0.0f);
    return own + element_directed_;
  }
  /// Directed links with the far-field transfer (a cluster at one end or two separated elements).
  std::size_t far_field_links() const { return directed_links() - element_directed_; }
  std::size_t stored_links() const { return links_.size() + cluster_links_.size(); }
  std::size_t leaf_links() const { return leaf_link_count_; }
  std::size_t link_pairs() const { return pairs_.size() - (recorded_element_pairs_ ? element_pairs_ : 0) + element_pairs_; }
  std::size_t cluster_link_pairs() const { return cluster_pairs_; }
  std::uint64_t cluster_estimates() const { return transfer_.estimates(); }
  std::size_t link_bytes() const {
    return links_.capacity() * sizeof(DirectedLink) + cluster_links_.capacity() * sizeof(ClusterLink) +
           (offsets_.capacity() + cluster_offsets_.capacity()) * sizeof(std::uint64_t) +
           leaf_links_.leaf.capacity() * sizeof(NodeId) + leaf_links_.other_side.capacity() * sizeof(std::uint32_t) +
           (leaf_links_.factor.capacity() + leaf_links_.weight.capacity()) * sizeof(double) +
           leaf_links_.leaf_offsets.capacity() * sizeof(std::uint64_t) +
           leaf_links_.pairs.capacity() * sizeof(detail::LeafLinks::Pair);
  }
  std::size_t stored_cluster_links() const { return cluster_links_.size(); }
  const std::vector<PairLink>& pairs() const { return pairs_; }
  Vec3 centre(NodeRef r) const { return transfer_.shape(r).centre; }
  void release_pairs() { std::vector<PairLink>().swap(pairs_); }

 private:
  std::size_t dense_size() const { return h_.size() + tree_.size(); }
  std::size_t dense(NodeRef r) const {
    return is_cluster(r) ? h_.size() + static_cast<std::size_t>(cluster_index(r)) : static_cast<std::size_t>(r);
  }
  bool can_split(NodeRef r) const { return is_cluster(r) || h_.node(r).area * 0.25 >= tol_.aeps; }
  const Rgb& current_radiosity(NodeRef r) const {
    return is_cluster(r) ? cluster_radiosity_[static_cast<std::size_t>(cluster_index(r))] : h_.node(r).radiosity;
  }

  std::vector<NodeRef> split(NodeRef r) {
    if (is_cluster(r)) {
      const Cluster& k = tree_.cluster(cluster_index(r));
      return {k.children[0], k.children[1]};
    }
    const NodeId first = h_.split(r);
    return {first, first + 1, first + 2, first + 3};
  }

  // The refinement oracle: HSA's factor test (and B*F test, HSA 1991 sec. 4.2) on the factors'
  // values for element pairs and on their bounds when a cluster is involved.
  double weight(NodeRef r) const {
    if (is_cluster(r)) return cluster_weight_[static_cast<std::size_t>(cluster_index(r))];
    return refine_tol_.source_weight.empty() ? 1.0 : refine_tol_.source_weight[static_cast<std::size_t>(h_.node(r).patch)];
  }

  // The feps test weighs what p gathers, F(p -> q), by q's a-priori radiosity (as
  // solve_hierarchical()'s oracle, hierarchical_refine.h source_weights()), and the other way round.
  bool too_large(double f_pq, double f_qp, NodeRef p, NodeRef q) const {
    if (tol_.feps > 0.0 && std::max(f_pq * weight(q), f_qp * weight(p)) > tol_.feps) return true;
    if (tol_.bfeps > 0.0) {
      const double b_p = brightest(current_radiosity(p), channels_), b_q = brightest(current_radiosity(q), channels_);
      if (std::max(b_q * f_pq, b_p * f_qp) > tol_.bfeps) return true;
    }
    return false;
  }

  void decide(Candidate& c) const {
    if (c.p == c.q) {
      c.action = is_cluster(c.p) ? Action::kSelf : Action::kDrop;  // a planar element sees nothing of itself
      return;
    }
    if (ctx_.effects().cull_facing_away && transfer_.facing_away(c.p, c.q)) {
      c.action = Action::kDrop;
      return;
    }
    const NodeShape sp = transfer_.shape(c.p), sq = transfer_.shape(c.q);
    const double r = (sq.centre - sp.centre).norm(), reach = sp.radius + sq.radius;
    if (r > kSeparation * reach) {
      // Well separated: the far-field transfer holds, with a relative error of about the change of
      // the 1/r^2 falloff across the two bounding spheres, 2 (r_p + r_q) / r (the error a link
      // makes, as in HSA 1991 sec. 4, rather than the size of its factor). Any pair, elements too:
      // far element pairs then need no exact kernel.
      const double variation = 2.0 * reach / r;
      const FormFactorEstimate far = transfer_.far_field(c.p, sp, c.q, sq);
      if (far.facing_away) {
        c.action = Action::kDrop;
        return;
      }
      if (!too_large(far.value * variation, far.reverse * variation, c.p, c.q)) {
        c.estimate = transfer_.estimate(c.p, sp, c.q, sq);
        // A shadow boundary may cross the pair: its sampled visibility error counts in full.
        const double vis_pq = c.estimate.error, vis_qp = c.estimate.error * sp.area / sq.area;
        if (!too_large(far.value * variation + vis_pq, far.reverse * variation + vis_qp, c.p, c.q)) {
          c.action = (c.estimate.value > 0.0 || c.estimate.reverse > 0.0) ? Action::kLink : Action::kDrop;
          return;
        }
      }
    }
    if (!is_cluster(c.p) && !is_cluster(c.q)) {
      c.action = Action::kElements;
      return;
    }
    // Split the node with the larger bounding sphere (Smits et al. 1994 split the larger side).
    const bool p_can = can_split(c.p), q_can = can_split(c.q);
    c.action = (p_can && (!q_can || sp.radius >= sq.radius)) ? Action::kSplitP : Action::kSplitQ;
  }

  // Interior elements and clusters get the area average of their children (bottom-up).
  void pull() {
    for (std::size_t i = h_.size(); i-- > 0;) {
      const ElementNode& n = h_.node(static_cast<NodeId>(i));
      if (n.is_leaf()) continue;
      Rgb sum = Rgb::Zero();
      double area = 0.0;
      for (int k = 0; k < 4; ++k) {
        const std::size_t child = static_cast<std::size_t>(n.first_child + k);
        const double a = h_.node(static_cast<NodeId>(child)).area;
        sum += a * radiosity_[child];
        area += a;
      }
      radiosity_[i] = sum / area;
    }
    pull_clusters();
  }

  // A cluster's radiosity: the area mean of its children (for the B*F oracle and reports), and per
  // signed axis the mean over its surfaces weighted by their projected area along that axis
  // (Sillion 1995's oriented clusters, with the six axis directions as the basis): what it shows
  // towards a direction.
  void pull_clusters() {
    for (std::size_t c = tree_.size(); c-- > 0;) {
      const Cluster& k = tree_.cluster(static_cast<int>(c));
      Rgb sum = Rgb::Zero();
      Bins weighted = {Rgb::Zero(), Rgb::Zero(), Rgb::Zero(), Rgb::Zero(), Rgb::Zero(), Rgb::Zero()};
      for (const NodeRef child : k.children) {
        if (is_cluster(child)) {
          const std::size_t ci = static_cast<std::size_t>(cluster_index(child));
          const Cluster& kc = tree_.cluster(cluster_index(child));
          sum += kc.area * radiosity_[dense(child)];
          if (!cluster_directional_.empty())
            for (int a = 0; a < 3; ++a) {
              weighted[a] += kc.axis_plus[a] * cluster_directional_[ci][a];
              weighted[3 + a] += kc.axis_minus[a] * cluster_directional_[ci][3 + a];
            }
        } else {
          const ElementNode& e = h_.node(child);
          const Rgb& b = radiosity_[static_cast<std::size_t>(child)];
          sum += e.area * b;
          const Vec3& n = scene_.patches[static_cast<std::size_t>(e.patch)].normal;
          for (int a = 0; a < 3; ++a) {
            weighted[a] += e.area * std::max(0.0, n[a]) * b;
            weighted[3 + a] += e.area * std::max(0.0, -n[a]) * b;
          }
        }
      }
      radiosity_[h_.size() + c] = sum / k.area;
      if (!cluster_directional_.empty())
        for (int a = 0; a < 3; ++a) {
          cluster_directional_[c][a] = k.axis_plus[a] > 0.0 ? Rgb(weighted[a] / k.axis_plus[a]) : Rgb::Zero();
          cluster_directional_[c][3 + a] = k.axis_minus[a] > 0.0 ? Rgb(weighted[3 + a] / k.axis_minus[a]) : Rgb::Zero();
        }
    }
  }

  // Radiosity that node `source` (dense index) shows towards the unit direction u.
  Rgb shown(std::size_t source, const float* u) const {
    if (source < h_.size()) return radiosity_[source];
    const std::size_t c = source - h_.size();
    const Cluster& k = tree_.cluster(static_cast<int>(c));
    Rgb sum = Rgb::Zero();
    double weight = 0.0;
    for (int a = 0; a < 3; ++a) {
      const double ua = u[a];
      const double w = ua > 0.0 ? ua * k.axis_plus[a] : -ua * k.axis_minus[a];
      sum += w * cluster_directional_[c][ua > 0.0 ? a : 3 + a];
      weight += w;
    }
    return weight > 0.0 ? Rgb(sum / weight) : radiosity_[source];
  }

  // HSA 1991 GatherRad over the receiver-grouped links, in parallel over receivers: each sums its
  // own links in their fixed order, so the bits do not depend on the thread count.
  void gather() {
    const std::size_t elements = h_.size();
    // Near element pairs: solve_hierarchical()'s leaf-resolved gather, on the hierarchy's nodes.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, elements, 4096), [&](const tbb::blocked_range<std::size_t>& range) {
      for (std::size_t i = range.begin(); i != range.end(); ++i) h_.node(static_cast<NodeId>(i)).radiosity = radiosity_[i];
    });
    detail::gather_leaf_links(h_, leaf_links_);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, dense_size(), 512),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t i = range.begin(); i != range.end(); ++i) {
                          Rgb sum = i < elements ? h_.node(static_cast<NodeId>(i)).gathered : Rgb::Zero();
                          for (std::uint64_t k = offsets_[i]; k < offsets_[i + 1]; ++k)
                            sum += static_cast<double>(links_[k].factor) *
                                   radiosity_[static_cast<std::size_t>(links_[k].source)];
                          if (i < elements) {
                            // An element receives what each source shows towards it.
                            for (std::uint64_t k = cluster_offsets_[i]; k < cluster_offsets_[i + 1]; ++k) {
                              const ClusterLink& l = cluster_links_[k];
                              const float back[3] = {-l.to_source[0], -l.to_source[1], -l.to_source[2]};
                              sum += static_cast<double>(l.factor) * shown(static_cast<std::size_t>(l.source), back);
                            }
                            gathered_[i] = sum;
                            continue;
                          }
                          // A cluster receives the link's power A_R F B_S, spread over its surfaces
                          // by their projected area towards the source, per signed axis, so that
                          // what its surfaces get sums to that power (Sillion 1995, oriented
                          // receivers; exact for axis-aligned surfaces in the far field).
                          const std::size_t c = i - elements;
                          const Cluster& kc = tree_.cluster(static_cast<int>(c));
                          Bins bins = {Rgb::Zero(), Rgb::Zero(), Rgb::Zero(), Rgb::Zero(), Rgb::Zero(), Rgb::Zero()};
                          for (std::uint64_t k = cluster_offsets_[i]; k < cluster_offsets_[i + 1]; ++k) {
                            const ClusterLink& l = cluster_links_[k];
                            const float back[3] = {-l.to_source[0], -l.to_source[1], -l.to_source[2]};
                            double facing = 0.0;
                            for (int a = 0; a < 3; ++a)
                              facing += l.to_source[a] > 0.0f ? l.to_source[a] * kc.axis_plus[a]
                                                              : -l.to_source[a] * kc.axis_minus[a];
                            if (!(facing > 0.0)) continue;
                            const Rgb power = (static_cast<double>(l.factor) * kc.area / facing) *
                                              shown(static_cast<std::size_t>(l.source), back);
                            for (int a = 0; a < 3; ++a) {
                              const double da = l.to_source[a];
                              if (da > 0.0) bins[a] += da * power;
                              else if (da < 0.0) bins[3 + a] += -da * power;
                            }
                          }
                          cluster_bins_[c] = bins;
                          gathered_[i] = sum;  // no element-style links end at clusters
                        }
                      });
  }

  // HSA 1991 PushPullRad through clusters and quadtrees; returns the stopping measure.
  double push_pull() {
    for (std::size_t c = 0; c < tree_.size(); ++c) {  // parents before children
      const int parent = tree_.cluster(static_cast<int>(c)).parent;
      cluster_down_[c] = cluster_bins_[c];
      if (parent >= 0)
        for (int a = 0; a < 6; ++a) cluster_down_[c][a] += cluster_down_[static_cast<std::size_t>(parent)][a];
    }
    tbb::parallel_for(tbb::blocked_range<int>(0, h_.patch_count(), 8), [&](const tbb::blocked_range<int>& range) {
      for (int p = range.begin(); p != range.end(); ++p) {
        const int parent = tree_.parent_of_patch(p);
        double change = 0.0, largest = 0.0;
        // The patch's share of its clusters' bins: its irradiance from the cluster links.
        Rgb down = Rgb::Zero();
        if (parent >= 0) {
          const Vec3& n = scene_.patches[static_cast<std::size_t>(p)].normal;
          const Bins& bins = cluster_down_[static_cast<std::size_t>(parent)];
          for (int a = 0; a < 3; ++a) down += n[a] > 0.0 ? Rgb(n[a] * bins[a]) : Rgb(-n[a] * bins[3 + a]);
        }
        push_pull_element(h_.root(p), down, &change, &largest);
        patch_change_[static_cast<std::size_t>(p)] = change;
        patch_largest_[static_cast<std::size_t>(p)] = largest;
      }
    });
    pull_clusters();
    double change = 0.0, largest = 0.0;
    for (int p = 0; p < h_.patch_count(); ++p) {
      change = std::max(change, patch_change_[static_cast<std::size_t>(p)]);
      largest = std::max(largest, patch_largest_[static_cast<std::size_t>(p)]);
    }
    return stopping_change(change, largest);
  }

  Rgb push_pull_element(NodeId id, const Rgb& down, double* change, double* largest) {
    const ElementNode& n = h_.node(id);
    const std::size_t i = static_cast<std::size_t>(id);
    const Rgb total = down + gathered_[i];
    if (n.is_leaf()) {
      const Rgb b = n.emission + n.reflectance * total;
      for (int c = 0; c < channels_; ++c) {
        *change = std::max(*change, std::abs(b[c] - radiosity_[i][c]));
        *largest = std::max(*largest, std::abs(b[c] - n.emission[c]));
      }
      radiosity_[i] = b;
      return b;
    }
    Rgb sum = Rgb::Zero();
    double area = 0.0;
    for (int k = 0; k < 4; ++k) {
      const NodeId child = n.first_child + k;
      const double a = h_.node(child).area;
      sum += a * push_pull_element(child, total, change, largest);
      area += a;
    }
    radiosity_[i] = sum / area;
    return radiosity_[i];
  }

  SolverContext& ctx_;
  const Scene& scene_;
  ElementHierarchy& h_;
  const ClusterTree& tree_;
  HierarchicalTolerances tol_;
  int channels_;
  ClusterTransfer transfer_;
  std::vector<Rgb> cluster_radiosity_;  // between passes, for the B*F oracle
  detail::RefineTolerances refine_tol_;
  std::vector<double> cluster_weight_;
  std::vector<PairLink> pairs_;  // far-field and cluster links (then element pairs when recording links)
  std::size_t cluster_pairs_ = 0;
  detail::LeafLinks leaf_links_;  // near element pairs, resolved to leaves (solve_hierarchical's gather)
  std::size_t element_pairs_ = 0, element_directed_ = 0, leaf_link_count_ = 0;
  bool recorded_element_pairs_ = false;
  std::vector<std::uint64_t> offsets_;
  std::vector<DirectedLink> links_;
  std::vector<Rgb> radiosity_, gathered_;
  std::vector<std::uint64_t> cluster_offsets_;
  std::vector<ClusterLink> cluster_links_;
  std::vector<Bins> cluster_bins_, cluster_down_, cluster_directional_;
  std::vector<double> patch_change_, patch_largest_;
};

}  // namespace

bool uses_clustering(const Scene& scene, const SolveOptions& options) {
  if (options.method != Method::kHierarchical) return false;
  switch (options.clustering) {
    case Clustering::kOn: return true;
    case Clustering::kOff: return false;
    case Clustering::kAuto: return scene.patches.size() >= kAutoClusteringPatches;
  }
  return false;
}

SolveSummary solve_clustered_hierarchical(const Scene& scene, const SolveOptions& requested, Solution* out) {
  // The analytic kernel for element pairs, as solve_hierarchical() (exact, reciprocal at any size).
  SolveOptions options = requested;
  options.kernel = FormFactorKernel::kAnalytic;
  SolverContext ctx(scene, options, Method::kHierarchical);
  ElementHierarchy h(scene);
  const HierarchicalTolerances t = hierarchical_tolerances(scene, options);
  auto& figures = ctx.summary().figures;
  figures["clustering"] = 1;
  ctx.summary().effects.reasons.push_back(
      "clustering: on (a volume hierarchy above the patches, linked from one root self-link)");
  if (auto done = start_hierarchical(ctx, h, t, out)) return *done;
  std::unique_ptr<ClusterTree> tree;
  {
    auto phase = ctx.phase("clusters");
    tree = std::make_unique<ClusterTree>(scene);
  }
  figures["clusters"] = static_cast<double>(tree->size());
  ClusteredSolver solver(ctx, h, *tree, t);
  const double bound = radiosity_bound(scene);
  int passes = 0;
  std::size_t last_pairs = 0;
  while (true) {
    const std::size_t grown = solver.refine();
    ++passes;
    solver.build_links();
    ctx.progress(fmt::format("clustered hierarchical: pass {}: {} nodes, {} clusters, {} links ({} with a cluster)",
                             passes, h.size(), tree->size(), solver.directed_links(), solver.cluster_link_pairs()));
    if (passes > 1 && grown == 0 && solver.link_pairs() == last_pairs) break;
    last_pairs = solver.link_pairs();
    if (!solver.solve(bound)) break;
    if (t.bfeps <= 0.0 || passes >= kMaxRefinePasses) break;
  }

  end_hierarchical(ctx, h);
  figures["refine_passes"] = passes;
  figures["link_pairs"] = static_cast<double>(solver.link_pairs());
  figures["far_field_links"] = static_cast<double>(solver.far_field_links());
  figures["cluster_link_pairs"] = static_cast<double>(solver.cluster_link_pairs());
  figures["cluster_estimates"] = static_cast<double>(solver.cluster_estimates());
  figures["leaf_links"] = static_cast<double>(solver.leaf_links());
  figures["stored_links"] = static_cast<double>(solver.stored_links());
  figures["bytes_per_link"] = static_cast<double>(sizeof(DirectedLink));
  figures["bytes_per_cluster_link"] = static_cast<double>(sizeof(ClusterLink));
  figures["stored_cluster_links"] = static_cast<double>(solver.stored_cluster_links());
  figures["link_bytes"] = static_cast<double>(solver.link_bytes());
  std::vector<std::pair<Vec3, Vec3>> segments;
  if (out != nullptr && options.record_links) {
    for (const PairLink& l : solver.pairs()) segments.emplace_back(solver.centre(l.p), solver.centre(l.q));
  }
  const std::size_t directed = solver.directed_links();
  solver.release_pairs();
  SolveSummary summary = ctx.finish(h, directed, out);
  if (out != nullptr) out->link_segments = std::move(segments);
  return summary;
}

}  // namespace hrad
