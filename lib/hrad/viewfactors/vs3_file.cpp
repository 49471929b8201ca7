#include "hrad/viewfactors/vs3_file.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include <fmt/format.h>

#include "hrad/core/error.h"
#include "hrad/formfactor/clip_polygon.h"
#include "hrad/geometry/polygon.h"
#include "hrad/io/scene_faces.h"

namespace hrad {
namespace {

struct Record {
  char type = 'S';
  std::size_t line = 0;
  std::vector<int> vertices;  // 0-based
  int base = 0, cmb = 0;      // 1-based, 0 = none
  double emit = 1.0;
  std::string name;
};

class LineReader {
 public:
  LineReader(const std::string& path, std::size_t line, const std::string& text)
      : path_(path), line_(line), in_(text) {}
  bool next(std::string* word) { return static_cast<bool>(in_ >> *word); }
  std::string word(const char* what) {
    std::string w;
    if (!next(&w)) throw_at(path_, line_, fmt::format("missing {}", what));
    return w;
  }
  double number(const char* what) { return to_number(word(what), what); }
  int integer(const char* what) {
    const std::string w = word(what);
    int value = 0;
    const auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), value);
    if (ec != std::errc() || end != w.data() + w.size())
      throw_at(path_, line_, fmt::format("{}: '{}' is not an integer", what, w));
    return value;
  }
  double to_number(const std::string& w, const char* what) const {
    double value = 0.0;
    const char* begin = w.data() + (!w.empty() && w[0] == '+' ? 1 : 0);
    const auto [end, ec] = std::from_chars(begin, w.data() + w.size(), value);
    if (ec != std::errc() || end != w.data() + w.size() || !std::isfinite(value))
      throw_at(path_, line_, fmt::format("{}: '{}' is not a finite number", what, w));
    return value;
  }
  std::string rest() {
    std::string r, w;
    while (next(&w)) r += (r.empty() ? "" : " ") + w;
    return r;
  }

 private:
  const std::string& path_;
  std::size_t line_;
  std::istringstream in_;
};

// The pieces of the convex polygon `piece` outside the convex polygon `hole` (both counter-clockwise
// about `n`): for each edge of the hole in turn, the part of what is left outside that edge's line.
void subtract_convex(const std::vector<Vec3>& piece, const std::vector<Vec3>& hole, const Vec3& n,
                     std::vector<std::vector<Vec3>>& out) {
  std::vector<Vec3> rest = piece, part, inside;
  std::vector<double> d;
  for (std::size_t k = 0; k < hole.size() && rest.size() >= 3; ++k) {
    const Vec3& a = hole[k];
    const Vec3 inward = n.cross(hole[(k + 1) % hole.size()] - a);
    d.resize(rest.size());
    for (std::size_t i = 0; i < rest.size(); ++i) d[i] = -inward.dot(rest[i] - a);
    detail::clip_to_half_space(rest, d, part);
    if (part.size() >= 3) out.push_back(part);
    for (double& x : d) x = -x;
    detail::clip_to_half_space(rest, d, inside);
    rest.swap(inside);
  }
}

}  // namespace

Vs3Model read_vs3(const std::string& path, std::vector<std::string>* warnings) {
  std::ifstream in(path);
  if (!in) throw_at(path, 0, "cannot open");
  Vs3Model model;
  model.scene.path = path;
  model.scene.files = {path};
  std::vector<Vec3> vertices;
  std::vector<Record> surfaces;
  bool have_format = false, ended = false;
  std::size_t line_no = 0;
  for (std::string text; !ended && std::getline(in, text);) {
    ++line_no;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    LineReader r(path, line_no, text);
    std::string type;
    if (!r.next(&type) || type[0] == '!') continue;
    if (type == "T") {
      model.title = r.rest();
    } else if (type == "C") {
      for (std::string kv; r.next(&kv);) {
        const std::size_t eq = kv.find('=');
        const std::string key = kv.substr(0, eq);
        if (eq == std::string::npos) throw_at(path, line_no, fmt::format("control '{}' is not key=value", kv));
        static const char* known[] = {"encl", "list", "eps",  "maxU", "maxO", "minO",
                                      "row",  "col",  "emit", "out",  "prjD"};
        if (std::find_if(std::begin(known), std::end(known), [&](const char* k) { return key == k; }) ==
            std::end(known))
          throw_at(path, line_no,
                   fmt::format("unknown control '{}' (encl, list, eps, maxU, maxO, minO, row, col, emit, out)", key));
        const double value = r.to_number(kv.substr(eq + 1), key.c_str());
        if (key == "encl") model.enclosure = value != 0.0;
      }
    } else if (type == "F") {
      const int f = r.integer("format");
      if (f == 2) throw_at(path, line_no, "two-dimensional geometry (F 2) is not supported");
      if (f != 3) throw_at(path, line_no, fmt::format("format {} is not 3", f));
      have_format = true;
    } else if (type == "V") {
      if (!have_format) throw_at(path, line_no, "vertex before the F 3 line");
      const int n = r.integer("vertex number");
      if (n != static_cast<int>(vertices.size()) + 1)
        throw_at(path, line_no, fmt::format("vertex {} out of order (expected {})", n, vertices.size() + 1));
      const double x = r.number("x"), y = r.number("y"), z = r.number("z");
      vertices.emplace_back(x, y, z);
    } else if (type == "S" || type == "M" || type == "N" || type == "O") {
      if (!have_format) throw_at(path, line_no, "surface before the F 3 line");
      Record s;
      s.type = type[0];
      s.line = line_no;
      const int n = r.integer("surface number");
      if (n != static_cast<int>(surfaces.size()) + 1)
        throw_at(path, line_no, fmt::format("surface {} out of order (expected {})", n, surfaces.size() + 1));
      for (int k = 0; k < 4; ++k) {
        const int v = r.integer("vertex");
        if (k == 3 && v == 0) break;
        if (v < 1 || v > static_cast<int>(vertices.size()))
          throw_at(path, line_no, fmt::format("vertex {} is not defined ({} vertices so far)", v, vertices.size()));
        s.vertices.push_back(v - 1);
      }
      s.base = r.integer("base");
      s.cmb = r.integer("cmb");
      s.emit = r.number("emit");
      s.name = r.rest();
      if (!(s.emit > 0.0 && s.emit <= 1.0))
        throw_at(path, line_no, fmt::format("emissivity {} is not in (0, 1]", s.emit));
      if ((s.type == 'M' || s.type == 'N') == (s.base == 0))
        throw_at(path, line_no,
                 s.base == 0 ? "a mask or null surface needs its base surface"
                             : "only mask (M) and null (N) surfaces have a base");
      if (s.base != 0 && (s.base < 1 || s.base > n - 1 || surfaces[static_cast<std::size_t>(s.base - 1)].type != 'S'))
        throw_at(path, line_no, fmt::format("base {} is not an earlier S surface", s.base));
      if (s.cmb < 0 || s.cmb == n) throw_at(path, line_no, fmt::format("cmb {} is not another surface", s.cmb));
      surfaces.push_back(std::move(s));
    } else if (type == "E" || type == "End" || type == "END") {
      ended = true;
    } else {
      throw_at(path, line_no, fmt::format("unknown record '{}' (T, C, F, V, S, M, N, O, End)", type));
    }
  }
  if (!have_format) throw_at(path, 0, "no F 3 line");
  if (surfaces.empty()) throw_at(path, 0, "no surface");

  // Combined surfaces share their target's unit (chains followed; a cycle or a combination into a
  // null or obstruction surface is an error).
  const int ns = static_cast<int>(surfaces.size());
  std::vector<int> target(static_cast<std::size_t>(ns));
  for (int i = 0; i < ns; ++i) {
    int t = i, steps = 0;
    while (surfaces[static_cast<std::size_t>(t)].cmb != 0) {
      const int next = surfaces[static_cast<std::size_t>(t)].cmb - 1;
      if (next >= ns)
        throw_at(path, surfaces[static_cast<std::size_t>(t)].line, fmt::format("cmb {} is not a surface", next + 1));
      if (++steps > ns) throw_at(path, surfaces[static_cast<std::size_t>(i)].line, "cmb surfaces form a cycle");
      t = next;
    }
    const char from = surfaces[static_cast<std::size_t>(i)].type, to = surfaces[static_cast<std::size_t>(t)].type;
    if (t != i && (to == 'N' || to == 'O' || from == 'N' || from == 'O'))
      throw_at(path, surfaces[static_cast<std::size_t>(i)].line, "only S and M surfaces can be combined");
    target[static_cast<std::size_t>(i)] = t;
  }
  std::vector<int> unit_of(static_cast<std::size_t>(ns), -1);
  std::vector<std::string> names;
  std::vector<double> emit_area, area_sum;
  for (int i = 0; i < ns; ++i) {
    const Record& s = surfaces[static_cast<std::size_t>(i)];
    if ((s.type == 'S' || s.type == 'M') && target[static_cast<std::size_t>(i)] == i) {
      unit_of[static_cast<std::size_t>(i)] = static_cast<int>(names.size());
      names.push_back(s.name.empty() ? fmt::format("s{}", i + 1) : s.name);
    }
  }
  for (int i = 0; i < ns; ++i)
    if (surfaces[static_cast<std::size_t>(i)].type == 'S' || surfaces[static_cast<std::size_t>(i)].type == 'M')
      unit_of[static_cast<std::size_t>(i)] = unit_of[static_cast<std::size_t>(target[static_cast<std::size_t>(i)])];

  // Polygons: the holes (M and N) of each base, checked to lie in its plane and inside it.
  std::vector<std::vector<Vec3>> polygon(static_cast<std::size_t>(ns));
  std::vector<std::vector<int>> holes(static_cast<std::size_t>(ns));
  for (int i = 0; i < ns; ++i) {
    const Record& s = surfaces[static_cast<std::size_t>(i)];
    for (int v : s.vertices) polygon[static_cast<std::size_t>(i)].push_back(vertices[static_cast<std::size_t>(v)]);
    const auto& p = polygon[static_cast<std::size_t>(i)];
    const double diameter = polygon_diameter(p);
    if (!(0.5 * newell_normal(p).norm() > 1e-14 * diameter * diameter)) throw_at(path, s.line, "surface has no area");
    if (s.base == 0) continue;
    const auto& b = polygon[static_cast<std::size_t>(s.base - 1)];
    const Vec3 n = newell_normal(b).normalized();
    const double tol = 1e-9 * polygon_diameter(b);
    for (const Vec3& x : p) {
      if (std::abs(n.dot(x - b[0])) > tol)
        throw_at(path, s.line, fmt::format("not in the plane of its base surface {}", s.base));
      for (std::size_t k = 0; k < b.size(); ++k)
        if (n.cross(b[(k + 1) % b.size()] - b[k]).dot(x - b[k]) < -tol * polygon_diameter(b))
          throw_at(path, s.line, fmt::format("not inside its base surface {}", s.base));
    }
    if (newell_normal(p).dot(n) < 0.0)
      std::reverse(polygon[static_cast<std::size_t>(i)].begin(), polygon[static_cast<std::size_t>(i)].end());
    holes[static_cast<std::size_t>(s.base - 1)].push_back(i);
  }

  // Materials: one per distinct emissivity, reflectance 1 - emit.
  std::map<double, int> material_of_emit;
  detail::FaceTallies tallies;
  std::vector<int> of_face;
  std::vector<double> unit_emit(names.size(), 0.0), unit_area(names.size(), 0.0);
  for (int i = 0; i < ns; ++i) {
    const Record& s = surfaces[static_cast<std::size_t>(i)];
    if (s.type == 'N') continue;
    auto [it, added] = material_of_emit.emplace(s.emit, static_cast<int>(model.scene.materials.size()));
    if (added)
      model.scene.materials.push_back({fmt::format("emit={}", s.emit), Rgb::Constant(1.0 - s.emit), Rgb::Zero()});
    std::vector<std::vector<Vec3>> pieces = {polygon[static_cast<std::size_t>(i)]};
    const Vec3 n = newell_normal(pieces[0]).normalized();
    const double a0 = polygon_area(pieces[0]);
    for (int h : holes[static_cast<std::size_t>(i)]) {
      std::vector<std::vector<Vec3>> next;
      for (const auto& piece : pieces) subtract_convex(piece, polygon[static_cast<std::size_t>(h)], n, next);
      pieces.swap(next);
    }
    double area = 0.0;
    for (auto& piece : pieces) {
      // Pieces that clipping left with no area (a hole touching the base's edge) are rounding, not
      // surfaces: the same relative test the scene readers apply.
      if (!(polygon_area(piece) > 1e-14 * a0)) continue;
      InputFace face;
      face.group = s.name;
      face.material = it->second;
      face.line = s.line;
      const std::size_t before = model.scene.patches.size();
      detail::add_input_face(model.scene, face, piece, 0.0, ObjReadOptions{}, tallies);
      for (std::size_t p = before; p < model.scene.patches.size(); ++p) area += model.scene.patches[p].area;
      of_face.push_back(unit_of[static_cast<std::size_t>(i)]);
    }
    if (!(area > 0.0)) throw_at(path, s.line, "nothing of the surface is left outside its masks and holes");
    const int u = unit_of[static_cast<std::size_t>(i)];
    if (u >= 0) {
      unit_emit[static_cast<std::size_t>(u)] += area * s.emit;
      unit_area[static_cast<std::size_t>(u)] += area;
    }
  }
  for (InputFace& f : model.scene.faces) {
    f.area = 0.0;
    for (int p : f.patches) f.area += model.scene.patches[static_cast<std::size_t>(p)].area;
  }
  for (std::size_t u = 0; u < names.size(); ++u) unit_emit[u] /= unit_area[u];
  detail::report_tallies(path, tallies, warnings);
  model.units = units_from_map(model.scene, std::move(of_face), std::move(names), std::move(unit_emit));
  return model;
}

void write_vs3(std::ostream& out, const Scene& scene, const SurfaceUnits& units, const std::string& title) {
  out << "T " << title << "\n";
  out << "C encl=0 list=0 eps=1.0e-4 maxU=8 maxO=8 minO=0 row=0 col=0 emit=0\n";
  out << "F 3\n";
  std::map<std::array<double, 3>, int> index;
  std::vector<std::vector<int>> patch_vertices(scene.patches.size());
  for (std::size_t p = 0; p < scene.patches.size(); ++p)
    for (const Vec3& v : scene.patches[p].vertices) {
      const auto [it, added] =
          index.emplace(std::array<double, 3>{v.x(), v.y(), v.z()}, static_cast<int>(index.size()) + 1);
      if (added) out << fmt::format("V {} {:.17g} {:.17g} {:.17g}\n", it->second, v.x(), v.y(), v.z());
      patch_vertices[p].push_back(it->second);
    }
  int number = 0;
  for (std::size_t f = 0; f < scene.faces.size(); ++f) {
    const InputFace& face = scene.faces[f];
    const double emit =
        face.material >= 0 ? 1.0 - scene.materials[static_cast<std::size_t>(face.material)].reflectance.mean() : 1.0;
    std::string name = units.names[static_cast<std::size_t>(units.of_face[f])];
    for (char& c : name)
      if (std::isspace(static_cast<unsigned char>(c))) c = '_';
    const int first = number + 1;
    for (int p : face.patches) {
      const auto& v = patch_vertices[static_cast<std::size_t>(p)];
      if (v.size() > 4)
        throw Error(fmt::format("--write-vs3: patch {} has {} vertices (View3D takes 3 or 4)", p, v.size()));
      ++number;
      out << fmt::format("S {} {} {} {} {} 0 {} {:.17g} {}\n", number, v[0], v[1], v[2], v.size() == 4 ? v[3] : 0,
                         number == first ? 0 : first, emit, name);
    }
  }
  out << "End\n";
}

}  // namespace hrad
