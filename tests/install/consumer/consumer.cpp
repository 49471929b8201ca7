// A program built against the installed package, as a user's would be: it reads box.obj (a closed
// unit cube, the floor emitting E = 1, every face reflecting rho = 0.5) and solves it with the full
// matrix and the analytic kernel. In a closed room of one reflectance, closure and reciprocity of
// the form factors give the power balance sum_i A_i B_i = sum_i A_i E_i / (1 - rho) = 2 (Cohen &
// Wallace 1993, sec. 2.6), whatever the mesh; the analytic factors are exact to ~1e-13.
#include <cmath>
#include <cstdio>

#include "hrad/io/scene_reader.h"
#include "hrad/solvers/solve.h"
#include "hrad/version.h"

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const hrad::Scene scene = hrad::read_scene(argv[1]);
  hrad::SolveOptions options;
  options.method = hrad::Method::kFull;
  options.kernel = hrad::FormFactorKernel::kAnalytic;
  options.max_area = 1.0 / 16.0;
  hrad::Solution solution;
  hrad::solve(scene, options, &solution);
  double power = 0.0;
  for (std::size_t p = 0; p < scene.patches.size(); ++p)
    power += scene.patches[p].area * solution.patch_radiosity[p].x();
  std::printf("hrad %s: %zu elements, power %.15g (closed form 2)\n", HRAD_VERSION, solution.faces.size(), power);
  return std::abs(power - 2.0) <= 1e-9 * 2.0 ? 0 : 1;
}
