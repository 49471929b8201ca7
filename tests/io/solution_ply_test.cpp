#include "hrad/io/solution_ply.h"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>

#include <gtest/gtest.h>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include "../support/temp_dir.h"
#include "hrad/core/error.h"
#include "hrad/core/face_geometry.h"
#include "hrad/core/tone_map.h"

namespace hrad {
namespace {

// Two unit quads sharing an edge (patch 0, split into two elements) and a triangle (patch 3).
Solution small_solution() {
  Solution s;
  s.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(2, 1, 0), Vec3(1, 1, 0),
                Vec3(0, 1, 0), Vec3(0, 0, 5), Vec3(3, 0, 5), Vec3(0, 2, 5)};
  for (int i = 0; i < 9; ++i) s.vertex_radiosity.push_back(Rgb(0.1 * i + 1.0 / 3.0, 1e-9 * i, 12345.678901234 + i));
  s.faces = {{0, 1, 4, 5}, {1, 2, 3, 4}, {6, 7, 8}};
  s.face_patch = {0, 0, 3};
  s.face_radiosity = {Rgb(0.25, 0.5, 1.0 / 7.0), Rgb(0.75, 0.0, 2.0), Rgb(100.0, 200.0, 300.0)};
  s.patch_radiosity = {Rgb(0.5, 0.25, (1.0 / 7.0 + 2.0) / 2), Rgb::Zero(), Rgb::Zero(), Rgb(100.0, 200.0, 300.0)};
  return s;
}

TEST(SolutionPly, RoundTripKeepsTopologyAndExactRadiosity) {
  test::TempDir dir;
  const Solution s = small_solution();
  const std::string path = dir.path("sol.ply");
  write_solution_ply(path, s, 1.0);
  EXPECT_EQ(dir.entries(), 1u);  // no temporary file left behind
  const Solution r = read_solution_ply(path);
  ASSERT_EQ(r.vertices.size(), s.vertices.size());
  for (std::size_t i = 0; i < s.vertices.size(); ++i) {
    EXPECT_NEAR((r.vertices[i] - s.vertices[i]).norm(), 0.0, 1e-6);  // float positions
    for (int c = 0; c < 3; ++c) EXPECT_EQ(r.vertex_radiosity[i][c], s.vertex_radiosity[i][c]);
  }
  EXPECT_EQ(r.faces, s.faces);
  EXPECT_EQ(r.face_patch, s.face_patch);
  for (std::size_t f = 0; f < s.faces.size(); ++f)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(r.face_radiosity[f][c], s.face_radiosity[f][c]);
  // Patch 0: two elements of area 1 each -> plain mean; patches 1, 2 have no face -> zero.
  ASSERT_EQ(r.patch_radiosity.size(), 4u);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(r.patch_radiosity[0][c], s.patch_radiosity[0][c], 1e-12);
    EXPECT_EQ(r.patch_radiosity[1][c], 0.0);
    EXPECT_NEAR(r.patch_radiosity[3][c], s.patch_radiosity[3][c], 1e-12);
  }
}

TEST(SolutionPly, VertexColoursAreToneMappedRadiosity) {
  test::TempDir dir;
  Solution s = small_solution();
  s.vertex_radiosity[0] = Rgb(0.5, 0.0, 2.0);
  const std::string path = dir.path("sol.ply");
  write_solution_ply(path, s, 1.0);
  struct Traits : OpenMesh::DefaultTraits {};
  OpenMesh::PolyMesh_ArrayKernelT<Traits> mesh;
  mesh.request_vertex_colors();
  OpenMesh::IO::Options opt = OpenMesh::IO::Options::VertexColor;
  ASSERT_TRUE(OpenMesh::IO::read_mesh(mesh, path, opt));
  ASSERT_TRUE(opt.check(OpenMesh::IO::Options::VertexColor));
  const auto c = mesh.color(mesh.vertex_handle(0));
  // sRGB(0.5) = 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354 -> 188; 0 -> 0; 2 clamps to 1 -> 255.
  EXPECT_EQ(int(c[0]), 188);
  EXPECT_EQ(int(c[1]), 0);
  EXPECT_EQ(int(c[2]), 255);
}

TEST(SolutionPly, NonManifoldFacesKeepTheirSharedVertices) {
  // Three triangles on one edge (0,1): a half-edge mesh cannot hold the third; the PLY is a plain
  // face list, so every face comes back with the vertices it was written with.
  Solution s;
  s.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 1, 0), Vec3(0.5, -1, 0), Vec3(0.5, 0, 1)};
  s.vertex_radiosity.assign(5, Rgb(1, 2, 3));
  s.faces = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  s.face_patch = {0, 1, 2};
  s.face_radiosity = {Rgb(1, 1, 1), Rgb(2, 2, 2), Rgb(3, 3, 3)};
  test::TempDir dir;
  write_solution_ply(dir.path("nm.ply"), s, 1.0);
  const Solution r = read_solution_ply(dir.path("nm.ply"));
  EXPECT_EQ(r.vertices, s.vertices);
  EXPECT_EQ(r.faces, s.faces);
  EXPECT_EQ(r.face_patch, s.face_patch);
  for (std::size_t f = 0; f < 3; ++f) EXPECT_EQ(r.face_radiosity[f][0], s.face_radiosity[f][0]);
}

// Positions are stored in double precision: a 1e-6 x 1e-6 element at 1 km from the origin keeps its
// area (in float32 its corners, 6e-5 apart at that magnitude, collapsed onto one another).
TEST(SolutionPly, TinyElementFarFromTheOriginRoundTripsExactly) {
  Solution s;
  const Vec3 o(1000.0, 999.5, -1000.0);
  s.vertices = {o, o + Vec3(1e-6, 0, 0), o + Vec3(1e-6, 1e-6, 0), o + Vec3(0, 1e-6, 0)};
  s.vertex_radiosity.assign(4, Rgb(1, 1, 1));
  s.faces = {{0, 1, 2, 3}};
  s.face_patch = {0};
  s.face_radiosity = {Rgb(0.5, 0.5, 0.5)};
  test::TempDir dir;
  write_solution_ply(dir.path("tiny.ply"), s, 1.0);
  const Solution r = read_solution_ply(dir.path("tiny.ply"));
  EXPECT_EQ(r.vertices, s.vertices);  // bit for bit: a permutation and a sign change are exact
  EXPECT_NEAR(face_area(r, 0), 1e-12, 1e-12 * 1e-6);
}

// Blender imports PLY positions as they are, with +Z up; hrad's scenes are +Y up (OBJ, glTF). The
// file stores (x, -z, y) and says so in a comment: an OBJ point (1, 2, 3) is written as (1, -3, 2),
// and a file without the comment is read as it is.
TEST(SolutionPly, StoresZUpForBlenderAndSaysSo) {
  Solution s = small_solution();
  test::TempDir dir;
  write_solution_ply(dir.path("s.ply"), s, 1.0);
  std::ifstream in(dir.path("s.ply"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(bytes.find("comment hrad axes: stored (x, -z, y)"), std::string::npos);
  EXPECT_NE(bytes.find("property double x\nproperty double y\nproperty double z\n"), std::string::npos);
  const std::size_t body = bytes.find("end_header\n") + 11;
  double first[3];
  std::memcpy(first, bytes.data() + body + 51 * 6, sizeof first);  // vertex 6 = (0, 0, 5): 51 bytes per vertex
  EXPECT_EQ(first[0], 0.0);
  EXPECT_EQ(first[1], -5.0);
  EXPECT_EQ(first[2], 0.0);
  const std::string plain = dir.write("plain.ply",
                                      "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
                                      "property double z\nproperty double radiosity_r\nproperty double radiosity_g\n"
                                      "property double radiosity_b\nelement face 1\n"
                                      "property list uchar int vertex_indices\nproperty double radiosity_r\n"
                                      "property double radiosity_g\nproperty double radiosity_b\nproperty int patch\n"
                                      "end_header\n1 2 3 0 0 0\n2 2 3 0 0 0\n1 3 3 0 0 0\n3 0 1 2 1 1 1 0\n");
  EXPECT_EQ(read_solution_ply(plain).vertices[0], Vec3(1, 2, 3));
}

void expect_error_naming(const std::string& path, const std::string& fragment) {
  try {
    read_solution_ply(path);
    FAIL() << "no error for " << path;
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
  }
}

TEST(SolutionPly, BadFilesAreErrorsNamingTheFile) {
  test::TempDir dir;
  expect_error_naming(dir.path("missing.ply"), "cannot open");
  expect_error_naming(dir.write("garbage.ply", "this is not a ply file\n\x01\x02\x03"), "not a readable PLY");
  expect_error_naming(dir.write("plain.ply",
                                "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                                "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
                      "radiosity_r");
  expect_error_naming(dir.write("nopatch.ply",
                                "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                "property float z\nproperty double radiosity_r\nproperty double radiosity_g\n"
                                "property double radiosity_b\nelement face 1\nproperty list uchar int vertex_indices\n"
                                "property double radiosity_r\nproperty double radiosity_g\n"
                                "property double radiosity_b\nend_header\n0 0 0 1 1 1\n1 0 0 1 1 1\n0 1 0 1 1 1\n"
                                "3 0 1 2 1 1 1\n"),
                      "patch");
  expect_error_naming(
      dir.write("badindex.ply",
                "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                "property float z\nproperty double radiosity_r\nproperty double radiosity_g\n"
                "property double radiosity_b\nelement face 1\nproperty list uchar int vertex_indices\n"
                "property double radiosity_r\nproperty double radiosity_g\nproperty double radiosity_b\n"
                "property int patch\nend_header\n0 0 0 1 1 1\n1 0 0 1 1 1\n0 1 0 1 1 1\n"
                "3 0 1 99 1 1 1 0\n"),
      "1 of 1 faces are invalid");
}

TEST(SolutionPly, TruncatedFilesAreErrorsNotHangs) {
  // OpenMesh's reader alone loops without end on a header cut short; every cut must be an error.
  test::TempDir dir;
  const std::string path = dir.path("sol.ply");
  write_solution_ply(path, small_solution(), 1.0);
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (std::size_t cut : {std::size_t{0}, std::size_t{2}, std::size_t{60}, bytes.find("end_header") + 5,
                          bytes.find("end_header") + 11, bytes.size() / 2, bytes.size() - 1}) {
    const std::string cut_path = dir.write("cut.ply", bytes.substr(0, cut));
    EXPECT_THROW(read_solution_ply(cut_path), Error) << "cut at " << cut << " of " << bytes.size();
  }
  // An ASCII body one record short is caught too.
  expect_error_naming(dir.write("short.ply",
                                "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                                "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n"),
                      "truncated");
}

TEST(SolutionPly, InconsistentSolutionIsAnErrorAndLeavesNoFile) {
  Solution s = small_solution();
  s.faces[1][2] = 42;
  test::TempDir dir;
  EXPECT_THROW(write_solution_ply(dir.path("bad.ply"), s, 1.0), Error);
  EXPECT_EQ(dir.entries(), 0u);
}

}  // namespace
}  // namespace hrad

namespace hrad {
namespace {

// Links as a hierarchical solve stores them: 3 roots (patches 0..2 of small_solution()'s ids), root
// 0 split twice, two clusters, links between elements and clusters with hidden patches listed.
SolutionLinks small_links() {
  SolutionLinks l;
  l.first_child = {4, -1, -1, -1, -1, 8, -1, -1, -1, -1, -1, -1};
  l.cluster_parent = {-1, 0};
  l.links = {
      {0, 1, false, {}, {}}, {6, -2, true, {}, {0, 3}}, {-3, -2, false, {1}, {2, 3, 40000}}, {11, 9, true, {}, {}}};
  return l;
}

// The links come back exactly; a file written without them reads back without them (and so does a
// file of any other PLY writer); both are the same solution.
TEST(SolutionPly, LinksRoundTripExactly) {
  test::TempDir dir;
  const SolutionLinks links = small_links();
  write_solution_ply(dir.path("with.ply"), small_solution(), 1.0, &links);
  write_solution_ply(dir.path("without.ply"), small_solution(), 1.0);
  std::optional<SolutionLinks> read;
  const Solution with = read_solution_ply(dir.path("with.ply"), &read);
  ASSERT_TRUE(read.has_value());
  EXPECT_TRUE(*read == links);
  const Solution without = read_solution_ply(dir.path("without.ply"), &read);
  EXPECT_FALSE(read.has_value());
  EXPECT_EQ(with.faces, without.faces);
  EXPECT_EQ(with.face_patch, without.face_patch);
  // 17 bytes a link and 4 a listed patch, 4 a node and 4 a cluster, beside the header's lines.
  const std::size_t listed = 6;
  const std::size_t body =
      4 * links.first_child.size() + 4 * links.cluster_parent.size() + 17 * links.links.size() + 4 * listed;
  const std::string header_lines =
      "element node 12\nproperty int first_child\nelement cluster 2\nproperty int parent\nelement link 4\n"
      "property int p\nproperty int q\nproperty uchar partial\nproperty list int int hidden_p\n"
      "property list int int hidden_q\n";
  EXPECT_EQ(std::filesystem::file_size(dir.path("with.ply")),
            std::filesystem::file_size(dir.path("without.ply")) + body + header_lines.size());
}

// A link element that does not describe a hierarchy is a one-line error naming the file, the
// element and the record, whether written (nothing is left behind) or read.
TEST(SolutionPly, MalformedLinksAreErrorsNamingTheRecord) {
  test::TempDir dir;
  SolutionLinks bad = small_links();
  bad.links[1].q = -4;  // cluster 2 of 2
  try {
    write_solution_ply(dir.path("bad.ply"), small_solution(), 1.0, &bad);
    ADD_FAILURE() << "written";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind(dir.path("bad.ply") + ": cannot write solution: element link 1: q = -4", 0),
              0u)
        << e.what();
  }
  EXPECT_EQ(dir.entries(), 0u);
  // Read: one triangle (patch 0), one node, no cluster, and links whose records are wrong.
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
      "property double radiosity_r\nproperty double radiosity_g\nproperty double radiosity_b\n"
      "element face 1\nproperty list uchar int vertex_indices\nproperty double radiosity_r\n"
      "property double radiosity_g\nproperty double radiosity_b\nproperty int patch\n"
      "element node 1\nproperty int first_child\nelement cluster 0\nproperty int parent\nelement link 2\n"
      "property int p\nproperty int q\nproperty uchar partial\nproperty list int int hidden_p\n"
      "property list int int hidden_q\nend_header\n0 0 0 1 1 1\n1 0 0 1 1 1\n0 1 0 1 1 1\n3 0 1 2 1 1 1 0\n-1\n";
  const std::pair<std::string, std::string> cases[] = {
      {"0 0 0 0 0\n0 1 0 0 0\n", "element link 1: q = 1 is neither an element node"},
      {"0 0 0 0 0\n0 0 2 0 0\n", "element link 1: partial = 2 is not an integer in [0, 1]"},
      {"0 0 0 0 0\n0 -2 0 0 0\n", "element link 1: q = -2 is neither"},
      {"0 0 0 0 2 5 5\n0 0 0 0 0\n", "element link 0: hidden_q lists patch 5"},
      {"0 0 0 1 -1 0\n0 0 0 0 0\n", "element link 0: hidden_p = -1 is not an integer"},
  };
  for (const auto& [records, message] : cases) {
    const std::string path = dir.write("links.ply", head + records);
    std::optional<SolutionLinks> links;
    try {
      read_solution_ply(path, &links);
      ADD_FAILURE() << records;
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()).rfind(path + ": " + message, 0), 0u) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
    // Read without asking for links, the solution itself is fine.
    EXPECT_EQ(read_solution_ply(path).faces.size(), 1u);
  }
}

}  // namespace
}  // namespace hrad
