#include "hrad/experiments/reference_samples.h"

#include <fstream>
#include <sstream>
#include <vector>

#include <fmt/format.h>

#include "hrad/analysis/error_metrics.h"
#include "hrad/core/error.h"

namespace hrad {
namespace {

using nlohmann::json;

json read_json(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(fmt::format("{}: cannot open (expected a sweep's output folder)", path));
  std::ostringstream text;
  text << in.rdbuf();
  try {
    return json::parse(text.str());
  } catch (const json::parse_error& e) {
    throw Error(fmt::format("{}: invalid JSON at byte {}", path, e.byte));
  }
}

}  // namespace

void write_reference_samples(std::ostream& out, const Scene& scene, const Reference& reference, int samples_per_patch) {
  const std::vector<SurfaceSample> samples = patch_samples(scene, samples_per_patch);
  if (reference.gathered.size() != samples.size())
    throw Error(fmt::format("reference: {} gathered values for {} samples", reference.gathered.size(), samples.size()));
  out << "{\"samples_per_patch\": " << samples_per_patch
      << ", \"layout\": \"jittered\", \"columns\": [\"patch\", \"x\", \"y\", \"z\", \"area\", \"r\", \"g\", \"b\"],\n"
      << "\"samples\": [\n";
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const SurfaceSample& s = samples[i];
    const Rgb& b = reference.gathered[i];
    // Shortest round-trip digits: the positions read back to the bit.
    out << fmt::format("[{}, {}, {}, {}, {}, {}, {}, {}]{}\n", s.patch, s.position.x(), s.position.y(), s.position.z(),
                       s.area, b[0], b[1], b[2], i + 1 < samples.size() ? "," : "");
  }
  out << "]}\n";
}

Reference read_reference_samples(const std::string& dir, const Scene& scene, int samples_per_patch) {
  const std::string description_path = dir + "/reference.json", samples_path = dir + "/reference_samples.json";
  Reference ref;
  ref.description = read_json(description_path);
  const json doc = read_json(samples_path);
  const auto fail = [&](const std::string& what) { throw Error(fmt::format("{}: {}", samples_path, what)); };
  if (!doc.is_object() || !doc.contains("samples") || !doc["samples"].is_array())
    fail("expected an object with an array \"samples\"");
  if (doc.value("samples_per_patch", -1) != samples_per_patch)
    fail(fmt::format("made with {} samples per patch, this sweep uses {} (--samples)",
                     doc.value("samples_per_patch", -1), samples_per_patch));
  if (doc.value("layout", std::string()) != "jittered") fail("layout must be \"jittered\"");
  const std::vector<SurfaceSample> samples = patch_samples(scene, samples_per_patch);
  const json& rows = doc["samples"];
  if (rows.size() != samples.size())
    fail(fmt::format("{} samples, this scene has {}: another scene?", rows.size(), samples.size()));
  const auto [lo, hi] = scene.bounds();
  const double tolerance = 1e-9 * (hi - lo).norm();
  ref.gathered.resize(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const json& r = rows[i];
    if (!r.is_array() || r.size() != 8 || !r[0].is_number_integer())
      fail(fmt::format("sample {}: expected [patch, x, y, z, area, r, g, b]", i));
    for (std::size_t k = 1; k < 8; ++k)
      if (!r[k].is_number()) fail(fmt::format("sample {}: column {} is not a number", i, k));
    const Vec3 x(r[1].get<double>(), r[2].get<double>(), r[3].get<double>());
    if (r[0].get<int>() != samples[i].patch || !((x - samples[i].position).norm() <= tolerance))
      fail(fmt::format("sample {} is at patch {} ({}, {}, {}), this scene's at patch {} ({}, {}, {}): another scene?",
                       i, r[0].get<int>(), x.x(), x.y(), x.z(), samples[i].patch, samples[i].position.x(),
                       samples[i].position.y(), samples[i].position.z()));
    ref.gathered[i] = Rgb(r[5].get<double>(), r[6].get<double>(), r[7].get<double>());
  }
  ref.description["reused_from"] = dir;
  return ref;
}

}  // namespace hrad
