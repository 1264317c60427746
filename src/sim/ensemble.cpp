#include "sim/ensemble.hpp"

#include "core/error.hpp"
#include "core/task_order.hpp"
#include "physics/linear_solver.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>

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
  t.far_groups += p.far_groups;
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

FrameStats total_of(const std::vector<PartFrame>& parts) {
  FrameStats total;
  if (!parts.empty()) total.frame = parts.front().stats.frame;
  for (const PartFrame& p : parts) accumulate(total, p.stats);
  return total;
}

SimOptions Ensemble::part_options() const {
  SimOptions o = options_;
  o.threads = part_threads_;
  return o;
}

Simulation::Log Ensemble::part_log(int group) const {
  if (!log_) return {};
  return [log = log_, mutex = log_mutex_, label = labels_[static_cast<std::size_t>(group)]](const std::string& msg) {
    std::lock_guard<std::mutex> lock(*mutex);
    log(label + msg);
  };
}

template <class Make>
void Ensemble::make_parts(Scene scene, std::optional<std::vector<int>> here, std::size_t expected_groups, const std::string& source, Make&& make) {
  std::vector<Scene> scenes = split_groups(std::move(scene));
  if (expected_groups > 0 && expected_groups != scenes.size())
    throw InputError(source, "", "holds " + std::to_string(expected_groups) + " garment groups where the scene has " +
                                     std::to_string(scenes.size()));
  const int n = static_cast<int>(scenes.size());
  frame_ = -scenes.front().preroll_frames;
  here_ = here ? *here : index_order(scenes.size());
  const int local = static_cast<int>(here_.size());
  team_ = std::max(1, std::min(options_.threads, local));
  part_threads_ = std::max(1, options_.threads / std::max(1, local));
  for (const Scene& s : scenes) labels_.push_back(n > 1 ? s.garments.front().group + ": " : "");
  parts_.resize(here_.size());
  part_seconds_.assign(here_.size(), 0.0);
  for_each_in_order(index_order(here_.size()), team_, [&](int k) {
    const int g = here_[static_cast<std::size_t>(k)];
    parts_[static_cast<std::size_t>(k)] = make(static_cast<std::size_t>(g), std::move(scenes[static_cast<std::size_t>(g)]), part_options(), part_log(g));
  });
  for (auto& part : parts_) part->share_depth_cache(bodies_);
  waiting_.resize(scenes.size());
  for (std::size_t g = 0; g < scenes.size(); ++g)
    if (std::find(here_.begin(), here_.end(), static_cast<int>(g)) == here_.end()) waiting_[g] = std::make_unique<Scene>(std::move(scenes[g]));
}

Ensemble::Ensemble(Scene scene, const SimOptions& options, Simulation::Log log, std::optional<std::vector<int>> here)
    : name_(scene.name), path_(scene.path), options_(options), log_(std::move(log)) {
  make_parts(std::move(scene), std::move(here), 0, "", [](std::size_t, Scene part, const SimOptions& o, Simulation::Log l) {
    return std::make_unique<Simulation>(std::move(part), o, std::move(l));
  });
}

Ensemble::Ensemble(Scene scene, const SimOptions& options, Simulation::Log log, std::vector<ResumePoint> from, const std::string& source,
                   std::optional<std::vector<int>> here)
    : name_(scene.name), path_(scene.path), options_(options), log_(std::move(log)) {
  if (from.empty()) throw InputError(source, "", "holds no garment group");
  const int resumed_at = from.front().frame;
  make_parts(std::move(scene), std::move(here), from.size(), source, [&](std::size_t g, Scene part, const SimOptions& o, Simulation::Log l) {
    return std::make_unique<Simulation>(std::move(part), o, std::move(l), std::move(from[g]), source);
  });
  frame_ = resumed_at;
}

bool Ensemble::restart_changes_results() const { return carries_state(group_scene(0).solver.linear); }

void Ensemble::restart_solvers() {
  for (auto& p : parts_) p->restart_solvers();
}

const Simulation& Ensemble::part(int group) const {
  const auto at = std::find(here_.begin(), here_.end(), group);
  if (at == here_.end()) throw std::logic_error("Ensemble::part: group " + std::to_string(group) + " is not here");
  return *parts_[static_cast<std::size_t>(at - here_.begin())];
}

const Scene& Ensemble::group_scene(int group) const {
  const auto g = static_cast<std::size_t>(group);
  if (waiting_.at(g)) return *waiting_[g];
  return part(group).scene();
}

void Ensemble::drop(int group) {
  const auto at = std::find(here_.begin(), here_.end(), group);
  if (at == here_.end()) throw std::logic_error("Ensemble::drop: group " + std::to_string(group) + " is not here");
  const auto k = static_cast<std::size_t>(at - here_.begin());
  waiting_[static_cast<std::size_t>(group)] = std::make_unique<Scene>(parts_[k]->scene());
  parts_.erase(parts_.begin() + static_cast<std::ptrdiff_t>(k));
  part_seconds_.erase(part_seconds_.begin() + static_cast<std::ptrdiff_t>(k));
  here_.erase(at);
  team_ = std::max(1, std::min(options_.threads, static_cast<int>(here_.size())));
}

void Ensemble::adopt(int group, ResumePoint from, const std::string& source) {
  const auto g = static_cast<std::size_t>(group);
  if (g >= waiting_.size() || !waiting_[g]) throw std::logic_error("Ensemble::adopt: group " + std::to_string(group) + " is not waiting");
  auto part = std::make_unique<Simulation>(Scene(*waiting_[g]), part_options(), part_log(group), std::move(from), source);
  part->share_depth_cache(bodies_);
  waiting_[g].reset();
  const auto at = std::lower_bound(here_.begin(), here_.end(), group);
  const auto k = at - here_.begin();
  here_.insert(at, group);
  parts_.insert(parts_.begin() + k, std::move(part));
  part_seconds_.insert(part_seconds_.begin() + k, 0.0);
  team_ = std::max(1, std::min(options_.threads, static_cast<int>(here_.size())));
}

std::vector<PartFrame> Ensemble::step_parts() {
  std::vector<PartFrame> frames(parts_.size());
  // Longest processing time first (Graham 1969): the parts that took longest last frame start
  // first, so that a costly part (a dancer in close-up) does not start last and leave the other
  // threads idle. Each part's result does not depend on when it runs.
  for_each_in_order(largest_first(part_seconds_), team_, [&](int k) {
    const auto i = static_cast<std::size_t>(k);
    const auto start = std::chrono::steady_clock::now();
    frames[i].group = here_[i];
    frames[i].stats = parts_[i]->step_frame();
    frames[i].seconds = part_seconds_[i] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  });
  ++frame_;
  return frames;
}

FrameStats Ensemble::step_frame() {
  const auto t0 = std::chrono::steady_clock::now();
  FrameStats total = total_of(step_parts());
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
