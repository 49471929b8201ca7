// The scene: planar input polygons (patches) with Lambertian materials.
// Produced by io/, read by every solver; it knows nothing of files.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "hrad/core/emission_units.h"
#include "hrad/core/types.h"

namespace hrad {

struct Material {
  std::string name;
  Rgb reflectance = Rgb::Zero();  ///< diffuse reflectance per channel, in [0, 1)
  Rgb emission = Rgb::Zero();     ///< emitted exitance per channel, >= 0 (W/m^2 or any consistent unit)

  bool is_emitter() const { return (emission > 0.0).any(); }
};

/// One planar, convex input polygon. Its front is the side its counter-clockwise vertex
/// order faces (right-hand rule); `normal` is the unit front normal.
struct Patch {
  std::vector<Vec3> vertices;  ///< 3 or 4 vertices, counter-clockwise seen from the front
  Vec3 normal = Vec3::Zero();
  double area = 0.0;
  int material = -1;  ///< index into Scene::materials
  int face = -1;      ///< index of the input face it came from (a face may give several patches)
  std::string group;  ///< the `o`/`g` name of the input face
};

/// One face of the input file, in file order (reports list radiosity per face).
struct InputFace {
  std::string group;
  int material = -1;
  std::size_t line = 0;  ///< line of the `f` statement in the scene file
  double area = 0.0;
  std::vector<int> patches;  ///< the patches it became (one unless it was split)
};

struct Scene {
  std::string path;  ///< the file it was read from, for messages
  std::vector<std::string>
      files;  ///< every file read to make it (scene, material libraries): outputs must not replace them
  std::vector<Material> materials;
  std::vector<Patch> patches;
  std::vector<InputFace> faces;
  /// The unit of the materials' emission, when the file declares it (README "Scene format").
  std::optional<DeclaredEmissionUnits> emission_units;

  double total_area() const;
  int emitter_count() const;
  /// Corners of the patches' axis-aligned bounding box (+inf / -inf when there are none).
  std::pair<Vec3, Vec3> bounds() const;
  const Material& material_of(const Patch& p) const { return materials[p.material]; }
};

/// Rebuilds every face's patch list and area from the patches' face indices (after patches were cut
/// or replaced). A face left without patches keeps no area.
void relink_faces(Scene& scene);

}  // namespace hrad
