// The patch rules every scene reader shares (README "Scene format"): an input face becomes one patch
// when it is planar, convex and has 3 or 4 vertices; other faces are triangulated; zero-area faces are
// skipped; faces bent beyond the planarity tolerance are split into triangles; faces without a
// material get the default one. Findings are tallied and reported as one warning line per kind.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "hrad/core/scene.h"
#include "hrad/io/obj_reader.h"

namespace hrad::detail {

struct FaceTallies {
  struct Tally {
    std::size_t count = 0, first_line = 0;
    double worst = 0.0;
    void add(std::size_t line, double value);
  };
  Tally no_material, zero_area, non_planar;
};

/// The scene's default material (added on first use), for faces without one; counts the face.
int default_material(Scene& scene, std::size_t line, FaceTallies& tallies);

/// Appends `face` (material and line set) to scene.faces and its patches to scene.patches.
/// `step` is the coarsest printed step of its coordinates (0 for binary files): see ObjReadOptions.
void add_input_face(Scene& scene, InputFace face, std::vector<Vec3> vertices, double step,
                    const ObjReadOptions& options, FaceTallies& tallies);

/// One warning per kind of finding, "path:line: warning: ..." at the first face it concerns.
void report_tallies(const std::string& path, const FaceTallies& tallies, std::vector<std::string>* warnings);

}  // namespace hrad::detail
