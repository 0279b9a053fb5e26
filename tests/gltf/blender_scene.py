# Run inside Blender (blender -b --factory-startup --python this.py -- OUT.gltf): builds a
# small scene the way a user would, through Blender's Python API, and exports it with
# Blender's glTF exporter. tests/gltf/check_gltf.py writes the same scene directly in the
# course's format (its blender_scene_json) and compares the two renders; the numbers here
# and there must agree.
#   ground  a 20 x 20 plane at z = 0, grey, fully rough
#   red     a cube of side 2 at (-2.5, 0, 1), diffuse red, roughness 0.5
#   metal   a cube of side 2 at (0, 0, 1), turned 30 degrees about z, gold metal, roughness 0.5
#   glass   a cube of side 2 at (2.5, 0, 1), scaled by 0.8, glass (transmission 1, IOR 1.5)
#   light   a 1000 W point light at (0, -4, 6)
#   camera  at (0, -10, 3), turned 80 degrees about x (looking along +y, a little down),
#           40 degrees vertical field of view, 320 x 240 pixels
import math
import sys

import bpy

out = sys.argv[sys.argv.index("--") + 1]
bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
scene.render.resolution_x, scene.render.resolution_y = 320, 240


def material(name, base, metallic, roughness, transmission=0.0):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    p = m.node_tree.nodes["Principled BSDF"]
    p.inputs["Base Color"].default_value = (*base, 1.0)
    p.inputs["Metallic"].default_value = metallic
    p.inputs["Roughness"].default_value = roughness
    p.inputs["Transmission"].default_value = transmission
    p.inputs["IOR"].default_value = 1.5
    return m


def add(obj, mat):
    obj.data.materials.append(mat)
    return obj


bpy.ops.mesh.primitive_plane_add(size=20, location=(0, 0, 0))
add(bpy.context.object, material("ground", (0.8, 0.8, 0.8), 0.0, 1.0)).name = "ground"
bpy.ops.mesh.primitive_cube_add(size=2, location=(-2.5, 0, 1))
add(bpy.context.object, material("red", (0.8, 0.1, 0.1), 0.0, 0.5)).name = "red"
bpy.ops.mesh.primitive_cube_add(size=2, location=(0, 0, 1), rotation=(0, 0, math.radians(30)))
add(bpy.context.object, material("gold", (0.9, 0.7, 0.3), 1.0, 0.5)).name = "metal"
bpy.ops.mesh.primitive_cube_add(size=2, location=(2.5, 0, 1), scale=(0.8, 0.8, 0.8))
add(bpy.context.object, material("glass", (1.0, 1.0, 1.0), 0.0, 0.0, transmission=1.0)).name = "glass"

bpy.ops.object.light_add(type="POINT", location=(0, -4, 6))
bpy.context.object.data.energy = 1000.0
bpy.context.object.data.shadow_soft_size = 0.0

bpy.ops.object.camera_add(location=(0, -10, 3), rotation=(math.radians(80), 0, 0))
cam = bpy.context.object
cam.data.sensor_fit = "VERTICAL"
cam.data.angle = math.radians(40)
scene.camera = cam

bpy.ops.export_scene.gltf(filepath=out, export_format="GLTF_SEPARATE", export_cameras=True, export_lights=True,
                          export_extras=True)
print("blender scene:", out, len(bpy.data.objects), "objects")
