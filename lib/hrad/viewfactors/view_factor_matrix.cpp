#include "hrad/viewfactors/view_factor_matrix.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <memory>
#include <utility>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "hrad/core/error.h"
#include "hrad/core/rng.h"
#include "hrad/core/stopwatch.h"
#include "hrad/viewfactors/pair_bound.h"

namespace hrad {
namespace {

// Sums of nonnegative bounds, one per patch, added from any thread in any order with the same
// result: fixed point in units of 2^-44, each term rounded up (so the sum still bounds).
class BoundSums {
 public:
  explicit BoundSums(std::size_t n) : sums_(n) {}
  void add(std::size_t p, double bound) {
    sums_[p].fetch_add(static_cast<std::uint64_t>(std::ceil(std::ldexp(bound, kBits))), std::memory_order_relaxed);
  }
  double operator[](std::size_t p) const {
    return std::ldexp(static_cast<double>(sums_[p].load(std::memory_order_relaxed)), -kBits);
  }

 private:
  static constexpr int kBits = 44;
  std::vector<std::atomic<std::uint64_t>> sums_;
};

// What the matrix keeps of one pair's result; `estimated`: its visible fraction was sampled (or
// integrated by a Gauss rule), so the row cap may scale it.
struct PairValue {
  int q;
  double exchange, error;
  bool estimated;
};

// One entry of the upper triangle of E: the exchange of exactly classified pairs and that of
// estimated ones, kept apart until the row cap.
struct UpperEntry {
  int v;
  double exact, estimated;
};

struct RowResult {
  std::vector<PairValue> pairs;                  // q > p with a nonzero exchange or error
  std::vector<std::pair<int, double>> deferred;  // partly visible pairs (q > p) and their unoccluded exchange
  ViewFactorCounters counters;
};

// A partly visible pair whose fraction is sampled once every row's budget is known.
struct DeferredPair {
  int p, q;
  double unoccluded;
};

// One pair as the matrix computes it: dropped by the cheap bound (pair_bound.h; a zero bound,
// facing away in floating point, is left to the exact test), or its exchange (classified only,
// when `defer`: sampled once every row's budget is known).
struct ScreenedPair {
  bool cheap_drop = false;
  FactorBound bound;
  PairExchange exchange;
};

ScreenedPair screen_pair(const FormFactorEvaluator& evaluator, const std::vector<PatchBoundShape>& shapes, int p, int q,
                         const PairExchangeOptions& options, bool defer) {
  ScreenedPair s;
  if (options.threshold > 0.0) {
    s.bound = factor_bound(shapes[static_cast<std::size_t>(p)], shapes[static_cast<std::size_t>(q)]);
    s.cheap_drop =
        (s.bound.pq > 0.0 || s.bound.qp > 0.0) && s.bound.pq < options.threshold && s.bound.qp < options.threshold;
    if (s.cheap_drop) return s;
  }
  s.exchange = defer ? classify_pair(evaluator, p, q, options) : pair_exchange(evaluator, p, q, options);
  return s;
}

// True when the pair's result is kept (an entry or a sampling error), and whether it waits for
// rays (a deferred partly visible pair).
bool deferred_pair(const PairExchange& e, bool defer) {
  return defer && e.pair_class == PairClass::kPartial && e.unoccluded > 0.0 && !e.shaft_skipped;
}

// `samples` pairs drawn uniformly from the eligible pairs (deterministic), screened as the matrix
// screens them: the share that is stored or deferred, scaled to all pairs, plus 3 standard errors
// of the binomial count (a high estimate).
PairSample sample_pairs(const FormFactorEvaluator& evaluator, const std::vector<PatchBoundShape>& shapes,
                        const std::vector<int>& eligible_patches, const PairExchangeOptions& options, bool defer,
                        double pairs, int samples) {
  PairSample r;
  r.pairs = pairs;
  if (eligible_patches.size() < 2 || samples <= 0) return r;
  detail::Rng rng(0x5eed);
  std::vector<std::pair<int, int>> drawn(static_cast<std::size_t>(samples));
  for (auto& [p, q] : drawn) {
    do {
      p = eligible_patches[rng.below(eligible_patches.size())];
      q = eligible_patches[rng.below(eligible_patches.size())];
    } while (p == q);
  }
  std::atomic<int> stored{0}, waiting{0};
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, drawn.size(), 16), [&](const tbb::blocked_range<std::size_t>& b) {
        for (std::size_t k = b.begin(); k < b.end(); ++k) {
          const auto [p, q] = drawn[k];
          const ScreenedPair s = screen_pair(evaluator, shapes, std::min(p, q), std::max(p, q), options, defer);
          if (s.cheap_drop || s.exchange.dropped) continue;
          if (deferred_pair(s.exchange, defer)) {
            ++waiting;
            ++stored;
          } else if (s.exchange.exchange > 0.0) {
            ++stored;
          }
        }
      });
  r.sampled = samples;
  auto high = [&](int count) {
    const double share = double(count) / samples;
    return std::min(1.0, share + 3.0 * std::sqrt(std::max(share * (1.0 - share), 1.0 / samples) / samples)) * pairs;
  };
  r.stored = high(stored.load());
  r.deferred = high(waiting.load());
  return r;
}

// A pair whose patches lie in one unit u counts in A_u F_uu both ways (p -> q and q -> p): twice its
// exchange, and twice its error.
double same_unit_multiplier(int u, int v) { return u == v ? 2.0 : 1.0; }

// Rays for each deferred pair so that each row's sampled part has a standard error of at most
// `sigma` (the binomial bound: a fraction's variance is at most 1/(4 n)). Pair k adds c_kw =
// m U_k / A_w to row w (m = 2 when both patches are in w) with standard error c_kw / (2 sqrt(n_k));
// n_k >= c_kw S_w / (4 sigma^2), S_w = sum_k c_kw, gives row w a variance of at most sigma^2.
// (Neyman allocation for the bound; clamped to [kMinSampledRays, max_rays], where the target may be missed: the
// reported row errors say by how much.)
std::vector<int> row_error_rays(const std::vector<DeferredPair>& deferred, const std::vector<int>& unit,
                                const std::vector<double>& area, double sigma, int max_rays) {
  std::vector<double> sum(area.size(), 0.0);
  auto shares = [&](const DeferredPair& d) {
    const int u = unit[static_cast<std::size_t>(d.p)], v = unit[static_cast<std::size_t>(d.q)];
    const double m = same_unit_multiplier(u, v);
    return std::array<std::pair<int, double>, 2>{{{u, m * d.unoccluded / area[static_cast<std::size_t>(u)]},
                                                  {v, m * d.unoccluded / area[static_cast<std::size_t>(v)]}}};
  };
  for (const DeferredPair& d : deferred) {
    const auto s = shares(d);
    sum[static_cast<std::size_t>(s[0].first)] += s[0].second;
    if (s[1].first != s[0].first) sum[static_cast<std::size_t>(s[1].first)] += s[1].second;
  }
  std::vector<int> rays(deferred.size());
  for (std::size_t k = 0; k < deferred.size(); ++k) {
    double need = 0.0;
    for (const auto& [w, c] : shares(deferred[k])) need = std::max(need, c * sum[static_cast<std::size_t>(w)]);
    need = std::ceil(need / (4.0 * sigma * sigma));
    rays[k] = static_cast<int>(std::clamp(need, double(kMinSampledRays), static_cast<double>(max_rays)));
  }
  return rays;
}

// The row cap. A row's true sum is at most 1 (the factors of one face to the others cover at most
// its hemisphere), but a sum of estimated fractions can exceed it. Row u, with exact exchange X_u
// and estimated exchange S_u, gets s_u = (A_u - X_u) / S_u in [0, 1] when X_u + S_u > A_u (else 1),
// and every estimated entry E_uv is multiplied by min(s_u, s_v): E stays symmetric (reciprocity
// exact), entries only shrink (0 <= F <= unobstructed kept), exact entries are untouched (closed
// rows whose pairs are all exact keep their closure), and row u sums to at most X_u + s_u S_u = A_u
// (to rounding). Returns what each row lost, in factor units; counts the rows that were above 1.
std::vector<double> cap_rows(std::vector<std::vector<UpperEntry>>& upper, const std::vector<double>& area,
                             std::uint64_t* capped_rows) {
  const std::size_t n = upper.size();
  std::vector<double> exact(n, 0.0), estimated(n, 0.0);
  for (std::size_t u = 0; u < n; ++u)
    for (const UpperEntry& e : upper[u]) {
      exact[u] += e.exact;
      estimated[u] += e.estimated;
      if (e.v != static_cast<int>(u)) {
        exact[static_cast<std::size_t>(e.v)] += e.exact;
        estimated[static_cast<std::size_t>(e.v)] += e.estimated;
      }
    }
  std::vector<double> scale(n, 1.0), lost(n, 0.0);
  *capped_rows = 0;
  for (std::size_t u = 0; u < n; ++u)
    if (exact[u] + estimated[u] > area[u] && estimated[u] > 0.0) {
      scale[u] = std::clamp((area[u] - exact[u]) / estimated[u], 0.0, 1.0);
      ++*capped_rows;
    }
  if (*capped_rows == 0) return lost;
  for (std::size_t u = 0; u < n; ++u)
    for (UpperEntry& e : upper[u]) {
      const auto v = static_cast<std::size_t>(e.v);
      const double s = std::min(scale[u], scale[v]);
      if (s == 1.0 || e.estimated == 0.0) continue;
      const double cut = e.estimated * (1.0 - s);
      e.estimated *= s;
      lost[u] += cut / area[u];
      if (v != u) lost[v] += cut / area[v];
    }
  return lost;
}

}  // namespace

double ViewFactorMatrix::factor(int u, int v) const {
  const auto begin = column.begin() + row_begin[static_cast<std::size_t>(u)];
  const auto end = column.begin() + row_begin[static_cast<std::size_t>(u) + 1];
  const auto it = std::lower_bound(begin, end, v);
  return it != end && *it == v ? factor(u, it - column.begin()) : 0.0;
}

double ViewFactorMatrix::row_sum(int u) const {
  double s = 0.0;
  for (std::int64_t k = row_begin[static_cast<std::size_t>(u)]; k < row_begin[static_cast<std::size_t>(u) + 1]; ++k)
    s += exchange[static_cast<std::size_t>(k)];
  return s / area[static_cast<std::size_t>(u)];
}

std::size_t ViewFactorMatrix::bytes() const {
  return row_begin.size() * sizeof(std::int64_t) + column.size() * sizeof(int) +
         (exchange.size() + area.size() + sampling_error.size() + skipped_bound.size() + capped.size()) *
             sizeof(double);
}

double max_reciprocity_error(const ViewFactorMatrix& m) {
  double worst = 0.0;
  for (int u = 0; u < m.n; ++u)
    for (std::int64_t k = m.row_begin[static_cast<std::size_t>(u)]; k < m.row_begin[static_cast<std::size_t>(u) + 1];
         ++k) {
      const int v = m.column[static_cast<std::size_t>(k)];
      const double e = std::abs(m.area[static_cast<std::size_t>(u)] * m.factor(u, k) -
                                m.area[static_cast<std::size_t>(v)] * m.factor(v, u));
      worst = std::max(worst, e / m.area[static_cast<std::size_t>(u)]);
    }
  return worst;
}

ViewFactorMatrix compute_view_factors(const Scene& scene, const SurfaceUnits& units, const ViewFactorOptions& options) {
  Stopwatch clock;
  const int n = units.size();
  for (int u = 0; u < n; ++u)
    if (!(units.area[static_cast<std::size_t>(u)] > 0.0))
      throw Error(fmt::format("surface '{}' has no area", units.names[static_cast<std::size_t>(u)]));
  const std::size_t np = scene.patches.size();
  std::vector<int> unit(np);
  std::vector<char> eligible(np);
  std::uint64_t eligible_count = 0;
  for (std::size_t p = 0; p < np; ++p) {
    unit[p] = units.of_patch(scene, static_cast<int>(p));
    eligible[p] = unit[p] >= 0;
    eligible_count += eligible[p] ? 1 : 0;
  }

  VisibilityOptions vo;
  vo.exact_shaft_contacts = options.exact_shaft_contacts;
  const std::unique_ptr<Visibility> visibility = make_visibility(scene, vo);
  Effects effects;
  effects.visibility = visibility->scene_has_occlusion();
  effects.cull_facing_away = true;
  const FormFactorEvaluator evaluator(scene, effects, visibility.get(), 64, FormFactorKernel::kAnalytic);

  ViewFactorMatrix m;
  m.n = n;
  m.area = units.area;
  ViewFactorCounters& c = m.counters;
  c.patch_pairs = eligible_count * (eligible_count - (eligible_count > 0 ? 1 : 0)) / 2;

  // With a threshold, a pair is dropped when a bound of its unobstructed factors is below it both
  // ways: first the cheap bound (pair_bound.h), then the closed form (pair_exchange()).
  const bool pruned = options.threshold > 0.0;
  PairExchangeOptions pair_options = options.pair;
  pair_options.threshold = options.threshold;
  pair_options.sample_below = options.sample_below;
  const std::vector<PatchBoundShape> shapes = pruned ? patch_bound_shapes(scene) : std::vector<PatchBoundShape>{};
  const bool defer = options.row_error > 0.0 && options.pair.partial == PartialVisibility::kSampled;
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  if (options.before_pairs) {
    std::vector<int> eligible_patches;
    for (std::size_t p = 0; p < np; ++p)
      if (eligible[p]) eligible_patches.push_back(static_cast<int>(p));
    PairSample sample;
    arena.execute([&] {
      sample = sample_pairs(evaluator, shapes, eligible_patches, pair_options, defer, double(c.patch_pairs),
                            static_cast<int>(std::min<std::uint64_t>(c.patch_pairs, kWorkSamples)));
    });
    options.before_pairs(sample);
  }
  BoundSums dropped(pruned ? np : 0);
  std::vector<std::uint64_t> row_pairs(np, 0);
  std::uint64_t total = 0;
  {
    std::uint64_t later = eligible_count;
    for (std::size_t p = 0; p < np; ++p) {
      if (eligible[p]) --later;
      row_pairs[p] = eligible[p] ? later : 0;
      total += row_pairs[p];
    }
  }
  ProgressReporter progress("view factors", total, "pairs", options.progress);

  // Upper triangle of E per unit (v >= u), appended in patch order, then summed in that order:
  // the same bits at any thread count.
  std::vector<std::vector<UpperEntry>> upper(static_cast<std::size_t>(n));
  std::vector<double> variance(static_cast<std::size_t>(n), 0.0);
  // A pair sampled to exchange 0 adds its error to the rows but no entry.
  auto add = [&](std::size_t p, int q, double exchange, double error, bool estimated) {
    const int u = unit[p], v = unit[static_cast<std::size_t>(q)];
    auto entry = [estimated](int w, double e) { return estimated ? UpperEntry{w, 0.0, e} : UpperEntry{w, e, 0.0}; };
    if (u == v) {
      const double m = same_unit_multiplier(u, v);
      if (exchange > 0.0) upper[static_cast<std::size_t>(u)].push_back(entry(u, m * exchange));
      variance[static_cast<std::size_t>(u)] += m * m * error * error;
    } else {
      if (exchange > 0.0) upper[static_cast<std::size_t>(std::min(u, v))].push_back(entry(std::max(u, v), exchange));
      variance[static_cast<std::size_t>(u)] += error * error;
      variance[static_cast<std::size_t>(v)] += error * error;
    }
  };
  std::vector<DeferredPair> deferred;
  constexpr std::size_t kChunk = 128;
  std::vector<RowResult> rows;
  for (std::size_t begin = 0; begin < np; begin += kChunk) {
    const std::size_t end = std::min(np, begin + kChunk);
    rows.assign(end - begin, RowResult{});
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t p = r.begin(); p < r.end(); ++p) {
          if (!eligible[p]) continue;
          RowResult& row = rows[p - begin];
          auto one = [&](int q) {
            ViewFactorCounters& k = row.counters;
            const ScreenedPair s = screen_pair(evaluator, shapes, static_cast<int>(p), q, pair_options, defer);
            if (s.cheap_drop) {
              ++k.skipped_pairs;
              dropped.add(p, s.bound.pq);
              dropped.add(static_cast<std::size_t>(q), s.bound.qp);
              return;
            }
            const PairExchange& e = s.exchange;
            k.closed_forms += static_cast<std::uint64_t>(e.closed_forms);
            if (e.dropped) {
              ++k.skipped_pairs;
              ++k.dropped_by_closed_form;
              dropped.add(p, e.dropped_pq);
              dropped.add(static_cast<std::size_t>(q), e.dropped_qp);
              return;
            }
            switch (e.pair_class) {
              case PairClass::kFacingAway:
                ++k.facing_away;
                break;
              case PairClass::kFullyVisible:
                ++k.fully_visible;
                break;
              case PairClass::kFullyHidden:
                ++k.fully_hidden;
                break;
              case PairClass::kPartial:
                ++k.partial;
                break;
            }
            k.rays += static_cast<std::uint64_t>(e.rays);
            k.regions += static_cast<std::uint64_t>(e.regions);
            k.shaft_skipped += e.shaft_skipped ? 1 : 0;
            if (deferred_pair(e, defer))
              row.deferred.emplace_back(q, e.unoccluded);
            else if (e.exchange > 0.0 || e.error > 0.0)
              row.pairs.push_back({q, e.exchange, e.error, e.pair_class == PairClass::kPartial});
          };
          for (std::size_t q = p + 1; q < np; ++q)
            if (eligible[q]) one(static_cast<int>(q));
          progress.advance(row_pairs[p]);
        }
      });
    });
    for (std::size_t p = begin; p < end; ++p) {
      RowResult& row = rows[p - begin];
      for (const PairValue& e : row.pairs) add(p, e.q, e.exchange, e.error, e.estimated);
      for (const auto& [q, unoccluded] : row.deferred) deferred.push_back({static_cast<int>(p), q, unoccluded});
      c.facing_away += row.counters.facing_away;
      c.fully_visible += row.counters.fully_visible;
      c.fully_hidden += row.counters.fully_hidden;
      c.partial += row.counters.partial;
      c.closed_forms += row.counters.closed_forms;
      c.skipped_pairs += row.counters.skipped_pairs;
      c.dropped_by_closed_form += row.counters.dropped_by_closed_form;
      c.shaft_skipped += row.counters.shaft_skipped;
      c.rays += row.counters.rays;
      c.regions += row.counters.regions;
    }
  }
  progress.finish();
  rows.clear();
  rows.shrink_to_fit();
  c.classify_seconds = clock.seconds();

  if (!deferred.empty()) {
    // The first budget comes from the binomial bound; the kernel-weighted estimator can exceed it
    // (uneven weights), so rows whose estimated error is still above the target get their pairs'
    // rays raised by the ratio of variances and sampled afresh, for up to three more rounds.
    std::vector<int> rays = row_error_rays(deferred, unit, m.area, options.row_error, options.pair.max_rays);
    std::vector<PairExchange> sampled(deferred.size());
    std::vector<char> redo(deferred.size(), 1);
    const double target = options.row_error * options.row_error;
    for (int round = 0; round < 4; ++round) {
      std::uint64_t round_rays = 0;
      for (std::size_t k = 0; k < deferred.size(); ++k)
        if (redo[k]) round_rays += static_cast<std::uint64_t>(rays[k]);
      if (round_rays == 0) break;
      ProgressReporter sampling(round == 0 ? "visible fractions" : "visible fractions, rows above the target",
                                round_rays, "rays", options.progress);
      arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, deferred.size(), 256),
                          [&](const tbb::blocked_range<std::size_t>& r) {
                            for (std::size_t k = r.begin(); k < r.end(); ++k) {
                              if (!redo[k]) continue;
                              PairExchange e;
                              e.pair_class = PairClass::kPartial;
                              e.unoccluded = deferred[k].unoccluded;
                              e.rays = sampled[k].rays;
                              sample_partial(evaluator, deferred[k].p, deferred[k].q, rays[k], &e);
                              sampled[k] = e;
                              sampling.advance(static_cast<std::uint64_t>(rays[k]));
                            }
                          });
      });
      sampling.finish();
      // Each row's estimated variance from its sampled pairs (the pairs' own error estimates).
      std::vector<double> row_variance(static_cast<std::size_t>(n), 0.0);
      for (std::size_t k = 0; k < deferred.size(); ++k) {
        const int u = unit[static_cast<std::size_t>(deferred[k].p)], v = unit[static_cast<std::size_t>(deferred[k].q)];
        const double e = sampled[k].error * same_unit_multiplier(u, v);
        row_variance[static_cast<std::size_t>(u)] +=
            e * e / (m.area[static_cast<std::size_t>(u)] * m.area[static_cast<std::size_t>(u)]);
        if (v != u)
          row_variance[static_cast<std::size_t>(v)] +=
              e * e / (m.area[static_cast<std::size_t>(v)] * m.area[static_cast<std::size_t>(v)]);
      }
      for (std::size_t k = 0; k < deferred.size(); ++k) {
        const int u = unit[static_cast<std::size_t>(deferred[k].p)], v = unit[static_cast<std::size_t>(deferred[k].q)];
        const double ratio =
            std::max(row_variance[static_cast<std::size_t>(u)], row_variance[static_cast<std::size_t>(v)]) / target;
        redo[k] = ratio > 1.0 && rays[k] < options.pair.max_rays;
        if (redo[k]) rays[k] = static_cast<int>(std::min(std::ceil(ratio * rays[k]), double(options.pair.max_rays)));
      }
    }
    for (std::size_t k = 0; k < deferred.size(); ++k) {
      c.rays += static_cast<std::uint64_t>(sampled[k].rays);
      if (sampled[k].exchange > 0.0 || sampled[k].error > 0.0)
        add(static_cast<std::size_t>(deferred[k].p), deferred[k].q, sampled[k].exchange, sampled[k].error, true);
    }
    std::vector<DeferredPair>().swap(deferred);
  }

  // Sum duplicates (units of several patches) in append order, then lay out both triangles.
  std::vector<std::int64_t> count(static_cast<std::size_t>(n) + 1, 0);
  for (int u = 0; u < n; ++u) {
    auto& list = upper[static_cast<std::size_t>(u)];
    std::stable_sort(list.begin(), list.end(), [](const UpperEntry& x, const UpperEntry& y) { return x.v < y.v; });
    std::size_t out = 0;
    for (std::size_t i = 0; i < list.size(); ++i) {
      if (out > 0 && list[out - 1].v == list[i].v) {
        list[out - 1].exact += list[i].exact;
        list[out - 1].estimated += list[i].estimated;
      } else {
        list[out++] = list[i];
      }
    }
    list.resize(out);
    list.shrink_to_fit();
    for (const UpperEntry& e : list) {
      ++count[static_cast<std::size_t>(u)];
      if (e.v != u) ++count[static_cast<std::size_t>(e.v)];
    }
  }
  m.capped = cap_rows(upper, m.area, &c.capped_rows);
  m.row_begin.assign(static_cast<std::size_t>(n) + 1, 0);
  for (int u = 0; u < n; ++u)
    m.row_begin[static_cast<std::size_t>(u) + 1] =
        m.row_begin[static_cast<std::size_t>(u)] + count[static_cast<std::size_t>(u)];
  m.column.resize(static_cast<std::size_t>(m.row_begin.back()));
  m.exchange.resize(m.column.size());
  std::vector<std::int64_t> fill(m.row_begin.begin(), m.row_begin.end() - 1);
  for (int u = 0; u < n; ++u) {
    // Row u's lower entries (from rows w < u) were filled before; its upper ones follow in order.
    for (const UpperEntry& entry : upper[static_cast<std::size_t>(u)]) {
      const int v = entry.v;
      const double e = entry.exact + entry.estimated;
      const auto k = static_cast<std::size_t>(fill[static_cast<std::size_t>(u)]++);
      m.column[k] = v;
      m.exchange[k] = e;
      if (v != u) {
        const auto kv = static_cast<std::size_t>(fill[static_cast<std::size_t>(v)]++);
        m.column[kv] = u;
        m.exchange[kv] = e;
      }
    }
    std::vector<UpperEntry>().swap(upper[static_cast<std::size_t>(u)]);
  }

  m.sampling_error.resize(static_cast<std::size_t>(n));
  m.skipped_bound.assign(static_cast<std::size_t>(n), 0.0);
  for (int u = 0; u < n; ++u)
    m.sampling_error[static_cast<std::size_t>(u)] =
        std::sqrt(variance[static_cast<std::size_t>(u)]) / m.area[static_cast<std::size_t>(u)];
  if (pruned)
    for (std::size_t p = 0; p < np; ++p)
      if (eligible[p])
        m.skipped_bound[static_cast<std::size_t>(unit[p])] +=
            scene.patches[p].area * dropped[p] / m.area[static_cast<std::size_t>(unit[p])];
  c.seconds = clock.seconds();
  return m;
}

}  // namespace hrad
