// glTF 2.0 scenes through tinygltf (Debian's libtinygltf-dev); see scene_reader.h for what is read.
// Images are never decoded (radiosity needs no textures): the image loader accepts and drops them.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>

#include <fmt/format.h>
#include <Eigen/Geometry>

#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include "hrad/core/error.h"
#include "hrad/io/input_file.h"
#include "hrad/io/scene_directives.h"
#include "hrad/io/scene_faces.h"
#include "hrad/io/scene_reader.h"

namespace hrad {
namespace {

bool drop_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

using Transform = Eigen::Matrix4d;

Transform local_transform(const tinygltf::Node& node) {
  Transform m = Transform::Identity();
  if (node.matrix.size() == 16) {
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m(r, c) = node.matrix[static_cast<std::size_t>(4 * c + r)];  // column-major
    return m;
  }
  // T * R * S (glTF 2.0 sec. 3.5.3).
  if (node.scale.size() == 3) m = Eigen::Vector4d(node.scale[0], node.scale[1], node.scale[2], 1.0).asDiagonal();
  if (node.rotation.size() == 4) {
    const Eigen::Quaterniond q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);  // w, x, y, z
    Transform r = Transform::Identity();
    r.topLeftCorner<3, 3>() = q.normalized().toRotationMatrix();
    m = r * m;
  }
  if (node.translation.size() == 3) {
    Transform t = Transform::Identity();
    t.topRightCorner<3, 1>() = Eigen::Vector3d(node.translation[0], node.translation[1], node.translation[2]);
    m = t * m;
  }
  return m;
}

/// The `count` elements of accessor `index` as doubles, `components` each.
std::vector<double> read_accessor(const tinygltf::Model& model, int index, int components, const std::string& path,
                                  const std::string& pointer) {
  auto fail = [&](const std::string& what) { throw Error(fmt::format("{}: {}: {}", path, pointer, what)); };
  if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size()) fail("accessor index out of range");
  const tinygltf::Accessor& a = model.accessors[static_cast<std::size_t>(index)];
  if (tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type)) != components)
    fail(fmt::format("accessor {} has {} components per element, expected {}", index,
                     tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type)), components));
  if (a.bufferView < 0 || static_cast<std::size_t>(a.bufferView) >= model.bufferViews.size())
    fail(fmt::format("accessor {} has no buffer view (sparse accessors are not read)", index));
  const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(a.bufferView)];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size())
    fail("buffer index out of range");
  const std::vector<unsigned char>& data = model.buffers[static_cast<std::size_t>(view.buffer)].data;
  const int size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
  if (size <= 0) fail(fmt::format("accessor {} has an unknown component type", index));
  const std::size_t stride = view.byteStride > 0 ? view.byteStride : static_cast<std::size_t>(size * components);
  const std::size_t start = view.byteOffset + a.byteOffset;
  if (a.count > 0 && start + (a.count - 1) * stride + static_cast<std::size_t>(size * components) > data.size())
    fail(fmt::format("accessor {} reads past the end of its buffer", index));
  std::vector<double> out;
  out.reserve(a.count * static_cast<std::size_t>(components));
  for (std::size_t i = 0; i < a.count; ++i)
    for (int c = 0; c < components; ++c) {
      const unsigned char* p = data.data() + start + i * stride + static_cast<std::size_t>(c * size);
      switch (a.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: {
          float v;
          std::memcpy(&v, p, 4);
          out.push_back(v);
          break;
        }
        case TINYGLTF_COMPONENT_TYPE_DOUBLE: {
          double v;
          std::memcpy(&v, p, 8);
          out.push_back(v);
          break;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
          std::uint32_t v;
          std::memcpy(&v, p, 4);
          out.push_back(v);
          break;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
          std::uint16_t v;
          std::memcpy(&v, p, 2);
          out.push_back(v);
          break;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
          out.push_back(*p);
          break;
        default:
          fail(fmt::format("accessor {}: component type {} is not read", index, a.componentType));
      }
    }
  return out;
}

}  // namespace

Scene read_gltf_scene(const std::string& path, std::vector<std::string>* warnings, const ObjReadOptions& options) {
  const std::string bytes = read_input_file(path);
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(drop_image, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  const std::string base = std::filesystem::path(path).parent_path().string();
  const bool binary = bytes.rfind("glTF", 0) == 0;
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const bool ok =
      binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, data, static_cast<unsigned>(bytes.size()), base)
             : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), static_cast<unsigned>(bytes.size()), base);
  if (!ok || !err.empty()) {
    std::string first = err.substr(0, err.find('\n'));
    throw Error(fmt::format("{}: not a readable glTF 2.0 file: {}", path, first.empty() ? "unknown error" : first));
  }

  Scene scene;
  scene.path = path;
  scene.files.push_back(path);
  for (const tinygltf::Buffer& b : model.buffers)
    if (!b.uri.empty() && b.uri.rfind("data:", 0) != 0)
      scene.files.push_back((std::filesystem::path(base) / b.uri).string());
  if (const tinygltf::Value& extras = model.asset.extras; extras.IsObject() && extras.Has("hrad")) {
    const tinygltf::Value& hrad = extras.Get("hrad");
    const std::string pointer = fmt::format("{}: /asset/extras/hrad", path);
    if (!hrad.IsObject()) throw Error(fmt::format("{}: not an object", pointer));
    for (const std::string& key : hrad.Keys()) {
      if (key != "emission-units")
        throw Error(fmt::format("{}: unknown hrad declaration '{}' (known: emission-units)", pointer, key));
      const tinygltf::Value& value = hrad.Get(key);
      if (!value.IsString()) throw Error(fmt::format("{}/emission-units: not a string", pointer));
      detail::declare_emission_units(scene, value.Get<std::string>(), pointer + "/emission-units");
    }
  }
  detail::FaceTallies tallies;
  std::map<int, int> material_of;  // glTF material -> scene material
  const auto scene_material = [&](int m, std::size_t face_number) {
    if (m < 0 || static_cast<std::size_t>(m) >= model.materials.size())
      return detail::default_material(scene, face_number, tallies);
    if (const auto it = material_of.find(m); it != material_of.end()) return it->second;
    const tinygltf::Material& gm = model.materials[static_cast<std::size_t>(m)];
    const std::vector<double>& base_colour = gm.pbrMetallicRoughness.baseColorFactor;
    Rgb rho = base_colour.size() >= 3 ? Rgb(base_colour[0], base_colour[1], base_colour[2]) : Rgb::Constant(1.0);
    double strength = 1.0;
    if (const auto ext = gm.extensions.find("KHR_materials_emissive_strength"); ext != gm.extensions.end())
      if (ext->second.Has("emissiveStrength")) strength = ext->second.Get("emissiveStrength").GetNumberAsDouble();
    const std::vector<double>& ef = gm.emissiveFactor;
    const Rgb e = ef.size() >= 3 ? Rgb(strength * ef[0], strength * ef[1], strength * ef[2]) : Rgb(Rgb::Zero());
    const std::string pointer = fmt::format("/materials/{}", m);
    if (!rho.allFinite() || (rho < 0.0).any() || (rho >= 1.0).any())
      throw Error(fmt::format("{}: {}: baseColorFactor {} {} {} is outside [0, 1) (a reflectance below 1 is needed)",
                              path, pointer, rho[0], rho[1], rho[2]));
    if (!e.allFinite() || (e < 0.0).any())
      throw Error(fmt::format("{}: {}: emission {} {} {} is negative or not finite", path, pointer, e[0], e[1], e[2]));
    scene.materials.push_back(Material{gm.name.empty() ? fmt::format("material_{}", m) : gm.name, rho, e});
    return material_of[m] = static_cast<int>(scene.materials.size()) - 1;
  };

  std::function<void(int, const Transform&, int)> visit = [&](int n, const Transform& parent, int depth) {
    if (n < 0 || static_cast<std::size_t>(n) >= model.nodes.size() || depth > 256)
      throw Error(fmt::format("{}: /nodes/{}: node index out of range or a cycle", path, n));
    const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(n)];
    const Transform world = parent * local_transform(node);
    if (node.mesh >= 0) {
      if (static_cast<std::size_t>(node.mesh) >= model.meshes.size())
        throw Error(fmt::format("{}: /nodes/{}/mesh: index out of range", path, n));
      const tinygltf::Mesh& mesh = model.meshes[static_cast<std::size_t>(node.mesh)];
      for (std::size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
        const tinygltf::Primitive& prim = mesh.primitives[pi];
        const std::string pointer = fmt::format("/meshes/{}/primitives/{}", node.mesh, pi);
        if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1)
          throw Error(fmt::format("{}: {}: mode {} is not read (only triangles, mode 4)", path, pointer, prim.mode));
        const auto pos = prim.attributes.find("POSITION");
        if (pos == prim.attributes.end()) throw Error(fmt::format("{}: {}: no POSITION attribute", path, pointer));
        const std::vector<double> p = read_accessor(model, pos->second, 3, path, pointer + "/attributes/POSITION");
        const std::size_t vertices = p.size() / 3;
        std::vector<double> idx;
        if (prim.indices >= 0) {
          idx = read_accessor(model, prim.indices, 1, path, pointer + "/indices");
        } else {
          for (std::size_t i = 0; i < vertices; ++i) idx.push_back(static_cast<double>(i));
        }
        if (idx.size() % 3 != 0)
          throw Error(fmt::format("{}: {}/indices: {} indices do not make triangles", path, pointer, idx.size()));
        // The node's name, as exporters name the object (Blender's OBJ `o` lines carry the same name).
        const std::string group = !node.name.empty()   ? node.name
                                  : !mesh.name.empty() ? mesh.name
                                                       : fmt::format("mesh_{}", node.mesh);
        for (std::size_t t = 0; t < idx.size(); t += 3) {
          std::vector<Vec3> v;
          for (int k = 0; k < 3; ++k) {
            const double i = idx[t + static_cast<std::size_t>(k)];
            if (!(i >= 0 && i < static_cast<double>(vertices)))
              throw Error(
                  fmt::format("{}: {}/indices: index {} out of range ({} vertices)", path, pointer, i, vertices));
            const auto vi = static_cast<std::size_t>(i);
            const Eigen::Vector4d x = world * Eigen::Vector4d(p[3 * vi], p[3 * vi + 1], p[3 * vi + 2], 1.0);
            v.push_back(x.head<3>());
            if (!v.back().allFinite() || v.back().cwiseAbs().maxCoeff() > options.max_abs_coordinate)
              throw Error(fmt::format("{}: {}: a position is not finite or out of range", path, pointer));
          }
          InputFace face;
          face.group = group;
          face.line = scene.faces.size() + 1;
          face.material = scene_material(prim.material, face.line);
          detail::add_input_face(scene, std::move(face), std::move(v), 0.0, options, tallies);
        }
      }
    }
    for (int child : node.children) visit(child, world, depth + 1);
  };
  const int s = model.defaultScene >= 0 ? model.defaultScene : 0;
  if (model.scenes.empty()) throw Error(fmt::format("{}: /scenes: no scene", path));
  if (static_cast<std::size_t>(s) >= model.scenes.size())
    throw Error(fmt::format("{}: /scene: index out of range", path));
  for (int n : model.scenes[static_cast<std::size_t>(s)].nodes) visit(n, Transform::Identity(), 0);
  detail::report_tallies(path, tallies, warnings);
  if (scene.patches.empty()) throw Error(fmt::format("{}: no patch left (no triangle with a positive area)", path));
  return scene;
}

}  // namespace hrad
