# A rigged humanoid as another package's artist hands it over, made headless from the
# project's own figure (tests/scenes/test_rigged_humanoid.cpp and bench/RESULTS.md use it):
#
#   blender -b --factory-startup --python make_rigged_humanoid.py -- MOTION.bvh BODY.obj OUT.fbx
#
# The BVH becomes an armature with its clip, the body OBJ (y up, in the motion's rest pose) its
# mesh, skinned by Blender's automatic (heat) weights; the joints are renamed to 3ds Max
# Biped's scheme ("Bip01 Pelvis", "Bip01 L Thigh", ...) and the file is written as an FBX
# with z up, in centimetres, with leaf bones (the chains' ends).
import builtins
import sys

import bpy
import io_anim_bvh.import_bvh as bvh_reader

bvh_reader.open = lambda f, mode="r", *a, **k: builtins.open(f, mode.replace("U", ""), *a, **k)  # Python 3.11 has no 'U' mode

BIPED = {"Hips": "Bip01 Pelvis", "Spine": "Bip01 Spine", "Chest": "Bip01 Spine1", "Neck": "Bip01 Neck", "Head": "Bip01 Head"}
for side, s in (("Left", "L"), ("Right", "R")):
    BIPED.update({side + "Shoulder": "Bip01 %s Clavicle" % s, side + "Arm": "Bip01 %s UpperArm" % s,
                  side + "ForeArm": "Bip01 %s Forearm" % s, side + "Hand": "Bip01 %s Hand" % s,
                  side + "UpLeg": "Bip01 %s Thigh" % s, side + "Leg": "Bip01 %s Calf" % s,
                  side + "Foot": "Bip01 %s Foot" % s, side + "Toe": "Bip01 %s Toe0" % s})


def absolute_root(bvh, out):
    """The BVH with the root's offset added to its position channels: Blender's reader takes
    those channels as where the root is, not as a move from its offset (BVH's convention)."""
    lines = open(bvh).read().split("\n")
    offset = [float(v) for v in next(l for l in lines if l.strip().startswith("OFFSET")).split()[1:4]]
    motion = next(i for i, l in enumerate(lines) if l.strip() == "MOTION")
    for i in range(motion + 3, len(lines)):
        values = lines[i].split()
        if len(values) >= 3:
            lines[i] = " ".join(["%.9g" % (float(values[k]) + offset[k]) for k in range(3)] + values[3:])
    open(out, "w").write("\n".join(lines))


def main(bvh, body, out):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    absolute_root(bvh, out + ".bvh")
    bpy.ops.import_anim.bvh(filepath=out + ".bvh", axis_forward="-Z", axis_up="Y", global_scale=1.0, rotate_mode="NATIVE",
                            update_scene_fps=True, update_scene_duration=True)
    rig = bpy.context.active_object
    bpy.ops.wm.obj_import(filepath=body, forward_axis="NEGATIVE_Z", up_axis="Y")
    skin = next(o for o in bpy.context.scene.objects if o.type == "MESH")
    for bone in rig.data.bones:
        bone.name = BIPED.get(bone.name, bone.name)
    bpy.ops.object.select_all(action="DESELECT")
    skin.select_set(True)
    rig.select_set(True)
    bpy.context.view_layer.objects.active = rig
    bpy.ops.object.parent_set(type="ARMATURE_AUTO")
    bpy.ops.export_scene.fbx(filepath=out, use_selection=True, axis_forward="-Y", axis_up="Z", apply_unit_scale=True,
                             global_scale=1.0, add_leaf_bones=True, bake_anim=True, bake_anim_use_all_actions=False,
                             bake_anim_use_nla_strips=False)
    print("make_rigged_humanoid: %d bones, %d vertices in %d groups, frames %d to %d -> %s" % (
        len(rig.data.bones), len(skin.data.vertices), len(skin.vertex_groups), bpy.context.scene.frame_start,
        bpy.context.scene.frame_end, out))


if __name__ == "__main__":
    main(*sys.argv[sys.argv.index("--") + 1:][:3])
