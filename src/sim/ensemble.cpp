#include "sim/ensemble.hpp"

#include "core/error.hpp"
#include "core/task_order.hpp"

#include <algorithm>
#include <chrono>

namespace vdc {

void accumulate(FrameStats& t, const FrameStats& p) {
  t.faces += p.faces;
  t.vertices += p.vertices;
  t.substeps += p.substeps;
  t.halvings += p.halvings;
  t.solver_iterations += p.solver_iterations;
  t.factorizations += p.factorizations;
  t.assemble_seconds += p.assemble_seconds;
  t.solve_seconds += p.solve_seconds;
  t.remesh_seconds += p.remesh_seconds;
  t.splits += p.splits;
  t.flips += p.flips;
  t.collapses += p.collapses;
  t.proximities += p.proximities;
  t.untangle_moves += p.untangle_moves;
  t.remesh_undone += p.remesh_undone;
  t.remesh_refused += p.remesh_refused;
  t.visible_faces += p.visible_faces;
  t.back_facing_faces += p.back_facing_faces;
  t.out_of_frame_faces += p.out_of_frame_faces;
  t.defocused_faces += p.defocused_faces;
  t.blurred_faces += p.blurred_faces;
  t.hidden_faces += p.hidden_faces;
  t.view_seconds += p.view_seconds;
  t.impacts += p.impacts;
  t.collision_iterations += p.collision_iterations;
  t.collision_fallbacks += p.collision_fallbacks;
  t.velocity_clamps += p.velocity_clamps;
  t.collision_candidates = std::max(t.collision_candidates, p.collision_candidates);
  t.collision_seconds += p.collision_seconds;
  t.energy.kinetic += p.energy.kinetic;
  t.energy.gravitational += p.energy.gravitational;
  t.energy.elastic += p.energy.elastic;
}

template <class Make>
void Ensemble::make_parts(Scene scene, std::size_t expected_parts, const std::string& source, Make&& make) {
  std::vector<Scene> scenes = split_groups(std::move(scene));
  if (expected_parts > 0 && expected_parts != scenes.size())
    throw InputError(source, "", "holds " + std::to_string(expected_parts) + " garment groups where the scene has " +
                                     std::to_string(scenes.size()));
  const int n = static_cast<int>(scenes.size());
  team_ = std::max(1, std::min(options_.threads, n));
  SimOptions part_options = options_;
  part_options.threads = std::max(1, options_.threads / n);
  std::vector<std::string> labels;
  for (const Scene& s : scenes) labels.push_back(n > 1 ? s.garments.front().group + ": " : "");
  parts_.resize(scenes.size());
  part_seconds_.assign(scenes.size(), 0.0);
  for_each_in_order(index_order(scenes.size()), team_, [&](int k) {
    const auto i = static_cast<std::size_t>(k);
    Simulation::Log part_log;
    if (log_)
      part_log = [this, label = labels[i]](const std::string& msg) {
        std::lock_guard<std::mutex> lock(log_mutex_);
        log_(label + msg);
      };
    parts_[i] = make(i, std::move(scenes[i]), part_options, part_log);
  });
  const auto bodies = std::make_shared<DepthCache>();  // the same for every group
  for (auto& part : parts_) part->share_depth_cache(bodies);
}

Ensemble::Ensemble(Scene scene, const SimOptions& options, Simulation::Log log)
    : name_(scene.name), path_(scene.path), options_(options), log_(std::move(log)) {
  make_parts(std::move(scene), 0, "", [](std::size_t, Scene part, const SimOptions& o, Simulation::Log l) {
    return std::make_unique<Simulation>(std::move(part), o, std::move(l));
  });
}

Ensemble::Ensemble(Scene scene, const SimOptions& options, Simulation::Log log, std::vector<ResumePoint> from, const std::string& source)
    : name_(scene.name), path_(scene.path), options_(options), log_(std::move(log)) {
  if (from.empty()) throw InputError(source, "", "holds no garment group");
  make_parts(std::move(scene), from.size(), source, [&](std::size_t k, Scene part, const SimOptions& o, Simulation::Log l) {
    return std::make_unique<Simulation>(std::move(part), o, std::move(l), std::move(from[k]), source);
  });
}

void Ensemble::restart_solvers() {
  for (auto& p : parts_) p->restart_solvers();
}

FrameStats Ensemble::step_frame() {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<FrameStats> frames(parts_.size());
  // Longest processing time first (Graham 1969): the parts that took longest last frame start
  // first, so that a costly part (a dancer in close-up) does not start last and leave the other
  // threads idle. Each part's result does not depend on when it runs.
  for_each_in_order(largest_first(part_seconds_), team_, [&](int k) {
    const auto i = static_cast<std::size_t>(k);
    const auto start = std::chrono::steady_clock::now();
    frames[i] = parts_[i]->step_frame();
    part_seconds_[i] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  });
  FrameStats total;
  total.frame = frames.front().frame;
  for (const FrameStats& f : frames) accumulate(total, f);
  total.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return total;
}

int Ensemble::num_faces() const {
  int n = 0;
  for (const auto& p : parts_) n += p->num_faces();
  return n;
}

int Ensemble::num_nodes() const {
  int n = 0;
  for (const auto& p : parts_) n += p->num_nodes();
  return n;
}

}  // namespace vdc
