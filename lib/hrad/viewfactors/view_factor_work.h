// What a view-factor matrix will cost, estimated before any pair of it is computed, so that a
// request the machine cannot hold (a dense CSV of tens of thousands of faces on a small disk, a
// matrix without --threshold beyond the memory) is refused in seconds with the estimate and the
// option to change, instead of failing after hours.
//
//   stored pairs   from a PairSample (view_factor_matrix.h): kWorkSamples pairs drawn at random and
//                  screened as the computation screens them, the share that is stored (and that
//                  waits for rays with a row budget) plus 3 standard errors, times all pairs
//   memory         kBytesPerPatch per patch (scene, acceleration structure, per-row sums) plus,
//                  per stored pair, its two compressed-row entries and its entry while the matrix
//                  is assembled, and per waiting pair its pending sample
//   output         dense and View3D layouts: all n^2 factors, at least "0," each and
//                  kDigitsPerFactor more per stored one; triplets and Matrix Market: one line per
//                  stored factor (two per pair)
#pragma once

#include <string>

#include "hrad/viewfactors/matrix_formats.h"
#include "hrad/viewfactors/view_factor_matrix.h"

namespace hrad {

/// Scene, acceleration structure and per-row arrays, per patch: the 21,963-facet city peaked at
/// 343 MB with 5.7 M stored pairs (274 MB of them), about 3 kB per patch for the rest; rounded up.
inline constexpr double kBytesPerPatch = 4096.0;
/// Two compressed-row entries (column and value, both rows) and the assembly's entry.
inline constexpr double kBytesPerStoredPair = 2 * (4 + 8) + 24;
/// With a row budget, a partly visible pair waits for its rays with its result (sample_partial()).
inline constexpr double kBytesPerDeferredPair = 16 + sizeof(PairExchange) + 5;
/// A stored factor in text: 17 significant digits, a point, an exponent.
inline constexpr double kDigitsPerFactor = 23.0;
/// A sparse line "i,j,F\n" or "i j F\n": two indices of up to 6 digits and a factor.
inline constexpr double kBytesPerSparseLine = 40.0;

struct ViewFactorWork {
  double surfaces = 0.0;      ///< rows (units)
  double stored_pairs = 0.0;  ///< pairs of patches the matrix is estimated to store
  double memory_bytes = 0.0;  ///< peak memory
  double output_bytes = 0.0;  ///< size of --out
};

/// The estimate for `surfaces` rows over `patches` patches.
ViewFactorWork estimate_view_factor_work(const PairSample& sample, double surfaces, double patches,
                                         MatrixFormat format);

/// hrad::Error when the estimate needs more than 80% of `available_memory` or of `free_disk` (0:
/// unknown, not checked), naming the option to change and the estimate:
/// "--out F.csv: a dense matrix of 21963 surfaces is about 2.6 GB of text and the disk has 1.2 GB
/// free: write a sparse format (.mtx or --format triplets)".
void check_view_factor_work(const ViewFactorWork& work, const ViewFactorOptions& options, MatrixFormat format,
                            const std::string& out, double available_memory, double free_disk);

}  // namespace hrad
