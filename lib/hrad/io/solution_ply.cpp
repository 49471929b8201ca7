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
#include "hrad/geometry/front_patch.h"
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
// Written when the solve kept faces whole that read_scene() cuts by default along near faces (io/near_faces.h):
// readers of the scene keep them whole alike.
constexpr const char* kNearFacesKeptComment =
    "hrad scene: faces not cut along near faces (hrad solve --no-cut-near-faces)";

std::string links_defect(const SolutionLinks& links);

void check_consistent(const std::string& path, const Solution& s, const SolutionLinks* links) {
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
  if (links != nullptr)
    if (const std::string defect = links_defect(*links); !defect.empty()) fail(defect);
}

// What is wrong with `links` (empty when nothing): the ranges the header of solution_ply.h states.
std::string links_defect(const SolutionLinks& links) {
  const std::int64_t nodes = static_cast<std::int64_t>(links.first_child.size());
  const std::int64_t clusters = static_cast<std::int64_t>(links.cluster_parent.size());
  for (std::int64_t i = 0; i < nodes; ++i) {
    const std::int64_t c = links.first_child[static_cast<std::size_t>(i)];
    if (c != -1 && !(c > i && c + 3 < nodes))
      return fmt::format("element node {}: first_child {} is neither -1 nor a block of 4 of the {} nodes after it", i,
                         c, nodes);
  }
  for (std::int64_t k = 0; k < clusters; ++k) {
    const std::int64_t p = links.cluster_parent[static_cast<std::size_t>(k)];
    if (!(p == -1 ? k == 0 : p >= 0 && p < k))
      return fmt::format("element cluster {}: parent {} is not a cluster before it (-1 for cluster 0 only)", k, p);
  }
  for (std::size_t k = 0; k < links.links.size(); ++k) {
    const SolutionLinks::Link& l = links.links[k];
    for (const auto& [name, end] : {std::pair{"p", l.p}, std::pair{"q", l.q}})
      if (!(end >= 0 ? end < nodes : end <= -2 && -2 - static_cast<std::int64_t>(end) < clusters))
        return fmt::format("element link {}: {} = {} is neither an element node (0 to {}) nor a cluster (-2 to {})", k,
                           name, end, nodes - 1, -1 - clusters);
    for (const auto& [name, list] : {std::pair{"hidden_p", &l.hidden_p}, std::pair{"hidden_q", &l.hidden_q}})
      for (std::size_t i = 0; i < list->size(); ++i)
        if ((*list)[i] < 0 || (i > 0 && (*list)[i] <= (*list)[i - 1]))
          return fmt::format("element link {}: {} lists patch {} (patch ids are >= 0 and ascending)", k, name,
                             (*list)[i]);
  }
  return {};
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

// A property of stored links whose values are integers in [lo, hi] (scalars or list items).
const PlyProperty& integers_of(const std::string& path, const PlyElement& e, const char* name, bool list, double lo,
                               double hi) {
  const PlyProperty* p = e.property(name);
  if (p == nullptr || p->list != list)
    throw Error(fmt::format("{}: element {} has no {}property '{}'", path, e.name, list ? "list " : "", name));
  for (std::size_t i = 0; i < p->values.size(); ++i) {
    const double v = p->values[i];
    if (!(v >= lo && v <= hi && v == std::floor(v))) {
      std::size_t record = i;
      if (list)
        record =
            static_cast<std::size_t>(std::upper_bound(p->offsets.begin(), p->offsets.end(), i) - p->offsets.begin()) -
            1;
      throw Error(fmt::format("{}: element {} {}: {} = {} is not an integer in [{}, {}]", path, e.name, record, name, v,
                              lo, hi));
    }
  }
  return *p;
}

SolutionLinks read_links(const std::string& path, const PlyData& ply) {
  const PlyElement* node = ply.element("node");
  const PlyElement* cluster = ply.element("cluster");
  const PlyElement* link = ply.element("link");
  if (node == nullptr) throw Error(fmt::format("{}: element link without element node", path));
  constexpr double kIntMin = -2147483648.0, kIntMax = 2147483647.0;
  SolutionLinks out;
  for (double v : integers_of(path, *node, "first_child", false, -1, kIntMax).values)
    out.first_child.push_back(static_cast<std::int32_t>(v));
  if (cluster != nullptr)
    for (double v : integers_of(path, *cluster, "parent", false, -1, kIntMax).values)
      out.cluster_parent.push_back(static_cast<std::int32_t>(v));
  const PlyProperty& p = integers_of(path, *link, "p", false, kIntMin, kIntMax);
  const PlyProperty& q = integers_of(path, *link, "q", false, kIntMin, kIntMax);
  const PlyProperty& partial = integers_of(path, *link, "partial", false, 0, 1);
  const PlyProperty& hidden_p = integers_of(path, *link, "hidden_p", true, 0, kIntMax);
  const PlyProperty& hidden_q = integers_of(path, *link, "hidden_q", true, 0, kIntMax);
  out.links.resize(link->count);
  for (std::size_t k = 0; k < link->count; ++k) {
    SolutionLinks::Link& l = out.links[k];
    l.p = static_cast<std::int32_t>(p.values[k]);
    l.q = static_cast<std::int32_t>(q.values[k]);
    l.partial = partial.values[k] != 0.0;
    for (std::size_t i = hidden_p.offsets[k]; i < hidden_p.offsets[k + 1]; ++i)
      l.hidden_p.push_back(static_cast<std::int32_t>(hidden_p.values[i]));
    for (std::size_t i = hidden_q.offsets[k]; i < hidden_q.offsets[k + 1]; ++i)
      l.hidden_q.push_back(static_cast<std::int32_t>(hidden_q.values[i]));
  }
  if (const std::string defect = links_defect(out); !defect.empty()) throw Error(fmt::format("{}: {}", path, defect));
  return out;
}

}  // namespace

void write_solution_ply(std::ostream& out, const Solution& solution, double exposure, const std::string& path,
                        const SolutionLinks* links) {
  check_consistent(path, solution, links);
  std::string header = "ply\nformat binary_little_endian 1.0\n";
  header += "comment written by hrad: leaf elements with per-vertex and per-element radiosity\n";
  header += fmt::format("comment {}\n", kZUpComment);
  if (!solution.near_faces_cut) header += fmt::format("comment {}\n", kNearFacesKeptComment);
  header += fmt::format("element vertex {}\n", solution.vertices.size());
  header += "property double x\nproperty double y\nproperty double z\n";
  header += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  for (const char* c : kChannel) header += fmt::format("property double {}\n", c);
  header += fmt::format("element face {}\n", solution.faces.size());
  header += "property list uchar int vertex_indices\n";
  for (const char* c : kChannel) header += fmt::format("property double {}\n", c);
  header += fmt::format("property int {}\n", kPatch);
  if (links != nullptr) {
    header += fmt::format("element node {}\nproperty int first_child\n", links->first_child.size());
    header += fmt::format("element cluster {}\nproperty int parent\n", links->cluster_parent.size());
    header += fmt::format("element link {}\n", links->links.size());
    header += "property int p\nproperty int q\nproperty uchar partial\n";
    header += "property list int int hidden_p\nproperty list int int hidden_q\n";
  }
  header += "end_header\n";

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
  if (links != nullptr) {
    for (std::int32_t c : links->first_child) put(body, c);
    for (std::int32_t c : links->cluster_parent) put(body, c);
    for (const SolutionLinks::Link& l : links->links) {
      put(body, l.p);
      put(body, l.q);
      put(body, static_cast<std::uint8_t>(l.partial ? 1 : 0));
      for (const std::vector<std::int32_t>* list : {&l.hidden_p, &l.hidden_q}) {
        put(body, static_cast<std::int32_t>(list->size()));
        for (std::int32_t patch : *list) put(body, patch);
      }
    }
  }
  out << header;
  out.write(body.data(), static_cast<std::streamsize>(body.size()));
}

void write_solution_ply(const std::string& path, const Solution& solution, double exposure,
                        const SolutionLinks* links) {
  check_consistent(path, solution, links);
  write_file_atomically(
      path, [&](std::ostream& out) { write_solution_ply(out, solution, exposure, path, links); }, /*binary=*/true);
}

Solution read_solution_ply(const std::string& path, std::optional<SolutionLinks>* links) {
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
  bool near_faces_cut = true;
  for (const std::string& c : ply.comments) near_faces_cut = near_faces_cut && c != kNearFacesKeptComment;

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
  s.near_faces_cut = near_faces_cut;
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
  if (links != nullptr) {
    links->reset();
    if (ply.element("link") != nullptr) *links = read_links(path, ply);
  }
  return s;
}

void check_solution_patches(const Solution& solution, const std::string& solution_path, const Scene& scene,
                            const std::string& scene_path) {
  for (int p : solution.face_patch)
    if (p < 0 || static_cast<std::size_t>(p) >= scene.patches.size())
      throw Error(
          fmt::format("{}: patch id {} but {} has {} patches", solution_path, p, scene_path, scene.patches.size()));
  // Each leaf's vertex mean lies on its patch: patch ids of the same count but of another reading of the scene
  // (cut along near faces or kept whole) do not.
  const double tolerance = probe_tolerance(scene);
  for (std::size_t i = 0; i < solution.faces.size() && i < solution.face_patch.size(); ++i) {
    if (solution.faces[i].empty()) continue;
    if (!on_patch(scene.patches[static_cast<std::size_t>(solution.face_patch[i])], face_centroid(solution, i),
                  tolerance))
      throw Error(
          fmt::format("{}: leaf {} does not lie on patch {} of {}: a solution of another scene, or of this one "
                      "read otherwise (a solve with --no-cut-near-faces says so in its PLY)",
                      solution_path, i, solution.face_patch[i], scene_path));
  }
}

}  // namespace hrad
