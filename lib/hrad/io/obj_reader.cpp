#include "hrad/io/obj_reader.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <fmt/format.h>

#define TINYOBJLOADER_USE_DOUBLE
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>

#include "hrad/core/error.h"
#include "hrad/geometry/polygon.h"
#include "hrad/io/input_file.h"

// tinyobjloader does the parsing; this file adds what a radiosity scene needs on top of it:
// the line of every statement (for messages), range checks, and the patch rules of obj_reader.h.

namespace hrad {
namespace {

// Tokens separated by spaces and tabs only: tinyobjloader's IS_SPACE, so that both passes agree on
// what a statement is (with >>, a line "v\f 1 2 3" was a vertex here and not there).
std::vector<std::string> tokens_of(const std::string& line) {
  std::vector<std::string> t;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) t.push_back(line.substr(start, i - start));
  }
  return t;
}

std::vector<std::string> split_lines(const std::string& path, const std::string& bytes) {
  std::vector<std::string> lines;
  std::istringstream in(bytes);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find('\0') != std::string::npos) throw_at(path, lines.size() + 1, "binary data in a text file");
    // tinyobjloader ends a line at a lone carriage return too: refuse what the two passes would
    // read differently (a fuzzer found "v\r 5 0 0" counted as a vertex here and not there).
    if (line.find('\r') != std::string::npos) throw_at(path, lines.size() + 1, "carriage return inside a line");
    lines.push_back(std::move(line));
  }
  return lines;
}

/// Checks that tokens [first, first + count) of `t` are finite numbers within `limit`.
void check_numbers(const std::string& file, std::size_t line, const std::vector<std::string>& t,
                   std::size_t first, std::size_t count, double limit) {
  if (t.size() < first + count)
    throw_at(file, line, fmt::format("'{}' needs {} numbers, got {}", t[0], count, t.size() - first));
  for (std::size_t i = first; i < first + count; ++i) {
    char* end = nullptr;
    const double x = std::strtod(t[i].c_str(), &end);
    if (end == t[i].c_str() || *end != '\0') throw_at(file, line, fmt::format("'{}' is not a number", t[i]));
    if (!std::isfinite(x)) throw_at(file, line, fmt::format("'{}' is not a finite number", t[i]));
    if (std::abs(x) > limit) throw_at(file, line, fmt::format("'{}' is out of range (|x| > {:g})", t[i], limit));
  }
}

// Where each statement of the OBJ stands, found by one pass over its lines.
struct ObjLines {
  std::vector<std::size_t> vertex;   // line of the k-th `v`
  std::vector<std::size_t> face;     // line of the k-th `f`
  std::vector<std::pair<std::size_t, std::string>> mtllib;  // line and file name
  std::map<std::string, std::size_t> first_usemtl;          // material name -> first `usemtl` line
};

ObjLines scan_obj(const std::string& path, const std::string& bytes, const ObjReadOptions& options) {
  const std::vector<std::string> lines = split_lines(path, bytes);
  ObjLines at;
  bool any_statement = false;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::size_t line = i + 1;
    const std::vector<std::string> t = tokens_of(lines[i]);
    if (t.empty() || t[0][0] == '#') continue;
    any_statement = true;
    const std::string& key = t[0];
    if (key == "v") {
      check_numbers(path, line, t, 1, 3, options.max_abs_coordinate);
      at.vertex.push_back(line);
    } else if (key == "f") {
      if (t.size() < 4) throw_at(path, line, fmt::format("face has {} vertices, needs at least 3", t.size() - 1));
      for (std::size_t k = 1; k < t.size(); ++k) {
        char* end = nullptr;
        const long index = std::strtol(t[k].c_str(), &end, 10);
        if (end == t[k].c_str() || (*end != '\0' && *end != '/'))
          throw_at(path, line, fmt::format("face index '{}' is not an integer", t[k]));
        const long n = static_cast<long>(at.vertex.size());
        if (index == 0 || index > n || index < -n)
          throw_at(path, line, fmt::format("face index {} out of range ({} vertices defined so far)", index, n));
      }
      at.face.push_back(line);
    } else if (key == "mtllib") {
      if (t.size() < 2) throw_at(path, line, "mtllib names no file");
      at.mtllib.emplace_back(line, t[1]);
    } else if (key == "usemtl") {
      if (t.size() < 2) throw_at(path, line, "usemtl names no material");
      at.first_usemtl.emplace(t[1], line);
    } else if (key == "vt" || key == "vn" || key == "vp" || key == "o" || key == "g" || key == "s" ||
               key == "l" || key == "p") {
      // texture coordinates, normals, groups and smoothing are accepted; lines and points ignored
    } else {
      std::string shown = key.substr(0, 32);
      for (char& ch : shown)
        if (!std::isprint(static_cast<unsigned char>(ch))) ch = '?';
      throw_at(path, line, fmt::format("unknown statement '{}'", shown));
    }
  }
  if (!any_statement) throw_at(path, 0, "empty scene file");
  return at;
}

// Lines of an MTL file: where each material starts and where its Kd and Ke stand.
struct MtlLines {
  std::string path;
  std::map<std::string, std::size_t> newmtl, kd, ke;
};

MtlLines scan_mtl(const std::string& path, const std::string& bytes) {
  const std::vector<std::string> lines = split_lines(path, bytes);
  MtlLines at;
  at.path = path;
  std::string current;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::size_t line = i + 1;
    const std::vector<std::string> t = tokens_of(lines[i]);
    if (t.empty() || t[0][0] == '#') continue;
    if (t[0] == "newmtl") {
      if (t.size() < 2) throw_at(path, line, "newmtl names no material");
      current = t[1];
      at.newmtl[current] = line;
    } else if (t[0] == "Kd" || t[0] == "Ke") {
      if (current.empty()) throw_at(path, line, fmt::format("'{}' before any newmtl", t[0]));
      check_numbers(path, line, t, 1, 3, 1e30);
      (t[0] == "Kd" ? at.kd : at.ke)[current] = line;
    }
  }
  return at;
}

// Reads MTL files from the OBJ's folder, remembering where each was found for messages.
class MtlReader : public tinyobj::MaterialReader {
 public:
  explicit MtlReader(std::string dir) : dir_(std::move(dir)) {}
  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* ids, std::string* warn, std::string* err) override {
    const std::string path = (std::filesystem::path(dir_) / name).string();
    const std::string bytes = read_input_file(path);
    scans.push_back(scan_mtl(path, bytes));  // throws on a malformed file
    files.push_back(path);
    std::istringstream in(bytes);
    tinyobj::LoadMtl(ids, materials, &in, warn, err);
    return true;
  }
  std::vector<MtlLines> scans;
  std::vector<std::string> files;

 private:
  std::string dir_;
};

const MtlLines* find_material(const std::vector<MtlLines>& scans, const std::string& name) {
  for (const MtlLines& s : scans)
    if (s.newmtl.count(name)) return &s;
  return nullptr;
}

Material make_material(const tinyobj::material_t& m, const MtlLines& at) {
  Material out;
  out.name = m.name;
  out.reflectance = Rgb(m.diffuse[0], m.diffuse[1], m.diffuse[2]);
  out.emission = Rgb(m.emission[0], m.emission[1], m.emission[2]);
  const auto line_of = [&](const std::map<std::string, std::size_t>& where) {
    const auto it = where.find(m.name);
    return it != where.end() ? it->second : at.newmtl.at(m.name);
  };
  if ((out.reflectance < 0.0).any() || (out.reflectance >= 1.0).any())
    throw_at(at.path, line_of(at.kd),
             fmt::format("material '{}': reflectance Kd {} {} {} is outside [0, 1)", m.name, out.reflectance[0],
                         out.reflectance[1], out.reflectance[2]));
  if ((out.emission < 0.0).any())
    throw_at(at.path, line_of(at.ke),
             fmt::format("material '{}': emission Ke {} {} {} is negative", m.name, out.emission[0], out.emission[1],
                         out.emission[2]));
  return out;
}

void add_patch(Scene& scene, int face, std::vector<Vec3> vertices) {
  Patch p;
  const Vec3 n = newell_normal(vertices);
  p.area = 0.5 * n.norm();
  p.normal = n.normalized();
  p.vertices = std::move(vertices);
  p.material = scene.faces[face].material;
  p.group = scene.faces[face].group;
  p.face = face;
  scene.faces[face].patches.push_back(static_cast<int>(scene.patches.size()));
  scene.faces[face].area += p.area;
  scene.patches.push_back(std::move(p));
}

}  // namespace

Scene read_obj_scene(const std::string& path, std::vector<std::string>* warnings, const ObjReadOptions& options) {
  const auto warn = [&](std::size_t line, const std::string& message) {
    if (warnings) warnings->push_back(fmt::format("{}:{}: warning: {}", path, line, message));
  };
  const std::string bytes = read_input_file(path);
  const ObjLines at = scan_obj(path, bytes, options);
  for (const auto& [line, name] : at.mtllib) {
    const std::string mtl = (std::filesystem::path(path).parent_path() / name).string();
    std::error_code ec;
    if (!std::filesystem::exists(mtl, ec)) throw_at(path, line, fmt::format("cannot open material library '{}'", name));
  }

  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn_text, err_text;
  MtlReader mtl_reader(std::filesystem::path(path).parent_path().string());
  std::istringstream in(bytes);
  const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn_text, &err_text, &in, &mtl_reader,
                                   /*triangulate=*/false);
  if (!ok || !err_text.empty()) {
    std::string first = err_text.substr(0, err_text.find('\n'));
    throw_at(path, 0, first.empty() ? "cannot be read as OBJ" : first);
  }

  // The line scan validated every face index against its own vertex count: it must be the parser's.
  if (attrib.vertices.size() != 3 * at.vertex.size())
    throw_at(path, 0, fmt::format("{} `v` statements, but {} vertices parsed", at.vertex.size(), attrib.vertices.size() / 3));

  Scene scene;
  scene.path = path;
  scene.files.push_back(path);
  scene.files.insert(scene.files.end(), mtl_reader.files.begin(), mtl_reader.files.end());
  std::map<int, int> material_index;  // tinyobj id -> scene id, only materials faces use
  for (const tinyobj::shape_t& shape : shapes) {
    const tinyobj::mesh_t& mesh = shape.mesh;
    std::size_t offset = 0;
    for (std::size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
      const std::size_t face_number = scene.faces.size();
      if (face_number >= at.face.size()) throw_at(path, 0, "more faces parsed than `f` statements");
      const std::size_t line = at.face[face_number];
      const int mat = mesh.material_ids[f];
      if (mat < 0) throw_at(path, line, "face has no material (no usemtl before it, or the name is not in the MTL)");
      if (!material_index.count(mat)) {
        const MtlLines* where = find_material(mtl_reader.scans, materials[mat].name);
        if (!where) throw_at(path, line, fmt::format("material '{}' is not defined", materials[mat].name));
        material_index[mat] = static_cast<int>(scene.materials.size());
        scene.materials.push_back(make_material(materials[mat], *where));
      }
      InputFace face;
      face.group = shape.name;
      face.material = material_index[mat];
      face.line = line;
      scene.faces.push_back(face);

      std::vector<Vec3> v;
      for (std::size_t k = 0; k < mesh.num_face_vertices[f]; ++k) {
        const int vi = mesh.indices[offset + k].vertex_index;
        if (vi < 0 || 3 * static_cast<std::size_t>(vi) + 2 >= attrib.vertices.size())
          throw_at(path, line, fmt::format("face index {} out of range", vi + 1));
        const Vec3 x(attrib.vertices[3 * vi], attrib.vertices[3 * vi + 1], attrib.vertices[3 * vi + 2]);
        if (v.empty() || x != v.back()) v.push_back(x);
      }
      offset += mesh.num_face_vertices[f];
      while (v.size() > 1 && v.front() == v.back()) v.pop_back();

      const int fi = static_cast<int>(face_number);
      const double diameter = v.size() >= 3 ? polygon_diameter(v) : 0.0;
      const Vec3 n = v.size() >= 3 ? newell_normal(v) : Vec3::Zero();
      // Zero area: relative to the diameter so that the test does not depend on the unit of length.
      if (v.size() < 3 || !(0.5 * n.norm() > 1e-14 * diameter * diameter)) {
        warn(line, "zero-area face skipped");
        continue;
      }
      const Vec3 unit = n.normalized();
      const bool planar = planarity_deviation(v, unit) <= options.planarity_tolerance * diameter;
      if (!planar)
        warn(line, fmt::format("face is non-planar by {:.3g} (diameter {:.3g}): split into triangles",
                               planarity_deviation(v, unit), diameter));
      if (planar && v.size() <= 4 && is_convex(v, unit)) {
        add_patch(scene, fi, v);
        continue;
      }
      for (const auto& tri : triangulate(v, unit)) {
        std::vector<Vec3> t = {v[tri[0]], v[tri[1]], v[tri[2]]};
        if (0.5 * newell_normal(t).norm() > 1e-14 * diameter * diameter) add_patch(scene, fi, std::move(t));
      }
    }
  }
  if (scene.faces.size() != at.face.size()) throw_at(path, 0, "not every `f` statement could be read as a face");
  if (scene.patches.empty()) throw_at(path, 0, "no patch left (no face with a positive area)");
  return scene;
}

}  // namespace hrad
