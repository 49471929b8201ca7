#include "hrad/analysis/face_error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "hrad/core/error.h"

namespace hrad {

FaceErrors face_errors(const std::vector<FaceValues>& faces) {
  if (faces.empty()) throw Error("no faces to compare");
  struct Sums {
    std::size_t faces = 0;
    double area = 0.0, error2 = 0.0, offset = 0.0, total = 0.0;
  };
  std::map<std::string, Sums> by_key;
  double error2 = 0.0, reference2 = 0.0, noise2 = 0.0, offset = 0.0, total = 0.0, largest = -1.0;
  FaceErrors result;
  result.faces = faces.size();
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const FaceValues& v = faces[f];
    const Rgb d = v.reflected - v.reference;
    const double e2 = v.area * d.square().sum();
    error2 += e2;
    reference2 += v.area * v.reference.square().sum();
    noise2 += v.area * v.reference_se.square().sum();
    offset += v.area * d.sum();
    total += v.area * v.reference.sum();
    Sums& s = by_key[v.key];
    ++s.faces;
    s.area += v.area;
    s.error2 += e2;
    s.offset += v.area * d.sum();
    s.total += v.area * v.reference.sum();
    const double r = std::sqrt(v.reference.square().sum());
    result.face_error.push_back(r > 0.0 ? std::sqrt(d.square().sum()) / r : std::numeric_limits<double>::infinity());
    result.face_share.push_back(e2);
    if (e2 > largest) {
      largest = e2;
      result.largest_face = static_cast<int>(f);
    }
  }
  for (double& share : result.face_share) share = error2 > 0.0 ? share / error2 : 0.0;
  result.largest_face_error = result.face_error[static_cast<std::size_t>(result.largest_face)];
  if (!(reference2 > 0.0)) throw Error("the reference reflects no light on any face: no relative error");
  result.relative_l2 = std::sqrt(error2 / reference2);
  result.reference_noise = std::sqrt(noise2 / reference2);
  result.noise_corrected = std::sqrt(std::max(0.0, error2 - noise2) / reference2);
  result.bias = total != 0.0 ? offset / total : 0.0;
  result.largest_face_share = error2 > 0.0 ? largest / error2 : 0.0;
  for (const auto& [key, s] : by_key)
    result.groups.push_back({key, s.faces, s.area, std::sqrt(s.error2 / reference2),
                             error2 > 0.0 ? s.error2 / error2 : 0.0, s.total != 0.0 ? s.offset / s.total : 0.0});
  std::stable_sort(result.groups.begin(), result.groups.end(),
                   [](const GroupError& a, const GroupError& b) { return a.error_share > b.error_share; });
  return result;
}

}  // namespace hrad
