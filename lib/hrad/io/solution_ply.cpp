#include "hrad/io/solution_ply.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <fmt/format.h>

#include "hrad/core/error.h"
#include "hrad/io/atomic_file.h"
#include "hrad/render/face_geometry.h"
#include "hrad/render/tone_map.h"

namespace hrad {
namespace {

struct PlyTraits : OpenMesh::DefaultTraitsDouble {
  typedef OpenMesh::Vec3uc Color;
};
using PlyMesh = OpenMesh::PolyMesh_ArrayKernelT<PlyTraits>;

constexpr const char* kChannel[3] = {"radiosity_r", "radiosity_g", "radiosity_b"};
constexpr const char* kPatch = "patch";

void check_consistent(const std::string& path, const Solution& s) {
  auto fail = [&](const std::string& what) { throw Error(fmt::format("{}: cannot write solution: {}", path, what)); };
  if (s.vertex_radiosity.size() != s.vertices.size())
    fail(fmt::format("{} vertex radiosities for {} vertices", s.vertex_radiosity.size(), s.vertices.size()));
  if (s.face_radiosity.size() != s.faces.size() || s.face_patch.size() != s.faces.size())
    fail(fmt::format("{} faces but {} face radiosities and {} patch ids", s.faces.size(), s.face_radiosity.size(),
                     s.face_patch.size()));
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    if (s.faces[f].size() < 3) fail(fmt::format("face {} has {} vertices", f, s.faces[f].size()));
    for (int v : s.faces[f])
      if (v < 0 || static_cast<std::size_t>(v) >= s.vertices.size())
        fail(fmt::format("face {} has vertex index {} out of range", f, v));
    if (s.face_patch[f] < 0) fail(fmt::format("face {} has patch id {}", f, s.face_patch[f]));
  }
}

// OpenMesh's PLY reader loops without end (growing memory) on some truncated files, e.g. a
// header cut before end_header. So the structure is checked here first: the header's syntax and
// that the body holds every record the header announces.
struct PlyProperty {
  int size = 0;        ///< scalar size in bytes, or the list items' size
  int count_size = 0;  ///< list count size in bytes; 0 for a scalar
};
struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::vector<PlyProperty> properties;
};

int ply_type_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "int32" || t == "uint32" || t == "float" || t == "float32") return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

/// Returns the header's element counts by name.
std::map<std::string, std::size_t> check_ply_structure(const std::string& path, const std::string& bytes) {
  auto fail = [&](const std::string& what) { throw Error(fmt::format("{}: not a readable PLY file: {}", path, what)); };
  const std::size_t header_end = bytes.find("end_header");
  if (bytes.rfind("ply", 0) != 0) fail("it does not start with 'ply'");
  if (header_end == std::string::npos) fail("no end_header");
  std::size_t body = bytes.find('\n', header_end);
  if (body == std::string::npos) fail("nothing after end_header");
  ++body;
  std::istringstream header(bytes.substr(0, header_end));
  std::string line, format;
  std::vector<PlyElement> elements;
  std::size_t line_no = 0;
  while (std::getline(header, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "format") {
      std::string version;
      words >> format >> version;
    } else if (key == "element") {
      PlyElement e;
      long long count = -1;
      if (!(words >> e.name >> count) || count < 0 || count > 2'000'000'000LL)
        fail(fmt::format("header line {}: bad element line '{}'", line_no, line));
      e.count = static_cast<std::size_t>(count);
      elements.push_back(e);
    } else if (key == "property") {
      if (elements.empty()) fail(fmt::format("header line {}: property before any element", line_no));
      std::string type;
      words >> type;
      PlyProperty prop;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type;
        prop.count_size = ply_type_size(count_type);
        prop.size = ply_type_size(item_type);
        if (prop.count_size == 0 || prop.size == 0) fail(fmt::format("header line {}: bad list type '{}'", line_no, line));
      } else {
        prop.size = ply_type_size(type);
        if (prop.size == 0) fail(fmt::format("header line {}: unknown type in '{}'", line_no, line));
      }
      elements.back().properties.push_back(prop);
    }
  }
  std::map<std::string, std::size_t> counts;
  for (const PlyElement& e : elements) counts[e.name] = e.count;
  const bool ascii = format == "ascii";
  const bool little = format == "binary_little_endian";
  if (!ascii && !little && format != "binary_big_endian") fail(fmt::format("unknown format '{}'", format));

  if (ascii) {  // count the tokens each record needs
    std::istringstream in(bytes.substr(body));
    std::string token;
    for (const PlyElement& e : elements)
      for (std::size_t r = 0; r < e.count; ++r)
        for (const PlyProperty& prop : e.properties) {
          if (!(in >> token)) fail(fmt::format("truncated in element '{}' record {}", e.name, r));
          if (prop.count_size == 0) continue;
          long long n = -1;
          try {
            n = std::stoll(token);
          } catch (const std::exception&) {
          }
          if (n < 0 || n > 1'000'000) fail(fmt::format("bad list length '{}' in element '{}' record {}", token, e.name, r));
          for (long long k = 0; k < n; ++k)
            if (!(in >> token)) fail(fmt::format("truncated in element '{}' record {}", e.name, r));
        }
    return counts;
  }
  std::size_t at = body;
  for (const PlyElement& e : elements)
    for (std::size_t r = 0; r < e.count; ++r)
      for (const PlyProperty& prop : e.properties) {
        std::size_t n = 1;
        if (prop.count_size != 0) {
          if (at + prop.count_size > bytes.size()) fail(fmt::format("truncated in element '{}' record {}", e.name, r));
          n = 0;
          for (int k = 0; k < prop.count_size; ++k) {
            const std::size_t byte = static_cast<unsigned char>(bytes[at + (little ? prop.count_size - 1 - k : k)]);
            n = (n << 8) | byte;
          }
          if (n > 1'000'000) fail(fmt::format("bad list length {} in element '{}' record {}", n, e.name, r));
          at += prop.count_size;
        }
        at += n * prop.size;
        if (at > bytes.size()) fail(fmt::format("truncated in element '{}' record {}", e.name, r));
      }
  return counts;
}

/// add_face without OpenMesh's "complex edge" message: the caller handles the failure.
OpenMesh::FaceHandle add_face_quietly(PlyMesh& mesh, const std::vector<OpenMesh::VertexHandle>& vertices) {
  const bool was_enabled = omerr().is_enabled();
  omerr().disable();
  const OpenMesh::FaceHandle fh = mesh.add_face(vertices);
  if (was_enabled) omerr().enable();
  return fh;
}

}  // namespace

void write_solution_ply(const std::string& path, const Solution& solution, double exposure) {
  check_consistent(path, solution);
  PlyMesh mesh;
  mesh.request_vertex_colors();
  OpenMesh::VPropHandleT<double> vrad[3];
  OpenMesh::FPropHandleT<double> frad[3];
  OpenMesh::FPropHandleT<int> fpatch;
  for (int c = 0; c < 3; ++c) {
    mesh.add_property(vrad[c], kChannel[c]);
    mesh.property(vrad[c]).set_persistent(true);
    mesh.add_property(frad[c], kChannel[c]);
    mesh.property(frad[c]).set_persistent(true);
  }
  mesh.add_property(fpatch, kPatch);
  mesh.property(fpatch).set_persistent(true);

  auto add_vertex = [&](int i) {
    const Vec3& p = solution.vertices[i];
    const OpenMesh::VertexHandle vh = mesh.add_vertex(PlyMesh::Point(p.x(), p.y(), p.z()));
    const Rgb8 rgb = tone_map(solution.vertex_radiosity[i], exposure);
    mesh.set_color(vh, PlyMesh::Color(rgb[0], rgb[1], rgb[2]));
    for (int c = 0; c < 3; ++c) mesh.property(vrad[c], vh) = solution.vertex_radiosity[i][c];
    return vh;
  };
  std::vector<OpenMesh::VertexHandle> handles;
  handles.reserve(solution.vertices.size());
  for (std::size_t i = 0; i < solution.vertices.size(); ++i) handles.push_back(add_vertex(static_cast<int>(i)));

  std::vector<OpenMesh::VertexHandle> face_handles;
  for (std::size_t f = 0; f < solution.faces.size(); ++f) {
    face_handles.clear();
    for (int v : solution.faces[f]) face_handles.push_back(handles[v]);
    OpenMesh::FaceHandle fh = add_face_quietly(mesh, face_handles);
    if (!fh.is_valid()) {  // non-manifold here: give the face its own vertices (see header)
      face_handles.clear();
      for (int v : solution.faces[f]) face_handles.push_back(add_vertex(v));
      fh = mesh.add_face(face_handles);
      if (!fh.is_valid()) throw Error(fmt::format("{}: cannot write solution: face {} is degenerate", path, f));
    }
    for (int c = 0; c < 3; ++c) mesh.property(frad[c], fh) = solution.face_radiosity[f][c];
    mesh.property(fpatch, fh) = solution.face_patch[f];
  }

  const OpenMesh::IO::Options options =
      OpenMesh::IO::Options::Binary | OpenMesh::IO::Options::VertexColor | OpenMesh::IO::Options::Custom;
  write_file_atomically(
      path,
      [&](std::ostream& out) {
        if (!OpenMesh::IO::write_mesh(mesh, out, ".ply", options, 17))
          throw Error(fmt::format("{}: PLY writer failed", path));
      },
      /*binary=*/true);
}

Solution read_solution_ply(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file || std::filesystem::is_directory(path)) throw Error(fmt::format("{}: cannot open solution PLY", path));
  const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const std::map<std::string, std::size_t> counts = check_ply_structure(path, bytes);
  std::istringstream in(bytes);
  PlyMesh mesh;
  OpenMesh::IO::Options options = OpenMesh::IO::Options::Custom;
  if (!OpenMesh::IO::read_mesh(mesh, in, ".ply", options))
    throw Error(fmt::format("{}: not a readable PLY file", path));
  if (counts.contains("face") && mesh.n_faces() != counts.at("face"))
    throw Error(fmt::format("{}: {} of {} faces are invalid (vertex index out of range, repeated or non-manifold)", path,
                            counts.at("face") - mesh.n_faces(), counts.at("face")));
  if (counts.contains("vertex") && mesh.n_vertices() != counts.at("vertex"))
    throw Error(fmt::format("{}: {} vertices read but the header announces {} (OpenMesh duplicated vertices of "
                            "non-manifold faces)",
                            path, mesh.n_vertices(), counts.at("vertex")));

  OpenMesh::VPropHandleT<double> vrad[3];
  OpenMesh::FPropHandleT<double> frad[3];
  OpenMesh::FPropHandleT<int> fpatch;
  for (int c = 0; c < 3; ++c) {
    if (!mesh.get_property_handle(vrad[c], kChannel[c]))
      throw Error(fmt::format("{}: not an hrad solution: no double vertex property '{}'", path, kChannel[c]));
    if (!mesh.get_property_handle(frad[c], kChannel[c]))
      throw Error(fmt::format("{}: not an hrad solution: no double face property '{}'", path, kChannel[c]));
  }
  if (!mesh.get_property_handle(fpatch, kPatch))
    throw Error(fmt::format("{}: not an hrad solution: no int face property '{}'", path, kPatch));

  Solution s;
  s.vertices.reserve(mesh.n_vertices());
  for (const auto vh : mesh.vertices()) {
    const PlyMesh::Point& p = mesh.point(vh);
    s.vertices.emplace_back(p[0], p[1], p[2]);
    s.vertex_radiosity.emplace_back(mesh.property(vrad[0], vh), mesh.property(vrad[1], vh), mesh.property(vrad[2], vh));
    if (!s.vertices.back().allFinite() || !s.vertex_radiosity.back().allFinite())
      throw Error(fmt::format("{}: vertex {} has a non-finite position or radiosity", path, vh.idx()));
  }
  int patches = 0;
  for (const auto fh : mesh.faces()) {
    std::vector<int> face;
    for (const auto vh : mesh.fv_range(fh)) face.push_back(vh.idx());
    s.faces.push_back(std::move(face));
    s.face_radiosity.emplace_back(mesh.property(frad[0], fh), mesh.property(frad[1], fh), mesh.property(frad[2], fh));
    const int p = mesh.property(fpatch, fh);
    if (p < 0) throw Error(fmt::format("{}: face {} has a negative patch id {}", path, fh.idx(), p));
    if (!s.face_radiosity.back().allFinite())
      throw Error(fmt::format("{}: face {} has a non-finite radiosity", path, fh.idx()));
    s.face_patch.push_back(p);
    patches = std::max(patches, p + 1);
  }

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

}  // namespace hrad
