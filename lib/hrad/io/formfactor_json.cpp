// The `hrad formfactor --json` document (see formfactor_json.h): parsing and writing only, so that
// the command, the fuzzer and the tests read and write exactly the same thing.
#include "hrad/io/formfactor_json.h"

#include <cmath>
#include <cstdint>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "hrad/core/error.h"
#include "hrad/geometry/polygon.h"

namespace hrad {
namespace {

using nlohmann::json;

struct PairSite {
  const std::string& file;
  std::string label;  // "pair 3 (\"a\")"
  [[noreturn]] void fail(const std::string& what) const { throw Error(fmt::format("{}: {}: {}", file, label, what)); }
};

Vec3 read_vec3(const json& j, const PairSite& site, const std::string& key) {
  if (!j.is_array() || j.size() != 3) site.fail(fmt::format("'{}' must be an array of 3 numbers", key));
  Vec3 v;
  for (int i = 0; i < 3; ++i) {
    if (!j[i].is_number()) site.fail(fmt::format("'{}' must be an array of 3 numbers", key));
    v[i] = j[i].get<double>();
    if (!std::isfinite(v[i])) site.fail(fmt::format("'{}' has a non-finite coordinate", key));
  }
  return v;
}

std::vector<Vec3> read_polygon(const json& pair, const PairSite& site, const std::string& key) {
  if (!pair.contains(key)) site.fail(fmt::format("missing '{}'", key));
  const json& j = pair.at(key);
  if (!j.is_array()) site.fail(fmt::format("'{}' must be an array of [x, y, z] vertices", key));
  std::vector<Vec3> p;
  for (std::size_t i = 0; i < j.size(); ++i) p.push_back(read_vec3(j[i], site, fmt::format("{}[{}]", key, i)));
  if (p.size() < 3) site.fail(fmt::format("polygon '{}' has {} vertices (at least 3 needed)", key, p.size()));
  const Vec3 n = newell_normal(p);
  const double diameter = polygon_diameter(p);
  if (!(0.5 * n.norm() > 1e-14 * diameter * diameter)) site.fail(fmt::format("polygon '{}' has zero area", key));
  const double off_plane = planarity_deviation(p, n.normalized());
  if (off_plane > 1e-7 * diameter)
    site.fail(fmt::format("polygon '{}' is not planar (a vertex is {:.3g} off its plane, diameter {:.3g})", key,
                          off_plane, diameter));
  return p;
}

std::string number(double x) { return fmt::format("{:.17g}", x); }

}  // namespace

std::vector<FormFactorQuery> read_formfactor_json(const std::string& text, const std::string& path) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    // e.what() repeats the byte offset; keep the parser's own wording after its prefix.
    std::string what = e.what();
    const auto colon = what.find("parse error");
    throw Error(fmt::format("{}: invalid JSON at byte {}: {}", path, e.byte,
                            colon == std::string::npos ? what : what.substr(colon)));
  } catch (const json::exception& e) {  // e.g. a number out of the double range
    throw Error(fmt::format("{}: invalid JSON: {}", path, e.what()));
  }
  if (!doc.is_object() || !doc.contains("pairs") || !doc.at("pairs").is_array())
    throw Error(fmt::format("{}: expected an object with an array \"pairs\"", path));
  const json& pairs = doc.at("pairs");
  std::vector<FormFactorQuery> queries;
  queries.reserve(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const json& pair = pairs[i];
    PairSite site{path, fmt::format("pair {}", i)};
    if (!pair.is_object()) site.fail("must be an object");
    FormFactorQuery q;
    if (pair.contains("name")) {
      const json& name = pair.at("name");
      if (!name.is_string()) site.fail("'name' must be a string");
      q.name = name.get<std::string>();
      site.label = fmt::format("pair {} ({})", i, name.dump());
    }
    for (const auto& item : pair.items())
      if (item.key() != "name" && item.key() != "from" && item.key() != "to" && item.key() != "from_point" &&
          item.key() != "from_normal")
        site.fail(fmt::format("unknown key '{}'", item.key()));
    q.to = read_polygon(pair, site, "to");
    if (pair.contains("from_point") || pair.contains("from_normal")) {
      if (pair.contains("from")) site.fail("give either 'from' or 'from_point' and 'from_normal', not both");
      if (!pair.contains("from_point") || !pair.contains("from_normal"))
        site.fail("'from_point' and 'from_normal' go together");
      q.from_point = read_vec3(pair.at("from_point"), site, "from_point");
      const Vec3 n = read_vec3(pair.at("from_normal"), site, "from_normal");
      if (!(n.norm() > 0.0)) site.fail("'from_normal' has zero length");
      q.from_normal = n.normalized();
    } else {
      q.from = read_polygon(pair, site, "from");
    }
    queries.push_back(std::move(q));
  }
  return queries;
}

std::string write_formfactor_json(std::span<const FormFactorQuery> queries, std::span<const FormFactorAnswer> answers) {
  if (queries.size() != answers.size())
    throw Error(fmt::format("write_formfactor_json: {} queries but {} answers", queries.size(), answers.size()));
  std::string out = "{\"pairs\": [";
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const json name = queries[i].name ? json(*queries[i].name) : json(static_cast<std::int64_t>(i));
    const FormFactorAnswer& a = answers[i];
    out += fmt::format("{}{{\"name\": {}, \"F_from_to\": {}, \"F_to_from\": {}}}", i ? ", " : "", name.dump(),
                       number(a.from_to), a.to_from ? number(*a.to_from) : "null");
  }
  out += "]}\n";
  return out;
}

}  // namespace hrad
