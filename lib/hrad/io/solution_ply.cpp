#include "hrad/io/solution_ply.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

#include <fmt/format.h>

#include "hrad/core/error.h"
#include "hrad/core/face_geometry.h"
#include "hrad/core/tone_map.h"
#include "hrad/io/atomic_file.h"
#include "hrad/io/input_file.h"
#include "hrad/io/ply_file.h"

namespace hrad {
namespace {

constexpr const char* kChannel[3] = {"radiosity_r", "radiosity_g", "radiosity_b"};
constexpr const char* kPatch = "patch";
// Written as a header comment; a file carrying it has its positions turned back on reading.
constexpr const char* kZUpComment =
    "hrad axes: stored (x, -z, y) of the scene's (x, y, z): +Z up, as Blender imports PLY";

void check_consistent(const std::string& path, const Solution& s) {
  auto fail = [&](const std::string& what) { throw Error(fmt::format("{}: cannot write solution: {}", path, what)); };
  if (s.vertex_radiosity.size() != s.vertices.size())
    fail(fmt::format("{} vertex radiosities for {} vertices", s.vertex_radiosity.size(), s.vertices.size()));
  if (s.face_radiosity.size() != s.faces.size() || s.face_patch.size() != s.faces.size())
    fail(fmt::format("{} faces but {} face radiosities and {} patch ids", s.faces.size(), s.face_radiosity.size(),
                     s.face_patch.size()));
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    if (s.faces[f].size() < 3 || s.faces[f].size() > 255)
      fail(fmt::format("face {} has {} vertices", f, s.faces[f].size()));
    for (int v : s.faces[f])
      if (v < 0 || static_cast<std::size_t>(v) >= s.vertices.size())
        fail(fmt::format("face {} has vertex index {} out of range", f, v));
    if (s.face_patch[f] < 0) fail(fmt::format("face {} has patch id {}", f, s.face_patch[f]));
  }
}

template <typename T>
void put(std::string& out, T value) {
  static_assert(std::endian::native == std::endian::little, "the PLY body is written as binary_little_endian");
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

const std::vector<double>& values_of(const std::string& path, const PlyElement& e, const char* name) {
  const PlyProperty* p = e.property(name);
  if (p == nullptr || p->list)
    throw Error(fmt::format("{}: not an hrad solution: no {} property '{}'", path,
                            e.name == "vertex" ? "vertex" : "face", name));
  return p->values;
}

}  // namespace

void write_solution_ply(std::ostream& out, const Solution& solution, double exposure, const std::string& path) {
  check_consistent(path, solution);
  std::string header = "ply\nformat binary_little_endian 1.0\n";
  header += "comment written by hrad: leaf elements with per-vertex and per-element radiosity\n";
  header += fmt::format("comment {}\n", kZUpComment);
  header += fmt::format("element vertex {}\n", solution.vertices.size());
  header += "property double x\nproperty double y\nproperty double z\n";
  header += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  for (const char* c : kChannel) header += fmt::format("property double {}\n", c);
  header += fmt::format("element face {}\n", solution.faces.size());
  header += "property list uchar int vertex_indices\n";
  for (const char* c : kChannel) header += fmt::format("property double {}\n", c);
  header += fmt::format("property int {}\nend_header\n", kPatch);

  std::string body;
  body.reserve(solution.vertices.size() * 51 + solution.faces.size() * 45);
  for (std::size_t i = 0; i < solution.vertices.size(); ++i) {
    const Vec3& p = solution.vertices[i];
    put(body, p.x());
    put(body, -p.z());
    put(body, p.y());
    const Rgb8 rgb = tone_map(solution.vertex_radiosity[i], exposure);
    for (int c = 0; c < 3; ++c) put(body, static_cast<std::uint8_t>(rgb[c]));
    for (int c = 0; c < 3; ++c) put(body, solution.vertex_radiosity[i][c]);
  }
  for (std::size_t f = 0; f < solution.faces.size(); ++f) {
    put(body, static_cast<std::uint8_t>(solution.faces[f].size()));
    for (int v : solution.faces[f]) put(body, static_cast<std::int32_t>(v));
    for (int c = 0; c < 3; ++c) put(body, solution.face_radiosity[f][c]);
    put(body, static_cast<std::int32_t>(solution.face_patch[f]));
  }
  out << header;
  out.write(body.data(), static_cast<std::streamsize>(body.size()));
}

void write_solution_ply(const std::string& path, const Solution& solution, double exposure) {
  check_consistent(path, solution);
  write_file_atomically(
      path, [&](std::ostream& out) { write_solution_ply(out, solution, exposure, path); }, /*binary=*/true);
}

Solution read_solution_ply(const std::string& path) {
  const std::string bytes = read_input_file(path);
  if (!looks_like_ply(bytes))
    throw Error(fmt::format("{}: not a readable PLY file: it does not start with 'ply'", path));
  const PlyData ply = parse_ply(path, bytes);
  const PlyElement* vertex = ply.element("vertex");
  const PlyElement* face = ply.element("face");
  if (vertex == nullptr || face == nullptr)
    throw Error(fmt::format("{}: not an hrad solution: no 'vertex' or no 'face' element", path));
  bool z_up = false;
  for (const std::string& c : ply.comments) z_up = z_up || c == kZUpComment;

  const std::vector<double>& x = values_of(path, *vertex, "x");
  const std::vector<double>& y = values_of(path, *vertex, "y");
  const std::vector<double>& z = values_of(path, *vertex, "z");
  const std::vector<double>* vrad[3];
  const std::vector<double>* frad[3];
  for (int c = 0; c < 3; ++c) vrad[c] = &values_of(path, *vertex, kChannel[c]);
  const PlyProperty* indices = face->property("vertex_indices");
  if (indices == nullptr) indices = face->property("vertex_index");
  if (indices == nullptr || !indices->list)
    throw Error(fmt::format("{}: not an hrad solution: no face list property 'vertex_indices'", path));
  for (int c = 0; c < 3; ++c) frad[c] = &values_of(path, *face, kChannel[c]);
  const std::vector<double>& patch = values_of(path, *face, kPatch);

  Solution s;
  s.vertices.reserve(vertex->count);
  for (std::size_t i = 0; i < vertex->count; ++i) {
    s.vertices.push_back(z_up ? Vec3(x[i], z[i], -y[i]) : Vec3(x[i], y[i], z[i]));
    s.vertex_radiosity.emplace_back((*vrad[0])[i], (*vrad[1])[i], (*vrad[2])[i]);
    if (!s.vertices.back().allFinite() || !s.vertex_radiosity.back().allFinite())
      throw Error(fmt::format("{}: vertex {} has a non-finite position or radiosity", path, i));
  }
  std::size_t invalid = 0, first_invalid = 0;
  int patches = 0;
  for (std::size_t f = 0; f < face->count; ++f) {
    std::vector<int> ids;
    bool ok = indices->offsets[f + 1] - indices->offsets[f] >= 3;
    for (std::size_t k = indices->offsets[f]; k < indices->offsets[f + 1]; ++k) {
      const double v = indices->values[k];
      ok = ok && v >= 0 && v < static_cast<double>(vertex->count);
      ids.push_back(static_cast<int>(v));
    }
    if (!ok) {
      if (invalid++ == 0) first_invalid = f;
      continue;
    }
    s.faces.push_back(std::move(ids));
    s.face_radiosity.emplace_back((*frad[0])[f], (*frad[1])[f], (*frad[2])[f]);
    if (!s.face_radiosity.back().allFinite())
      throw Error(fmt::format("{}: face {} has a non-finite radiosity", path, f));
    const double p = patch[f];
    if (!(p >= 0 && p <= 2e9 && p == std::floor(p)))
      throw Error(fmt::format("{}: face {} has a negative or non-integer patch id {}", path, f, p));
    s.face_patch.push_back(static_cast<int>(p));
    patches = std::max(patches, s.face_patch.back() + 1);
  }
  if (invalid > 0)
    throw Error(
        fmt::format("{}: {} of {} faces are invalid (fewer than 3 vertices or a vertex index out of range; "
                    "the first is face {})",
                    path, invalid, face->count, first_invalid));

  // patch_radiosity: area-weighted mean of each patch's faces (Solution's definition).
  std::vector<Rgb> sum(patches, Rgb::Zero());
  std::vector<double> area(patches, 0.0);
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    const double a = face_area(s, f);
    sum[s.face_patch[f]] += a * s.face_radiosity[f];
    area[s.face_patch[f]] += a;
  }
  s.patch_radiosity.resize(patches, Rgb::Zero());
  for (int p = 0; p < patches; ++p)
    if (area[p] > 0.0) s.patch_radiosity[p] = sum[p] / area[p];
  return s;
}

void check_solution_patches(const Solution& solution, const std::string& solution_path, const Scene& scene,
                            const std::string& scene_path) {
  for (int p : solution.face_patch)
    if (p < 0 || static_cast<std::size_t>(p) >= scene.patches.size())
      throw Error(
          fmt::format("{}: patch id {} but {} has {} patches", solution_path, p, scene_path, scene.patches.size()));
}

}  // namespace hrad
