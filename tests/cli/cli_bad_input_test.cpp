// Bad input to every subcommand: a clear one-line error on stderr naming the file, line,
// pair or option, a non-zero exit, no crash, and no output file left behind. Option errors come
// before any work: stderr holds the error line only (no progress).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "run_hrad.h"
#include "support/source_tree.h"

namespace hrad::test {
namespace {

struct BadInput {
  std::string name;
  std::map<std::string, std::string> files;  ///< written into the scratch folder first
  std::string args;                          ///< "{d}" is replaced by the scratch folder
  std::string expected;                      ///< must appear in the error line
};

std::ostream& operator<<(std::ostream& o, const BadInput& c) { return o << c.name; }

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

const std::string kScene = "notebooks_data/scenes/two_far_surfaces.obj";
const std::string kCornell = "notebooks_data/scenes/cornell_box.obj";
const std::string kSquares = R"({"pairs": [{"name": "a", "from": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]],
                                            "to": [[0,0,1],[0,1,1],[1,1,1],[1,0,1]]}]})";

// One face of a solve report, and the header of the ruler's face CSV (hrad compare's inputs).
const char* const kOneFaceReport =
    R"({"patches": [{"face": 0, "line": 3, "group": "floor", "material": "grey", "area": 1.0,
                     "emission": [0, 0, 0], "radiosity": [0.5, 0.5, 0.5]}]})";
const char* const kRulerHeader =
    "face,group,area,radiosity_r,radiosity_g,radiosity_b,radiosity_r_se,radiosity_g_se,radiosity_b_se\n";

const BadInput kCases[] = {
    {"no_subcommand", {}, "", "subcommand"},
    {"unknown_subcommand", {}, "frobnicate", "frobnicate"},
    {"unknown_option", {}, "solve " + kScene + " --frobnicate 3", "--frobnicate"},
    {"info_missing_file", {}, "info {d}/missing.obj", "missing.obj"},
    {"info_bad_vertex", {{"bad.obj", "v 0 0 0\nv 1 0 0\nv 1 oops 0\nf 1 2 3\n"}}, "info {d}/bad.obj", "bad.obj:3"},
    {"info_bad_face_index", {{"bad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 7\n"}}, "info {d}/bad.obj", "bad.obj:4"},
    {"solve_unknown_method", {}, "solve " + kScene + " --method magic --out {d}/s.ply --report {d}/r.json", "--method"},
    {"solve_nan_feps", {}, "solve " + kScene + " --feps nan --out {d}/s.ply", "--feps"},
    {"solve_text_feps", {}, "solve " + kScene + " --feps abc --out {d}/s.ply", "--feps"},
    {"solve_negative_aeps", {}, "solve " + kScene + " --aeps -1 --out {d}/s.ply", "--aeps"},
    {"solve_negative_bfeps", {}, "solve " + kScene + " --bfeps -0.1 --out {d}/s.ply", "--bfeps"},
    {"solve_zero_tolerance", {}, "solve " + kScene + " --tolerance 0 --out {d}/s.ply", "--tolerance"},
    {"solve_power_noise_below_least", {}, "solve " + kScene + " --power-noise 1e-6 --out {d}/s.ply", "--power-noise"},
    {"solve_closure_unknown", {}, "solve " + kScene + " --closure always --out {d}/s.ply", "--closure"},
    {"solve_negative_max_area", {}, "solve " + kScene + " --method full --max-area -2 --out {d}/s.ply", "--max-area"},
    // A full matrix larger than the machine's memory: refused before meshing, not std::bad_alloc.
    {"solve_full_matrix_too_large",
     {},
     "solve " + kScene + " --method full --max-area 1e-9 --out {d}/s.ply --report {d}/r.json",
     "--max-area"},
    {"solve_inf_patch_area",
     {},
     "solve " + kScene + " --method substructure --patch-area inf --out {d}/s.ply",
     "--patch-area"},
    {"solve_zero_max_iterations",
     {},
     "solve " + kScene + " --max-iterations 0 --report {d}/r.json",
     "--max-iterations"},
    {"solve_unknown_linear_solver",
     {},
     "solve " + kScene + " --method full --linear-solver qr --out {d}/s.ply",
     "--linear-solver"},
    {"solve_unknown_effects", {}, "solve " + kScene + " --effects some --out {d}/s.ply", "--effects"},
    {"solve_unknown_kernel", {}, "solve " + kScene + " --kernel exact --out {d}/s.ply", "--kernel"},
    {"solve_unknown_source_levels",
     {},
     "solve " + kScene + " --source-levels some --report {d}/r.json",
     "--source-levels"},
    {"solve_too_many_source_levels",
     {},
     "solve " + kScene + " --source-levels 7 --report {d}/r.json",
     "--source-levels"},
    {"sweep_unknown_source_levels", {}, "sweep " + kScene + " --source-levels 2x --out {d}/sw", "--source-levels"},
    {"solve_zero_visibility_samples",
     {},
     "solve " + kScene + " --visibility-samples 0 --out {d}/s.ply",
     "--visibility-samples"},
    {"solve_negative_threads", {}, "solve " + kScene + " --threads -1 --out {d}/s.ply", "--threads"},
    {"solve_negative_seed", {}, "solve " + kScene + " --seed -3 --out {d}/s.ply", "--seed"},
    {"solve_zero_exposure", {}, "solve " + kScene + " --exposure 0 --out {d}/s.ply", "--exposure"},
    {"solve_missing_scene", {}, "solve {d}/missing.obj --out {d}/s.ply --report {d}/r.json", "missing.obj"},
    {"solve_reflectance_one",
     {{"room.obj", "mtllib room.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl white\nf 1 2 3\n"},
      {"room.mtl", "newmtl white\nKd 1 1 1\n"}},
     "solve {d}/room.obj --out {d}/s.ply",
     "room.mtl:2"},
    {"solve_unwritable_output",
     {},
     "solve " + kScene + " --quiet --out /proc/hrad-no-such/s.ply",
     "/proc/hrad-no-such"},
    {"render_missing_solution", {}, "render {d}/missing.ply --out {d}/i.png", "missing.ply"},
    {"render_truncated_solution",
     {{"bad.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"}},
     "render {d}/bad.ply --out {d}/i.png",
     "bad.ply"},
    {"render_bad_camera", {}, "render {d}/missing.ply --out {d}/i.png --camera 1,2,3", "--camera"},
    {"render_zero_width", {}, "render {d}/missing.ply --out {d}/i.png --width 0", "--width"},
    {"render_negative_exposure", {}, "render {d}/missing.ply --out {d}/i.png --exposure -1", "--exposure"},
    {"render_reference_without_scene", {}, "render {d}/missing.ply --out {d}/i.png --reference {d}/r.ply", "--scene"},
    {"render_bad_error_range",
     {},
     "render {d}/missing.ply --out {d}/i.png --reference {d}/r.ply --scene " + kScene + " --error-range 2,1",
     "--error-range"},
    {"formfactor_missing_file", {}, "formfactor --json {d}/missing.json", "missing.json"},
    {"formfactor_malformed_json",
     {{"bad.json", "{\"pairs\": [ {\"name\": \"a\", \"from\": [[0,0,0]"}},
     "formfactor --json {d}/bad.json",
     "bad.json"},
    {"formfactor_degenerate_polygon",
     {{"bad.json",
       R"({"pairs": [{"name": "flat", "from": [[0,0,0],[1,0,0],[2,0,0]], "to": [[0,0,1],[0,1,1],[1,1,1]]}]})"}},
     "formfactor --json {d}/bad.json",
     "flat"},
    {"formfactor_zero_normal",
     {{"bad.json",
       R"({"pairs": [{"name": "p", "from_point": [0,0,0], "from_normal": [0,0,0], "to": [[0,0,1],[0,1,1],[1,1,1]]}]})"}},
     "formfactor --json {d}/bad.json",
     "p"},
    {"sweep_zero_samples", {}, "sweep " + kScene + " --out {d}/sweep --samples 0", "--samples"},
    {"sweep_target_error_above_one", {}, "sweep " + kScene + " --out {d}/sweep --target-error 2", "--target-error"},
    {"sweep_negative_reference",
     {},
     "sweep " + kScene + " --out {d}/sweep --reference-elements -5",
     "--reference-elements"},
    {"sweep_empty_list_item", {}, "sweep " + kScene + " --out {d}/sweep --feps 0.1,,0.01", "--feps"},
    {"sweep_list_out_of_range", {}, "sweep " + kScene + " --out {d}/sweep --aeps 0.1,2", "--aeps"},
    {"sweep_unknown_gather_sources",
     {},
     "sweep " + kScene + " --out {d}/sweep --gather-sources leaves",
     "--gather-sources"},
    {"sweep_gather_sources_without_gather",
     {},
     "sweep " + kScene + " --out {d}/sweep --no-gather --gather-sources all",
     "--gather-sources"},
    {"render_camera_trailing_comma",
     {},
     "render {d}/missing.ply --out {d}/i.png --camera 0,0,5,0,0,0,0,1,0,40,",
     "--camera"},
    {"render_final_gather_without_scene", {}, "render {d}/missing.ply --out {d}/i.png --final-gather", "--scene"},
    {"render_zero_samples_per_pixel",
     {},
     "render {d}/missing.ply --out {d}/i.png --samples-per-pixel 0",
     "--samples-per-pixel"},
    {"render_negative_gather_tolerance",
     {},
     "render {d}/missing.ply --out {d}/i.png --final-gather --scene " + kScene + " --gather-tolerance -1",
     "--gather-tolerance"},
    {"render_zero_visibility_samples",
     {},
     "render {d}/missing.ply --out {d}/i.png --final-gather --scene " + kScene + " --visibility-samples 0",
     "--visibility-samples"},
    {"render_gather_option_without_final_gather",
     {},
     "render {d}/missing.ply --out {d}/i.png --visibility-samples 8",
     "--visibility-samples"},
    {"render_exr_of_wireframe", {}, "render {d}/missing.ply --out {d}/i.png --wireframe --exr {d}/i.exr", "--exr"},
    {"probe_neither_points_nor_grid", {}, "probe {d}/s.ply --scene " + kScene + " --out {d}/r.csv", "--points"},
    {"probe_points_and_grid",
     {{"p.csv", "x,y,z,nx,ny,nz\n0,1,0,0,1,0\n"}},
     "probe {d}/s.ply --scene " + kScene + " --points {d}/p.csv --grid y,0,0,0,1,1,2,2 --out {d}/r.csv",
     "--grid"},
    {"probe_without_scene", {}, "probe {d}/s.ply --grid y,0,0,0,1,1,2,2 --out {d}/r.csv", "--scene"},
    {"probe_grid_bad_axis",
     {},
     "probe {d}/s.ply --scene " + kScene + " --grid w,0,0,0,1,1,2,2 --out {d}/r.csv",
     "--grid"},
    {"probe_grid_seven_numbers",
     {},
     "probe {d}/s.ply --scene " + kScene + " --grid y,0,0,0,1,1,2 --out {d}/r.csv",
     "--grid"},
    {"probe_grid_empty_rectangle",
     {},
     "probe {d}/s.ply --scene " + kScene + " --grid y,0,1,0,1,1,2,2 --out {d}/r.csv",
     "--grid"},
    {"probe_grid_fractional_count",
     {},
     "probe {d}/s.ply --scene " + kScene + " --grid -z,0,0,0,1,1,2.5,2 --out {d}/r.csv",
     "NU"},
    {"probe_negative_gather_tolerance",
     {},
     "probe {d}/s.ply --scene " + kScene + " --grid y,0,0,0,1,1,2,2 --gather-tolerance -0.1 --out {d}/r.csv",
     "--gather-tolerance"},
    {"probe_samples_with_exact_visibility",
     {},
     "probe {d}/s.ply --scene " + kScene +
         " --grid y,0,0,0,1,1,2,2 --exact-visibility --visibility-samples 8 --out {d}/r.csv",
     "--visibility-samples"},
    {"probe_unknown_emission_units",
     {},
     "probe {d}/s.ply --scene " + kScene + " --grid y,0,0,0,1,1,2,2 --emission-units cd/m2 --out {d}/r.csv",
     "--emission-units"},
    {"probe_isolux_without_grid",
     {{"p.csv", "x,y,z,nx,ny,nz\n0,1,0,0,1,0\n"}},
     "probe {d}/s.ply --scene " + kScene + " --points {d}/p.csv --isolux {d}/i.png --out {d}/r.csv",
     "--isolux"},
    {"probe_bad_points_cell",
     {{"p.csv", "x,y,z,nx,ny,nz\n0,1,0,0,1,0\n0,1,abc,0,1,0\n"}},
     "probe {d}/s.ply --scene " + kScene + " --points {d}/p.csv --out {d}/r.csv",
     "p.csv:3"},
    {"probe_zero_normal",
     {{"p.csv", "x,y,z,nx,ny,nz\n\n0,1,0,0,0,0\n"}},
     "probe {d}/s.ply --scene " + kScene + " --points {d}/p.csv --out {d}/r.csv",
     "p.csv:3"},
    {"probe_missing_solution",
     {},
     "probe {d}/missing.ply --scene " + kScene + " --grid y,0,0,0,1,1,2,2 --out {d}/r.csv",
     "missing.ply"},
    {"sweep_missing_scene", {}, "sweep {d}/missing.obj --out {d}/sweep", "missing.obj"},
    {"reference_neither_points_nor_faces", {}, "reference " + kScene + " --out {d}/r.csv", "--points"},
    {"reference_points_and_faces",
     {{"p.csv", "x,y,z,nx,ny,nz\n0,1,0,0,1,0\n"}},
     "reference " + kScene + " --points {d}/p.csv --faces --out {d}/r.csv",
     "--faces"},
    {"reference_one_sample", {}, "reference " + kScene + " --faces --samples 1 --out {d}/r.csv", "--samples"},
    {"reference_negative_depth", {}, "reference " + kScene + " --faces --max-depth -1 --out {d}/r.csv", "--max-depth"},
    {"reference_negative_threads", {}, "reference " + kScene + " --faces --threads -2 --out {d}/r.csv", "--threads"},
    {"reference_missing_points",
     {},
     "reference " + kScene + " --points {d}/missing.csv --out {d}/r.csv",
     "missing.csv"},
    {"reference_bad_points_row",
     {{"p.csv", "x,y,z,nx,ny,nz\n0,1,0,0,1,0\n0,1,0,0,0,0\n"}},
     "reference " + kScene + " --points {d}/p.csv --out {d}/r.csv",
     "p.csv:3"},
    {"reference_bad_points_header",
     {{"p.csv", "x,y,z\n0,1,0\n"}},
     "reference " + kScene + " --points {d}/p.csv --out {d}/r.csv",
     "p.csv:1"},
    {"compare_missing_report", {}, "compare {d}/missing.json --against {d}/r.csv", "missing.json"},
    {"compare_not_a_report", {{"a.json", "{\"faces\": 3}"}}, "compare {d}/a.json --against {d}/a.json", "'patches'"},
    {"compare_report_wrong_type",
     {{"a.json", R"({"patches": [{"line": "three", "area": 1, "emission": [0, 0, 0], "radiosity": [1, 1, 1]}]})"}},
     "compare {d}/a.json --against {d}/a.json",
     "patches[0]"},
    {"compare_ruler_bad_number",
     {{"a.json", kOneFaceReport}, {"r.csv", std::string(kRulerHeader) + "0,floor,1,0.5,0.5,oops,0,0,0\n"}},
     "compare {d}/a.json --against {d}/r.csv",
     "r.csv:2"},
    {"compare_ruler_other_scene",
     {{"a.json", kOneFaceReport},
      {"r.csv", std::string(kRulerHeader) + "0,floor,1,0.5,0.5,0.5,0,0,0\n1,floor,1,0.5,0.5,0.5,0,0,0\n"}},
     "compare {d}/a.json --against {d}/r.csv",
     "not the same scene"},
    {"compare_ruler_other_area",
     {{"a.json", kOneFaceReport}, {"r.csv", std::string(kRulerHeader) + "0,floor,2,0.5,0.5,0.5,0,0,0\n"}},
     "compare {d}/a.json --against {d}/r.csv",
     "r.csv:2"},
    {"compare_bad_by", {{"a.json", kOneFaceReport}}, "compare {d}/a.json --against {d}/a.json --by colour", "--by"},
    {"compare_faces_out_is_the_reference",
     {{"a.json", kOneFaceReport}, {"b.json", kOneFaceReport}},
     "compare {d}/a.json --against {d}/b.json --faces-out {d}/b.json",
     "--faces-out"},
    {"compare_out_is_the_report",
     {{"a.json", kOneFaceReport}},
     "compare {d}/a.json --against {d}/a.json --out {d}/a.json",
     "--out"},
    {"reference_missing_scene", {}, "reference {d}/missing.obj --faces --out {d}/r.csv", "missing.obj"},
    {"reference_unwritable_output",
     {},
     "reference " + kScene + " --faces --samples 2 --out /proc/hrad-no-such/r.csv",
     "/proc/hrad-no-such"},
    // Unbounded or absurd work, refused before meshing with the estimate and the option to change
    // (solvers/work_estimate.h); each ran until killed before.
    {"solve_aeps_1e_300",
     {},
     "solve " + kCornell + " --aeps 1e-300 --out {d}/s.ply --report {d}/r.json",
     "raise --aeps"},
    {"solve_aeps_1e_6", {}, "solve " + kCornell + " --aeps 1e-6 --out {d}/s.ply", "raise --aeps (now 1e-06)"},
    {"solve_substructure_tiny_max_area",
     {},
     "solve " + kCornell + " --method substructure --max-area 1e-4 --out {d}/s.ply",
     "raise --max-area"},
    {"solve_visibility_samples_million",
     {},
     "solve " + kCornell + " --visibility-samples 1000000 --out {d}/s.ply",
     "--visibility-samples"},
    // Sizes within the options' ranges that do not fit this process (ulimit -v 4 GB): refused up front,
    // not std::bad_alloc.
    {"render_larger_than_memory",
     {},
     "--version >/dev/null; ulimit -v 4000000; '" + test::hrad_executable() +
         "' render {d}/missing.ply --out {d}/i.png --width 16384 --height 16384",
     "--width"},
    {"scene_generate_larger_than_memory",
     {},
     "--version >/dev/null; ulimit -v 4000000; '" + test::hrad_executable() +
         "' scene generate --polygons 10000000 --out {d}/g.obj",
     "--polygons"},
    // Numbers CLI11 would take: a seed beyond 64 bits, an empty list.
    {"scene_seed_beyond_64_bits",
     {},
     "scene generate --polygons 100 --seed 99999999999999999999 --out {d}/g.obj",
     "--seed"},
    {"solve_seed_beyond_64_bits", {}, "solve " + kScene + " --seed 99999999999999999999 --out {d}/s.ply", "--seed"},
    {"probe_negative_seed",
     {{"p.csv", "x,y,z,nx,ny,nz\n0,1,0,0,1,0\n"}},
     "probe {d}/s.ply --scene " + kScene + " --points {d}/p.csv --out {d}/r.csv --seed -1",
     "--seed"},
    {"render_negative_seed", {}, "render {d}/missing.ply --out {d}/i.png --seed -1", "--seed"},
    {"reference_negative_seed",
     {{"p.csv", "x,y,z,nx,ny,nz\n0,1,0,0,1,0\n"}},
     "reference " + kScene + " --points {d}/p.csv --out {d}/r.csv --seed -1",
     "--seed"},
    {"sweep_empty_elements", {}, "sweep " + kScene + " --out {d}/sweep --elements ''", "--elements"},
    {"figures_unknown_figure", {}, "figures --out {d}/figs --only 7", "--only"},
    {"figures_missing_scenes", {}, "figures --out {d}/figs --only 1 --scenes {d}/nowhere", "nowhere"},
};

class CliBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(CliBadInput, OneLineErrorNonZeroExitNothingWritten) {
  const BadInput& c = GetParam();
  TempDir dir;
  for (const auto& [name, text] : c.files) dir.write(name, text);
  const RunResult r = run_hrad(replace_all(c.args, "{d}", dir.root().string()), dir);
  EXPECT_TRUE(r.exit_code == 1 || r.exit_code == 2) << "exit " << r.exit_code << "\n" << r.err;
  const auto lines = r.err_lines();
  ASSERT_EQ(lines.size(), 1u) << "stderr:\n" << r.err;
  EXPECT_EQ(lines[0].rfind("hrad: error: ", 0), 0u) << lines[0];
  EXPECT_NE(lines[0].find(c.expected), std::string::npos) << "'" << c.expected << "' not in: " << lines[0];
  EXPECT_EQ(dir.entries(), c.files.size()) << "an output (or temporary) file was left behind";
}

INSTANTIATE_TEST_SUITE_P(AllSubcommands, CliBadInput, ::testing::ValuesIn(kCases),
                         [](const auto& info) { return info.param.name; });

// The commands that end in plots check that the plots' Python can import matplotlib before any work
// (scripts/run.sh installs no matplotlib): one line naming the Python and how to install it, exit 1,
// nothing written. HRAD_PYTHON stands for a Python without matplotlib.
TEST(CliPlots, SweepAndFiguresWithoutMatplotlibStopBeforeTheirWork) {
  for (const std::string command : {"sweep " + kScene + " --out {d}/sweep", std::string("figures --out {d}/figures")}) {
    TempDir dir;
    const RunResult r = run_hrad("--version >/dev/null; HRAD_PYTHON=/bin/false '" + test::hrad_executable() + "' " +
                                     replace_all(command, "{d}", dir.root().string()),
                                 dir);
    EXPECT_EQ(r.exit_code, 1) << command << "\n" << r.err;
    const auto lines = r.err_lines();
    ASSERT_EQ(lines.size(), 1u) << command << "\n" << r.err;
    EXPECT_EQ(lines[0].rfind("hrad: error: /bin/false: cannot import matplotlib", 0), 0u) << lines[0];
    EXPECT_NE(lines[0].find("scripts/install_deps.sh"), std::string::npos) << lines[0];
    EXPECT_EQ(dir.entries(), 0u) << command << ": an output (or temporary) file was left behind";
  }
}

// A 4000-polygon office (5.7 k patches cut along its boxes' bottoms) needs ~350 MB at its peak (0.82 M links).
// Under a 250 MB address space the estimate (links per element and bytes per link measured on offices,
// work_estimate.h) refuses it before any work (up to ~360 MB). Under 380 MB the estimate fits (it is an average, not a bound) but the work does
// not: the allocation failure is one line naming what was being allocated and the option that
// makes it smaller, exit 1, nothing written.
TEST(CliOutOfMemory, NamesWhatWasBeingAllocatedAndTheOption) {
  TempDir dir;
  const std::string d = dir.root().string();
  ASSERT_EQ(run_hrad("scene generate --polygons 4000 --out " + d + "/o.obj", dir).exit_code, 0);
  const RunResult refused =
      run_hrad("--version >/dev/null; ulimit -v 250000; '" + test::hrad_executable() + "' solve " + d +
                   "/o.obj --threads 1 --quiet --out " + d + "/s.ply --report " + d + "/r.json",
               dir);
  EXPECT_EQ(refused.exit_code, 1) << refused.err;
  EXPECT_NE(refused.err.find("elements need"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("raise --aeps"), std::string::npos) << refused.err;
  EXPECT_EQ(dir.entries(), 2u) << "an output (or temporary) file was left behind";
  const RunResult r = run_hrad("--version >/dev/null; ulimit -v 380000; '" + test::hrad_executable() + "' solve " + d +
                                   "/o.obj --threads 1 --quiet --out " + d + "/s.ply --report " + d + "/r.json",
                               dir);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  // Any warnings of the reader's, then one error line.
  const auto lines = r.err_lines();
  ASSERT_GE(lines.size(), 1u) << r.err;
  for (std::size_t i = 0; i + 1 < lines.size(); ++i) EXPECT_NE(lines[i].find(": warning: "), std::string::npos);
  EXPECT_EQ(lines.back().rfind("hrad: error: out of memory in 'solve' while allocating the ", 0), 0u) << r.err;
  EXPECT_NE(lines.back().find(": raise --aeps"), std::string::npos) << lines.back();
  EXPECT_EQ(dir.entries(), 2u) << "an output (or temporary) file was left behind";
}

// The power check after a solve needs an Embree device, which a tight address-space limit can refuse
// (Embree reserves memory when it starts). The solve's own work must not be lost then: the solution
// and the report are written, with a warning in place of the power line (or, where the limit leaves
// Embree room, the power line as usual).
TEST(CliOutOfMemory, ASolveUnderATightLimitIsWrittenEvenIfThePowerCheckCannotRun) {
  TempDir dir;
  const std::string d = dir.root().string();
  const RunResult r = run_hrad("--version >/dev/null; ulimit -v 150000; '" + test::hrad_executable() + "' solve '" +
                                   test::source_dir() + "/notebooks_data/scenes/simple_room.obj' --threads 1 --out " +
                                   d + "/s.ply --report " + d + "/r.json",
                               dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(d + "/s.ply"));
  ASSERT_TRUE(std::filesystem::exists(d + "/r.json"));
  const bool line = r.out.find("power: emitted") != std::string::npos;
  const bool warned = r.err.find("warning: power balance not checked (") != std::string::npos;
  EXPECT_NE(line, warned) << r.out << r.err;
  std::ifstream in(d + "/r.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["power_balance"].is_null(), warned);
  EXPECT_GT(report["elements"].get<double>(), 0.0);
}

}  // namespace
}  // namespace hrad::test
