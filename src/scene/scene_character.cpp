// An obstacle's `character` block (docs/scene-format.md, "obstacles[i]"): a BVH motion, in
// metres once scaled, driving the procedural body or the character's own skin, or a rigged
// character's file with its skin, weights and clip; with the shot's first frame, the dressing
// pose and the pre-roll into the shot.
#include "scene/scene_blocks.hpp"

#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>

#include "core/bvh.hpp"
#include "io/obj.hpp"
#include "scene/bvh_motion.hpp"
#include "scene/dressing.hpp"
#include "scene/joint_names.hpp"
#include "core/surface_repair.hpp"
#include "scene/rigged_model.hpp"
#include "scene/scene_values.hpp"

namespace vdc {

namespace {

// A capture whose first pose is further than this from the dressing pose (m, any joint) gets
// kDefaultPreroll seconds of pre-roll unless its scene says otherwise.
constexpr double kStillDistance = 0.01, kDefaultPreroll = 1.0, kLongestPreroll = 60.0;

// A character's skeleton must be of a person's size once scaled: a capture in other units (CMU's
// captures in inches, others in centimetres) would otherwise make a figure metres or millimetres
// tall, and the garments around it meaningless. The size is the largest extent of its joints in
// the rest pose, and of a rigged skin (whose joints may be few); `place` is what the error names
// (the scale, or the motion without one).
void check_figure_size(const Motion& motion, const std::optional<Skin>& skin, double scale, const JsonValue& place) {
  constexpr double kShortest = 0.5, kTallest = 3.0, kTypical = 1.7;  // m
  Aabb box;
  const auto rest = motion.world(Body::rest_pose(motion.skeleton));
  for (const auto& joint : rest) box.grow(Vec3(joint.translation()));
  if (skin)
    for (const auto& pulls : skin->weights)
      for (const SkinWeight& w : pulls) box.grow(rest[static_cast<std::size_t>(w.joint)] * w.local);
  const double size = (box.hi - box.lo).maxCoeff();
  if (size >= kShortest && size <= kTallest) return;
  std::ostringstream problem;
  problem << "the figure is " << std::setprecision(3) << size << " m tall with scale " << scale << " (its " << (skin ? "skin's" : "skeleton's")
          << " extent in the rest pose), not 0.5 to 3 m";
  if (size > 0) problem << ": scale " << std::setprecision(3) << scale * kTypical / size << " would make it 1.7 m";
  place.fail(problem.str());
}

// How far a capture's root stands, across the floor, from the origin at a frame: the
// shift that brings the figure to where the scene's transform places it (its height kept).
Vec3 recentering(const Motion& motion, int frame) {
  const Vec3 root = motion.world(motion.frame_pose(static_cast<std::size_t>(frame))).front().translation();
  return Vec3(root.x(), 0.0, root.z());
}

// The joints renamed as the block's `joint_names` asks.
void rename_as_asked(const JsonValue& c, Motion& motion) {
  const auto names = c.find("joint_names");
  if (!names) return;
  std::map<std::string, std::string> renames;
  for (const auto& [from, to] : names->members()) {
    const std::string name = to.string();
    if (name.empty()) to.fail("a joint's new name must not be empty");
    renames[from] = name;
  }
  try {
    rename_joints(motion.skeleton, renames);
  } catch (const std::invalid_argument& e) {
    names->fail(std::string("the motion has no joint '") + e.what() + "' to rename");
  }
}

// A skin's mirror image across x = 0, as `mirrored` makes its motion's (each joint taking its
// partner's motion, reflected): positions reflected, faces turned over, and each weight moved
// to the joint's partner with its joint-local position reflected.
void mirror_skin(Skin& skin, const std::vector<std::size_t>& partner) {
  const Vec3 reflect(-1, 1, 1);
  for (Vec3& x : skin.mesh.positions) x = x.cwiseProduct(reflect);
  for (auto& face : skin.mesh.faces) std::swap(face[1], face[2]);
  for (auto& pulls : skin.weights)
    for (SkinWeight& w : pulls) {
      w.joint = static_cast<int>(partner[static_cast<std::size_t>(w.joint)]);
      w.local = w.local.cwiseProduct(reflect);
    }
}

// The character's motion and, when it brings one, its skin (in the motion's units): a BVH
// `motion` with an optional OBJ `skin`, or a rigged `file` with its own skin and weights; the
// joints renamed and mirrored as the block asks; what reading it found added to `notes`.
std::pair<Motion, std::optional<Skin>> read_figure(const JsonValue& c, const std::string& scene_path, std::vector<std::string>& notes) {
  std::pair<Motion, std::optional<Skin>> out;
  auto& [motion, skin] = out;
  if (auto rigged = c.find("file")) {
    const std::string path = resolve_file(*rigged, scene_path);
    ClipChoice clip;
    if (auto k = c.find("clip")) clip = k->is_string() ? ClipChoice(k->string()) : ClipChoice(k->integer());
    RiggedModel model = with_key(c.has("clip") ? c.at("clip") : *rigged, [&] { return read_rigged_model(path, clip); });
    motion = std::move(model.motion);
    notes.insert(notes.end(), model.notes.begin(), model.notes.end());
    skin = Skin{std::move(model.skin), std::move(model.weights)};
  } else {
    const JsonValue file = c.at("motion");
    const std::string path = resolve_file(file, scene_path);
    motion = with_key(file, [&] { return read_bvh(path); });
    if (motion.frames.empty()) file.fail("the motion has no frames");
    if (auto s = c.find("skin")) {
      const std::string skin_path = resolve_file(*s, scene_path);
      skin = with_key(*s, [&] {
        try {  // repaired as any obstacle surface
          RepairedSurface r = repair_surface(read_obj_source(skin_path, false));
          if (const std::string found = r.repairs.summary(); !found.empty()) notes.push_back(skin_path + ": " + found);
          return Skin{std::move(r.mesh), {}};
        } catch (const MeshBuildError& e) {
          throw InputError(skin_path, "", std::string("cannot be a collision surface: ") + e.what());
        }
      });
    }
  }
  rename_as_asked(c, motion);
  if (c.boolean_or("mirror", false)) {
    try {
      if (skin && !skin->weights.empty()) mirror_skin(*skin, mirror_image_joints(motion.skeleton));
      motion = mirrored(motion);
    } catch (const std::invalid_argument& e) {
      c.at("mirror").fail(std::string("cannot mirror the motion: ") + e.what());
    }
  }
  return out;
}

// A skin scaled with its motion's lengths.
void scale_skin(Skin& skin, double scale) {
  for (Vec3& x : skin.mesh.positions) x *= scale;
  for (auto& pulls : skin.weights)
    for (SkinWeight& w : pulls) w.local *= scale;
}

// The shot starts at `first_frame`, by default after the capture's leading reference frames
// (its T-pose), which are then the pose the garments are made in (dressing.hpp).
int first_frame(const JsonValue& c, const Motion& motion, int reference) {
  const auto f = c.find("first_frame");
  if (!f) return reference;
  const long long k = f->integer();
  if (k < 0 || k >= static_cast<long long>(motion.frames.size()))
    f->fail("must be between 0 and " + std::to_string(motion.frames.size() - 1) + " (the motion's last frame)");
  return static_cast<int>(k);
}

// The dressing pose and the pre-roll into the shot; the frames before the shot's first dropped.
Dressing dress_and_trim(const JsonValue& c, Motion& motion, int reference, int first) {
  Dressing dressing;
  dressing.pose = dressing_pose(motion, std::min(reference, first), first);
  motion.frames.erase(motion.frames.begin(), motion.frames.begin() + first);
  // A capture that does not start in the dressing pose moves into it over a second by default.
  const double apart = largest_joint_distance(motion, *dressing.pose, motion.frame_pose(0));
  dressing.preroll = c.has("preroll") ? c.at("preroll").non_negative() : apart > kStillDistance ? kDefaultPreroll : 0.0;
  if (dressing.preroll > kLongestPreroll) c.at("preroll").fail("must be at most 60 s");
  return dressing;
}

// The body's build: by default as built as the project's figure, or slimmer if its arms would
// otherwise pass through its body where the garments are put on or anywhere in the shot.
double body_build(const JsonValue& c, const Motion& motion, const Pose& dressing, double start, double speed, double shot) {
  if (c.has("build")) return c.at("build").positive();
  std::vector<Pose> poses = clip_poses(MotionClip{&motion, start, speed}, 0.0, shot, kPoseSampleTime);
  poses.push_back(dressing);
  return build_clearing_arms(motion, poses, kArmClearance);
}

}  // namespace

std::shared_ptr<const Character> parse_character(const JsonValue& c, const std::optional<JsonValue>& transform,
                                                 const std::string& scene_path, double shot, BodyMeshCache& bodies,
                                                 std::vector<std::string>& notes) {
  if (c.has("file") && c.has("motion")) c.fail("a character has one of \"motion\" (a BVH file) and \"file\" (a rigged character), not both");
  if (c.has("file")) {
    c.only_keys({"file", "clip", "scale", "start", "speed", "recenter", "joint_names", "first_frame", "preroll", "mirror"});
  } else {
    c.only_keys({"motion", "skin", "scale", "build", "resolution", "start", "speed", "recenter", "joint_names", "first_frame", "preroll",
                 "mirror"});
  }
  auto [motion, skin] = read_figure(c, scene_path, notes);
  const double scale = c.positive_or("scale", 1.0);
  scale_lengths(motion, scale);
  if (skin) scale_skin(*skin, scale);
  const std::optional<Skin> rigged = skin && !skin->weights.empty() ? skin : std::nullopt;
  check_figure_size(motion, rigged, scale, c.has("scale") ? c.at("scale") : c.has("file") ? c.at("file") : c.at("motion"));
  const int reference = leading_reference_frames(motion);
  const int first = first_frame(c, motion, reference);
  if (c.boolean_or("recenter", true)) {
    const Vec3 shift = recentering(motion, first);
    motion.skeleton.joints.front().offset -= shift;
    if (skin)
      for (Vec3& x : skin->mesh.positions) x -= shift;
  }
  Dressing dressing = dress_and_trim(c, motion, reference, first);
  BodyParams body;
  body.resolution = c.positive_or("resolution", body.resolution);
  if (body.resolution < 0.005) c.at("resolution").fail("must be at least 0.005 m");
  const double start = c.number_or("start", 0.0), speed = c.positive_or("speed", 1.0);
  // A skin of its own is skinned by its weights, not by the build's.
  if (!skin || skin->weights.empty()) body.build = body_build(c, motion, *dressing.pose, start, speed, shot);
  const Transform placement = transform ? parse_transform(*transform) : Transform{};
  return std::make_shared<const Character>(std::move(motion), body, placement, start, speed, std::move(skin), std::move(dressing), &bodies);
}

}  // namespace vdc
