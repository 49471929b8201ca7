#include "hrad/render/pixel_samples.h"

#include <cmath>
#include <numeric>
#include <vector>

#include "hrad/core/rng.h"

namespace hrad {

Vec2 pixel_sample(int x, int y, int pass, int passes, std::uint64_t seed) {
  // One stream per pixel for the permutation, one per sample for its jitter.
  const std::uint64_t pixel =
      (static_cast<std::uint64_t>(static_cast<std::uint32_t>(y)) << 32) | static_cast<std::uint32_t>(x);
  detail::Rng pixel_rng(seed ^ (pixel * 0x9e3779b97f4a7c15ULL));
  const std::uint64_t pixel_stream = pixel_rng.next();
  detail::Rng rng(pixel_stream ^ (static_cast<std::uint64_t>(pass) * 0xd1b54a32d192ed03ULL));
  rng.next();
  const double u = rng.uniform(), v = rng.uniform();
  const int m = static_cast<int>(std::lround(std::sqrt(static_cast<double>(passes))));
  if (m * m == passes) return {x + (pass % m + u) / m, y + (pass / m + v) / m};
  std::vector<int> row(static_cast<std::size_t>(passes));
  std::iota(row.begin(), row.end(), 0);
  detail::Rng perm(pixel_stream);
  for (int i = passes - 1; i > 0; --i) std::swap(row[static_cast<std::size_t>(i)], row[perm.below(i + 1)]);
  return {x + (pass + u) / passes, y + (row[static_cast<std::size_t>(pass)] + v) / passes};
}

}  // namespace hrad
