#include "io/run_output.hpp"

#include <cstdio>
#include <filesystem>
#include <regex>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "io/obj.hpp"
#include "io/ply.hpp"

namespace vdc {

namespace fs = std::filesystem;

namespace {
std::string frame_file(const std::string& dir, const std::string& kind, const std::string& name, int frame,
                       const std::string& extension = ".obj") {
  char num[16];
  std::snprintf(num, sizeof num, "%04d", frame);
  return dir + "/frames/" + kind + "_" + name + "." + num + extension;
}
}  // namespace

std::map<int, FrameFiles> read_frame_files(const std::string& run_dir) {
  const fs::path dir = fs::path(run_dir) / "frames";
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(dir.string(), "", "no such directory (is " + run_dir + " the output of vdcloth run?)");
  static const std::regex name(R"(^((cloth|obstacle)_.+)\.([0-9]{4,})\.obj$)");
  std::map<int, FrameFiles> frames;
  for (const auto& entry : fs::directory_iterator(dir)) {
    std::smatch m;
    const std::string file = entry.path().filename().string();
    if (std::regex_match(file, m, name)) frames[std::stoi(m[3].str())][m[1].str()] = entry.path().string();
  }
  if (frames.empty()) throw InputError(dir.string(), "", "no frame meshes (was the run made with --mesh-every 0?)");
  return frames;
}

RunOutput::RunOutput(const std::string& dir) : dir_(dir) {
  std::error_code ec;
  fs::create_directories(fs::path(dir) / "frames", ec);
  if (ec) throw InputError(dir, "", "cannot create output directory: " + ec.message());
  for (const auto& entry : fs::directory_iterator(fs::path(dir) / "frames")) {
    const std::string name = entry.path().filename().string();
    if ((entry.path().extension() == ".obj" || entry.path().extension() == ".ply") &&
        (name.rfind("cloth_", 0) == 0 || name.rfind("obstacle_", 0) == 0))
      fs::remove(entry.path());
  }
  fs::remove(fs::path(dir) / "summary.json", ec);
  stats_.open(dir + "/stats.csv");
  if (!stats_) throw InputError(dir + "/stats.csv", "", "cannot write");
  stats_ << "frame,faces,vertices,seconds,substeps,halvings,solver_iterations,factorizations,assemble_seconds,solve_seconds,"
            "remesh_seconds,splits,flips,collapses,collision_seconds,impacts,collision_iterations,collision_fallbacks,kinetic_energy,gravitational_energy,elastic_energy,"
            "proximity_pairs,untangle_moves,visible_faces,back_facing_faces,out_of_frame_faces,view_seconds,velocity_clamps\n";
}

void RunOutput::write_frame(const Ensemble& run, int frame) const {
  for (const auto& part : run.parts()) {
    for (const auto& g : part->scene().garments) {
      if (!write_obj(g.mesh, frame_file(dir_, "cloth", g.name, frame)))
        throw InputError(frame_file(dir_, "cloth", g.name, frame), "", "cannot write");
      // View mode: each garment's faces with their view factors, beside the OBJ.
      if (g.mesh.face_attrs().has(kViewFactorAttr) &&
          !write_ply_with_face_values(g.mesh, frame_file(dir_, "cloth", g.name, frame, ".ply"), "view", kViewFactorAttr))
        throw InputError(frame_file(dir_, "cloth", g.name, frame, ".ply"), "", "cannot write");
    }
    // Obstacles of no group are in every part: written once, from the first.
    for (const auto& o : part->scene().obstacles)
      if ((part == run.parts().front() || !o.group.empty()) && !write_obj(o.mesh, frame_file(dir_, "obstacle", o.name, frame)))
        throw InputError(frame_file(dir_, "obstacle", o.name, frame), "", "cannot write");
  }
}

void RunOutput::write_stats_row(const FrameStats& s) {
  char line[1024];
  std::snprintf(line, sizeof line, "%d,%d,%d,%.6f,%d,%d,%d,%d,%.6f,%.6f,%.6f,%d,%d,%d,%.6f,%d,%d,%d,%.9g,%.9g,%.9g,%d,%d,%d,%d,%d,%.6f,%d\n", s.frame, s.faces, s.vertices, s.seconds,
                s.substeps, s.halvings, s.solver_iterations, s.factorizations, s.assemble_seconds, s.solve_seconds, s.remesh_seconds, s.splits, s.flips, s.collapses, s.collision_seconds, s.impacts, s.collision_iterations,
                s.collision_fallbacks, s.energy.kinetic,
                s.energy.gravitational, s.energy.elastic, s.proximities, s.untangle_moves, s.visible_faces,
                s.back_facing_faces, s.out_of_frame_faces, s.view_seconds, s.velocity_clamps);
  stats_ << line << std::flush;
  if (rows_ == 0) min_faces_ = max_faces_ = s.faces;
  min_faces_ = std::min(min_faces_, s.faces);
  max_faces_ = std::max(max_faces_, s.faces);
  sum_faces_ += s.faces;
  sum_seconds_ += s.seconds;
  max_seconds_ = std::max(max_seconds_, s.seconds);
  ++rows_;
}

void RunOutput::write_summary(const Ensemble& run, const std::string& status, const std::string& error, double total_seconds,
                              int frames_done, int threads) const {
  nlohmann::json j;
  const Scene& scene = run.parts().front()->scene();
  j["scene"] = run.path();
  j["name"] = run.name();
  j["status"] = status;
  if (!error.empty()) j["error"] = error;
  j["mode"] = sim_mode_name(run.options().mode);
  j["threads"] = threads;
  j["groups"] = run.parts().size();
  j["frames"] = frames_done;
  j["frame_time"] = scene.frame_time;
  j["substeps"] = scene.substeps;
  j["linear_solver"] = linear_solver_name(scene.solver.linear);
  j["total_seconds"] = total_seconds;
  j["seconds_per_frame"] = {{"mean", rows_ ? sum_seconds_ / rows_ : 0.0}, {"max", max_seconds_}};
  j["faces"] = {{"min", min_faces_}, {"max", max_faces_}, {"mean", rows_ ? sum_faces_ / rows_ : 0.0}};
  nlohmann::json garments = nlohmann::json::array();
  for (const auto& part : run.parts())
    for (const auto& g : part->scene().garments)
      garments.push_back({{"name", g.name}, {"material", g.material.name}, {"faces", g.mesh.num_faces()}, {"vertices", g.mesh.num_nodes()}});
  j["garments"] = garments;
  std::ofstream out(dir_ + "/summary.json");
  out << j.dump(2) << "\n";
  if (!out) throw InputError(dir_ + "/summary.json", "", "cannot write");
}

}  // namespace vdc
