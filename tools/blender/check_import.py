# Checks the add-on against a run, in Blender without a window:
#   blender -b --factory-startup --python tools/blender/check_import.py -- RUN_DIR
# At every written frame each imported object must hold the vertex and face counts of its OBJ
# (counted here from the file's lines), each cloth mesh its `pattern` UV layer and, with a PLY,
# its `view` face attribute
# equal to the PLY's values, and each camera the position and viewing direction of its
# camera.json or camera_NAME.json, turned from y-up to z-up. Exit status 1 on any difference.
import json
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import vdcloth_import  # noqa: E402

run_dir = sys.argv[sys.argv.index("--") + 1]
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)


def counts(path):
    v = f = 0
    with open(path) as file:
        for line in file:
            v += line.startswith("v ")
            f += line.startswith("f ")
    return v, f


def last_face_uvs(path):
    """The material coordinates of the last face's corners, read from the file's lines."""
    vt, last = [], None
    with open(path) as file:
        for line in file:
            if line.startswith("vt "):
                vt.append(tuple(float(c) for c in line.split()[1:3]))
            elif line.startswith("f "):
                last = line
    return [vt[int(c.split("/")[1]) - 1] for c in last.split()[1:]]


made = vdcloth_import.import_run(run_dir)
scene = bpy.context.scene
files = vdcloth_import.frame_files(run_dir)
checked = 0
for (kind, name), by_frame in files.items():
    obj = bpy.data.objects[kind + "_" + name]
    for frame, path in sorted(by_frame.items()):
        scene.frame_set(frame)
        v, f = counts(path)
        check((len(obj.data.vertices), len(obj.data.polygons)) == (v, f),
              "%s frame %d: %d vertices, %d faces, the OBJ %d, %d" % (obj.name, frame, len(obj.data.vertices), len(obj.data.polygons), v, f))
        if kind == "cloth":
            layer = obj.data.uv_layers.get("pattern")
            check(layer is not None and len(layer.data) == sum(len(p.vertices) for p in obj.data.polygons),
                  "%s frame %d: no pattern UV layer" % (obj.name, frame))
            if layer is not None:
                last = obj.data.polygons[-1]
                got = [tuple(layer.data[i].uv) for i in last.loop_indices]
                check(all(abs(a[k] - b[k]) < 1e-5 for a, b in zip(got, last_face_uvs(path)) for k in range(2)),
                      "%s frame %d: pattern UVs %s, the OBJ's %s" % (obj.name, frame, got, last_face_uvs(path)))
        ply = path[:-4] + ".ply"
        if kind == "cloth" and os.path.exists(ply):
            columns = vdcloth_import.read_ply_columns(ply)
            if "reason" in columns:
                reason = obj.data.attributes.get("view_reason")
                check(reason is not None and [a.value for a in reason.data] == [int(r) for r in columns["reason"]],
                      "%s frame %d: view_reason attribute differs from the PLY" % (obj.name, frame))
            if "camera" in columns:
                decider = obj.data.attributes.get("view_camera")
                check(decider is not None and [a.value for a in decider.data] == [int(c) for c in columns["camera"]],
                      "%s frame %d: view_camera attribute differs from the PLY" % (obj.name, frame))
            values = columns["view"]
            attribute = obj.data.attributes.get("view")
            check(attribute is not None and attribute.domain == "FACE", "%s frame %d: no view face attribute" % (obj.name, frame))
            if attribute is not None:
                got = [a.value for a in attribute.data]
                check(len(got) == len(values) and all(abs(a - b) <= 1e-6 for a, b in zip(got, values)),
                      "%s frame %d: view attribute differs from the PLY" % (obj.name, frame))
        checked += 1

cameras = 0
for k, camera_path in enumerate(vdcloth_import.camera_files(run_dir)):
    with open(camera_path) as file:
        lens = json.load(file)
    frames = lens["frames"]
    camera = bpy.data.objects.get("shot_" + lens["name"] if "name" in lens else "shot")
    check(camera is not None, "no camera object for %s" % camera_path)
    if camera is None:
        continue
    check((scene.camera == camera) == (k == 0), "%s: the scene's camera is the first camera, not another" % camera.name)
    dof = lens.get("depth_of_field")
    check(camera.data.dof.use_dof == bool(dof), "camera depth of field %s, camera.json %s" % (camera.data.dof.use_dof, dof))
    if dof:
        focus = dof["focus_distance"] if not dof.get("follows_target") else camera.data.dof.focus_distance  # else checked by frame
        check(abs(camera.data.dof.focus_distance - focus) < 1e-5 and abs(camera.data.dof.aperture_fstop - dof["f_stop"]) < 1e-5,
              "camera focus %g m at f/%g, camera.json %s" % (camera.data.dof.focus_distance, camera.data.dof.aperture_fstop, dof))
        check(abs(camera.data.lens - lens["focal_length_mm"]) < 1e-3, "camera lens %g mm, camera.json %g" % (camera.data.lens, lens["focal_length_mm"]))
    for frame in frames:
        scene.frame_set(frame["frame"])
        if "focus_distance" in frame:
            check(abs(camera.data.dof.focus_distance - frame["focus_distance"]) < 1e-4,
                  "camera focus %g m at frame %d, camera.json %g" % (camera.data.dof.focus_distance, frame["frame"], frame["focus_distance"]))
        m = camera.matrix_world
        position = vdcloth_import.to_blender(frame["position"])
        forward = vdcloth_import.to_blender(frame["forward"]).normalized()
        looks = -m.to_3x3().col[2]
        check((m.translation - position).length < 1e-4, "camera frame %d at %s, expected %s" % (frame["frame"], tuple(m.translation), tuple(position)))
        check((looks.normalized() - forward).length < 1e-4, "camera frame %d looks along %s, expected %s" % (frame["frame"], tuple(looks), tuple(forward)))
        cameras += 1

print("check_import: %d object frames and %d camera frames checked, %d failure(s)" % (checked, cameras, len(failures)))
for f in failures[:20]:
    print("check_import: " + f)
sys.exit(1 if failures or checked == 0 else 0)
