// Character obstacles in scenes: the skinned body placed by its transform, moving with the
// motion from its start time, and refused when an obstacle names both a mesh and a character.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "scene/bvh_motion.hpp"
#include "io/obj.hpp"
#include "scene/figure.hpp"
#include "scene/scene.hpp"
#include "support/humanoid_skeletons.hpp"
#include "support/scene_crossings.hpp"
#include "support/temp_file.hpp"

namespace vdc {
namespace {

using test::temp_dir;

namespace fs = std::filesystem;

std::string write_scene(const std::string& obstacle) {
  const fs::path dir = fs::temp_directory_path() / ("vdcloth_character_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "scene.json") << R"({"garments": [{"name": "s", "mesh": {"grid": {"size": [1, 1], "cells": [1, 1]}},
    "material": {"density": 0.1, "stretch": {"warp": 100, "weft": 100, "shear": 10}, "bending": 1e-6}}],
    "obstacles": [)" + obstacle + "]}";
  return (dir / "scene.json").string();
}

TEST(Character, PlacedSkinnedBodyFollowsItsMotion) {
  const std::string motion = std::string(VDCLOTH_SOURCE_DIR) + "/motions/dance.bvh";
  Scene s = load_scene(write_scene(R"({"name": "d", "character": {"motion": ")" + motion +
                                   R"(", "start": 0.5, "resolution": 0.04}, "transform": {"translate": [2, 0, 0], "rotate": [0, 90, 0]}})"));
  fs::remove_all(fs::path(s.path).parent_path());
  ASSERT_EQ(s.obstacles.size(), 1u);
  const ObstacleSpec& o = s.obstacles[0];
  ASSERT_TRUE(o.character);
  EXPECT_TRUE(o.moves());
  // Before the clip starts the body holds its rest pose: the rest mesh, turned and moved.
  const std::vector<Vec3> x0 = o.positions_at(0.0);
  const MeshSource& rest = o.character->rest_mesh();
  ASSERT_EQ(x0.size(), rest.positions.size());
  for (std::size_t i = 0; i < x0.size(); i += 97) {
    const Vec3& p = rest.positions[i];
    EXPECT_LT((x0[i] - Vec3(2 + p.z(), p.y(), -p.x())).norm(), 1e-12) << i;
  }
  for (NodeId n : o.mesh.nodes()) ASSERT_EQ(o.mesh.x(n), x0[static_cast<std::size_t>(n.idx)]);
  // Three seconds into the dance the body has moved.
  const std::vector<Vec3> x3 = o.positions_at(3.5);
  double moved = 0;
  for (std::size_t i = 0; i < x0.size(); ++i) moved = std::max(moved, (x3[i] - x0[i]).norm());
  EXPECT_GT(moved, 0.2);
}

// The ball occlusion culls bodies by holds every vertex of the placed, scaled body through the
// whole dance, found without skinning; an obstacle a rigid motion moves has none (radius -1).
TEST(Character, ItsReachHoldsTheBodyThroughTheWholeMotion) {
  const std::string motion = std::string(VDCLOTH_SOURCE_DIR) + "/motions/dance.bvh";
  Scene s = load_scene(write_scene(R"({"name": "d", "character": {"motion": ")" + motion +
                                   R"(", "resolution": 0.04}, "transform": {"translate": [2, 0, 0], "rotate": [0, 90, 0], "scale": 1.2}})"));
  fs::remove_all(fs::path(s.path).parent_path());
  const ObstacleSpec& o = s.obstacles[0];
  double closest_call = 0;  // the largest share of the radius any vertex needs
  for (double t = 0; t <= 10; t += 0.25) {
    const auto [centre, radius] = o.reach_at(t);
    ASSERT_GT(radius, 1.2 * 1.5);  // at least the figure's height, scaled
    ASSERT_LT(radius, 1.2 * 2.5);
    for (const Vec3& x : o.positions_at(t)) {
      ASSERT_LE((x - centre).norm(), radius) << "t = " << t;
      closest_call = std::max(closest_call, (x - centre).norm() / radius);
    }
  }
  EXPECT_GT(closest_call, 0.4);
  Scene moved = load_scene(write_scene(R"({"name": "d", "character": {"motion": ")" + motion +
                                       R"(", "resolution": 0.04}, "motion": {"translate": [{"time": 0, "offset": [0, 0, 0]}, {"time": 1, "offset": [1, 0, 0]}]}})"));
  fs::remove_all(fs::path(moved.path).parent_path());
  EXPECT_EQ(moved.obstacles[0].reach_at(0.5).second, -1.0);
}

// "mirror": the character dances the mirror image: its left hand where the unmirrored one's
// right hand is, reflected in the plane x = 0 it is placed on.
TEST(Character, AMirroredCharacterDancesTheMirrorImage) {
  const std::string motion = std::string(VDCLOTH_SOURCE_DIR) + "/motions/dance.bvh";
  auto load = [&](bool mirror) {
    Scene s = load_scene(write_scene(R"({"name": "d", "character": {"motion": ")" + motion + R"(", "resolution": 0.05, "mirror": )" +
                                     (mirror ? "true" : "false") + "}}"));
    fs::remove_all(fs::path(s.path).parent_path());
    return s.obstacles[0].character;
  };
  const auto plain = load(false), mirror = load(true);
  const auto& skeleton = plain->motion().skeleton;
  int left = -1, right = -1;
  for (std::size_t j = 0; j < skeleton.joints.size(); ++j) {
    if (skeleton.joints[j].name == "LeftHand") left = static_cast<int>(j);
    if (skeleton.joints[j].name == "RightHand") right = static_cast<int>(j);
  }
  ASSERT_GE(left, 0);
  ASSERT_GE(right, 0);
  for (double t : {0.0, 1.3, 4.1}) {
    const Vec3 r = plain->joint_transform(right, t).translation(), l = mirror->joint_transform(left, t).translation();
    EXPECT_LT((l - Vec3(-r.x(), r.y(), r.z())).norm(), 1e-9) << "t = " << t;
  }
}

TEST(Character, AnObstacleIsAMeshOrACharacter) {
  const std::string motion = std::string(VDCLOTH_SOURCE_DIR) + "/motions/dance.bvh";
  const std::string both = write_scene(R"({"name": "d", "mesh": {"sphere": {"radius": 1}}, "character": {"motion": ")" + motion + R"("}})");
  EXPECT_THROW(load_scene(both), InputError);
  const std::string missing = write_scene(R"({"name": "d", "character": {"motion": "nowhere.bvh"}})");
  try {
    load_scene(missing);
    ADD_FAILURE() << "accepted a missing motion";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("obstacles[0].character.motion"), std::string::npos) << e.what();
  }
  fs::remove_all(fs::path(missing).parent_path());
}

// A skin from a file: the procedural body written to OBJ and given back as the character's
// `skin` moves exactly as the procedural character (same mesh, same automatic weights), and the
// skin is scaled with the motion.
TEST(Character, SkinFromAFileIsSkinnedLikeTheProceduralBody) {
  const std::string motion = std::string(VDCLOTH_SOURCE_DIR) + "/motions/dance.bvh";
  Scene procedural = load_scene(write_scene(R"({"name": "d", "character": {"motion": ")" + motion + R"(", "resolution": 0.05}})"));
  const fs::path dir = fs::path(procedural.path).parent_path();
  ASSERT_TRUE(write_obj(procedural.obstacles[0].mesh, (dir / "skin.obj").string()));
  // Written at the rest pose (time 0): the file is the rest mesh. A skin and a motion both in
  // units of half a metre come back to the same body with scale 0.5.
  std::ofstream(dir / "half.obj") << [&] {
    std::ifstream in(dir / "skin.obj");
    std::string line, out;
    while (std::getline(in, line)) {
      if (line.rfind("v ", 0) == 0) {
        std::istringstream v(line.substr(2));
        double x, y, z;
        v >> x >> y >> z;
        char buf[128];
        std::snprintf(buf, sizeof buf, "v %.17g %.17g %.17g", 2 * x, 2 * y, 2 * z);
        line = buf;
      }
      out += line + "\n";
    }
    return out;
  }();
  Scene from_file = load_scene(write_scene(R"({"name": "d", "character": {"motion": ")" + motion + R"(", "skin": "skin.obj"}})"));
  Motion doubled = read_bvh(motion);
  scale_lengths(doubled, 2.0);
  write_bvh(doubled, (dir / "double.bvh").string());
  Scene halved = load_scene(write_scene(R"({"name": "d", "character": {"motion": "double.bvh", "skin": "half.obj", "scale": 0.5}})"));
  fs::remove_all(dir);
  for (double t : {0.0, 1.3, 4.0}) {
    const std::vector<Vec3> a = procedural.obstacles[0].positions_at(t), b = from_file.obstacles[0].positions_at(t),
                            c = halved.obstacles[0].positions_at(t);
    ASSERT_EQ(a.size(), b.size());
    ASSERT_EQ(a.size(), c.size());
    double worst = 0, worst_halved = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      worst = std::max(worst, (a[i] - b[i]).norm());
      worst_halved = std::max(worst_halved, (a[i] - c[i]).norm());
    }
    EXPECT_EQ(worst, 0.0) << t;
    EXPECT_LT(worst_halved, 1e-12) << t;
  }
}


// A capture whose root starts away from the origin is brought over it (its height kept): the
// dance moved 1.5 m along x and -2 m along z comes back to the dance; with "recenter": false it
// stays where the capture has it.
TEST(Character, ACaptureStartsWhereTheSceneStandsItUnlessAskedNotTo) {
  const std::string motion = std::string(VDCLOTH_SOURCE_DIR) + "/motions/dance.bvh";
  Scene own = load_scene(write_scene(R"({"name": "d", "character": {"motion": ")" + motion + R"(", "resolution": 0.05}})"));
  const fs::path dir = fs::path(own.path).parent_path();
  Motion away = read_bvh(motion);
  const Joint& root = away.skeleton.joints.front();
  for (auto& frame : away.frames)
    for (std::size_t c = 0; c < root.channels.size(); ++c) {
      double& value = frame[static_cast<std::size_t>(root.first_channel) + c];
      if (root.channels[c] == Channel::XPosition) value += 1.5;
      if (root.channels[c] == Channel::ZPosition) value -= 2.0;
    }
  ASSERT_TRUE(write_bvh(away, (dir / "away.bvh").string()));
  Scene recentered = load_scene(write_scene(R"({"name": "d", "character": {"motion": "away.bvh", "resolution": 0.05}})"));
  Scene kept = load_scene(write_scene(R"({"name": "d", "character": {"motion": "away.bvh", "resolution": 0.05, "recenter": false}})"));
  fs::remove_all(dir);
  for (double t : {0.0, 2.0, 5.0}) {
    const std::vector<Vec3> a = own.obstacles[0].positions_at(t), b = recentered.obstacles[0].positions_at(t),
                            c = kept.obstacles[0].positions_at(t);
    ASSERT_EQ(a.size(), b.size());
    ASSERT_EQ(a.size(), c.size());
    double back = 0, away_by = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      back = std::max(back, (b[i] - a[i]).norm());
      away_by = std::max(away_by, (c[i] - a[i] - Vec3(1.5, 0, -2)).norm());
    }
    EXPECT_LT(back, 1e-9) << t;     // the file's values are rounded when written
    EXPECT_LT(away_by, 1e-9) << t;
  }
}

// A character's scene with a fitted dress and a belt held at the hips, as loaded: a shot of four
// frames, so that the arms' reach the held belt must clear is measured over a few poses only.
Scene dressed(const fs::path& dir, const std::string& motion, double scale = 1, const std::string& hips = "Hips", const std::string& extra = "") {
  std::ofstream(dir / "scene.json") << R"({"frames": 4, "garments": [
    {"name": "dress", "mesh": {"dress": {}}, "material": {"density": 0.1, "stretch": {"warp": 100, "weft": 100, "shear": 10}, "bending": 1e-6}},
    {"name": "belt", "mesh": {"tube": {"top": [1.06, 0.23], "bottom": [0.99, 0.23]}},
     "material": {"density": 0.1, "stretch": {"warp": 100, "weft": 100, "shear": 10}, "bending": 1e-6},
     "handles": [{"box": [[-1, 1.055, -1], [1, 1.065, 1]], "attach": {"obstacle": "d", "joint": ")" +
                                            hips + R"("}}]}],
    "obstacles": [{"name": "d", "character": {"motion": ")" +
                                            motion + R"(", "resolution": 0.05, "scale": )" + std::to_string(scale) + extra + "}}]}";
  return load_scene((dir / "scene.json").string());
}

// The farthest any garment node of `a` is from the same node of `b` (infinite when their meshes differ).
double garments_apart(const Scene& a, const Scene& b) {
  double apart = 0;
  for (std::size_t g = 0; g < a.garments.size(); ++g) {
    const Mesh &x = a.garments[g].mesh, &y = b.garments[g].mesh;
    if (x.num_nodes() != y.num_nodes()) return INFINITY;
    for (NodeId n : x.nodes()) apart = std::max(apart, (x.x(n) - y.x(n)).norm());
  }
  return apart;
}

// The figure is found by its shape: every motion the project ships and the captures of
// assimp-testmodels, renamed j0, j1, ... with their joints in another order, dress alike (the
// same garment nodes within a millimetre) and hold the belt at the same joint.
TEST(Character, AFigureDressesAlikeWhateverItsJointsAreCalledAndInWhatOrder) {
  const fs::path dir = temp_dir("renamed");
  const std::string captures = "/usr/share/assimp/models/BVH/";
  // One motion of each skeleton: karate's is dance's, 01_03's is 01_01's (Humanoid's tests
  // recognise every one renamed).
  const std::vector<std::pair<std::string, double>> motions{
      {std::string(VDCLOTH_SOURCE_DIR) + "/motions/dance.bvh", 1.0}, {captures + "01_01.bvh", 0.056}, {captures + "Boxing_Toes.bvh", 0.01}};
  for (const auto& [motion, scale] : motions) {
    const Motion original = read_bvh(motion);
    std::vector<int> moved_to;
    ASSERT_TRUE(write_bvh(test::renamed_and_reordered(original, &moved_to), (dir / "renamed.bvh").string()));
    const Scene own = dressed(dir, motion, scale), renamed = dressed(dir, "renamed.bvh", scale, "Hips");
    EXPECT_LT(garments_apart(own, renamed), 1e-3) << motion;
    EXPECT_EQ(moved_to[static_cast<std::size_t>(own.garments[1].handles[0].joint)], renamed.garments[1].handles[0].joint) << motion;
    EXPECT_EQ(own.garments[0].fitted_to, renamed.garments[0].fitted_to) << motion;
  }
  fs::remove_all(dir);
}

// The dancer of solo-dancer dressed by CMU's captures (assimp-testmodels) as they are, without
// joint_names: the run starts with nothing crossing (the pre-roll and the shot from there are
// scenes/test_characters.cpp's CaptureShot).
TEST(Character, CmuCapturesDressTheDancerWithoutCrossings) {
  const fs::path dir = temp_dir("cmu");
  for (const char* capture : {"01_01.bvh", "01_03.bvh"}) {
    std::stringstream text;
    text << std::ifstream(std::string(VDCLOTH_SOURCE_DIR) + "/scenes/solo-dancer.json").rdbuf();
    std::string scene = text.str();
    const std::string motion = R"("motion": "../motions/dance.bvh")";
    ASSERT_NE(scene.find(motion), std::string::npos);
    scene.replace(scene.find(motion), motion.size(), R"("scale": 0.056, "motion": "/usr/share/assimp/models/BVH/)" + std::string(capture) + "\"");
    for (std::size_t at = scene.find("../"); at != std::string::npos; at = scene.find("../", at)) scene.replace(at, 3, std::string(VDCLOTH_SOURCE_DIR) + "/");
    std::ofstream(dir / "scene.json") << scene;
    const Simulation run(load_scene((dir / "scene.json").string()), SimOptions{SimMode::Adaptive, 1});
    EXPECT_EQ(run.scene().garments[0].fitted_to, "dancer") << capture;
    EXPECT_EQ(test::first_crossing(run), "") << capture;
  }
  fs::remove_all(dir);
}

// The project's figure as three other schemes rig it: the upper arm called Shoulder with a Collar
// above it, twist joints halfway along the upper arms, forearms and thighs, and Biped's tree and
// names. Each dresses without a crossing: the first exactly as the project's figure, the second
// within a millimetre (the twists change neither the landmarks nor the body's bones), Biped
// within 1.5 cm (its body differs: no joint at the project's chest, so the capsule from chest to
// neck that tapers on the project's figure runs full width up to where the arms part).
TEST(Character, OtherRigsOfTheFigureDressAsIt) {
  const fs::path dir = temp_dir("rigs");
  const Skeleton figure = figure_skeleton();
  ASSERT_TRUE(write_bvh(test::standing(figure), (dir / "figure.bvh").string()));
  const Scene own = dressed(dir, "figure.bvh");
  Motion collar = test::standing(figure);
  for (Joint& j : collar.skeleton.joints) {
    for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
             {"Shoulder", "Collar"}, {"ForeArm", "Elbow"}, {"Arm", "Shoulder"}, {"Hand", "Wrist"}, {"UpLeg", "Hip"}, {"Leg", "Knee"}, {"Foot", "Ankle"}, {"Toe", "Toes"}})
      if (const std::size_t at = j.name.find(from); at != std::string::npos && !j.end_site) {
        j.name.replace(at, from.size(), to);
        break;
      }
  }
  ASSERT_EQ(collar.skeleton.joints[7].name, "LeftShoulder");  // the upper arm
  struct Rig {
    std::string name;
    Motion motion;
    double apart;  // m: how far its garments may be from the project's figure's
  };
  for (const Rig& rig : {Rig{"collar", collar, 1e-9}, Rig{"twist", test::standing(test::twist_skeleton()), 1e-3},
                         Rig{"biped", test::standing(test::biped_skeleton()), 0.015}}) {
    ASSERT_TRUE(write_bvh(rig.motion, (dir / (rig.name + ".bvh")).string()));
    const Scene dressed_rig = dressed(dir, rig.name + ".bvh", 1, rig.name == "biped" ? "Bip01 Pelvis" : "Hips");
    EXPECT_EQ(test::first_crossing(dressed_rig), "") << rig.name;
    EXPECT_LT(garments_apart(own, dressed_rig), rig.apart) << rig.name;
  }
  fs::remove_all(dir);
}

// Names a scene gives: a capture's own joint by its name, its joints renamed by joint_names,
// and the errors for a rename of a joint the capture lacks and a joint of neither.
TEST(Character, AScenesJointNamesFindAndRenameACapturesJoints) {
  const fs::path dir = temp_dir("names");
  const std::string motion = std::string(VDCLOTH_SOURCE_DIR) + "/motions/dance.bvh";
  Motion other = read_bvh(motion);
  for (Joint& j : other.skeleton.joints)
    if (j.name == "Hips") j.name = "pelvis_ctrl";
  ASSERT_TRUE(write_bvh(other, (dir / "other.bvh").string()));
  const Scene own = dressed(dir, motion);
  const Scene by_own_name = dressed(dir, "other.bvh", 1, "pelvis_ctrl");
  const Scene renamed = dressed(dir, "other.bvh", 1, "Hips", R"(, "joint_names": {"pelvis_ctrl": "Hips"})");
  EXPECT_EQ(by_own_name.garments[1].handles[0].joint, 0);
  EXPECT_EQ(renamed.garments[1].handles[0].joint, 0);
  EXPECT_EQ(garments_apart(own, renamed), 0.0);
  try {
    dressed(dir, "other.bvh", 1, "Hips", R"(, "joint_names": {"LeftArm_x": "LeftArm"})");
    ADD_FAILURE() << "a rename of a joint the motion does not have was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("joint_names: the motion has no joint 'LeftArm_x' to rename"), std::string::npos) << e.what();
  }
  try {
    dressed(dir, motion, 1, "Tail");
    ADD_FAILURE() << "a missing joint was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the motion has no joint 'Tail'; its joints: Hips"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

// A capture of a 1.6 m figure at 120 frames a second that holds a T-pose for one frame before its motion: the shot
// starts after that frame, the run a second earlier (the default pre-roll) with the figure in
// the T-pose, and the garments are made for the 1.6 m figure, their handles the same nodes.
TEST(Character, ACaptureIsDressedInItsReferencePoseAndPrerolledIntoItsFirstPose) {
  const fs::path dir = fs::temp_directory_path() / ("vdcloth_dressing_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const double s = 1.6 / 1.75;
  const Skeleton figure = figure_skeleton(1.6);
  PoseKey t_pose, rest, step;
  t_pose.rotation = {{"LeftArm", Vec3(0, 0, 50)}, {"RightArm", Vec3(0, 0, -50)}};
  step.time = 1;
  step.root = Vec3(0.2, 0, 0);
  Motion capture = author_motion(figure, {rest, step}, 120, "walk");
  capture.frames.insert(capture.frames.begin(), author_motion(figure, {t_pose}, 120, "tee").frames.front());
  ASSERT_TRUE(write_bvh(capture, (dir / "capture.bvh").string()));
  auto scene = [&](const std::string& dress_fit) {
    std::ofstream(dir / "scene.json") << R"({"garments": [
      {"name": "dress", "mesh": {"dress": {}}, "material": {"density": 0.1, "stretch": {"warp": 100, "weft": 100, "shear": 10}, "bending": 1e-6})" +
                                               dress_fit + R"(},
      {"name": "belt", "mesh": {"tube": {"top": [1.06, 0.23], "bottom": [0.99, 0.23]}},
       "material": {"density": 0.1, "stretch": {"warp": 100, "weft": 100, "shear": 10}, "bending": 1e-6},
       "handles": [{"box": [[-1, 1.055, -1], [1, 1.065, 1]], "attach": {"obstacle": "walker", "joint": "Hips"}}]}],
      "obstacles": [{"name": "walker", "character": {"motion": "capture.bvh", "resolution": 0.05}}]})";
    return load_scene((dir / "scene.json").string());
  };
  const Scene fitted = scene("");
  const Scene as_given = scene(R"(, "fit": false)");
  EXPECT_THROW(scene(R"(, "fit": "nobody")"), InputError);
  fs::remove_all(dir);

  EXPECT_EQ(fitted.preroll_frames, 25);
  EXPECT_NEAR(fitted.start_time(), -1.0, 1e-12);
  const Character& walker = *fitted.obstacles[0].character;
  EXPECT_EQ(walker.preroll(), 1.0);
  EXPECT_EQ(walker.motion().frames.size(), capture.frames.size() - 1);  // the T-pose is not played
  // The body starts in the T-pose and is in the first frame's pose when the shot starts.
  const std::vector<Vec3> t_posed = walker.positions_at(-1), first = walker.positions_at(0);
  for (NodeId n : fitted.obstacles[0].mesh.nodes()) ASSERT_EQ(fitted.obstacles[0].mesh.x(n), t_posed[static_cast<std::size_t>(n.idx)]);
  double moved = 0;
  for (std::size_t i = 0; i < first.size(); ++i) moved = std::max(moved, (first[i] - t_posed[i]).norm());
  EXPECT_GT(moved, 0.3);
  EXPECT_TRUE(walker.skinned(walker.dressing_pose()) == t_posed);

  // The dress's hem hangs at the 1.6 m figure's 0.45 x 1.6 / 1.75 m instead of 0.45 m.
  auto lowest = [](const Mesh& m) {
    double y = 1e9;
    for (NodeId n : m.nodes()) y = std::min(y, m.x(n).y());
    return y;
  };
  EXPECT_NEAR(lowest(fitted.garments[0].mesh), s * 0.45, 1e-9);
  EXPECT_NEAR(lowest(as_given.garments[0].mesh), 0.45, 1e-9);
  EXPECT_EQ(fitted.garments[0].mesh.num_nodes(), as_given.garments[0].mesh.num_nodes());
  // The belt's handle holds its top ring, now at 1.06 x 1.6 / 1.75 m, carried by the hips from
  // where they are at the run's start.
  const Mesh& belt = fitted.garments[1].mesh;
  const auto& which = belt.node_attrs().get<int32_t>(kHandleAttr);
  const auto& anchor = belt.node_attrs().get<Vec3>(kAnchorAttr);
  int held = 0;
  for (NodeId n : belt.nodes())
    if (which[n] == 0) {
      ++held;
      EXPECT_NEAR(belt.x(n).y(), s * 1.06, 1e-9);
      EXPECT_EQ(anchor[n], belt.x(n));
      EXPECT_TRUE(belt.flags(n) & kNodeHandle);
    }
  EXPECT_EQ(held, 48);
  const ClothHandle& handle = fitted.garments[1].handles[0];
  EXPECT_TRUE(handle.carry(fitted.start_time()).isApprox(Eigen::Affine3d::Identity(), 1e-12));
  // At the shot's start the hips have stepped 0 m (the step starts there) and stand as in the
  // T-pose: the belt is where it was made.
  EXPECT_LT((handle.carry(0.0).translation()).norm(), 1e-9);
}

}  // namespace
}  // namespace vdc
