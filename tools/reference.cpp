// hrad reference SCENE --points P.csv --out R.csv [--samples N] [--seed S] [--threads T]
// hrad reference SCENE --faces --out R.csv [...]
//
// An independent Monte Carlo reference for a scene's light (lib/hrad/reference/reference.h): path
// tracing with next-event estimation, cosine-weighted bounces and multiple importance sampling, on
// its own ray casting (Embree), sharing no kernel with the solvers. Every number comes with its
// standard error; the same seed gives the same bits at any thread count.
//
//   --points P.csv     probe points, one a row under the header x,y,z,nx,ny,nz (position and the
//                      direction the probe faces); a point on a patch's front (within 1e-6 of the
//                      scene's size, normal within ~1.4 mrad) also gets that patch's radiosity
//   --faces            the area-mean radiosity of every input face instead, from stratified points
//   --out R.csv        the results, written atomically:
//                        points: x,y,z,nx,ny,nz (the normal as a unit vector), face (the input face
//                        the point lies on, empty for a point in space), irradiance_r,_g,_b and
//                        irradiance_r_se,_g_se,_b_se (exitance units: what a reflectance multiplies),
//                        radiosity_r,_g,_b and radiosity_r_se,_g_se,_b_se (empty off patches)
//                        faces: face (index in file order), group, area, radiosity_r,_g,_b,
//                        radiosity_r_se,_g_se,_b_se (faces that reflect nothing: their emission, se 0)
//   --samples N        paths per point, or stratified points per face (one path each); default 1024.
//                      The standard error falls as 1/sqrt(N)
//   --seed S           random seed (default 1)
//   --max-depth D      longest path in segments, 0 = no limit (default; Russian roulette ends paths
//                      without bias); 1 = direct light only
//   --threads T        worker threads (default: all cores); the results do not depend on it
//   --quiet            no progress on stderr
// Progress (queries done, time elapsed, time left) goes to stderr every 2 s for runs longer than
// that; a summary (rays cast, paths, seconds) to stdout. Bad options and files are a one-line error naming
// the option or file:line, before any work.
#include <iostream>
#include <string>

#include <fmt/format.h>

#include "commands.h"
#include "csv_cells.h"
#include "hrad/core/error.h"
#include "hrad/io/atomic_file.h"
#include "hrad/io/points_csv.h"
#include "hrad/io/scene_reader.h"
#include "hrad/reference/reference.h"
#include "seed_option.h"

namespace hrad::cli {
namespace {

void print_summary(const std::string& what, const ReferenceSummary& s) {
  std::cout << fmt::format(
      "{}: {} paths, {} rays ({} closest-hit, {} shadow) in {:.3f} s (BVH {:.3f} s), {:.3g} rays/s\n", what, s.paths,
      s.rays(), s.closest_hit_rays, s.shadow_rays, s.total_seconds, s.build_seconds,
      s.trace_seconds > 0.0 ? static_cast<double>(s.rays()) / s.trace_seconds : 0.0);
}

}  // namespace

void add_reference_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "reference", "Monte Carlo reference (path tracing, own ray casting): irradiance at points or face radiosity");
  struct Args {
    std::string scene, points, out;
    bool faces = false, quiet = false;
    int samples = 1024, max_depth = 0, threads = 0;
    std::uint64_t seed = 1;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("SCENE", args->scene, "Scene file (.obj)")->required();
  cmd->add_option("--points", args->points, "Probe points (CSV with header x,y,z,nx,ny,nz)");
  cmd->add_flag("--faces", args->faces, "Area-mean radiosity of every input face");
  cmd->add_option("--out", args->out, "Write the results (CSV) here")->required();
  cmd->add_option("--samples", args->samples, "Paths per point / points per face (default 1024)");
  cmd->add_option("--seed", args->seed, "Random seed (default 1)")->check(cli::seed_validator());
  cmd->add_option("--max-depth", args->max_depth, "Longest path in segments, 0 = no limit (default)");
  cmd->add_option("--threads", args->threads, "Worker threads (default: all cores)");
  cmd->add_flag("--quiet", args->quiet, "No progress on stderr");
  cmd->callback([args] {
    if (args->points.empty() == !args->faces)
      throw Error(args->faces ? "--points and --faces exclude each other" : "give --points P.csv or --faces");
    ReferenceOptions options;
    options.samples = args->samples;
    options.seed = args->seed;
    options.max_depth = args->max_depth;
    options.threads = args->threads;
    validate_reference_options(options);

    std::vector<std::string> warnings;
    // Faces whole: the ruler traces surfaces, which cutting along near faces does not change (nor its samples).
    ObjReadOptions read_options;
    read_options.cut_near_faces = false;
    const Scene scene = read_scene(args->scene, &warnings, read_options);
    std::vector<ProbePoint> points;
    if (!args->faces) points = read_points_csv(args->points);
    for (const std::string& w : warnings) std::cerr << w << "\n";
    if (!args->quiet) options.progress = [](std::string_view line) { std::cerr << "hrad " << line << "\n"; };

    if (args->faces) {
      std::vector<FaceEstimate> faces;
      const ReferenceSummary summary = reference_faces(scene, options, &faces);
      write_file_atomically(args->out, [&](std::ostream& o) {
        o << "face,group,area,radiosity_r,radiosity_g,radiosity_b,radiosity_r_se,radiosity_g_se,radiosity_b_se\n";
        for (std::size_t f = 0; f < faces.size(); ++f)
          o << fmt::format("{},{},{},{},{}\n", f, csv_cell(scene.faces[f].group), scene.faces[f].area,
                           rgb_cells(faces[f].radiosity), rgb_cells(faces[f].radiosity_se));
      });
      print_summary(fmt::format("{}: {} faces x {} points", scene.path, faces.size(), options.samples), summary);
      return;
    }
    std::vector<PointEstimate> estimates;
    const ReferenceSummary summary = reference_points(scene, points, options, &estimates);
    write_file_atomically(args->out, [&](std::ostream& o) {
      o << "x,y,z,nx,ny,nz,face,irradiance_r,irradiance_g,irradiance_b,irradiance_r_se,irradiance_g_se,"
           "irradiance_b_se,radiosity_r,radiosity_g,radiosity_b,radiosity_r_se,radiosity_g_se,radiosity_b_se\n";
      for (std::size_t i = 0; i < points.size(); ++i) {
        const PointEstimate& e = estimates[i];
        const ProbePoint& p = points[i];
        o << fmt::format("{},{},{},{},{},{},", p.position.x(), p.position.y(), p.position.z(), p.normal.x(),
                         p.normal.y(), p.normal.z());
        o << (e.patch >= 0 ? std::to_string(scene.patches[static_cast<std::size_t>(e.patch)].face) : std::string());
        o << fmt::format(",{},{},", rgb_cells(e.irradiance), rgb_cells(e.irradiance_se));
        o << (e.patch >= 0 ? fmt::format("{},{}", rgb_cells(e.radiosity), rgb_cells(e.radiosity_se)) : ",,,,,") << "\n";
      }
    });
    print_summary(fmt::format("{}: {} points x {} paths", scene.path, points.size(), options.samples), summary);
  });
}

}  // namespace hrad::cli
