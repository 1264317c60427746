#include "sim/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "core/task_order.hpp"
#include "remesh/remesher.hpp"
#include "remesh/sizing.hpp"
#include "view/level_of_detail.hpp"
#include "view/view_sizing.hpp"
#include "remesh/obstacle_planes.hpp"
#include "collision/intersection.hpp"
#include "collision/untangle.hpp"

namespace vdc {

bool parse_sim_mode(const std::string& name, SimMode& mode) {
  if (name == "fixed") mode = SimMode::Fixed;
  else if (name == "adaptive") mode = SimMode::Adaptive;
  else if (name == "view") mode = SimMode::View;
  else return false;
  return true;
}

const char* sim_mode_name(SimMode mode) {
  switch (mode) {
    case SimMode::Fixed: return "fixed";
    case SimMode::Adaptive: return "adaptive";
    case SimMode::View: return "view";
  }
  return "?";
}

namespace {
CollisionMesh collision_mesh(const Mesh& mesh) {
  CollisionMesh cm;
  for (FaceId f : mesh.faces()) cm.faces.push_back({mesh.face_node(f, 0).idx, mesh.face_node(f, 1).idx, mesh.face_node(f, 2).idx});
  return cm;
}
}  // namespace

Simulation::Simulation(Scene scene, const SimOptions& options, Log log)
    : scene_(std::move(scene)), options_(options), log_(std::move(log)), frame_(-scene_.preroll_frames) {
  check_options_and_collect_obstacles();
  for (const auto& g : scene_.garments) {
    Mesh& mesh = garments_.emplace_back(g.mesh);
    if (!mesh.is_compact()) mesh.compact();
    if (options_.mode == SimMode::Fixed) {
      // The non-adaptive baseline: one remesh to a uniform resolution, never again.
      set_uniform_sizing(mesh, scene_.fixed_size > 0 ? scene_.fixed_size : scene_.remeshing.size_min);
      remesh(mesh);
    }
  }
  rebuild();
  FrameStats start;
  if (untangle_garments(start).remaining > 0) report_start_crossings();
}

Simulation::Simulation(Scene scene, const SimOptions& options, Log log, ResumePoint from, const std::string& source)
    : scene_(std::move(scene)), options_(options), log_(std::move(log)), frame_(from.frame) {
  check_options_and_collect_obstacles();
  if (from.garments.size() != scene_.garments.size() || from.names.size() != from.garments.size())
    throw InputError(source, "", "holds " + std::to_string(from.garments.size()) + " garment meshes where the scene has " +
                                     std::to_string(scene_.garments.size()));
  for (std::size_t g = 0; g < from.garments.size(); ++g) {
    const auto& garment = scene_.garments[g];
    const Mesh& mesh = from.garments[g];
    if (from.names[g] != garment.name)
      throw InputError(source, "", "has garment '" + from.names[g] + "' where the scene has '" + garment.name + "'");
    if (!mesh.is_compact()) throw InputError(source, garment.name, "the garment's mesh has unused slots, which a checkpoint never has");
    // What the simulation reads from the mesh's attributes must be there, of its type and range.
    try {
      const auto& which = mesh.node_attrs().get<int32_t>(kHandleAttr);
      mesh.node_attrs().get<Vec3>(kAnchorAttr);
      for (NodeId n : mesh.nodes())
        if (which[n] < -1 || which[n] >= static_cast<int32_t>(garment.handles.size()))
          throw InputError(source, garment.name, "node " + std::to_string(n.idx) + " names handle " + std::to_string(which[n]) +
                                                     " of the garment's " + std::to_string(garment.handles.size()));
    } catch (const std::logic_error& e) {
      throw InputError(source, garment.name, std::string("the garment's mesh does not fit the scene: ") + e.what());
    }
    garments_.push_back(std::move(from.garments[g]));
  }
  place_obstacles();
  try {
    rebuild();
  } catch (const std::logic_error& e) {
    throw InputError(source, "", std::string("the garment meshes do not fit the scene: ") + e.what());
  }
}

void Simulation::check_options_and_collect_obstacles() {
  if (options_.mode == SimMode::View && scene_.cameras.empty())
    throw InputError(scene_.path, "camera", "--mode view needs a camera: add a \"camera\" block (or \"cameras\") to the scene");
  for (const auto& o : scene_.obstacles) {
    obstacle_faces_.push_back(collision_mesh(o.mesh));
    obstacles_.push_back(o.mesh);
  }
}

void Simulation::place_obstacles() {
  const std::vector<std::vector<Vec3>> x = obstacle_positions(time());
  for (std::size_t i = 0; i < scene_.obstacles.size(); ++i) {
    Mesh& mesh = obstacles_[i];
    if (scene_.obstacles[i].moves())
      for (NodeId n : mesh.nodes()) mesh.x(n) = x[i][static_cast<std::size_t>(n.idx)];
  }
}

std::vector<std::vector<Vec3>> Simulation::obstacle_positions(double t) {
  for (const auto& kept : obstacle_positions_)
    if (!kept.x.empty() && kept.t == t) return kept.x;
  ObstaclePositions fresh{t, {}};
  for (const auto& o : scene_.obstacles) fresh.x.push_back(o.positions_at(t));
  obstacle_positions_[1] = std::move(obstacle_positions_[0]);
  obstacle_positions_[0] = fresh;
  return fresh.x;
}

void Simulation::remesh_garments(FrameStats& stats) {
  auto t0 = std::chrono::steady_clock::now();
  // The meshes the frame starts with, free of crossings when the last step ended without any: the
  // fallback for a remesh whose crossings untangling cannot remove (size_and_remesh keeps them as
  // sized, so that they carry this frame's view and compression factors).
  std::vector<Mesh> started_with(garments_.size());
  // The pre-roll is never seen: it is sized as in adaptive mode, so the shot's first frame is the
  // adaptive run's, and the view's coarsening starts with the shot.
  const bool viewing = options_.mode == SimMode::View && frame_ >= 0;
  const std::vector<std::vector<Vec3>> obstacle_x = obstacle_positions(time());
  // The collider's hierarchies where it has them (a resumed run has none yet, and builds its
  // own: the planes do not depend on which).
  const std::vector<const Bvh*> obstacle_trees =
      collider_ ? collider_->obstacle_face_trees(obstacle_x, options_.threads) : std::vector<const Bvh*>{};
  // For the proximity criterion the other garments are obstacles too: a layer's chords must not
  // sag through the layer beside it any more than through the body.
  std::vector<CollisionMesh> garment_meshes;
  std::vector<std::vector<Vec3>> garment_x;
  for (const Mesh& mesh : garments_) {
    garment_meshes.push_back(collision_mesh(mesh));
    std::vector<Vec3> x(static_cast<std::size_t>(mesh.node_capacity()), Vec3::Zero());
    for (NodeId n : mesh.nodes()) x[static_cast<std::size_t>(n.idx)] = mesh.x(n);
    garment_x.push_back(std::move(x));
  }
  // Each garment is kept from crossing the obstacles and the other garments as they stand before
  // any is remeshed.
  std::vector<Triangle> triangles;
  std::vector<int> owners;
  auto stand = [&](const CollisionMesh& mesh, const std::vector<Vec3>& x, int owner) {
    for (const auto& face : mesh.faces) {
      triangles.push_back({x[static_cast<std::size_t>(face[0])], x[static_cast<std::size_t>(face[1])], x[static_cast<std::size_t>(face[2])]});
      owners.push_back(owner);
    }
  };
  for (std::size_t o = 0; o < obstacle_faces_.size(); ++o) stand(obstacle_faces_[o], obstacle_x[o], -1);
  for (std::size_t g = 0; g < garments_.size(); ++g) stand(garment_meshes[g], garment_x[g], static_cast<int>(g));
  // The occlusion test's depth images, once a frame for every garment: the bodies and opaque
  // garments seen by each camera's window (none while settling: every factor is 1 then).
  std::vector<std::vector<DepthImage>> occluders;
  if (viewing && (scene_.view.back_occlusion || scene_.view.occlusion) && !(time() + 1e-9 < scene_.view.settle)) {
    const auto tv = std::chrono::steady_clock::now();
    depth_cache_->forget_before(time());
    for (std::size_t c = 0; c < scene_.cameras.size(); ++c)
      occluders.push_back(occlusion_images(AnticipationWindow(scene_.cameras[c].path, time(), scene_.frame_time, scene_.view),
                                           occluders_at(garment_meshes, garment_x, static_cast<int>(c)), scene_.view, options_.threads));
    stats.view_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - tv).count();
  }
  const StandingSurfaces standing(std::move(triangles), std::move(owners), options_.threads);
  const std::size_t count = garments_.size();
  std::vector<std::vector<ObstaclePlane>> planes(count);
  std::vector<std::unique_ptr<ViewSizing>> views(count);
  for (std::size_t gi = 0; gi < count; ++gi) {
    std::vector<CollisionMesh> near_meshes = obstacle_faces_;
    std::vector<std::vector<Vec3>> near_x = obstacle_x;
    for (std::size_t other = 0; other < count; ++other)
      if (other != gi) {
        near_meshes.push_back(garment_meshes[other]);
        near_x.push_back(garment_x[other]);
      }
    // Held: in repulsion range of a surface on either side.
    planes[gi] = nearest_obstacle_planes(garment_x[gi], near_meshes, near_x, scene_.remeshing.size_max, scene_.collision.repulsion_thickness,
                                         options_.threads, obstacle_trees);
    if (viewing) {
      auto tv = std::chrono::steady_clock::now();
      views[gi] = std::make_unique<ViewSizing>(scene_.camera_paths(), scene_.view, time(), scene_.frame_time, options_.threads);
      views[gi]->evaluate(garments_[gi], &occluders);
      stats.visible_faces += views[gi]->counts().visible;
      stats.back_facing_faces += views[gi]->counts().back_facing;
      stats.out_of_frame_faces += views[gi]->counts().out_of_frame;
      stats.defocused_faces += views[gi]->counts().defocused;
      stats.blurred_faces += views[gi]->counts().blurred;
      stats.hidden_faces += views[gi]->counts().hidden;
      stats.view_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - tv).count();
    }
  }
  for (const RemeshStats& r : size_and_remesh(views, planes, standing, started_with)) {
    stats.splits += r.splits;
    stats.flips += r.flips;
    stats.collapses += r.collapses;
    stats.remesh_refused += r.refused;
  }
  // Coarse faces remember the gathering they were made with (membrane.hpp), those the remesher
  // made too; not those coarsened for folds too fine for the image, which must gather as the
  // folded cloth does.
  if (viewing && gathering() > 0)
    for (Mesh& mesh : garments_) record_gathering(mesh, kFoldLedAttr);
  // An unchanged mesh keeps its system (elements, pattern, symbolic factorization) and collider.
  const bool changed = stats.splits + stats.flips + stats.collapses > 0;
  if (changed) rebuild();
  else if (viewing) {
    std::size_t first_face = 0;
    for (const Mesh& mesh : garments_) {
      update_compression(model_, mesh, first_face, gathering());
      first_face += static_cast<std::size_t>(mesh.num_faces());
    }
  }
  stats.remesh_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const UntangleReport remeshed = untangle_garments(stats);
  if (remeshed.remaining > 0 && changed) keep_fewer_crossings(std::move(started_with), remeshed.remaining, stats);
}

// What may hide cloth from the camera tau seconds from now, an extension of Koh et al. 2014's
// eq. 4 to what is in front: every body of the scene (its other garment groups' too) where its
// motion takes it, drawn once for all groups (the depth cache), then this group's garments not
// marked sheer moved along their nodes' velocities (held where they are without motion
// anticipation).
OccluderDrawing Simulation::occluders_at(const std::vector<CollisionMesh>& garment_meshes, const std::vector<std::vector<Vec3>>& garment_x,
                                         int camera) const {
  return [this, &garment_meshes, &garment_x, camera](DepthImage& image, double tau) {
    const double t = time() + tau;
    image = depth_cache_->at(camera, t, image.camera(), scene_.view.occlusion_scale, [&] {
      std::vector<Triangle> triangles;
      const Frustum frustum(image.camera());
      auto stand = [&](const ObstacleSpec& spec) {
        const auto [centre, radius] = spec.reach_at(t);
        if (radius >= 0 && ball_outside(frustum, centre, radius)) return;  // hides nothing in frame
        const std::vector<Vec3> x = spec.positions_at(t);
        auto at = [&](FaceId f, int k) { return x[static_cast<std::size_t>(spec.mesh.face_node(f, k).idx)]; };
        for (FaceId f : spec.mesh.faces()) triangles.push_back({at(f, 0), at(f, 1), at(f, 2)});
      };
      for (const ObstacleSpec& o : scene_.obstacles) stand(o);
      for (const auto& o : scene_.hiding) stand(*o);
      return triangles;
    });
    std::vector<Triangle> triangles;
    for (std::size_t g = 0; g < garments_.size(); ++g) {
      if (scene_.garments[g].sheer) continue;
      const Mesh& mesh = garments_[g];
      const bool moving = scene_.view.motion_anticipation;
      auto at = [&](int n) {
        const NodeId node(n);
        return moving ? Vec3(garment_x[g][static_cast<std::size_t>(n)] + tau * mesh.v(node)) : garment_x[g][static_cast<std::size_t>(n)];
      };
      for (const auto& face : garment_meshes[g].faces) triangles.push_back({at(face[0]), at(face[1]), at(face[2])});
    }
    image.draw(triangles);
  };
}

namespace {

// The view's factors on the mesh's faces, for the frame's output and the next frame's linger:
// the face's factor and what set it, and with several cameras which camera decided and each
// camera's own factor.
void record_view(Mesh& mesh, const ViewSizing& view) {
  auto& factor = mesh.face_attrs().get_or_add<double>(kViewFactorAttr, 1.0);
  auto& reason = mesh.face_attrs().get_or_add<double>(kViewReasonAttr, 0.0);
  for (FaceId f : mesh.faces()) {
    factor[f] = view.factors()[static_cast<std::size_t>(f.idx)];
    reason[f] = static_cast<double>(view.reasons()[static_cast<std::size_t>(f.idx)]);
  }
  if (view.cameras() == 1) return;
  auto& decider = mesh.face_attrs().get_or_add<double>(kViewCameraAttr, 0.0);
  for (FaceId f : mesh.faces()) decider[f] = view.deciders()[static_cast<std::size_t>(f.idx)];
  for (std::size_t c = 0; c < view.cameras(); ++c) {
    auto& own = mesh.face_attrs().get_or_add<double>(camera_factor_attr(c, view.cameras()), 1.0);
    for (FaceId f : mesh.faces()) own[f] = view.camera_factors(c)[static_cast<std::size_t>(f.idx)];
  }
}

}  // namespace

// Sizing (Narain et al. 2012, sec. 3) and remeshing touch one garment each, so a character's
// garments go side by side, each on one thread, the largest first: the view run's garments are
// too small for the loops inside them to use a second core well. Each garment's result does not
// depend on which thread made it.
std::vector<RemeshStats> Simulation::size_and_remesh(const std::vector<std::unique_ptr<ViewSizing>>& views,
                                                     const std::vector<std::vector<ObstaclePlane>>& planes,
                                                     const StandingSurfaces& standing, std::vector<Mesh>& started_with) {
  const std::size_t count = garments_.size();
  std::vector<double> faces;
  for (const Mesh& mesh : garments_) faces.push_back(mesh.num_faces());
  std::vector<RemeshStats> remeshed(count);
  const int team = std::max(1, std::min<int>(options_.threads, static_cast<int>(count)));
  // One garment alone has the threads for its sizing (not inside a team: a region there would
  // be a nested one).
  const int inner = team == 1 ? options_.threads : 1;
  for_each_in_order(largest_first(faces), team, [&](int k) {
    const auto gi = static_cast<std::size_t>(k);
    Mesh& mesh = garments_[gi];
    if (views[gi]) {
      record_view(mesh, *views[gi]);
    }
    compute_sizing(mesh, scene_.remeshing, views[gi].get(), planes[gi], inner);
    if (views[gi]) {
      // A face the camera lets be coarser than its physics asks cannot form the wrinkles that
      // would take up its compression (membrane.hpp); where the folds too fine for the image led,
      // the face softens as such folds would form, over view.fold_time, from its last factor
      // (a face attribute, so split faces keep their parent's and a checkpoint keeps them all).
      const auto& coarsening = mesh.face_attrs().get<double>(kCoarseningAttr);
      const auto& fold_led = mesh.face_attrs().get<double>(kFoldLedAttr);
      auto& compression = mesh.face_attrs().get_or_add<double>(kCompressionAttr, 1.0);
      for (FaceId f : mesh.faces()) {
        const double target = coarse_compression_factor(coarsening[f]);
        compression[f] = fold_led[f] > 0 ? eased_compression(compression[f], target, scene_.frame_time, scene_.view.fold_time) : target;
      }
    }
    started_with[gi] = mesh;  // sizing moved no node: the frame's start mesh, with this frame's factors
    remeshed[gi] = remesh(mesh, RemeshOptions{}, &standing, static_cast<int>(gi));
  });
  return remeshed;
}

// Coarsening can fold cloth through cloth in ways contour minimisation (Volino and Magnenat-
// Thalmann 2006) does not undo; the frame then goes on with whichever of its start mesh and the
// remeshed one has fewer crossings left after untangling.
void Simulation::keep_fewer_crossings(std::vector<Mesh> started_with, int remeshed_pairs, FrameStats& stats) {
  auto t0 = std::chrono::steady_clock::now();
  std::vector<Mesh> remeshed = std::move(garments_);
  garments_ = std::move(started_with);
  rebuild();
  FrameStats scratch;
  const int start_pairs = untangle_garments(scratch).remaining;
  std::ostringstream msg;
  msg << "frame " << frame_ << ": remeshing left " << remeshed_pairs << " crossing pair(s) that untangling could not remove; ";
  if (start_pairs < remeshed_pairs) {
    stats.untangle_moves += scratch.untangle_moves;
    stats.remesh_undone = 1;
    msg << "the frame keeps the mesh it started with (" << start_pairs << " crossing pair(s))";
  } else {
    garments_ = std::move(remeshed);
    rebuild();
    msg << "the mesh it started with has as many (" << start_pairs << "), so the remeshed one is kept";
  }
  if (log_) log_(msg.str());
  stats.remesh_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void Simulation::report_start_crossings() {
  if (!log_) return;
  const std::vector<std::vector<Vec3>> obstacle_x = obstacle_positions(time());
  for (std::size_t g = 0; g < garments_.size(); ++g) {
    const Mesh& mesh = garments_[g];
    std::vector<std::array<int32_t, 3>> faces;
    std::vector<Vec3> x(static_cast<std::size_t>(mesh.node_capacity()), Vec3::Zero());
    for (NodeId n : mesh.nodes()) x[static_cast<std::size_t>(n.idx)] = mesh.x(n);
    for (FaceId f : mesh.faces()) {
      std::array<int32_t, 3> nodes{};
      for (int k = 0; k < 3; ++k) nodes[static_cast<std::size_t>(k)] = mesh.face_node(f, k).idx;
      faces.push_back(nodes);
    }
    for (std::size_t o = 0; o < obstacle_faces_.size(); ++o) {
      const int pairs = count_intersections_between(faces, x, obstacle_faces_[o].faces, obstacle_x[o]);
      if (pairs == 0) continue;
      std::ostringstream msg;
      msg << "frame " << frame_ << ": garment '" << scene_.garments[g].name << "' crosses obstacle '" << scene_.obstacles[o].name << "' in " << pairs
          << " face pairs that untangling could not separate: it does not fit the body it is on (made for another figure or pose?);"
          << " remeshes that add crossings will be undone while it does";
      log_(msg.str());
    }
  }
}

UntangleReport Simulation::untangle_cloth(FrameStats& stats) {
  auto t0 = std::chrono::steady_clock::now();
  std::vector<char> fixed(static_cast<std::size_t>(model_.num_nodes), 0);
  for (const auto& c : constraints(time(), scene_.frame_time)) fixed[static_cast<std::size_t>(c.node)] = 1;
  const std::vector<std::vector<Vec3>> obstacle_x = obstacle_positions(time());
  UntangleParams params;
  params.thickness = scene_.collision.thickness;
  params.step = scene_.collision.thickness;
  params.max_iterations = scene_.collision.untangle_iterations;
  params.threads = options_.threads;
  const UntangleReport r = untangle(model_.face_nodes, x_, fixed, obstacle_faces_, obstacle_x, params,
                                    collider_->obstacle_face_trees(obstacle_x, options_.threads));
  stats.untangle_moves += r.moves;
  // Routine untangling (cloth-obstacle pairs cleared in one pass: nodes a split put on a chord
  // just inside a body) is counted in stats.csv's untangle_moves; the log gets what is not.
  const bool routine = r.cloth_pairs == 0 && r.iterations <= 1 && r.remaining == 0 && r.restored_pairs == 0;
  if (r.cloth_pairs + r.obstacle_pairs > 0 && !routine && log_) {
    std::ostringstream msg;
    msg << "frame " << frame_ << ": untangling " << r.cloth_pairs << " cloth-cloth and " << r.obstacle_pairs
        << " cloth-obstacle intersecting pairs: " << r.iterations << " iterations, " << r.moves << " vertex moves";
    if (r.restored_pairs > 0) msg << "; the last iterate had " << r.restored_pairs << " pairs, so the positions with the fewest were kept";
    if (r.remaining > 0) msg << "; " << r.remaining << " pairs remain";
    log_(msg.str());
  }
  stats.collision_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

UntangleReport Simulation::untangle_garments(FrameStats& stats) {
  gather_state();
  const UntangleReport r = untangle_cloth(stats);
  if (r.moves > 0) scatter_state();
  return r;
}

void Simulation::rebuild() {
  // The collider keeps the obstacles' hierarchies through remeshing and restarts alike: what it
  // finds does not depend on them (it takes its candidates in a fixed order), so a run resumed
  // with hierarchies built afresh finds what this one does.
  restart_pending_ = false;
  model_ = ClothModel();
  offsets_.clear();
  for (std::size_t g = 0; g < garments_.size(); ++g) offsets_.push_back(append_garment(model_, garments_[g], scene_.garments[g].material, gathering()));
  LinearSolverParams solver_params = scene_.solver.params;
  solver_params.threads = options_.threads;
  integrator_ = std::make_unique<ImplicitIntegrator>(model_, scene_.solver.linear, solver_params);
  if (!collider_) collider_ = std::make_unique<Collider>(model_.face_nodes, obstacle_faces_, model_.num_nodes);
  else collider_->set_cloth(model_.face_nodes, model_.num_nodes);
}

void Simulation::gather(Eigen::VectorXd& x, Eigen::VectorXd& v) const {
  x.resize(3 * static_cast<int64_t>(model_.num_nodes));
  v.resize(x.size());
  for (std::size_t g = 0; g < garments_.size(); ++g) {
    const Mesh& m = garments_[g];
    for (NodeId n : m.nodes()) {
      x.segment<3>(3 * (offsets_[g] + n.idx)) = m.x(n);
      v.segment<3>(3 * (offsets_[g] + n.idx)) = m.v(n);
    }
  }
}

void Simulation::scatter_state() {
  for (std::size_t g = 0; g < garments_.size(); ++g) {
    Mesh& m = garments_[g];
    for (NodeId n : m.nodes()) {
      m.x(n) = x_.segment<3>(3 * (offsets_[g] + n.idx));
      m.v(n) = v_.segment<3>(3 * (offsets_[g] + n.idx));
    }
  }
}

std::vector<VelocityConstraint> Simulation::constraints(double t_end, double h) const {
  std::vector<VelocityConstraint> out;
  for (std::size_t g = 0; g < garments_.size(); ++g) {
    const auto& garment = scene_.garments[g];
    const Mesh& mesh = garments_[g];
    const auto& which = mesh.node_attrs().get<int32_t>(kHandleAttr);
    const auto& anchor = mesh.node_attrs().get<Vec3>(kAnchorAttr);
    std::vector<Eigen::Affine3d> carried;
    for (const ClothHandle& handle : garment.handles) carried.push_back(handle.carry(t_end));
    for (NodeId n : mesh.nodes()) {
      if (which[n] < 0) continue;
      const auto k = static_cast<std::size_t>(which[n]);
      const ClothHandle& handle = garment.handles[k];
      if (!handle.active(t_end - 0.5 * h)) continue;
      const int32_t i = offsets_[g] + n.idx;
      const Vec3 target = handle.target(anchor[n], t_end, carried[k]);
      Vec3 v_new = (target - x_.segment<3>(3 * i)) / h;
      out.push_back({i, v_new - v_.segment<3>(3 * i)});
    }
  }
  return out;
}

// A substep, the steps still to take on a stack with the first half of a halved step on top, so
// that they are taken in time order; how each is recovered is step_recovery.hpp's policy.
void Simulation::advance(double t, double t_end, FrameStats& stats) {
  const StepRecoveryLimits limits{scene_.solver.max_step_halvings, kCollisionHalvings, scene_.solver.max_velocity_change};
  std::vector<StepInterval> pending{StepInterval{t, t_end, 0, 0}};
  while (!pending.empty()) {
    const StepInterval step = pending.back();
    pending.pop_back();
    StepReport refused;
    if (take_step(step, limits, stats, refused)) continue;
    const auto [first, second] = halves(step, refused, limits);
    pending.push_back(second);
    pending.push_back(first);
  }
}

bool Simulation::take_step(const StepInterval& step, const StepRecoveryLimits& limits, FrameStats& stats, StepReport& refused) {
  const double t = step.t, h = step.t_end - step.t;
  StepParams p;
  p.h = h;
  p.gravity = scene_.gravity;
  p.damping = scene_.air.damping;
  p.drag = scene_.air.drag;
  p.wind = scene_.air.wind;
  if (options_.mode == SimMode::View) p.coarse_damping = scene_.view.coarse_damping;
  p.threads = options_.threads;
  const std::vector<VelocityConstraint> held = constraints(step.t_end, h);
  std::vector<char> fixed(static_cast<std::size_t>(model_.num_nodes), 0);
  for (const auto& c : held) fixed[static_cast<std::size_t>(c.node)] = 1;
  ObstacleMotion obstacles{obstacle_positions(t), obstacle_positions(step.t_end)};
  const std::vector<ContactTerm> contacts = proximity_contacts(fixed, obstacles, h, stats);
  const Eigen::VectorXd x_start = x_, v_start = v_;
  auto solve = [&](VelocityLimit mode) {
    const StepReport report = integrator_->step(x_, v_, held, p, limits.max_velocity_change, contacts, mode);
    stats.assemble_seconds += report.assemble_seconds;
    stats.solve_seconds += report.solve_seconds;
    stats.solver_iterations += report.solver_iterations;
    stats.factorizations += report.factorizations;
    return report;
  };
  StepReport r = solve(VelocityLimit::Refuse);
  Recovery next = after_solve(r, step, limits);
  if (next == Recovery::Clamp) {
    const StepReport c = solve(VelocityLimit::Clamp);
    if (c.ok) {
      ++stats.velocity_clamps;
      if (log_) {
        std::ostringstream msg;
        msg << "frame " << frame_ + 1 << ": step at t = " << t << " s (h = " << h << " s): velocity change " << r.max_dv
            << " m/s does not shrink with the step; clamped to " << limits.max_velocity_change << " m/s at " << c.clamped_nodes << " node(s)";
        log_(msg.str());
      }
      r = c;
      next = Recovery::Accept;
    } else {
      next = after_failure(step, limits);
    }
  }
  if (next == Recovery::Accept) {
    // Impact zones that do not separate: first retry the step in halves (smaller motions meet
    // fewer impacts at once); at the last level the zones keep their start positions.
    const bool may_halve = zones_may_halve(step, limits);
    const CollisionStats c = resolve_collisions(x_start, h, fixed, obstacles, stats, !may_halve);
    if (c.fallbacks == 0 || !may_halve) {
      ++stats.substeps;
      return true;
    }
    x_ = x_start;
    v_ = v_start;
    r.failure = c.over_budget ? "continuous detection met " + std::to_string(c.candidates) + " candidate pairs in one round, over its bound"
                              : std::to_string(c.fallbacks) + " impact zone(s) did not separate";
    next = after_failure(step, limits);
  }
  if (next == Recovery::Fail) {
    std::ostringstream msg;
    msg << "frame " << frame_ + 1 << ": step at t = " << t << " s failed at the smallest step " << h << " s: " << r.failure;
    throw SimulationError(msg.str());
  }
  ++stats.halvings;
  if (log_) {
    std::ostringstream msg;
    msg << "frame " << frame_ + 1 << ": step at t = " << t << " s (h = " << h << " s) refused: " << r.failure
        << "; retrying as two steps of " << h / 2 << " s";
    log_(msg.str());
  }
  refused = r;
  return false;
}

std::vector<ContactTerm> Simulation::proximity_contacts(const std::vector<char>& fixed, const ObstacleMotion& obstacles, double h,
                                                        FrameStats& stats) {
  auto t0 = std::chrono::steady_clock::now();
  std::vector<std::vector<Vec3>> obstacle_v;
  for (std::size_t o = 0; o < obstacles.start.size(); ++o) {
    std::vector<Vec3> vel(obstacles.start[o].size());
    for (std::size_t i = 0; i < vel.size(); ++i) vel[i] = (obstacles.end[o][i] - obstacles.start[o][i]) / h;
    obstacle_v.push_back(std::move(vel));
  }
  const CollisionParams& c = scene_.collision;
  const std::vector<ProximityPair> pairs =
      collider_->proximities(x_, v_, fixed, obstacles.start, obstacle_v, c.repulsion_thickness, options_.threads);
  ContactParams params;
  params.band = c.repulsion_thickness;
  params.stiffness = c.repulsion_stiffness;
  params.friction = c.friction;
  std::vector<ContactTerm> terms = contact_terms(pairs, v_, model_.node_mass, h, params);
  stats.proximities = std::max(stats.proximities, static_cast<int>(pairs.size()));
  stats.collision_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return terms;
}

CollisionStats Simulation::resolve_collisions(const Eigen::VectorXd& x_start, double h, const std::vector<char>& fixed,
                                   const ObstacleMotion& obstacles, FrameStats& stats, bool last_resort) {
  auto t0 = std::chrono::steady_clock::now();
  CollisionParams params = scene_.collision;
  params.threads = options_.threads;
  CollisionStats c = collider_->resolve(x_start, x_, model_.node_mass, fixed, obstacles.start, obstacles.end, params);
  v_ = (x_ - x_start) / h;
  stats.impacts += c.impacts;
  stats.collision_iterations += c.iterations;
  stats.collision_candidates = std::max<long long>(stats.collision_candidates, c.candidates);
  if (last_resort) {
    stats.collision_fallbacks += c.fallbacks;
    if (c.fallbacks > 0 && log_) {
      std::ostringstream msg;
      msg << "frame " << frame_ + 1 << ": ";
      if (c.over_budget)
        msg << "continuous detection met " << c.candidates << " candidate pairs in one round at step " << h << " s, over its bound ("
            << params.max_candidates_per_primitive << " a cloth node or edge): the cloth keeps its start-of-step positions";
      else
        msg << c.fallbacks << " impact zone(s) did not separate in " << c.iterations << " rounds at step " << h
            << " s; they keep their start-of-step positions, carried by the obstacles they touch";
      log_(msg.str());
    }
  }
  stats.collision_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return c;
}

bool Simulation::beyond_resolution_now() const {
  if (options_.mode != SimMode::View || frame_ < 0 || scene_.view.far_remesh_every <= 1 || scene_.view.settling(time())) return false;
  if (time() + 1e-9 < scene_.view.far_after) return false;  // the drape forms on a mesh remeshed every frame
  std::vector<AnticipationWindow> windows;
  for (const CameraPath* path : scene_.camera_paths()) windows.emplace_back(*path, time(), scene_.frame_time, scene_.view);
  for (const Mesh& mesh : garments_) {
    std::vector<Vec3> x, v;
    for (NodeId n : mesh.nodes()) {
      x.push_back(mesh.x(n));
      v.push_back(mesh.v(n));
    }
    if (!beyond_resolution(windows, scene_.view, garment_reach(x, v), scene_.remeshing.size_max)) return false;
  }
  return true;
}

FrameStats Simulation::step_frame() {
  auto t0 = std::chrono::steady_clock::now();
  FrameStats stats;
  const double h = scene_.frame_time / scene_.substeps;
  const double t_frame = time();
  // Each step boundary's time computed once, so that a step starts at exactly the time the last
  // one ended (and the frame ends at the next frame's time): the obstacles' positions there, and
  // their collision hierarchies, are then the ones already computed, not a rounding away.
  auto boundary = [&](int s) { return s == scene_.substeps ? (frame_ + 1) * scene_.frame_time : t_frame + s * h; };
  // A group no camera resolves is remeshed on every far_remesh_every-th frame only (by frame
  // number, so a resumed run skips the same frames).
  stats.far_groups = beyond_resolution_now() ? 1 : 0;
  const bool skip_remesh = stats.far_groups > 0 && frame_ % scene_.view.far_remesh_every != 0;
  if (options_.mode != SimMode::Fixed && !skip_remesh) remesh_garments(stats);
  if (restart_pending_) rebuild();  // unless remeshing just did
  gather_state();
  for (int s = 0; s < scene_.substeps; ++s) advance(boundary(s), boundary(s + 1), stats);
  ++frame_;
  // A zone that fell back to its start-of-step positions rode along with the obstacles it
  // touched, which need not keep it outside them: such a frame ends untangled (Volino and
  // Magnenat-Thalmann 2006), as a remesh does.
  if (stats.collision_fallbacks > 0) untangle_cloth(stats);
  scatter_state();
  place_obstacles();
  stats.frame = frame_;
  stats.faces = num_faces();
  stats.vertices = num_nodes();
  stats.energy = energy();
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return stats;
}

int Simulation::num_faces() const {
  int n = 0;
  for (const Mesh& mesh : garments_) n += mesh.num_faces();
  return n;
}

int Simulation::num_nodes() const {
  int n = 0;
  for (const Mesh& mesh : garments_) n += mesh.num_nodes();
  return n;
}

EnergyReport Simulation::energy() const {
  Eigen::VectorXd x, v;
  gather(x, v);
  EnergyReport e;
  for (int32_t i = 0; i < model_.num_nodes; ++i) {
    const double m = model_.node_mass[static_cast<std::size_t>(i)];
    e.kinetic += 0.5 * m * v.segment<3>(3 * i).squaredNorm();
    e.gravitational -= m * scene_.gravity.dot(x.segment<3>(3 * i));
  }
  for (std::size_t f = 0; f < model_.face_nodes.size(); ++f) {
    const auto& n = model_.face_nodes[f];
    e.elastic += membrane_energy({x.segment<3>(3 * n[0]), x.segment<3>(3 * n[1]), x.segment<3>(3 * n[2])}, model_.membranes[f]);
  }
  for (std::size_t b = 0; b < model_.bend_nodes.size(); ++b) {
    const auto& n = model_.bend_nodes[b];
    e.elastic += bending_energy({x.segment<3>(3 * n[0]), x.segment<3>(3 * n[1]), x.segment<3>(3 * n[2]), x.segment<3>(3 * n[3])},
                                model_.bends[b]);
  }
  return e;
}

}  // namespace vdc
