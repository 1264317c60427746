# Blender add-on: loads a vdcloth run (RUN_DIR/frames, RUN_DIR/camera.json) into the scene.
# Each garment is one object whose mesh is swapped at every frame (remeshing changes its
# topology from frame to frame), with its pattern (material space, metres) as the UV layer
# `pattern` and the view factor as a float face attribute `view` where the run wrote it; each obstacle one object the same way; the shot camera keyed at every frame with
# constant interpolation, so cuts stay cuts. vdcloth is y-up, Blender z-up: (x, y, z) -> (x, -z, y).
#
# Install: Edit > Preferences > Add-ons > Install..., pick this file, enable "Import: vdcloth run";
# then File > Import > vdcloth run. From a script or `blender -b`:
#   import vdcloth_import; vdcloth_import.import_run("/path/to/run")
import glob
import json
import math
import os
import re

import bpy
from bpy_extras.io_utils import ImportHelper
from mathutils import Matrix, Vector

bl_info = {
    "name": "vdcloth run",
    "description": "Cloth, bodies, view factors and the shot camera of a vdcloth run",
    "blender": (3, 4, 0),
    "category": "Import-Export",
    "location": "File > Import > vdcloth run",
}

FRAME_FILE = re.compile(r"^(cloth|obstacle)_(.+)\.(\d{4,})\.obj$")


def to_blender(p):
    """A vdcloth (y-up) point or direction in Blender's z-up world."""
    return Vector((p[0], -p[2], p[1]))


def read_obj(path):
    """Positions, faces (0-based, polygons kept), material coordinates and the faces' indices
    into them (empty for an obstacle) of an OBJ as vdcloth writes it."""
    verts, faces, uvs, face_uvs = [], [], [], []
    with open(path) as f:
        for line in f:
            t = line.split()
            if not t:
                continue
            if t[0] == "v":
                verts.append(to_blender([float(c) for c in t[1:4]]))
            elif t[0] == "vt":
                uvs.append((float(t[1]), float(t[2])))
            elif t[0] == "f":
                corners = [c.split("/") for c in t[1:]]
                faces.append([int(c[0]) - 1 for c in corners])
                if all(len(c) > 1 and c[1] for c in corners):
                    face_uvs.append([int(c[1]) - 1 for c in corners])
    return verts, faces, uvs, face_uvs if len(face_uvs) == len(faces) else []


def read_ply_columns(path):
    """The per-face properties of the view factors' PLY ("view", and "reason" where written), by
    name, each a list in face order."""
    with open(path) as f:
        lines = f.read().split("\n")
    vertices = faces = 0
    names = []
    at = 0
    while lines[at] != "end_header":
        t = lines[at].split()
        if t[:2] == ["element", "vertex"]:
            vertices = int(t[2])
        elif t[:2] == ["element", "face"]:
            faces = int(t[2])
        elif t[:1] == ["property"] and faces and t[1] != "list":
            names.append(t[2])
        at += 1
    start = at + 1 + vertices
    rows = [lines[start + i].split() for i in range(faces)]
    return {name: [float(row[4 + k]) for row in rows] for k, name in enumerate(names)}


def read_ply_values(path):
    """The view factor of each face, in face order."""
    return read_ply_columns(path)["view"]


def frame_files(run_dir):
    """{(kind, name): {frame: path}} of RUN_DIR/frames."""
    found = {}
    for path in glob.glob(os.path.join(run_dir, "frames", "*.obj")):
        m = FRAME_FILE.match(os.path.basename(path))
        if m:
            found.setdefault((m.group(1), m.group(2)), {})[int(m.group(3))] = path
    if not found:
        raise ValueError(run_dir + ": no frame meshes in frames/ (was the run made with --mesh-every 0?)")
    return found


def build_mesh(name, path):
    verts, faces, uvs, face_uvs = read_obj(path)
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(verts, [], faces)
    if face_uvs:  # the garment's pattern pieces, in metres, laid side by side by the run
        layer = mesh.uv_layers.new(name="pattern")
        corners = [uvs[i] for face in face_uvs for i in face]
        layer.data.foreach_set("uv", [c for uv in corners for c in uv])
    ply = path[:-4] + ".ply"
    if os.path.exists(ply):
        columns = read_ply_columns(ply)
        if len(columns["view"]) == len(mesh.polygons):
            attribute = mesh.attributes.new(name="view", type="FLOAT", domain="FACE")
            attribute.data.foreach_set("value", columns["view"])
        # What set the face's resolution: 0 seen, 1 turned away, 2 out of frame, 3 defocused,
        # 4 motion-blurred.
        if len(columns.get("reason", [])) == len(mesh.polygons):
            attribute = mesh.attributes.new(name="view_reason", type="INT", domain="FACE")
            attribute.data.foreach_set("value", [int(r) for r in columns["reason"]])
        # A shot with several cameras: the camera whose factor the face took (its index).
        if len(columns.get("camera", [])) == len(mesh.polygons):
            attribute = mesh.attributes.new(name="view_camera", type="INT", domain="FACE")
            attribute.data.foreach_set("value", [int(c) for c in columns["camera"]])
    mesh.update()
    mesh.use_fake_user = True  # kept while another frame's mesh is shown
    return mesh


def camera_matrix(frame):
    """The camera's world matrix in Blender: it looks along its -Z with +Y up."""
    forward = to_blender(frame["forward"]).normalized()
    up = to_blender(frame["up"]).normalized()
    right = forward.cross(up).normalized()
    rotation = Matrix((right, up, -forward)).transposed()
    m = rotation.to_4x4()
    m.translation = to_blender(frame["position"])
    return m


def camera_files(run_dir):
    """The run's camera files in the scene's order: camera.json (the scene's one camera), or
    camera_NAME.json for each of its named cameras (ordered by their "index")."""
    single = os.path.join(run_dir, "camera.json")
    if os.path.exists(single):
        return [single]
    named = []
    for name in os.listdir(run_dir):
        if name.startswith("camera_") and name.endswith(".json"):
            path = os.path.join(run_dir, name)
            with open(path) as f:
                named.append((json.load(f).get("index", 0), name, path))
    return [path for _, _, path in sorted(named)]


def import_camera(path, scene, collection, first, first_frame=0):
    """One camera, keyed at every frame (run frame f at Blender frame first_frame + f): object
    "shot" (camera.json) or "shot_NAME"; the first becomes the scene's camera and sets the
    render's size, speed and motion blur."""
    with open(path) as f:
        cam = json.load(f)
    label = "shot_" + cam["name"] if "name" in cam else "shot"
    data = bpy.data.cameras.new(label)
    data.sensor_fit = "VERTICAL"
    if "sensor_height_mm" in cam:
        data.sensor_height = cam["sensor_height_mm"]
    data.angle_y = math.radians(cam["fov_y_degrees"])
    data.clip_start, data.clip_end = cam["near"], cam["far"]
    dof = cam.get("depth_of_field")
    if dof:
        data.dof.use_dof = True
        data.dof.focus_distance = dof["focus_distance"]
        data.dof.aperture_fstop = dof["f_stop"]
    if cam.get("shutter") and first:
        scene.render.use_motion_blur = True
        scene.render.motion_blur_shutter = cam["shutter"]
    obj = bpy.data.objects.new(label, data)
    collection.objects.link(obj)
    obj.rotation_mode = "XYZ"
    for frame in cam["frames"]:
        obj.matrix_world = camera_matrix(frame)
        at = first_frame + frame["frame"]
        obj.keyframe_insert("location", frame=at)
        obj.keyframe_insert("rotation_euler", frame=at)
        if dof and "focus_distance" in frame:  # the focus pulled frame by frame
            data.dof.focus_distance = frame["focus_distance"]
            data.keyframe_insert("dof.focus_distance", frame=at)
        if "fov_y_degrees" in frame:  # a zoom
            data.angle_y = math.radians(frame["fov_y_degrees"])
            data.keyframe_insert("lens", frame=at)
        if frame["cut"]:
            obj["cuts"] = list(obj.get("cuts", [])) + [at]
    curves = list(obj.animation_data.action.fcurves)
    if data.animation_data and data.animation_data.action:
        curves += list(data.animation_data.action.fcurves)
    for curve in curves:
        for key in curve.keyframe_points:
            key.interpolation = "CONSTANT"
    if first:
        scene.camera = obj
        scene.render.resolution_x, scene.render.resolution_y = cam["width"], cam["height"]
        scene.render.fps = max(1, round(1.0 / cam["frame_time"]))
    return obj


@bpy.app.handlers.persistent
def show_frame(scene, *args):
    """Shows each imported object's mesh of the last written frame at or before the current one."""
    for obj in scene.objects:
        frames = obj.get("vdcloth_frames")
        if not frames:
            continue
        current = scene.frame_current - obj.get("vdcloth_first_frame", 0)
        chosen = frames[0]
        for f in frames:
            if f <= current:
                chosen = f
        mesh = bpy.data.meshes.get("%s.%04d" % (obj["vdcloth_name"], chosen))
        if mesh is not None and obj.data != mesh:
            obj.data = mesh


def import_run(run_dir, every=1, context=None, first_frame=0):
    """Loads the run into the current scene, its frame f at Blender frame first_frame + f (a scene
    exported from Blender: its frame_start); returns the objects made."""
    context = context or bpy.context
    scene = context.scene
    collection = bpy.data.collections.new(os.path.basename(os.path.normpath(run_dir)) or "vdcloth")
    scene.collection.children.link(collection)
    made = []
    all_frames = set()
    for (kind, name), files in sorted(frame_files(run_dir).items()):
        frames = sorted(files)[::every]
        label = kind + "_" + name
        for f in frames:
            build_mesh("%s.%04d" % (label, f), files[f])
        obj = bpy.data.objects.new(label, bpy.data.meshes["%s.%04d" % (label, frames[0])])
        obj["vdcloth_name"] = label
        obj["vdcloth_frames"] = frames
        obj["vdcloth_first_frame"] = first_frame
        collection.objects.link(obj)
        made.append(obj)
        all_frames.update(frames)
    for k, path in enumerate(camera_files(run_dir)):
        made.append(import_camera(path, scene, collection, k == 0, first_frame))
    scene.frame_start, scene.frame_end = first_frame + min(all_frames), first_frame + max(all_frames)
    if show_frame not in bpy.app.handlers.frame_change_pre:
        bpy.app.handlers.frame_change_pre.append(show_frame)
    scene.frame_set(scene.frame_start)
    return made


class ImportVdclothRun(bpy.types.Operator, ImportHelper):
    """Load a vdcloth run directory (its frames/ and its cameras)"""

    bl_idname = "import_scene.vdcloth_run"
    bl_label = "Import vdcloth run"
    filename_ext = ""
    use_filter_folder = True
    every: bpy.props.IntProperty(name="Every Nth frame", default=1, min=1)
    first_frame: bpy.props.IntProperty(name="First frame", default=0, description="The Blender frame of the run's frame 0")

    def execute(self, context):
        run_dir = self.filepath if os.path.isdir(self.filepath) else os.path.dirname(self.filepath)
        try:
            import_run(run_dir, self.every, context, self.first_frame)
        except (OSError, ValueError) as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        return {"FINISHED"}


def menu(self, context):
    self.layout.operator(ImportVdclothRun.bl_idname, text="vdcloth run")


def register():
    bpy.utils.register_class(ImportVdclothRun)
    bpy.types.TOPBAR_MT_file_import.append(menu)


def unregister():
    bpy.types.TOPBAR_MT_file_import.remove(menu)
    bpy.utils.unregister_class(ImportVdclothRun)
