#include "app/table1.hpp"

#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <optional>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "app/check_command.hpp"
#include "app/cli.hpp"
#include "core/error.hpp"
#include "core/resource_usage.hpp"
#include "io/json_parse.hpp"
#include "output/checkpoint.hpp"
#include "output/run_output.hpp"
#include "scene/scene.hpp"

extern char** environ;

namespace vdc {

namespace fs = std::filesystem;

namespace {

const char* kTable1Help =
    "usage: vdcloth bench table1 [--frames N] [--fixed-frames N] [--out DIR] [--threads N] [--scenes DIR]\n"
    "                            [--scene NAME]... [--mode M]... [--mesh-every N] [--tables-only]\n"
    "                            [--resume]\n"
    "\n"
    "Runs karate, solo-dancer and dancers-10 (from DIR/<name>.json) in fixed, adaptive and view\n"
    "modes, each as a child `vdcloth run` into OUT/<scene>/<mode>/, and writes OUT/table1.md and\n"
    "OUT/table1.csv (faces, vertices and seconds per frame: min, max, mean; speed-ups relative to\n"
    "adaptive and to fixed; peak memory) and OUT/table1_<scene>_frames.csv (per frame: faces and seconds of the\n"
    "adaptive and view runs). Fixed mode runs at the scene's remeshing size_min (or fixed_size).\n"
    "\n"
    "options:\n"
    "  --frames N      frames of every run (default: each scene's `frames`)\n"
    "  --fixed-frames N  frames of the fixed runs only (default: as --frames): at size_min the\n"
    "                  baseline costs far more a frame, and its first frames measure that cost;\n"
    "                  speed-ups are taken over the frames both runs have\n"
    "  --out DIR       output directory (default: out/table1)\n"
    "  --threads N     worker threads of each run, 1 to 256 (default: all cores)\n"
    "  --scenes DIR    where the scenes are (default: scenes)\n"
    "  --scene NAME    run only this scene (repeatable; default: all three)\n"
    "  --mode M        run only this mode: fixed, adaptive or view (repeatable; default: all three);\n"
    "                  the tables still show every run found in OUT\n"
    "  --tables-only   run nothing: make the tables from the runs already in OUT\n"
    "  --mesh-every N  meshes written by each run, as `vdcloth run --mesh-every` (default: 0, none);\n"
    "                  with meshes, each run is checked for crossings at its frame ends (`vdcloth\n"
    "                  check`) once it is done, and the tables say how many frames had any\n"
    "  --resume        keep the runs in OUT that are done, go on with the unfinished ones from their\n"
    "                  checkpoints (`vdcloth run --resume`), and start the others\n";

struct Table1Args {
  std::optional<int> frames, fixed_frames;
  std::string out = "out/table1";
  int threads = 0;
  std::string scenes = "scenes";
  std::vector<std::string> only, modes;
  int mesh_every = 0;
  bool tables_only = false;
  bool resume = false;
};

Table1Args parse_table1_args(const std::vector<std::string>& args) {
  Table1Args r;
  for (ArgumentReader in(args); !in.done();) {
    const std::string& a = in.next();
    if (a == "--frames") r.frames = parse_positive_int(a, in.value());
    else if (a == "--fixed-frames") r.fixed_frames = parse_positive_int(a, in.value());
    else if (a == "--out") r.out = in.value();
    else if (a == "--threads") r.threads = parse_int_in(a, in.value(), 1, kMaxThreads);
    else if (a == "--scenes") r.scenes = in.value();
    else if (a == "--scene") r.only.push_back(in.value());
    else if (a == "--mode") {
      const std::string& m = in.value();
      if (m != "fixed" && m != "adaptive" && m != "view") throw UsageError("--mode expects fixed, adaptive or view, got '" + m + "'");
      r.modes.push_back(m);
    } else if (a == "--tables-only") r.tables_only = true;
    else if (a == "--resume") r.resume = true;
    else if (a == "--mesh-every") {
      const std::string& v = in.value();
      r.mesh_every = v == "0" ? 0 : parse_positive_int(a, v);
    } else throw UsageError("unknown option '" + a + "' of bench table1");
  }
  if (r.out.empty()) throw UsageError("--out needs a directory");
  return r;
}

struct Run {
  std::string scene, mode;
  int status = 0;          // exit status of the child
  long peak_kib = 0;       // its peak resident memory
  double cpu_seconds = 0;  // its user and system CPU time, all threads
  double steal = -1;       // share of the machine's CPU time the hypervisor took meanwhile (-1: unknown)
  std::optional<CheckSummary> check;  // frame-end crossings of its written meshes, if checked
  RunTable table;
};

// The run's frame-end check from RUN/check_status.txt, if one was made.
void read_check_status(const std::string& dir, Run& r) {
  std::ifstream status(dir + "/check_status.txt");
  CheckSummary c;
  if (status >> c.frames_checked >> c.frames_with_crossings) r.check = c;
  else r.check.reset();
}

// RUN/run_status.txt: exit status, peak memory, CPU seconds and steal, read back by --tables-only.
void write_run_status(const std::string& dir, const Run& r) {
  std::ofstream(dir + "/run_status.txt") << r.status << " " << r.peak_kib << " " << r.cpu_seconds << " " << r.steal << "\n";
}

// CPU time, peak memory and steal from the run's summary.json, which sums them over every
// process a resumed run was made in; left as they are when the summary does not have them.
void read_summary_usage(const std::string& dir, Run& r) {
  const nlohmann::json j = read_json_or_null(dir + "/summary.json");
  if (!j.is_object() || !j.contains("cpu_seconds") || !j.contains("peak_memory_kib")) return;
  if (!j["cpu_seconds"].is_number() || !j["peak_memory_kib"].is_number()) return;
  r.cpu_seconds = j["cpu_seconds"].get<double>();
  r.peak_kib = j["peak_memory_kib"].get<long>();
  if (j.contains("steal") && j["steal"].is_number()) r.steal = j["steal"].get<double>();
}

}  // namespace

double speedup_over_shared_frames(const RunTable& base, const RunTable& run, int* shared) {
  const std::size_t n = std::min(base.seconds.size(), run.seconds.size());
  if (shared) *shared = static_cast<int>(n);
  double base_sum = 0, run_sum = 0;
  for (std::size_t i = 0; i < n; ++i) base_sum += base.seconds[i], run_sum += run.seconds[i];
  return n > 0 && run_sum > 0 ? base_sum / run_sum : 0.0;
}

namespace {

std::string check_cell(const Run& r) {
  if (!r.check) return "";
  return std::to_string(r.check->frames_with_crossings) + " of " + std::to_string(r.check->frames_checked);
}

// Runs argv as a child process; returns its exit status (128 + signal if killed), peak memory
// and CPU time.
int run_child(const std::vector<std::string>& argv, long& peak_kib, double& cpu_seconds) {
  std::vector<char*> cargs;
  for (const auto& a : argv) cargs.push_back(const_cast<char*>(a.c_str()));
  cargs.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, "/proc/self/exe", nullptr, nullptr, cargs.data(), environ) != 0)
    throw InputError("/proc/self/exe", "", "cannot start a child run");
  int status = 0;
  rusage usage{};
  while (wait4(pid, &status, 0, &usage) < 0)
    if (errno != EINTR) throw InputError("/proc/self/exe", "", "lost a child run");
  peak_kib = usage.ru_maxrss;
  cpu_seconds = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

std::string fixed_cell(double x, int digits) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(digits) << x;
  return o.str();
}

std::string today() {
  const std::time_t now = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%d", std::gmtime(&now));
  return buf;
}

const Run* find_run(const std::vector<Run>& runs, const std::string& scene, const std::string& mode) {
  for (const Run& r : runs)
    if (r.scene == scene && r.mode == mode) return &r;
  return nullptr;
}

void write_tables(const std::vector<Run>& runs, const Table1Args& args, int threads) {
  std::ofstream csv(args.out + "/table1.csv");
  csv << "scene,mode,status,frames,faces_min,faces_max,faces_mean,vertices_min,vertices_max,vertices_mean,"
         "seconds_min,seconds_max,seconds_mean,speedup_vs_adaptive,speedup_vs_fixed,peak_memory_mib,cpu_seconds_per_frame,steal_percent,"
         "frames_checked,frames_with_crossings,speedup_vs_fixed_frames\n";
  std::ofstream md(args.out + "/table1.md");
  md << "# Table 1 on vdcloth's scenes\n\n"
     << today() << ", " << threads << " thread(s) a run, " << std::thread::hardware_concurrency() << " cores. "
     << "Speed-ups are mean seconds per frame relative to the scene's adaptive and fixed runs, over the frames both "
        "runs have (a fixed run made over the shot's first frames only says which). CPU s/frame is the run's "
        "CPU time (all threads) per frame; steal is the share of the machine's CPU time its host took during the run "
        "(virtual machines), which slows the wall clock. Crossings: frames whose written meshes have a garment crossing "
        "itself, another garment or an obstacle (`vdcloth check`), of the frames checked.\n\n"
     << "| scene | mode | frames | faces min / max / mean | vertices min / max / mean | s/frame min / max / mean | "
        "vs adaptive | vs fixed | peak memory | CPU s/frame | steal | crossings |\n"
     << "| --- | --- | ---: | --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  for (const Run& r : runs) {
    const RunTable& t = r.table;
    const Run* adaptive = find_run(runs, r.scene, "adaptive");
    const Run* fixed = find_run(runs, r.scene, "fixed");
    int fixed_frames = 0;
    const double vs_adaptive = adaptive ? speedup_over_shared_frames(adaptive->table, t) : 0.0;
    const double vs_fixed = fixed ? speedup_over_shared_frames(fixed->table, t, &fixed_frames) : 0.0;
    auto speedup_cell = [](double x) { return x > 0 ? fixed_cell(x, 2) : std::string(); };
    // A fixed baseline made over the shot's first frames only: its speed-up says over which.
    std::string vs_fixed_md = vs_fixed > 0 ? fixed_cell(vs_fixed, 2) + "x" : "";
    if (vs_fixed > 0 && fixed_frames < t.frames) vs_fixed_md += " (frames 1-" + std::to_string(fixed_frames) + ")";
    const std::string status = r.status == 0 ? "done" : "failed (exit " + std::to_string(r.status) + ")";
    const double cpu_per_frame = t.frames > 0 ? r.cpu_seconds / t.frames : 0.0;
    csv << r.scene << "," << r.mode << "," << (r.status == 0 ? "done" : "failed") << "," << t.frames << "," << t.faces_min << ","
        << t.faces_max << "," << fixed_cell(t.faces_mean, 1) << "," << t.vertices_min << "," << t.vertices_max << ","
        << fixed_cell(t.vertices_mean, 1) << "," << fixed_cell(t.seconds_min, 4) << "," << fixed_cell(t.seconds_max, 4) << ","
        << fixed_cell(t.seconds_mean, 4) << "," << speedup_cell(vs_adaptive) << "," << speedup_cell(vs_fixed) << ","
        << fixed_cell(static_cast<double>(r.peak_kib) / 1024, 0) << "," << fixed_cell(cpu_per_frame, 4) << ","
        << (r.steal < 0 ? "" : fixed_cell(100 * r.steal, 1)) << "," << (r.check ? std::to_string(r.check->frames_checked) : "") << ","
        << (r.check ? std::to_string(r.check->frames_with_crossings) : "") << "," << (vs_fixed > 0 ? std::to_string(fixed_frames) : "")
        << "\n";
    md << "| " << r.scene << " | " << r.mode << (r.status == 0 ? "" : " (" + status + ")") << " | " << t.frames << " | "
       << t.faces_min << " / " << t.faces_max << " / " << fixed_cell(t.faces_mean, 0) << " | " << t.vertices_min << " / "
       << t.vertices_max << " / " << fixed_cell(t.vertices_mean, 0) << " | " << fixed_cell(t.seconds_min, 3) << " / "
       << fixed_cell(t.seconds_max, 3) << " / " << fixed_cell(t.seconds_mean, 3) << " | "
       << (vs_adaptive > 0 ? speedup_cell(vs_adaptive) + "x" : "") << " | " << vs_fixed_md << " | " << fixed_cell(static_cast<double>(r.peak_kib) / 1024, 0) << " MiB | "
       << (cpu_per_frame > 0 ? fixed_cell(cpu_per_frame, 3) : "") << " | " << (r.steal < 0 ? "" : fixed_cell(100 * r.steal, 1) + "%") << " | "
       << check_cell(r) << " |\n";
  }
  // Per frame, adaptive against view (the data of Koh et al. 2014's Figure 5).
  std::vector<std::string> scenes;
  for (const Run& r : runs)
    if (std::find(scenes.begin(), scenes.end(), r.scene) == scenes.end()) scenes.push_back(r.scene);
  for (const std::string& scene : scenes) {
    const Run* a = find_run(runs, scene, "adaptive");
    const Run* v = find_run(runs, scene, "view");
    if (!a || !v) continue;
    std::ofstream f(args.out + "/table1_" + scene + "_frames.csv");
    f << "frame,adaptive_faces,adaptive_seconds,view_faces,view_seconds\n";
    const std::size_t n = std::max(a->table.faces.size(), v->table.faces.size());
    for (std::size_t i = 0; i < n; ++i) {
      f << i + 1;
      for (const Run* r : {a, v}) {
        if (i < r->table.faces.size()) f << "," << r->table.faces[i] << "," << fixed_cell(r->table.seconds[i], 6);
        else f << ",,";
      }
      f << "\n";
    }
  }
  if (!csv || !md) throw OutputError(args.out + "/table1.md", "cannot write");
}

}  // namespace

RunTable read_run_table(const std::string& stats_csv) {
  std::ifstream in(stats_csv);
  if (!in) throw InputError(stats_csv, "", "cannot read");
  std::string line;
  if (!std::getline(in, line) || line.rfind("frame,faces,vertices,seconds", 0) != 0)
    throw InputError(stats_csv, "line 1", "expected the header frame,faces,vertices,seconds,...");
  RunTable t;
  double faces_sum = 0, vertices_sum = 0, seconds_sum = 0;
  int line_no = 1;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty()) continue;
    std::istringstream row(line);
    std::string cell[4];
    for (auto& c : cell)
      if (!std::getline(row, c, ',')) throw InputError(stats_csv, "line " + std::to_string(line_no), "fewer than four columns");
    int faces = 0, vertices = 0;
    double seconds = 0;
    try {
      faces = std::stoi(cell[1]);
      vertices = std::stoi(cell[2]);
      seconds = std::stod(cell[3]);
    } catch (const std::exception&) {
      throw InputError(stats_csv, "line " + std::to_string(line_no), "not a number in the first four columns");
    }
    if (t.frames == 0) {
      t.faces_min = t.faces_max = faces;
      t.vertices_min = t.vertices_max = vertices;
      t.seconds_min = t.seconds_max = seconds;
    }
    ++t.frames;
    t.faces_min = std::min(t.faces_min, faces);
    t.faces_max = std::max(t.faces_max, faces);
    t.vertices_min = std::min(t.vertices_min, vertices);
    t.vertices_max = std::max(t.vertices_max, vertices);
    t.seconds_min = std::min(t.seconds_min, seconds);
    t.seconds_max = std::max(t.seconds_max, seconds);
    faces_sum += faces;
    vertices_sum += vertices;
    seconds_sum += seconds;
    t.faces.push_back(faces);
    t.seconds.push_back(seconds);
  }
  if (t.frames > 0) {
    t.faces_mean = faces_sum / t.frames;
    t.vertices_mean = vertices_sum / t.frames;
    t.seconds_mean = seconds_sum / t.frames;
  }
  return t;
}

int table1_command(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  for (const auto& a : argv)
    if (a == "--help" || a == "-h") {
      out << kTable1Help;
      return kExitOk;
    }
  const Table1Args args = parse_table1_args(argv);
  const std::vector<std::string> all{"karate", "solo-dancer", "dancers-10"};
  for (const auto& name : args.only)
    if (std::find(all.begin(), all.end(), name) == all.end())
      throw UsageError("--scene expects karate, solo-dancer or dancers-10, got '" + name + "'");
  std::vector<std::string> scenes;
  for (const auto& name : all)
    if (args.only.empty() || std::find(args.only.begin(), args.only.end(), name) != args.only.end()) scenes.push_back(name);
  // Every scene is read (and checked) before the first run starts.
  std::map<std::string, int> scene_frames;
  for (const auto& name : scenes) {
    const std::string path = args.scenes + "/" + name + ".json";
    if (std::error_code ec; !fs::is_regular_file(path, ec)) throw InputError(path, "", "scene not found (use --scenes DIR)");
    const Scene scene = load_scene(path);
    if (scene.cameras.empty()) throw InputError(path, "camera", "table1 needs a camera for its view-dependent runs");
    scene_frames[name] = scene.frames;
  }
  const int threads = args.threads > 0 ? args.threads : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  std::error_code ec;
  fs::create_directories(args.out, ec);
  if (ec) throw InputError(args.out, "", "cannot create output directory: " + ec.message());

  // Runs of other scenes and modes already in OUT stay in the tables.
  std::vector<Run> runs;
  for (const auto& name : all)
    for (const std::string mode : {"fixed", "adaptive", "view"}) {
      Run r;
      r.scene = name;
      r.mode = mode;
      const std::string dir = args.out + "/" + name + "/" + mode;
      const bool wanted = std::find(scenes.begin(), scenes.end(), name) != scenes.end() &&
                          (args.modes.empty() || std::find(args.modes.begin(), args.modes.end(), mode) != args.modes.end());
      const std::optional<int> frames = mode == std::string("fixed") && args.fixed_frames ? args.fixed_frames : args.frames;
      const bool kept = wanted && args.resume && run_is_done(dir, frames ? *frames : scene_frames[name]);
      if (wanted && !args.tables_only && !kept) {
        std::vector<std::string> child{"vdcloth", "run", args.scenes + "/" + name + ".json", "--mode", mode, "--out", dir,
                                       "--threads", std::to_string(threads), "--mesh-every", std::to_string(args.mesh_every)};
        if (frames) {
          child.push_back("--frames");
          child.push_back(std::to_string(*frames));
        }
        const bool resuming = args.resume && fs::is_regular_file(dir + "/" + kCheckpointFile);
        if (resuming) child.push_back("--resume");
        out << "vdcloth bench table1: " << name << ", " << mode << " mode" << (resuming ? ", resumed" : "") << std::endl;
        if (!resuming) fs::remove(dir + "/stats.csv", ec);
        const CpuTicks before = machine_ticks();
        r.status = run_child(child, r.peak_kib, r.cpu_seconds);
        const CpuTicks after = machine_ticks();
        if (after.total > before.total) r.steal = static_cast<double>(after.steal - before.steal) / static_cast<double>(after.total - before.total);
        if (r.status == 0) read_summary_usage(dir, r);  // all of a resumed run's processes, not only the last
        write_run_status(dir, r);
        if (r.status != 0) err << "vdcloth bench table1: " << name << " in " << mode << " mode failed (exit " << r.status << ")" << std::endl;
        // The frame-end check of its meshes, after the run so it never shares the machine with one.
        fs::remove(dir + "/check_status.txt", ec);
        if (r.status == 0 && args.mesh_every > 0) {
          out << "vdcloth bench table1: checking " << name << ", " << mode << " mode" << std::endl;
          try {
            check_run(dir, 1, out);
          } catch (const InputError& e) {
            err << "vdcloth bench table1: " << name << " in " << mode << " mode not checked: " << e.what() << std::endl;
          } catch (const OutputError& e) {
            err << "vdcloth bench table1: " << name << " in " << mode << " mode not checked: " << e.what() << std::endl;
          }
        }
      } else if (kept) {
        // Done, in one process or several (some perhaps outside table1): its summary has it all.
        r.status = 0;
        read_summary_usage(dir, r);
        write_run_status(dir, r);
      } else {
        // status and peak memory, then CPU seconds and steal (absent in older files)
        std::ifstream status(dir + "/run_status.txt");
        if (!(status >> r.status >> r.peak_kib)) continue;  // never run into OUT
        if (!(status >> r.cpu_seconds >> r.steal)) {
          r.cpu_seconds = 0;
          r.steal = -1;
        }
      }
      if (fs::is_regular_file(dir + "/stats.csv")) r.table = read_run_table(dir + "/stats.csv");
      read_check_status(dir, r);
      runs.push_back(std::move(r));
      write_tables(runs, args, threads);  // the table so far, in case the session ends early
    }
  out << "vdcloth bench table1: " << args.out << "/table1.md" << std::endl;
  if (runs.empty()) throw InputError(args.out, "", "no runs to tabulate (--tables-only needs earlier runs in this directory)");
  return std::all_of(runs.begin(), runs.end(), [](const Run& r) { return r.status == 0; }) ? kExitOk : kExitSimulationFailed;
}

}  // namespace vdc
