#include "output/run_output.hpp"

#include <algorithm>

#include <cstdio>
#include <filesystem>
#include <optional>
#include <regex>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/resource_usage.hpp"
#include "output/checkpoint.hpp"
#include "io/json_parse.hpp"
#include "io/obj.hpp"
#include "io/ply.hpp"
#include "view/view_factor.hpp"

namespace vdc {

namespace fs = std::filesystem;

namespace {
const char* const kStatsHeader =
    "frame,faces,vertices,seconds,substeps,halvings,solver_iterations,factorizations,assemble_seconds,solve_seconds,"
    "remesh_seconds,splits,flips,collapses,collision_seconds,impacts,collision_iterations,collision_fallbacks,kinetic_energy,gravitational_energy,elastic_energy,"
    "proximity_pairs,untangle_moves,visible_faces,back_facing_faces,out_of_frame_faces,view_seconds,velocity_clamps,"
    "remesh_undone,resident_mib,collision_candidates,remesh_refused,defocused_faces,blurred_faces,hidden_faces,far_groups";

// A frame file's name, <mesh>.<frame>.<extension> with mesh cloth_* or obstacle_*, taken apart.
struct FrameFileName {
  std::string mesh, extension;
  int frame = 0;
};
std::optional<FrameFileName> parse_frame_file(const std::string& file) {
  static const std::regex name(R"(^((cloth|obstacle)_.+)\.([0-9]{4,9})\.(obj|ply)$)");
  std::smatch m;
  if (!std::regex_match(file, m, name)) return std::nullopt;
  return FrameFileName{m[1].str(), m[4].str(), std::stoi(m[3].str())};
}

// Frame meshes' coordinates, in metres, to the micrometre: 1/2000 of the default collision
// thickness, a float's step 8 m from the origin, and about half the bytes of the exact form.
constexpr int kFrameDecimals = 6;

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
  std::map<int, FrameFiles> frames;
  for (const auto& entry : fs::directory_iterator(dir))
    if (const auto f = parse_frame_file(entry.path().filename().string()); f && f->extension == "obj")
      frames[f->frame][f->mesh] = entry.path().string();
  if (frames.empty()) throw InputError(dir.string(), "", "no frame meshes (was the run made with --mesh-every 0?)");
  return frames;
}

RunOutput::RunOutput(const std::string& dir) : dir_(dir) {
  std::error_code ec;
  fs::create_directories(fs::path(dir) / "frames", ec);
  if (ec) throw InputError(dir, "", "cannot create output directory: " + ec.message());
  for (const auto& entry : fs::directory_iterator(fs::path(dir) / "frames", ec)) {
    const std::string name = entry.path().filename().string();
    const bool earlier_frame = (entry.path().extension() == ".obj" || entry.path().extension() == ".ply") &&
                               (name.rfind("cloth_", 0) == 0 || name.rfind("obstacle_", 0) == 0);
    if (!earlier_frame) continue;
    std::error_code removing;
    fs::remove(entry.path(), removing);
    if (removing) throw InputError(entry.path().string(), "", "cannot remove this frame of an earlier run: " + removing.message());
  }
  if (ec) throw InputError(dir + "/frames", "", "cannot list: " + ec.message());
  fs::remove(fs::path(dir) / "summary.json", ec);
  std::ofstream(fs::path(dir) / kLogFile, std::ios::trunc);  // empty: no warning yet
  // What `vdcloth check` found of an earlier run's frames says nothing of this run's.
  fs::remove(fs::path(dir) / "check.csv", ec);
  fs::remove(fs::path(dir) / "check_status.txt", ec);
  // A checkpoint left by an earlier run must not be resumed into this one.
  fs::remove(fs::path(dir) / kCheckpointFile, ec);
  stats_.open(dir + "/stats.csv");
  if (!stats_) throw OutputError(dir + "/stats.csv", "cannot write");
  stats_ << kStatsHeader << "\n";
}

RunOutput::RunOutput(const std::string& dir, int resume_at) : dir_(dir) {
  std::error_code ec;
  fs::create_directories(fs::path(dir) / "frames", ec);
  if (ec) throw InputError(dir, "", "cannot create output directory: " + ec.message());
  const std::string stats_path = dir + "/stats.csv";
  std::ifstream in(stats_path);
  if (!in) throw InputError(stats_path, "", "cannot open (the run to resume has no statistics)");
  std::string header;
  std::getline(in, header);
  if (header != kStatsHeader) throw InputError(stats_path, "line 1", "not the statistics of this vdcloth's runs");
  std::vector<std::string> kept;
  int line_number = 1;
  for (std::string line; std::getline(in, line) && static_cast<int>(kept.size()) < resume_at;) {
    ++line_number;
    int frame = 0, faces = 0, vertices = 0;
    double seconds = 0;
    if (std::sscanf(line.c_str(), "%d,%d,%d,%lf", &frame, &faces, &vertices, &seconds) != 4 || frame != static_cast<int>(kept.size()) + 1)
      throw InputError(stats_path, "line " + std::to_string(line_number), "expected the row of frame " + std::to_string(kept.size() + 1));
    kept.push_back(line);
    tally(faces, seconds);
  }
  if (static_cast<int>(kept.size()) < resume_at)
    throw InputError(stats_path, "", "ends at frame " + std::to_string(kept.size()) + ", before the checkpoint's frame " + std::to_string(resume_at));
  in.close();
  // The kept rows go in first (written aside, then renamed over), so the run stays resumable
  // whenever this stops; then what the stopped process made after the checkpoint goes.
  {
    std::ofstream rows(stats_path + ".tmp", std::ios::trunc);
    rows << kStatsHeader << "\n";
    for (const auto& line : kept) rows << line << "\n";
    if (!rows.flush()) throw OutputError(stats_path + ".tmp", "cannot write");
  }
  fs::rename(stats_path + ".tmp", stats_path, ec);
  if (ec) throw OutputError(stats_path, "cannot write: " + ec.message());
  for (const auto& entry : fs::directory_iterator(fs::path(dir) / "frames", ec))
    if (const auto f = parse_frame_file(entry.path().filename().string()); f && f->frame > resume_at) fs::remove(entry.path(), ec);
  fs::remove(fs::path(dir) / "summary.json", ec);
  fs::remove(fs::path(dir) / "check.csv", ec);
  fs::remove(fs::path(dir) / "check_status.txt", ec);
  stats_.open(stats_path, std::ios::app);
  if (!stats_) throw OutputError(stats_path, "cannot write");
}

RunOutput RunOutput::joining(const std::string& dir) {
  RunOutput joined;
  joined.dir_ = dir;
  return joined;
}

void RunOutput::append_log(const std::string& line) const {
  std::ofstream log(dir_ + "/" + kLogFile, std::ios::app);
  log << line << "\n";
}

void RunOutput::tally(int faces, double seconds) {
  if (rows_ == 0) min_faces_ = max_faces_ = faces;
  min_faces_ = std::min(min_faces_, faces);
  max_faces_ = std::max(max_faces_, faces);
  sum_faces_ += faces;
  sum_seconds_ += seconds;
  max_seconds_ = std::max(max_seconds_, seconds);
  ++rows_;
}

void RunOutput::write_frame(const Ensemble& run, int frame) const {
  for (std::size_t k = 0; k < run.parts().size(); ++k) {
    const auto& part = run.parts()[k];
    const Scene& scene = part->scene();
    for (std::size_t g = 0; g < scene.garments.size(); ++g) {
      const std::string& name = scene.garments[g].name;
      const Mesh& mesh = part->garment_mesh(g);
      if (!write_obj(mesh, frame_file(dir_, "cloth", name, frame), ObjWriting{true, kFrameDecimals, true})) throw OutputError(frame_file(dir_, "cloth", name, frame), "cannot write");
      // View mode: each garment's faces with their view factors and what set them, beside the OBJ.
      std::vector<PlyFaceProperty> view{{"view", kViewFactorAttr}};
      if (mesh.face_attrs().has(kViewReasonAttr)) view.push_back({"reason", kViewReasonAttr, true});
      if (mesh.face_attrs().has(kViewCameraAttr)) view.push_back({"camera", kViewCameraAttr, true});  // several cameras: which decided
      if (mesh.face_attrs().has(kViewFactorAttr) &&
          !write_ply_with_face_values(mesh, frame_file(dir_, "cloth", name, frame, ".ply"), view, kFrameDecimals))
        throw OutputError(frame_file(dir_, "cloth", name, frame, ".ply"), "cannot write");
    }
    // Obstacles of no group are in every part: written once, from group 0's.
    for (std::size_t o = 0; o < scene.obstacles.size(); ++o) {
      const ObstacleSpec& spec = scene.obstacles[o];
      if ((run.here()[k] == 0 || !spec.group.empty()) &&
          !write_obj(part->obstacle_mesh(o), frame_file(dir_, "obstacle", spec.name, frame), ObjWriting{false, kFrameDecimals}))
        throw OutputError(frame_file(dir_, "obstacle", spec.name, frame), "cannot write");
    }
  }
}

void RunOutput::write_stats_row(const FrameStats& s) {
  char line[1024];
  std::snprintf(line, sizeof line, "%d,%d,%d,%.6f,%d,%d,%d,%d,%.6f,%.6f,%.6f,%d,%d,%d,%.6f,%d,%d,%d,%.9g,%.9g,%.9g,%d,%d,%d,%d,%d,%.6f,%d,%d,%.1f,%lld,%d,%d,%d,%d,%d\n", s.frame, s.faces, s.vertices, s.seconds,
                s.substeps, s.halvings, s.solver_iterations, s.factorizations, s.assemble_seconds, s.solve_seconds, s.remesh_seconds, s.splits, s.flips, s.collapses, s.collision_seconds, s.impacts, s.collision_iterations,
                s.collision_fallbacks, s.energy.kinetic,
                s.energy.gravitational, s.energy.elastic, s.proximities, s.untangle_moves, s.visible_faces,
                s.back_facing_faces, s.out_of_frame_faces, s.view_seconds, s.velocity_clamps, s.remesh_undone,
                static_cast<double>(resident_kib()) / 1024.0, s.collision_candidates, s.remesh_refused, s.defocused_faces,
                s.blurred_faces, s.hidden_faces, s.far_groups);
  stats_ << line << std::flush;
  if (!stats_) throw OutputError(dir_ + "/stats.csv", "cannot write");
  tally(s.faces, s.seconds);
}

bool run_is_done(const std::string& dir, int frames) {
  const nlohmann::json j = read_json_or_null(dir + "/summary.json");
  return j.is_object() && j.contains("status") && j["status"] == "done" && j.contains("frames") && j["frames"] == frames;
}

std::vector<GarmentSize> garment_sizes(const Simulation& part) {
  std::vector<GarmentSize> sizes;
  for (std::size_t g = 0; g < part.scene().garments.size(); ++g) sizes.push_back({part.garment_mesh(g).num_faces(), part.garment_mesh(g).num_nodes()});
  return sizes;
}

nlohmann::json RunOutput::summary(const Ensemble& run, const std::vector<std::vector<GarmentSize>>& sizes, const std::string& status, const std::string& error,
                                  const ResourceUsage& usage, int segments, int frames_done, int threads, const Perturbation& perturbation) const {
  nlohmann::json j;
  const Scene& scene = run.group_scene(0);
  j["scene"] = run.path();
  j["name"] = run.name();
  j["status"] = status;
  if (!error.empty()) j["error"] = error;
  j["mode"] = sim_mode_name(run.options().mode);
  j["threads"] = threads;
  j["version"] = VDCLOTH_VERSION;
  const MachineDescription machine = describe_machine();
  j["machine"] = {{"host", machine.host}, {"cpu", machine.cpu}, {"cores", machine.cores}};
  j["finished"] = utc_now_iso8601();
  j["groups"] = run.groups();
  j["frames"] = frames_done;
  j["frame_time"] = scene.frame_time;
  j["substeps"] = scene.substeps;
  j["preroll_frames"] = scene.preroll_frames;
  j["linear_solver"] = linear_solver_name(scene.solver.linear);
  j["perturbation"] = perturbation.gravity;
  j["resolution_perturbation"] = perturbation.resolution;
  j["total_seconds"] = usage.wall_seconds;
  j["segments"] = segments;
  j["cpu_seconds"] = usage.cpu_seconds;
  j["peak_memory_kib"] = usage.peak_kib;
  if (usage.steal() >= 0) j["steal"] = usage.steal();
  j["seconds_per_frame"] = {{"mean", rows_ ? sum_seconds_ / rows_ : 0.0}, {"max", max_seconds_}};
  j["faces"] = {{"min", min_faces_}, {"max", max_faces_}, {"mean", rows_ ? sum_faces_ / rows_ : 0.0}};
  nlohmann::json garments = nlohmann::json::array();
  for (int group = 0; group < run.groups(); ++group)
    for (std::size_t g = 0; g < run.group_scene(group).garments.size(); ++g) {
      const GarmentSpec& spec = run.group_scene(group).garments[g];
      // A group another process steps and has not reported yet (before a run's first frame): zeros.
      const auto& group_sizes = sizes.at(static_cast<std::size_t>(group));
      const GarmentSize size = g < group_sizes.size() ? group_sizes[g] : GarmentSize{};
      nlohmann::json garment{{"name", spec.name}, {"material", spec.material.name}, {"faces", size.faces}, {"vertices", size.vertices}};
      if (!spec.fitted_to.empty()) garment["fitted"] = {{"to", spec.fitted_to}, {"ease", spec.ease}};
      garments.push_back(garment);
    }
  j["garments"] = garments;
  // The characters as the run made them: their build, and how they come to their first pose.
  nlohmann::json characters = nlohmann::json::array();
  for (int group = 0; group < run.groups(); ++group)
    for (const ObstacleSpec& o : run.group_scene(group).obstacles)
      if (o.character && std::none_of(characters.begin(), characters.end(), [&](const nlohmann::json& c) { return c["name"] == o.name; }))
        characters.push_back({{"name", o.name}, {"build", o.character->body_params().build}, {"preroll", o.character->preroll()}});
  j["characters"] = characters;
  return j;
}

void RunOutput::write_summary(const nlohmann::json& summary) const {
  std::ofstream out(dir_ + "/summary.json");
  out << summary.dump(2) << "\n";
  if (!out) throw OutputError(dir_ + "/summary.json", "cannot write");
}

}  // namespace vdc
