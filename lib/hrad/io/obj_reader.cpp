#include "hrad/io/obj_reader.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include <fmt/format.h>

#define TINYOBJLOADER_USE_DOUBLE
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>

#include "hrad/core/error.h"
#include "hrad/geometry/polygon.h"
#include "hrad/io/input_file.h"
#include "hrad/io/scene_directives.h"
#include "hrad/io/scene_faces.h"

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

std::string trim(const std::string& text) {
  const std::size_t a = text.find_first_not_of(" \t");
  if (a == std::string::npos) return "";
  return text.substr(a, text.find_last_not_of(" \t") - a + 1);
}

/// The rest of a statement after its keyword, trimmed, without surrounding double quotes.
std::string argument_of(const std::string& line, const std::string& key) {
  std::string rest = trim(trim(line).substr(key.size()));
  if (rest.size() >= 2 && rest.front() == '"' && rest.back() == '"') rest = rest.substr(1, rest.size() - 2);
  return rest;
}

std::vector<std::string> split_lines(const std::string& path, const std::string& bytes) {
  std::vector<std::string> lines;
  std::istringstream in(bytes);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    // A UTF-8 byte order mark (Windows exporters write one) is not part of the first statement.
    if (lines.empty() && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);
    if (line.find('\0') != std::string::npos) throw_at(path, lines.size() + 1, "binary data in a text file");
    // tinyobjloader ends a line at a lone carriage return too: refuse what the two passes would
    // read differently (a fuzzer found "v\r 5 0 0" counted as a vertex here and not there).
    if (line.find('\r') != std::string::npos) throw_at(path, lines.size() + 1, "carriage return inside a line");
    // A comment after a statement ("f 1 2 3 # back wall"): tinyobjloader would read '#' as an index.
    // Not after a material, object or group name: 3ds Max names materials "Material #25", "Material
    // #26", which would all become one "Material". (File names after mtllib lose a trailing comment.)
    if (const std::size_t hash = line.find('#'); hash != std::string::npos && hash > 0) {
      const std::size_t first = line.find_first_not_of(" \t");
      const std::vector<std::string> t = first < hash ? tokens_of(line) : std::vector<std::string>{};
      const bool names = !t.empty() && (t[0] == "newmtl" || t[0] == "usemtl" || t[0] == "o" || t[0] == "g");
      if (first < hash && !names && (line[hash - 1] == ' ' || line[hash - 1] == '\t')) line.erase(hash);
    }
    lines.push_back(std::move(line));
  }
  return lines;
}

std::string join_lines(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& l : lines) text += l + "\n";
  return text;
}

/// A decimal number as both passes read it: std::from_chars, an optional leading '+', nothing else
/// (strtod would read the hex float "0x1p2" as 4, tinyobjloader reads it as 0).
std::optional<double> parse_number(const std::string& token) {
  const char* first = token.data();
  const char* last = first + token.size();
  if (first != last && *first == '+') ++first;
  double x = 0.0;
  const auto [end, ec] = std::from_chars(first, last, x, std::chars_format::general);
  if (ec != std::errc() || end != last) return std::nullopt;
  return x;
}

/// Digits after the decimal point of a number printed in fixed notation ("0.123456" -> 6), or -1
/// (no point, or an exponent).
int fixed_decimals(const std::string& token) {
  const std::size_t dot = token.find('.');
  if (dot == std::string::npos || token.find_first_of("eE") != std::string::npos) return -1;
  return static_cast<int>(token.size() - dot - 1);
}

/// Checks that tokens [first, first + count) of `t` are finite numbers within `limit`, and returns them.
std::vector<double> check_numbers(const std::string& file, std::size_t line, const std::vector<std::string>& t,
                                  std::size_t first, std::size_t count, double limit) {
  if (t.size() < first + count)
    throw_at(file, line, fmt::format("'{}' needs {} numbers, got {}", t[0], count, t.size() - first));
  std::vector<double> values;
  for (std::size_t i = first; i < first + count; ++i) {
    const std::optional<double> x = parse_number(t[i]);
    if (!x) throw_at(file, line, fmt::format("'{}' is not a number", t[i]));
    if (!std::isfinite(*x)) throw_at(file, line, fmt::format("'{}' is not a finite number", t[i]));
    if (std::abs(*x) > limit) throw_at(file, line, fmt::format("'{}' is out of range (|x| > {:g})", t[i], limit));
    values.push_back(*x);
  }
  return values;
}

// Material names reach tinyobjloader as short ids: it takes the whole rest of a `newmtl` line but
// only the first word of a `usemtl` line, so "Material 1" (spaces, as Blender and SketchUp write
// names) or a quoted name would not match. Both files are rewritten line for line with the ids.
class MaterialNames {
 public:
  std::string id_of(const std::string& name) {
    const auto [it, inserted] = ids_.try_emplace(name, "m" + std::to_string(ids_.size()));
    if (inserted) names_[it->second] = name;
    return it->second;
  }
  std::string name_of(const std::string& id) const {
    const auto it = names_.find(id);
    return it == names_.end() ? id : it->second;
  }

 private:
  std::map<std::string, std::string> ids_, names_;
};

// Where each statement of the OBJ stands, found by one pass over its (rewritten) lines.
struct ObjLines {
  std::vector<std::string> text;    // the lines as tinyobjloader reads them
  std::vector<std::size_t> vertex;  // line of the k-th `v`
  std::vector<double> coordinates;  // x y z of the k-th `v`, as this pass read them
  int decimals = -1;                // the decimals every fixed-notation coordinate has; -2 when they differ
  std::vector<std::size_t> face;    // line of the k-th `f`
  std::vector<std::vector<std::string>> mtllib;     // the files of the k-th `mtllib` line
  std::map<std::string, std::size_t> first_usemtl;  // material id -> first `usemtl` line
  std::vector<std::pair<std::size_t, std::string>> comments;  // line and text after '#' of comment lines
};

/// Records a comment line (text after its '#') for the scene's declarations (scene_directives.h).
void note_comment(std::vector<std::pair<std::size_t, std::string>>& comments, std::size_t line,
                  const std::string& text) {
  comments.emplace_back(line, text.substr(text.find('#') + 1));
}

/// The files an `mtllib` line names: the whole argument when such a file exists (a name with
/// spaces, as Blender writes "my scene.mtl"), else its words (several libraries on one line).
std::vector<std::string> mtllib_files(const std::string& path, std::size_t line, const std::string& argument) {
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (std::filesystem::exists(dir / argument, ec)) return {argument};
  std::vector<std::string> files;
  for (std::string name : tokens_of(argument)) {
    if (name.size() >= 2 && name.front() == '"' && name.back() == '"') name = name.substr(1, name.size() - 2);
    if (!std::filesystem::exists(dir / name, ec))
      throw_at(path, line, fmt::format("cannot open material library '{}'", name));
    files.push_back(name);
  }
  return files;
}

ObjLines scan_obj(const std::string& path, const std::string& bytes, const ObjReadOptions& options,
                  MaterialNames& names) {
  ObjLines at;
  at.text = split_lines(path, bytes);
  bool any_statement = false;
  ProgressReporter progress(fmt::format("reading {}", path), at.text.size(), "lines", options.progress);
  for (std::size_t i = 0; i < at.text.size(); ++i) {
    const std::size_t line = i + 1;
    progress.advance();
    const std::vector<std::string> t = tokens_of(at.text[i]);
    if (!t.empty() && t[0][0] == '#') note_comment(at.comments, line, at.text[i]);
    if (t.empty() || t[0][0] == '#') continue;
    any_statement = true;
    const std::string& key = t[0];
    if (key == "v") {
      // 3 coordinates, optionally a weight or a colour after them (ignored).
      const std::vector<double> x = check_numbers(path, line, t, 1, 3, options.max_abs_coordinate);
      at.coordinates.insert(at.coordinates.end(), x.begin(), x.end());
      for (int k = 1; k <= 3; ++k) {
        const int d = fixed_decimals(t[static_cast<std::size_t>(k)]);
        if (d >= 0) at.decimals = at.decimals == -1 || at.decimals == d ? d : -2;
      }
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
      const std::string argument = argument_of(at.text[i], key);
      if (argument.empty()) throw_at(path, line, "mtllib names no file");
      at.mtllib.push_back(mtllib_files(path, line, argument));
      at.text[i] = "mtllib " + std::to_string(at.mtllib.size() - 1);  // MtlReader reads the list
    } else if (key == "usemtl") {
      const std::string name = argument_of(at.text[i], key);
      if (name.empty()) throw_at(path, line, "usemtl names no material");
      at.text[i] = "usemtl " + names.id_of(name);
      at.first_usemtl.emplace(names.id_of(name), line);
    } else if (key == "vt" || key == "vn" || key == "vp" || key == "o" || key == "g" || key == "s" || key == "l" ||
               key == "p") {
      // texture coordinates, normals, groups and smoothing are accepted; lines and points ignored
    } else {
      std::string shown = key.substr(0, 32);
      for (char& ch : shown)
        if (!std::isprint(static_cast<unsigned char>(ch))) ch = '?';
      throw_at(path, line, fmt::format("unknown statement '{}'", shown));
    }
  }
  if (!any_statement) throw_at(path, 0, "empty scene file");
  progress.finish();
  return at;
}

// Lines of an MTL file: where each material starts and where its Kd and Ke stand.
struct MtlLines {
  std::string path;
  std::vector<std::string> text;  // the lines as tinyobjloader reads them
  std::map<std::string, std::size_t> newmtl, kd, ke;
  std::map<std::string, Rgb> kd_value,
      ke_value;  // as this pass read them (tinyobjloader's parser is off by an ulp at times)
  std::vector<std::pair<std::size_t, std::string>> comments;
};

MtlLines scan_mtl(const std::string& path, const std::string& bytes, MaterialNames& names) {
  MtlLines at;
  at.path = path;
  at.text = split_lines(path, bytes);
  std::string current;
  for (std::size_t i = 0; i < at.text.size(); ++i) {
    const std::size_t line = i + 1;
    const std::vector<std::string> t = tokens_of(at.text[i]);
    if (!t.empty() && t[0][0] == '#') note_comment(at.comments, line, at.text[i]);
    if (t.empty() || t[0][0] == '#') continue;
    if (t[0] == "newmtl") {
      const std::string name = argument_of(at.text[i], "newmtl");
      if (name.empty()) throw_at(path, line, "newmtl names no material");
      current = names.id_of(name);
      at.newmtl[current] = line;
      at.text[i] = "newmtl " + current;
    } else if (t[0] == "Kd" || t[0] == "Ke" || t[0] == "Ka" || t[0] == "Ks" || t[0] == "Tf") {
      if (current.empty()) throw_at(path, line, fmt::format("'{}' before any newmtl", t[0]));
      // The MTL format allows one value for all three channels ("Kd 0.7"); tinyobjloader would read
      // the missing ones as 0, so the line is given three.
      if (t.size() == 2) at.text[i] = fmt::format("{} {} {} {}", t[0], t[1], t[1], t[1]);
      const std::vector<double> x = check_numbers(path, line, tokens_of(at.text[i]), 1, 3, 1e30);
      if (t[0] == "Kd") {
        at.kd[current] = line;
        at.kd_value[current] = Rgb(x[0], x[1], x[2]);
      }
      if (t[0] == "Ke") {
        at.ke[current] = line;
        at.ke_value[current] = Rgb(x[0], x[1], x[2]);
      }
    }
  }
  return at;
}

// Reads the MTL files of the k-th `mtllib` line (tinyobjloader calls it with "k": see scan_obj),
// all of them, from the OBJ's folder, remembering where each was found for messages.
class MtlReader : public tinyobj::MaterialReader {
 public:
  MtlReader(std::string dir, const ObjLines& obj, MaterialNames& names)
      : dir_(std::move(dir)), obj_(obj), names_(names) {}
  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials, std::map<std::string, int>* ids,
                  std::string* warn, std::string* err) override {
    const std::size_t k = static_cast<std::size_t>(std::stoul(name));
    for (const std::string& file : obj_.mtllib.at(k)) {
      const std::string path = (std::filesystem::path(dir_) / file).string();
      if (std::find(files.begin(), files.end(), path) != files.end()) continue;
      scans.push_back(scan_mtl(path, read_input_file(path), names_));  // throws on a malformed file
      files.push_back(path);
      std::istringstream in(join_lines(scans.back().text));
      tinyobj::LoadMtl(ids, materials, &in, warn, err);
    }
    return true;
  }
  std::vector<MtlLines> scans;
  std::vector<std::string> files;

 private:
  std::string dir_;
  const ObjLines& obj_;
  MaterialNames& names_;
};

const MtlLines* find_material(const std::vector<MtlLines>& scans, const std::string& id) {
  for (const MtlLines& s : scans)
    if (s.newmtl.count(id)) return &s;
  return nullptr;
}

Material make_material(const tinyobj::material_t& m, const MtlLines& at, const MaterialNames& names) {
  Material out;
  out.name = names.name_of(m.name);
  const auto kd = at.kd_value.find(m.name);
  const auto ke = at.ke_value.find(m.name);
  out.reflectance = kd != at.kd_value.end() ? kd->second : Rgb(m.diffuse[0], m.diffuse[1], m.diffuse[2]);
  out.emission = ke != at.ke_value.end() ? ke->second : Rgb(m.emission[0], m.emission[1], m.emission[2]);
  const auto line_of = [&](const std::map<std::string, std::size_t>& where) {
    const auto it = where.find(m.name);
    return it != where.end() ? it->second : at.newmtl.at(m.name);
  };
  if ((out.reflectance < 0.0).any() || (out.reflectance >= 1.0).any())
    throw_at(at.path, line_of(at.kd),
             fmt::format("material '{}': reflectance Kd {} {} {} is outside [0, 1)", out.name, out.reflectance[0],
                         out.reflectance[1], out.reflectance[2]));
  if ((out.emission < 0.0).any())
    throw_at(at.path, line_of(at.ke),
             fmt::format("material '{}': emission Ke {} {} {} is negative", out.name, out.emission[0], out.emission[1],
                         out.emission[2]));
  return out;
}

}  // namespace

Scene read_obj_scene(const std::string& path, std::vector<std::string>* warnings, const ObjReadOptions& options) {
  MaterialNames names;
  const ObjLines at = scan_obj(path, read_input_file(path), options, names);

  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn_text, err_text;
  MtlReader mtl_reader(std::filesystem::path(path).parent_path().string(), at, names);
  std::istringstream in(join_lines(at.text));
  const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn_text, &err_text, &in, &mtl_reader,
                                   /*triangulate=*/false);
  if (!ok || !err_text.empty()) {
    std::string first = err_text.substr(0, err_text.find('\n'));
    throw_at(path, 0, first.empty() ? "cannot be read as OBJ" : first);
  }

  // The line scan validated every face index against its own vertices: they must be the parser's.
  // Positions are the scan's numbers (std::from_chars, correctly rounded; tinyobjloader's own parser
  // reads 0.057678 one ulp off); the parser's must agree to far better than any real difference
  // (the hex float "0x1p2": 4 for strtod, 0 for tinyobjloader), else the file is refused.
  if (attrib.vertices.size() != at.coordinates.size())
    throw_at(path, 0,
             fmt::format("{} `v` statements, but {} vertices parsed", at.vertex.size(), attrib.vertices.size() / 3));
  for (std::size_t i = 0; i < at.coordinates.size(); ++i)
    if (!(std::abs(attrib.vertices[i] - at.coordinates[i]) <= 1e-12 * std::abs(at.coordinates[i])))
      throw_at(path, at.vertex[i / 3],
               fmt::format("coordinate read as {} by the line scan but {} by the OBJ parser", at.coordinates[i],
                           attrib.vertices[i]));

  Scene scene;
  scene.path = path;
  scene.files.push_back(path);
  scene.files.insert(scene.files.end(), mtl_reader.files.begin(), mtl_reader.files.end());
  for (const auto& [line, text] : at.comments) detail::apply_scene_comment(scene, path, line, text);
  for (const MtlLines& mtl : mtl_reader.scans)
    for (const auto& [line, text] : mtl.comments) detail::apply_scene_comment(scene, mtl.path, line, text);
  std::map<int, int> material_index;  // tinyobj id -> scene id, only materials faces use
  // The file's printed precision: an exporter writing every coordinate with the same d >= 3 decimals
  // (Blender: 6, "%.6f") rounded them to 10^-d; a file printing shortest round-trip numbers (or few
  // decimals, as hand-written files and the published Cornell box do) is taken as exact.
  const double step = at.decimals >= 3 ? std::pow(10.0, -at.decimals) : 0.0;
  detail::FaceTallies tallies;
  for (const tinyobj::shape_t& shape : shapes) {
    const tinyobj::mesh_t& mesh = shape.mesh;
    std::size_t offset = 0;
    for (std::size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
      const std::size_t face_number = scene.faces.size();
      if (face_number >= at.face.size()) throw_at(path, 0, "more faces parsed than `f` statements");
      InputFace face;
      face.group = shape.name;
      face.line = at.face[face_number];
      const int mat = mesh.material_ids[f];
      if (mat < 0) {
        // No usemtl before the face, or a name no MTL defines: the default material, with a warning.
        face.material = detail::default_material(scene, face.line, tallies);
      } else {
        if (!material_index.count(mat)) {
          const MtlLines* where = find_material(mtl_reader.scans, materials[mat].name);
          if (!where)
            throw_at(path, face.line, fmt::format("material '{}' is not defined", names.name_of(materials[mat].name)));
          material_index[mat] = static_cast<int>(scene.materials.size());
          scene.materials.push_back(make_material(materials[mat], *where, names));
        }
        face.material = material_index[mat];
      }
      std::vector<Vec3> v;
      for (std::size_t k = 0; k < mesh.num_face_vertices[f]; ++k) {
        const int vi = mesh.indices[offset + k].vertex_index;
        if (vi < 0 || 3 * static_cast<std::size_t>(vi) + 2 >= attrib.vertices.size())
          throw_at(path, face.line, fmt::format("face index {} out of range", vi + 1));
        v.emplace_back(at.coordinates[3 * vi], at.coordinates[3 * vi + 1], at.coordinates[3 * vi + 2]);
      }
      offset += mesh.num_face_vertices[f];
      detail::add_input_face(scene, std::move(face), std::move(v), step, options, tallies);
    }
  }
  if (scene.faces.size() != at.face.size()) throw_at(path, 0, "not every `f` statement could be read as a face");
  detail::report_tallies(path, tallies, warnings);
  if (scene.patches.empty()) throw_at(path, 0, "no patch left (no face with a positive area)");
  return scene;
}

}  // namespace hrad
