#include "hrad/viewfactors/view_factor_work.h"

#include <algorithm>

#include <fmt/format.h>

#include "hrad/core/error.h"
#include "hrad/core/memory.h"

namespace hrad {
namespace {

bool dense_layout(MatrixFormat format) { return format == MatrixFormat::kDense || format == MatrixFormat::kView3d; }

bool exceeds(double bytes, double available) { return available > 0.0 && !(bytes <= 0.8 * available); }

}  // namespace

ViewFactorWork estimate_view_factor_work(const PairSample& sample, double surfaces, double patches,
                                         MatrixFormat format) {
  ViewFactorWork w;
  w.surfaces = surfaces;
  w.stored_pairs = sample.stored;
  w.memory_bytes =
      kBytesPerPatch * patches + sample.stored * kBytesPerStoredPair + sample.deferred * kBytesPerDeferredPair;
  // Entries between units: at most both directions of every stored pair, at most n^2.
  const double entries = std::min(surfaces * surfaces, 2.0 * sample.stored + surfaces);
  w.output_bytes =
      dense_layout(format) ? 2.0 * surfaces * surfaces + kDigitsPerFactor * entries : kBytesPerSparseLine * entries;
  return w;
}

void check_view_factor_work(const ViewFactorWork& w, const ViewFactorOptions& options, MatrixFormat format,
                            const std::string& out, double available_memory, double free_disk) {
  if (exceeds(w.memory_bytes, available_memory))
    throw Error(fmt::format(
        "viewfactors: {:.0f} surfaces would store about {:.3g} pairs, about {} of memory, and this process may use "
        "{}: raise --threshold (now {:g}){}",
        w.surfaces, w.stored_pairs, format_bytes(w.memory_bytes), format_bytes(available_memory), options.threshold,
        options.row_error > 0.0 ? " or leave out --row-error" : ""));
  if (exceeds(w.output_bytes, free_disk))
    throw Error(fmt::format("--out {}: {} of {:.0f} surfaces is about {} of text and the disk has {} free: {}", out,
                            dense_layout(format) ? "a dense matrix" : "the nonzeros", w.surfaces,
                            format_bytes(w.output_bytes), format_bytes(free_disk),
                            dense_layout(format) ? "write a sparse format (.mtx or --format triplets)"
                                                 : fmt::format("raise --threshold (now {:g})", options.threshold)));
}

}  // namespace hrad
