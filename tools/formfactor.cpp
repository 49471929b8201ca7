// hrad formfactor --json FILE
//
// Evaluates form factors for the pairs listed in FILE and prints them as JSON on stdout.
//
// FILE:
//   {"pairs": [
//     {"name": "a", "from": [[x,y,z], ...], "to": [[x,y,z], ...]},
//     {"name": "p", "from_point": [x,y,z], "from_normal": [nx,ny,nz], "to": [[x,y,z], ...]}]}
//
// | key           | meaning                                                                    |
// | ------------- | -------------------------------------------------------------------------- |
// | name          | optional label echoed in the output (default: the pair's index)            |
// | from, to      | planar polygons, >= 3 vertices, counter-clockwise seen from their front    |
// | from_point    | a differential area at this point instead of `from` ...                    |
// | from_normal   | ... facing this way (any non-zero length)                                  |
//
// Output: {"pairs": [{"name": "a", "F_from_to": ..., "F_to_from": ...}, ...]} with 17 significant
// digits; F_to_from is null for a point. Polygon pairs use hrad::polygon_to_polygon (closed form,
// both directions from one evaluation), points hrad::point_to_polygon.
// Errors (unreadable file, malformed JSON with its byte offset, a polygon with fewer than 3 vertices,
// non-finite coordinates, zero area, or vertices off its plane by more than 1e-7 of its diameter)
// are one line naming the file and the pair, with a non-zero exit.
#include <iostream>
#include <vector>

#include "commands.h"
#include "hrad/formfactor/point_to_polygon.h"
#include "hrad/formfactor/polygon_to_polygon.h"
#include "hrad/io/formfactor_json.h"
#include "hrad/io/input_file.h"

namespace hrad::cli {

void add_formfactor_command(CLI::App& app) {
  auto* cmd =
      app.add_subcommand("formfactor", "Form factors of polygon pairs and point-polygon pairs (JSON in, JSON out)");
  auto path = std::make_shared<std::string>();
  cmd->add_option("--json", *path,
                  "Input file: {\"pairs\": [{\"name\", \"from\" | \"from_point\" + \"from_normal\", \"to\"}]}")
      ->required();
  cmd->callback([path] {
    const std::vector<FormFactorQuery> queries = read_formfactor_json(read_input_file(*path), *path);
    std::vector<FormFactorAnswer> answers;
    answers.reserve(queries.size());
    for (const FormFactorQuery& q : queries) {
      if (q.from_is_point()) {
        answers.push_back({point_to_polygon(q.from_point, q.from_normal, q.to), std::nullopt});
      } else {
        const PairFormFactor f = polygon_to_polygon(q.from, q.to);
        answers.push_back({f.from_to, f.to_from});
      }
    }
    std::cout << write_formfactor_json(queries, answers);
  });
}

}  // namespace hrad::cli
