// Fuzzes the `hrad formfactor --json` input: any bytes give an output document or an hrad::Error,
// never a crash, a hang, a sanitizer report, or a factor that is NaN or outside [0, 1].
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include <nlohmann/json.hpp>

#include "hrad/core/error.h"
#include "hrad/io/formfactor_json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::string out;
  try {
    out = hrad::evaluate_formfactor_json(text, "fuzz.json");
  } catch (const hrad::Error&) {
    return 0;
  }
  const nlohmann::json j = nlohmann::json::parse(out);  // the output is always valid JSON
  for (const auto& pair : j.at("pairs"))
    for (const char* key : {"F_from_to", "F_to_from"}) {
      if (pair.at(key).is_null()) continue;
      const double f = pair.at(key).get<double>();
      if (!(f >= 0.0 && f <= 1.0 + 1e-9)) std::abort();
    }
  return 0;
}
