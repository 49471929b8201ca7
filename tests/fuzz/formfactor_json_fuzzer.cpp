// Fuzzes the `hrad formfactor --json` path: any bytes give an output document or an hrad::Error,
// never a crash, a hang, a sanitizer report, or a factor that is NaN or outside [0, 1]. The pairs
// are read, evaluated and written as tools/formfactor.cpp does.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hrad/core/error.h"
#include "hrad/formfactor/point_to_polygon.h"
#include "hrad/formfactor/polygon_to_polygon.h"
#include "hrad/io/formfactor_json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<hrad::FormFactorQuery> queries;
  try {
    queries = hrad::read_formfactor_json(text, "fuzz.json");
  } catch (const hrad::Error&) {
    return 0;
  }
  std::vector<hrad::FormFactorAnswer> answers;
  for (const hrad::FormFactorQuery& q : queries) {
    if (q.from_is_point()) {
      answers.push_back({hrad::point_to_polygon(q.from_point, q.from_normal, q.to), std::nullopt});
    } else {
      const hrad::PairFormFactor f = hrad::polygon_to_polygon(q.from, q.to);
      answers.push_back({f.from_to, f.to_from});
    }
  }
  const nlohmann::json j = nlohmann::json::parse(hrad::write_formfactor_json(queries, answers));  // valid JSON
  for (const auto& pair : j.at("pairs"))
    for (const char* key : {"F_from_to", "F_to_from"}) {
      if (pair.at(key).is_null()) continue;
      const double f = pair.at(key).get<double>();
      if (!(f >= 0.0 && f <= 1.0 + 1e-9)) std::abort();
    }
  return 0;
}
