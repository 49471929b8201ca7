// hrad compare REPORT --against REFERENCE [--by material|group] [--out C.json]
//
// Scores a solve report's per-face answer against a reference for the same scene: another solve
// report (`hrad solve --report`), or the Monte Carlo ruler's face CSV (`hrad reference --faces`),
// whose standard errors are accounted for. The measure is the area-weighted relative L2 of each
// input face's reflected radiosity B - E (lib/hrad/analysis/face_error.h: emitters count by what
// they reflect), with the area mean's bias, the face that errs most, and the error by material or
// group: what the README's per-polygon figures are.
//
//   --against R       a report (.json) or a ruler face CSV (any other name); its faces must be the
//                     report's, in order (same count, areas within 1e-6 relative)
//   --by KEY          material (default) or group: how the breakdown groups faces (the ruler's CSV
//                     names groups only; by material, a CSV reference takes REPORT's materials)
//   --out C.json      the same numbers as JSON (written atomically)
//   --faces-out F.csv one row per face (written atomically): face, line, group, material, area,
//                     reflected_r,_g,_b (B - E), reference_r,_g,_b, reference_se_r,_g,_b, error (|d| over
//                     the reference's |B - E|; empty where that is 0) and share (of sum A |d|^2): where a
//                     scene errs, for a plot or a colour map
// Bad options and files are a one-line error naming the option or file (and line), before any output.
#include <cmath>
#include <iostream>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "csv_cells.h"
#include "hrad/analysis/face_error.h"
#include "hrad/core/error.h"
#include "hrad/io/atomic_file.h"
#include "hrad/io/face_files.h"

namespace hrad::cli {
namespace {

bool is_json(const std::string& path) { return path.size() >= 5 && path.compare(path.size() - 5, 5, ".json") == 0; }

std::string percent(double x) { return std::isfinite(x) ? fmt::format("{:.3f}%", 100.0 * x) : "inf"; }

}  // namespace

void add_compare_command(CLI::App& app) {
  auto* cmd =
      app.add_subcommand("compare", "Per-face error of a solve report against another report or the ruler's face CSV");
  struct Args {
    std::string report, against, by = "material", out, faces_out;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("REPORT", args->report, "Solve report (JSON, hrad solve --report)")->required();
  cmd->add_option("--against", args->against, "Reference: a solve report (.json) or hrad reference --faces CSV")
      ->required();
  cmd->add_option("--by", args->by, "Group the breakdown by material (default) or group");
  cmd->add_option("--out", args->out, "Write the numbers as JSON here");
  cmd->add_option("--faces-out", args->faces_out, "Write each face's values and error as CSV here");
  cmd->callback([args] {
    if (args->by != "material" && args->by != "group")
      throw Error(fmt::format("--by must be material or group, got '{}'", args->by));
    OutputFiles outputs;
    if (!args->out.empty()) outputs.declare("--out", args->out);
    if (!args->faces_out.empty()) outputs.declare("--faces-out", args->faces_out);
    outputs.check_inputs({{"the report", args->report}, {"the reference", args->against}});
    const std::vector<FaceRecord> faces = read_report_faces(args->report);
    const bool json_reference = is_json(args->against);
    const std::vector<FaceRecord> reference =
        json_reference ? read_report_faces(args->against) : read_ruler_faces(args->against);
    if (reference.size() != faces.size())
      throw Error(fmt::format("{}: {} faces, {} has {}: not the same scene", args->against, reference.size(),
                              args->report, faces.size()));
    std::vector<FaceValues> values;
    for (std::size_t f = 0; f < faces.size(); ++f) {
      const FaceRecord &a = faces[f], &r = reference[f];
      if (!(std::abs(a.area - r.area) <= 1e-6 * std::max(a.area, r.area)))
        throw Error(fmt::format("{}{}: face {} has area {:.9g}, in {} {:.9g}: not the same scene", args->against,
                                json_reference ? "" : fmt::format(":{}", r.line), f, r.area, args->report, a.area));
      const Rgb e = *a.emission;  // the report's; the reference's own when it is a report
      FaceValues v;
      v.area = a.area;
      v.reflected = a.radiosity - e;
      v.reference = r.radiosity - (r.emission ? *r.emission : e);
      v.reference_se = r.radiosity_se;
      v.key = args->by == "group" ? a.group : a.material;
      values.push_back(std::move(v));
    }
    const FaceErrors s = face_errors(values);
    const FaceRecord& worst = faces[static_cast<std::size_t>(s.largest_face)];

    std::cout << fmt::format("{} against {}: {} faces, reflected radiosity (B - E), area-weighted\n", args->report,
                             args->against, s.faces);
    std::cout << fmt::format("  relative L2 {}", percent(s.relative_l2));
    if (s.reference_noise > 0.0)
      std::cout << fmt::format(" (the reference's noise {}; without it {})", percent(s.reference_noise),
                               percent(s.noise_corrected));
    std::cout << fmt::format(", bias {:+.3f}%\n", 100.0 * s.bias);
    std::cout << fmt::format(
        "  largest: face {} (line {}, group {}, material {}): {:.1f}% of the squared error, "
        "its own error {}\n",
        s.largest_face, worst.line, worst.group, worst.material, 100.0 * s.largest_face_share,
        percent(s.largest_face_error));
    std::cout << fmt::format("  {:<20} {:>7} {:>12} {:>9} {:>7} {:>9}\n", "by " + args->by, "faces", "area", "L2 part",
                             "share", "bias");
    for (const GroupError& g : s.groups)
      std::cout << fmt::format("  {:<20} {:>7} {:>12.6g} {:>9} {:>6.1f}% {:>+8.3f}%\n", g.key, g.faces, g.area,
                               percent(g.l2_part), 100.0 * g.error_share, 100.0 * g.bias);
    if (!args->faces_out.empty()) {
      write_file_atomically(args->faces_out, [&](std::ostream& o) {
        o << "face,line,group,material,area,reflected_r,reflected_g,reflected_b,reference_r,reference_g,reference_b,"
             "reference_se_r,reference_se_g,reference_se_b,error,share\n";
        for (std::size_t f = 0; f < values.size(); ++f) {
          const FaceValues& v = values[f];
          o << fmt::format("{},{},{},{},{},{},{},{},{},{}\n", f, faces[f].line, csv_cell(faces[f].group),
                           csv_cell(faces[f].material), v.area, rgb_cells(v.reflected), rgb_cells(v.reference),
                           rgb_cells(v.reference_se),
                           std::isfinite(s.face_error[f]) ? fmt::format("{}", s.face_error[f]) : "", s.face_share[f]);
        }
      });
    }
    if (!args->out.empty()) {
      nlohmann::json j = {{"report", args->report},
                          {"reference", args->against},
                          {"faces", s.faces},
                          {"relative_l2", s.relative_l2},
                          {"reference_noise", s.reference_noise},
                          {"noise_corrected", s.noise_corrected},
                          {"bias", s.bias},
                          {"largest_face",
                           {{"face", s.largest_face},
                            {"line", worst.line},
                            {"group", worst.group},
                            {"material", worst.material},
                            {"share", s.largest_face_share},
                            {"error", std::isfinite(s.largest_face_error) ? nlohmann::json(s.largest_face_error)
                                                                          : nlohmann::json(nullptr)}}},
                          {"by", args->by}};
      nlohmann::json groups = nlohmann::json::array();
      for (const GroupError& g : s.groups)
        groups.push_back({{"key", g.key},
                          {"faces", g.faces},
                          {"area", g.area},
                          {"l2_part", g.l2_part},
                          {"share", g.error_share},
                          {"bias", g.bias}});
      j["groups"] = groups;
      write_file_atomically(args->out, [&](std::ostream& o) { o << j.dump(2) << "\n"; });
    }
    outputs.commit();
  });
}

}  // namespace hrad::cli
