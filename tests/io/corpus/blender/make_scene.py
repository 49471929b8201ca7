"""Regenerates the Blender-exported corpus scene (OBJ + MTL and glTF of the same scene).

Run from this folder with Debian's Blender (3.4.1, `apt-get install blender`):
    blender -b --factory-startup --python make_scene.py -- OUT_DIR
It builds, in metres with Blender's +Z up (the exporters write +Y up, as OBJ and glTF expect):
  * a 4 x 3 x 4 m room (a cube scaled, normals flipped to face inwards), material "Wall" (grey 0.6);
  * a 1 m block on the floor with a Bevel modifier (applied on export: bevelled quads and corner
    triangles), material "Red";
  * an 8-sided cylinder (8-gon caps: n-gons), material "Blue", smooth shaded ("s 1" lines);
  * a UV sphere light (12 segments, 6 rings, radius 0.25 m) near the ceiling, smooth shaded,
    material "Light": Principled BSDF with emission colour 1 and strength 5, base colour black.
Then exports room.obj/room.mtl (Blender's OBJ exporter, modifiers applied, smooth groups, materials)
and room.gltf/room.bin (glTF 2.0 separate, modifiers applied).
"""
import sys

import bpy

out = sys.argv[sys.argv.index("--") + 1] if "--" in sys.argv else "."

bpy.ops.wm.read_factory_settings(use_empty=True)


def material(name, base, emission=None, strength=0.0):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    bsdf = m.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*base, 1.0)
    bsdf.inputs["Specular"].default_value = 0.0
    if emission is not None:
        bsdf.inputs["Emission"].default_value = (*emission, 1.0)
        bsdf.inputs["Emission Strength"].default_value = strength
    return m


def assign(obj, mat):
    obj.data.materials.append(mat)


bpy.ops.mesh.primitive_cube_add(size=1.0, location=(0, 0, 1.5))
room = bpy.context.active_object
room.name = "Room"
room.scale = (4.0, 4.0, 3.0)
bpy.ops.object.transform_apply(scale=True)
bpy.ops.object.mode_set(mode="EDIT")
bpy.ops.mesh.select_all(action="SELECT")
bpy.ops.mesh.flip_normals()
bpy.ops.object.mode_set(mode="OBJECT")
assign(room, material("Wall", (0.6, 0.6, 0.6)))

bpy.ops.mesh.primitive_cube_add(size=1.0, location=(-0.8, 0.5, 0.5))
block = bpy.context.active_object
block.name = "Block"
bevel = block.modifiers.new("Bevel", "BEVEL")
bevel.width = 0.1
bevel.segments = 1
assign(block, material("Red", (0.6, 0.1, 0.1)))

bpy.ops.mesh.primitive_cylinder_add(vertices=8, radius=0.4, depth=0.8, location=(0.9, -0.6, 0.4))
cylinder = bpy.context.active_object
cylinder.name = "Cylinder"
bpy.ops.object.shade_smooth()
assign(cylinder, material("Blue", (0.1, 0.1, 0.6)))

bpy.ops.mesh.primitive_uv_sphere_add(segments=12, ring_count=6, radius=0.25, location=(0.0, 0.0, 2.4))
sphere = bpy.context.active_object
sphere.name = "SphereLight"
bpy.ops.object.shade_smooth()
assign(sphere, material("Light", (0.0, 0.0, 0.0), emission=(1.0, 1.0, 1.0), strength=5.0))

bpy.ops.wm.obj_export(filepath=f"{out}/room.obj", apply_modifiers=True, export_smooth_groups=True,
                      export_materials=True, export_normals=True, export_uv=False,
                      forward_axis="NEGATIVE_Z", up_axis="Y")
bpy.ops.export_scene.gltf(filepath=f"{out}/room.gltf", export_format="GLTF_SEPARATE", export_apply=True,
                          export_yup=True, export_normals=False, export_texcoords=False)
print("wrote", out)
