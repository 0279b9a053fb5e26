# Run inside Blender (blender -b --factory-startup --python this.py -- IN.gltf OUT.gltf):
# imports IN into an empty scene with Blender's own glTF importer, and exports the scene
# again as OUT with its exporter, cameras, lights and custom properties (extras) included.
import sys

import numpy

# Debian 12's Blender 3.4 importer uses numpy.bool, which numpy 1.24 removed.
if not hasattr(numpy, "bool"):
    numpy.bool = bool

import bpy  # noqa: E402

args = sys.argv[sys.argv.index("--") + 1:]
src, dst = args[0], args[1]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=src)
bpy.ops.export_scene.gltf(filepath=dst, export_format="GLTF_SEPARATE", export_cameras=True, export_lights=True,
                          export_extras=True, export_apply=False)
print("blender round trip:", src, "->", dst, len(bpy.data.objects), "objects")
