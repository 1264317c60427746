# The Blender round trip, headless (tests/app/test_blender_round_trip.cpp runs it):
#
#   blender -b --factory-startup --python check_round_trip.py -- make DIR
#       builds a shot in an empty scene (a two-bone leg of a skinned tube bending at the knee, a
#       cloth square above it, a camera that moves, turns, rolls and zooms; frames 1 to 13 at 25
#       frames a second), saves it as DIR/shot.blend and exports it with vdcloth_export as
#       DIR/shot.json;
#   vdcloth run DIR/shot.json --mode adaptive --out DIR/run
#   blender -b DIR/shot.blend --python check_round_trip.py -- check DIR/run
#       loads the run back with vdcloth_import onto the same frames and compares, frame by
#       frame, the run's character with Blender's own deformed tube (every vertex of either
#       within 0.1 mm of the other's surface points) and the run's camera with the scene camera
#       (position within 0.1 mm, view and up directions within 1e-5, field of view within
#       1e-4 degrees); prints "check_round_trip: N frames checked, F failure(s)" with the largest
#       differences, and exits 1 on any failure.
import math
import os
import sys

import bpy
from mathutils import Vector
from mathutils.kdtree import KDTree

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import vdcloth_export  # noqa: E402
import vdcloth_import  # noqa: E402

FIRST, LAST = 1, 13


def tube(name, radius=0.15, height=1.6, around=16, rings=17):
    """A closed tube standing on the ground, weighted to vertex groups "hip" (below the knee at
    0.8 m) and "knee", blended over 0.2 m."""
    verts, faces = [], []
    for r in range(rings):
        z = height * r / (rings - 1)
        for k in range(around):
            a = 2 * math.pi * k / around
            verts.append((radius * math.cos(a), radius * math.sin(a), z))
    for r in range(rings - 1):
        for k in range(around):
            a, b = r * around + k, r * around + (k + 1) % around
            faces.append((a, b, b + around, a + around))
    verts += [(0, 0, 0), (0, 0, height)]
    bottom, top = len(verts) - 2, len(verts) - 1
    for k in range(around):
        faces.append((bottom, (k + 1) % around, k))
        faces.append((top, (rings - 1) * around + k, (rings - 1) * around + (k + 1) % around))
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(verts, [], faces)
    obj = bpy.data.objects.new(name, mesh)
    hip, knee = obj.vertex_groups.new(name="hip"), obj.vertex_groups.new(name="knee")
    for i, v in enumerate(verts):
        w = min(1.0, max(0.0, (v[2] - 0.7) / 0.2))
        if w < 1:
            hip.add([i], 1 - w, "REPLACE")
        if w > 0:
            knee.add([i], w, "REPLACE")
    return obj


def make(folder):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = FIRST, LAST
    scene.render.fps = 25
    scene.render.resolution_x, scene.render.resolution_y = 640, 360
    armature = bpy.data.armatures.new("rig")
    rig = bpy.data.objects.new("rig", armature)
    scene.collection.objects.link(rig)
    bpy.context.view_layer.objects.active = rig
    bpy.ops.object.mode_set(mode="EDIT")
    hip = armature.edit_bones.new("hip")
    hip.head, hip.tail = (0, 0, 0), (0, 0, 0.8)
    knee = armature.edit_bones.new("knee")
    knee.head, knee.tail, knee.parent = (0, 0, 0.8), (0, 0, 1.6), hip
    bpy.ops.object.mode_set(mode="OBJECT")
    leg = tube("leg")
    scene.collection.objects.link(leg)
    leg.parent = rig
    leg.modifiers.new("rig", "ARMATURE").object = rig
    rig.animation_data_create().action = bpy.data.actions.new("Bend")
    pose = rig.pose.bones["knee"]
    pose.rotation_mode = "XYZ"
    for frame, angle in ((FIRST, 0.0), (7, 30.0), (LAST, 45.0)):  # the clip starts at rest
        pose.rotation_euler = (math.radians(angle), 0, 0)
        pose.keyframe_insert("rotation_euler", frame=frame)
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=8, y_subdivisions=8, size=0.6, location=(0.05, 0.3, 1.72))
    cloth = bpy.context.active_object
    cloth.name = "cloth"
    data = bpy.data.cameras.new("lens")
    data.sensor_fit = "VERTICAL"
    data.angle_y = math.radians(35)
    camera = bpy.data.objects.new("Camera", data)
    scene.collection.objects.link(camera)
    scene.camera = camera
    camera.rotation_mode = "XYZ"
    for frame, place, turn, fov in ((FIRST, (3, -3, 1.5), (80, 0, 45), 35), (LAST, (2.5, -3.5, 1.2), (85, 12, 30), 28)):
        camera.location, camera.rotation_euler = place, [math.radians(a) for a in turn]
        data.angle_y = math.radians(fov)
        camera.keyframe_insert("location", frame=frame)
        camera.keyframe_insert("rotation_euler", frame=frame)
        data.keyframe_insert("lens", frame=frame)
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(folder, "shot.blend"))
    vdcloth_export.export_scene(os.path.join(folder, "shot.json"), characters=[leg], garments=[cloth])
    print("check_round_trip: made and exported", os.path.join(folder, "shot.json"))


def check(run):
    scene = bpy.context.scene
    leg, camera = bpy.data.objects["leg"], scene.camera
    made = {o.name: o for o in vdcloth_import.import_run(run, first_frame=scene.frame_start)}
    body, shot = made["obstacle_leg"], made["shot"]
    frames = failures = 0
    largest = [0.0] * 5  # body, camera position, view, up, field of view
    for frame in range(scene.frame_start, scene.frame_end + 1):
        scene.frame_set(frame)
        depsgraph = bpy.context.evaluated_depsgraph_get()
        evaluated = leg.evaluated_get(depsgraph)
        theirs = [evaluated.matrix_world @ v.co for v in evaluated.to_mesh().vertices]
        ours = [body.matrix_world @ v.co for v in body.data.vertices]
        worst = 0.0
        for points, others in ((theirs, ours), (ours, theirs)):
            tree = KDTree(len(others))
            for i, p in enumerate(others):
                tree.insert(p, i)
            tree.balance()
            worst = max([worst] + [tree.find(p)[2] for p in points])
        evaluated.to_mesh_clear()
        a, b = camera.matrix_world, shot.matrix_world
        position = (a.translation - b.translation).length
        view = (a.to_3x3() @ Vector((0, 0, -1)) - b.to_3x3() @ Vector((0, 0, -1))).length
        up = (a.to_3x3() @ Vector((0, 1, 0)) - b.to_3x3() @ Vector((0, 1, 0))).length
        fov = abs(math.degrees(camera.data.angle_y - shot.data.angle_y))
        largest = [max(x, y) for x, y in zip(largest, (worst, position, view, up, fov))]
        ok = worst < 1e-4 and position < 1e-4 and view < 1e-5 and up < 1e-5 and fov < 1e-4
        if not ok:
            failures += 1
            print("check_round_trip: frame %d: body %.3g m, camera %.3g m, view %.3g, up %.3g, fov %.3g degrees" % (frame, worst, position, view, up, fov))
        frames += 1
    print("check_round_trip: %d frames checked, %d failure(s); largest differences: body %.2g m, camera %.2g m, "
          "view %.2g, up %.2g, field of view %.2g degrees" % tuple([frames, failures] + largest))
    return failures == 0 and frames == LAST - FIRST + 1


if __name__ == "__main__":
    args = sys.argv[sys.argv.index("--") + 1:]
    if args[0] == "make":
        make(args[1])
    elif not check(args[1]):
        sys.exit(1)
