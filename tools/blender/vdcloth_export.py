# Blender add-on: writes the open Blender scene as a vdcloth scene (docs/scene-format.md) beside
# the files it names: each armature-deformed mesh given as a character, with its armature and its
# action, as a glTF file (the character's skin, weights and clip); each garment mesh as an OBJ
# (vdcloth is y-up, Blender z-up: (x, y, z) -> (x, z, -y)) whose pattern (`vt`, metres) is its
# UV map "pattern" if it has one (what the importer makes), else its active UV map scaled so that
# its area is the mesh's; the scene camera as a channel file, camera.chan (position, rotation
# with its roll, and vertical field of view at every frame, to ten decimals), with its clip
# planes; the frame range and rate.
#
# From a script or `blender -b`:
#   import vdcloth_export
#   vdcloth_export.export_scene("/path/shot.json", characters=[body], garments=[cape])
# then `vdcloth run /path/shot.json`, and vdcloth_import.import_run(run, first_frame=scene.frame_start)
# loads the result back onto the same frames.
import json
import math
import os

import bpy
from bpy_extras.io_utils import ExportHelper
from mathutils import Matrix

bl_info = {
    "name": "vdcloth scene",
    "description": "The scene's characters, garments and camera as a vdcloth scene",
    "blender": (3, 4, 0),
    "category": "Import-Export",
    "location": "File > Export > vdcloth scene",
}

# Plain-weave cotton (the project's materials/cotton.json), for garments given no material.
COTTON = {"density": 0.13, "stretch": {"warp": 5000, "weft": 3500, "shear": 300, "poisson": 0.2}, "bending": 1.0e-5}


def to_vdcloth(v):
    """A Blender (z-up) point in vdcloth's y-up world."""
    return (v[0], v[2], -v[1])


# Blender's world (z up) to vdcloth's (y up): (x, y, z) -> (x, z, -y).
TO_VDCLOTH = Matrix(((1, 0, 0), (0, 0, 1), (0, -1, 0)))


def vertical_fov(data, scene):
    """The camera's vertical field of view (radians) in the scene's image."""
    aspect = (scene.render.resolution_x * scene.render.pixel_aspect_x) / (scene.render.resolution_y * scene.render.pixel_aspect_y)
    if data.sensor_fit == "VERTICAL":
        return data.angle_y
    if data.sensor_fit == "HORIZONTAL" or aspect >= 1:
        return 2 * math.atan(math.tan(data.angle_x / 2) / aspect)
    return data.angle_x  # fitted automatically to a portrait image: the sensor's width spans its height


def write_chan(path, camera, scene):
    """The camera at every frame of the scene's range as `frame tx ty tz rx ry rz fov` (frame 0
    the range's first; rotation in degrees, ZXY order: camera-to-world Ry Rx Rz, the camera
    looking down its -z with +y up, as Blender's cameras do)."""
    current = scene.frame_current
    with open(path, "w") as f:
        for frame in range(scene.frame_start, scene.frame_end + 1):
            scene.frame_set(frame)
            world = camera.matrix_world
            turn = TO_VDCLOTH @ world.to_3x3().normalized()
            angles = turn.to_euler("ZXY")
            values = list(to_vdcloth(world.translation)) + [math.degrees(a) for a in angles]
            values.append(math.degrees(vertical_fov(camera.data, scene)))
            f.write("%d %s\n" % (frame - scene.frame_start, " ".join("%.10f" % v for v in values)))
    scene.frame_set(current)


def armature_of(obj):
    for modifier in obj.modifiers:
        if modifier.type == "ARMATURE" and modifier.object:
            return modifier.object
    raise ValueError(obj.name + ": not deformed by an armature (add an Armature modifier)")


def export_gltf(path, objects, animations=True):
    """The objects alone as a glTF file (y up), sampled at every frame of the scene's range."""
    bpy.ops.object.select_all(action="DESELECT")
    for obj in objects:
        obj.select_set(True)
    bpy.ops.export_scene.gltf(filepath=path, export_format="GLTF_SEPARATE", use_selection=True, export_yup=True,
                              export_apply=False, export_animations=animations, export_frame_range=True,
                              export_force_sampling=True, export_cameras=False, export_lights=False,
                              export_materials="NONE")


def write_garment_obj(path, obj):
    """The garment's mesh as an OBJ: world positions (y up), its pattern in metres as vt."""
    mesh = obj.data
    world = obj.matrix_world
    layer = mesh.uv_layers.get("pattern")
    scale = 1.0
    if layer is None:
        layer = mesh.uv_layers.active
        if layer is None:
            raise ValueError(obj.name + ": a garment needs a UV map (its pattern)")
        uv_area = 0.0
        for poly in mesh.polygons:
            corners = [layer.data[i].uv for i in poly.loop_indices]
            for k in range(1, len(corners) - 1):
                a, b, c = corners[0], corners[k], corners[k + 1]
                uv_area += abs((b - a).cross(c - a)) / 2
        world_area = sum(p.area for p in mesh.polygons) * abs(world.determinant()) ** (2.0 / 3.0)
        if uv_area <= 0:
            raise ValueError(obj.name + ": its UV map has no area")
        scale = (world_area / uv_area) ** 0.5
    with open(path, "w") as f:
        for v in mesh.vertices:
            f.write("v %.9g %.9g %.9g\n" % to_vdcloth(world @ v.co))
        for loop in mesh.loops:
            uv = layer.data[loop.index].uv
            f.write("vt %.9g %.9g\n" % (uv[0] * scale, uv[1] * scale))
        for poly in mesh.polygons:
            f.write("f " + " ".join("%d/%d" % (mesh.loops[i].vertex_index + 1, i + 1) for i in poly.loop_indices) + "\n")


def export_scene(path, characters, garments, camera=None, material=None, context=None):
    """Writes the scene file at `path` and, beside it, a glTF per character, an OBJ per garment
    and camera.chan; returns the scene as written (a dict)."""
    context = context or bpy.context
    scene = context.scene
    camera = camera or scene.camera
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(folder, exist_ok=True)
    fps = scene.render.fps / scene.render.fps_base
    out = {
        "name": os.path.splitext(os.path.basename(path))[0],
        "frame_time": 1.0 / fps,
        "frames": scene.frame_end - scene.frame_start,
        "garments": [],
        "obstacles": [],
    }
    for obj in characters:
        armature = armature_of(obj)
        file = obj.name + ".gltf"
        export_gltf(os.path.join(folder, file), [obj, armature])
        character = {"file": file, "recenter": False}
        if armature.animation_data and armature.animation_data.action:
            character["clip"] = armature.animation_data.action.name
        out["obstacles"].append({"name": obj.name, "character": character})
    for obj in garments:
        file = obj.name + ".obj"
        write_garment_obj(os.path.join(folder, file), obj)
        out["garments"].append({"name": obj.name, "mesh": file, "material": material or COTTON})
    if camera is not None:
        write_chan(os.path.join(folder, "camera.chan"), camera, scene)
        out["camera"] = {"chan": "camera.chan", "width": scene.render.resolution_x, "height": scene.render.resolution_y,
                         "near": camera.data.clip_start, "far": camera.data.clip_end}
    with open(path, "w") as f:
        json.dump(out, f, indent=1)
    return out


class ExportVdclothScene(bpy.types.Operator, ExportHelper):
    """Write the selected armature-deformed meshes as characters, the other selected meshes as
    garments and the scene camera as a vdcloth scene"""

    bl_idname = "export_scene.vdcloth_scene"
    bl_label = "Export vdcloth scene"
    filename_ext = ".json"

    def execute(self, context):
        selected = [o for o in context.selected_objects if o.type == "MESH"]
        characters = [o for o in selected if any(m.type == "ARMATURE" for m in o.modifiers)]
        garments = [o for o in selected if o not in characters]
        try:
            export_scene(self.filepath, characters, garments, context=context)
        except (OSError, ValueError) as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        return {"FINISHED"}


def menu(self, context):
    self.layout.operator(ExportVdclothScene.bl_idname, text="vdcloth scene")


def register():
    bpy.utils.register_class(ExportVdclothScene)
    bpy.types.TOPBAR_MT_file_export.append(menu)


def unregister():
    bpy.types.TOPBAR_MT_file_export.remove(menu)
    bpy.utils.unregister_class(ExportVdclothScene)
