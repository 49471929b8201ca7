// Fuzzes the polygon-pair kernel on random, degenerate and touching polygons: each polygon is a
// triangle or a parallelogram on a small integer grid (so shared vertices, shared and collinear
// edges, coplanar and touching pairs are common), scaled by a power of two. Checks: no NaN or
// Inf, 0 <= F <= 1, and reciprocity A_from F_from_to = A_to F_to_from.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "hrad/formfactor/polygon_to_polygon.h"
#include "hrad/geometry/polygon.h"

namespace {

struct Bytes {
  const std::uint8_t* p;
  std::size_t n;
  int next() { return n ? (--n, static_cast<int>(*p++)) : 0; }
  int small() { return static_cast<int>(static_cast<std::int8_t>(next())) % 5; }  // -4..4
};

std::vector<hrad::Vec3> polygon(Bytes& b, double scale) {
  const hrad::Vec3 o(b.small(), b.small(), b.small());
  const hrad::Vec3 u(b.small(), b.small(), b.small()), v(b.small(), b.small(), b.small());
  if (b.next() % 2) return {scale * o, scale * (o + u), scale * (o + v)};
  return {scale * o, scale * (o + u), scale * (o + u + v), scale * (o + v)};
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Bytes b{data, size};
  const double scale = std::ldexp(1.0, (b.next() % 61) - 30);  // 2^-30 .. 2^30
  const std::vector<hrad::Vec3> from = polygon(b, scale), to = polygon(b, scale);
  const double a_from = hrad::polygon_area(from), a_to = hrad::polygon_area(to);
  // Only non-degenerate polygons are the kernel's input (the readers reject the rest).
  if (!(a_from > 1e-9 * scale * scale) || !(a_to > 1e-9 * scale * scale)) return 0;
  const hrad::PairFormFactor f = hrad::polygon_to_polygon(from, to);
  if (!std::isfinite(f.from_to) || !std::isfinite(f.to_from)) std::abort();
  if (f.from_to < 0.0 || f.to_from < 0.0 || f.from_to > 1.0 + 1e-9 || f.to_from > 1.0 + 1e-9) std::abort();
  const double flux = a_from * f.from_to, back = a_to * f.to_from;
  if (std::abs(flux - back) > 1e-9 * std::max({flux, back, 1e-300 * scale * scale})) std::abort();
  return 0;
}
