// Reading a scene from any supported file, chosen by its extension (README "Scene format"):
//   .obj          Wavefront OBJ + MTL (obj_reader.h)
//   .ply          PLY polygons (Turk 1994) with per-face or per-vertex reflectance and emission:
//                 element vertex: x y z; optional red green blue (uchar / 255, or float) and
//                                 emission_r emission_g emission_b, averaged over a face's vertices;
//                 element face:   vertex_indices (or vertex_index), counter-clockwise seen from the front;
//                                 optional reflectance_r reflectance_g reflectance_b (float, [0, 1)),
//                                 red green blue, emission_r emission_g emission_b (>= 0).
//                 A face's own properties win over its vertices'; without any, the default material
//                 (obj_reader.h) with a warning. Coordinates are taken as they are.
//                 A solution PLY written by `hrad solve` is refused with a message saying so.
//   .gltf, .glb   glTF 2.0 (tinygltf): every triangle of every mesh primitive (mode TRIANGLES) of the
//                 default scene, node transforms applied; reflectance = the material's
//                 pbrMetallicRoughness.baseColorFactor (rgb), emission = emissiveFactor times
//                 KHR_materials_emissive_strength's emissiveStrength (1 without it); a face's group is its
//                 node's name (else its mesh's). Metres, +Y up,
//                 as OBJ. Errors name the file and the JSON pointer ("/meshes/0/primitives/1").
// Faces of every format follow the same patch rules (scene_faces.h); for PLY and glTF, a warning's
// "line" is the face's 1-based number in the file.
#pragma once

#include <string>
#include <vector>

#include "hrad/core/scene.h"
#include "hrad/io/obj_reader.h"

namespace hrad {

/// Reads `path` by its extension (anything else is read as OBJ); warnings as read_obj_scene's.
Scene read_scene(const std::string& path, std::vector<std::string>* warnings = nullptr,
                 const ObjReadOptions& options = {});

Scene read_ply_scene(const std::string& path, std::vector<std::string>* warnings = nullptr,
                     const ObjReadOptions& options = {});
Scene read_gltf_scene(const std::string& path, std::vector<std::string>* warnings = nullptr,
                      const ObjReadOptions& options = {});

}  // namespace hrad
