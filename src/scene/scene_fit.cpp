// A garment's `fit` (docs/scene-format.md, "garments[i]"): the procedural garments a character
// wears made again for its figure (fitting.hpp), in the pose they are put on in, each cut in
// the same rows so that its handles hold the same nodes.
#include "scene/scene_blocks.hpp"

#include <algorithm>
#include <stdexcept>
#include <variant>

#include "core/mesh_build.hpp"
#include "physics/cloth_model.hpp"
#include "scene/dressing.hpp"
#include "scene/figure.hpp"
#include "scene/joint_names.hpp"

namespace vdc {

namespace {

// The character a garment is fitted to: its "fit" (a character's name, or false for none), by
// default the one character among the obstacles it collides with (its group's and those of no
// group), if there is exactly one. Null: the garment is made as given.
const ObstacleSpec* garment_wearer(const JsonValue& j, const GarmentSpec& g, const GarmentMaking& making, const std::vector<ObstacleSpec>& obstacles) {
  const auto fit = j.find("fit");
  if (fit && fit->raw().is_boolean() && !fit->boolean()) return nullptr;
  if (fit && fit->is_string()) {
    const std::string name = fit->string();
    const auto o = std::find_if(obstacles.begin(), obstacles.end(), [&](const ObstacleSpec& x) { return x.name == name; });
    if (o == obstacles.end()) fit->fail("no obstacle named '" + name + "'");
    if (!o->character) fit->fail("'" + name + "' is not a character");
    if (!o->group.empty() && o->group != g.group) fit->fail("'" + name + "' is in another group than the garment");
    if (!making.pattern) fit->fail("only a procedural garment (dress or tube) can be fitted to a character");
    return &*o;
  }
  if (fit && !fit->raw().is_boolean()) fit->fail("expected a character's name, true (the default) or false");
  if (!making.pattern) return nullptr;
  const ObstacleSpec* wearer = nullptr;
  for (const auto& o : obstacles)
    if (o.character && (o.group.empty() || o.group == g.group)) {
      if (wearer) return nullptr;
      wearer = &o;
    }
  return wearer;
}

// The project's figure as garments are sized for, with a body made as `body` makes the wearer's
// (so the two are measured alike); `bodies` keeps its polygonized body for the next wearer.
FigureMeasure reference_figure(const BodyParams& body, BodyMeshCache& bodies) {
  Motion figure;
  figure.skeleton = figure_skeleton();
  figure.frames.assign(1, std::vector<double>(static_cast<std::size_t>(figure.skeleton.num_channels), 0.0));
  BodyParams as_made = body;
  as_made.build = 1.0;
  const Body made(figure, as_made, &bodies);
  const Pose rest = Body::rest_pose(figure.skeleton);
  return measure_figure(figure, rest, made.rest_mesh(), made.skin(rest), made.main_joints());
}

// The wearer measured in its dressing pose and the fit from `reference` to it; an error names
// the garment `first` when either cannot be made.
FigureMeasure measure_wearer(const Character& wearer, const std::string& wearer_name, const JsonValue& first,
                             const FigureMeasure& reference, std::optional<GarmentFit>& fit) {
  const Pose& pose = wearer.dressing_pose();
  try {
    FigureMeasure figure = measure_figure(wearer.motion(), pose, wearer.rest_mesh(), wearer.skinned(pose), wearer.main_joints());
    fit.emplace(reference, figure);
    return figure;
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    const bool joint = what.find(' ') == std::string::npos;
    (first.has("fit") ? first.at("fit") : first)
        .fail("cannot fit the garment to character '" + wearer_name + "': " + (joint ? missing_joint(wearer.motion().skeleton, what) : what) +
              " (or set \"fit\": false)");
  }
}

// The share of its ease each garment keeps so that held nodes stay clear of the arms over the
// run's time, [start_time, shot] (1 when nothing is held); `figure` gains the arms' reach.
double ease_clearing_arms(const std::vector<std::size_t>& worn, const std::vector<GarmentSpec>& garments,
                          const std::vector<GarmentMaking>& making, const Character& wearer, const FigureMeasure& reference,
                          FigureMeasure& figure, std::optional<GarmentFit>& fit, double start_time, double shot) {
  std::vector<HeldGarment> held;
  for (std::size_t g : worn) {
    HeldGarment& h = held.emplace_back(HeldGarment{*making[g].pattern, {}});
    const auto& which = garments[g].mesh.node_attrs().get<int32_t>(kHandleAttr);
    for (NodeId n : garments[g].mesh.nodes())
      if (which[n] >= 0) h.held.push_back(n.idx);
  }
  if (std::none_of(held.begin(), held.end(), [](const HeldGarment& h) { return !h.held.empty(); })) return 1.0;
  std::vector<Pose> moving;
  const double end = std::min(shot, wearer.start() + wearer.motion().duration() / wearer.speed());  // held after
  for (double t : sample_times(start_time, std::max(start_time, end), kPoseSampleTime)) moving.push_back(wearer.pose_at(t));
  measure_arm_reach(figure, wearer.motion(), wearer.dressing_pose(), wearer.rest_mesh(), wearer.main_joints(), moving,
                    [&](const Pose& p) { return wearer.skinned(p); });
  fit.emplace(reference, figure);
  return fit->ease_clearing_arms(held, kArmClearance);
}

// Garment `garment`'s mesh made again from its fitted pattern, placed and held as before.
void remake_garment(GarmentSpec& garment, const GarmentPattern& fitted, const GarmentFit& fit, const GarmentMaking& making) {
  MeshSource source = std::visit([](const auto& p) { return make_garment(p); }, fitted);
  for (Vec3& x : source.positions) x = fit.place(x);
  Mesh mesh = build_mesh(source);
  if (mesh.num_nodes() != garment.mesh.num_nodes() || mesh.num_faces() != garment.mesh.num_faces())
    throw std::logic_error("a fitted garment has other nodes than the garment it fits");
  if (making.transform)
    for (NodeId n : mesh.nodes()) mesh.x(n) = making.transform->apply(mesh.x(n));
  if (making.rest_initial) set_rest_angles_from_world(mesh);
  mesh.node_attrs().add<int32_t>(kHandleAttr, -1);
  mesh.node_attrs().add<Vec3>(kAnchorAttr, Vec3::Zero());
  const auto& chosen = garment.mesh.node_attrs().get<int32_t>(kHandleAttr);
  for (NodeId n : mesh.nodes())
    if (chosen[n] >= 0) hold_node(mesh, n, chosen[n]);
  garment.mesh = std::move(mesh);
}

// The garments `worn` by `wearer` made again for it. `start_time` and `shot` bound the run's
// time: the arms' reach is taken over it.
void fit_garments(const std::vector<JsonValue>& entries, std::vector<GarmentSpec>& garments, const std::vector<GarmentMaking>& making,
                  const std::vector<std::size_t>& worn, const Character& wearer, const std::string& wearer_name, double start_time,
                  double shot, BodyMeshCache& bodies) {
  const FigureMeasure reference = reference_figure(wearer.body_params(), bodies);
  std::optional<GarmentFit> fit;
  FigureMeasure figure = measure_wearer(wearer, wearer_name, entries[worn.front()], reference, fit);
  if (fit->identity()) return;
  const double ease = ease_clearing_arms(worn, garments, making, wearer, reference, figure, fit, start_time, shot);
  std::vector<GarmentPattern> patterns;
  for (std::size_t g : worn) patterns.push_back(*making[g].pattern);
  const std::vector<GarmentPattern> fitted = fit->fit(patterns, ease);
  for (std::size_t k = 0; k < worn.size(); ++k) {
    GarmentSpec& garment = garments[worn[k]];
    remake_garment(garment, fitted[k], *fit, making[worn[k]]);
    garment.fitted_to = wearer_name;
    garment.ease = ease;
  }
}

}  // namespace

void fit_worn_garments(const std::vector<JsonValue>& entries, std::vector<GarmentSpec>& garments, const std::vector<GarmentMaking>& making,
                       const std::vector<ObstacleSpec>& obstacles, double start_time, double shot, BodyMeshCache& bodies) {
  std::vector<std::pair<const ObstacleSpec*, std::vector<std::size_t>>> worn;  // by wearer, in scene order
  for (std::size_t gi = 0; gi < garments.size(); ++gi)
    if (const ObstacleSpec* wearer = garment_wearer(entries[gi], garments[gi], making[gi], obstacles)) {
      auto it = std::find_if(worn.begin(), worn.end(), [&](const auto& w) { return w.first == wearer; });
      if (it == worn.end()) it = worn.insert(worn.end(), {wearer, {}});
      it->second.push_back(gi);
    }
  for (const auto& [wearer, indices] : worn)
    fit_garments(entries, garments, making, indices, *wearer->character, wearer->name, start_time, shot, bodies);
}

}  // namespace vdc
