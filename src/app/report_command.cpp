#include "app/report_command.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>

#include <nlohmann/json.hpp>

#include "app/cli.hpp"
#include "app/report_assets.hpp"
#include "app/report_data.hpp"
#include "app/run_frames.hpp"
#include "core/error.hpp"

namespace vdc {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const char* kReportHelp =
    "usage: vdcloth report RUN_DIR [--compare OTHER_RUN_DIR] [--every N] [--camera NAME] [--out DIR]\n"
    "\n"
    "Writes a folder to open in a browser, from disk, with no server and no network: OUT/index.html\n"
    "shows the run (beside OTHER_RUN_DIR's with --compare):\n"
    "  - its frames in 3D with a timeline to scrub and play, through the shot camera (camera.json,\n"
    "    with its cuts) or an orbit camera, the cloth coloured by garment or by view factor, with\n"
    "    or without its mesh's edges;\n"
    "  - faces and seconds per frame (Koh et al. 2014's Figure 5) and where each frame's time went,\n"
    "    the camera's cuts marked;\n"
    "  - what ran, on what machine, how long, its peak memory, what `vdcloth check` found and the\n"
    "    run's log.\n"
    "It uses three.js and Chart.js from Debian (libjs-three, libjs-chart.js), copied into OUT/lib.\n"
    "\n"
    "options:\n"
    "  --compare DIR   a second run of the same scene (another mode, say): plotted beside it, and\n"
    "                  the frames both have drawn side by side\n"
    "  --every N       every Nth frame that has meshes goes into the viewer (default: all of them,\n"
    "                  or every Nth so that the report stays near 250 MB: a frame takes about a\n"
    "                  third of its OBJ and PLY files' size)\n"
    "  --camera NAME   the camera the 3D view starts with, of a run with several (camera_NAME.json);\n"
    "                  the page switches between them (default: the scene's first)\n"
    "  --out DIR       output directory (default: RUN_DIR/report), replaced if it holds a report\n";

struct ReportArgs {
  std::string run, compare, out, camera;
  int every = 0;  // 0: chosen from the frames' size
};

// The index of the camera named `name` among a run's cameras; UsageError listing them if none is.
int camera_index(const json& cameras, const std::string& name, const std::string& run_dir) {
  std::string names;
  for (std::size_t k = 0; k < cameras.size(); ++k) {
    const std::string own = cameras[k].value("name", std::string());
    if (own == name) return static_cast<int>(k);
    names += (names.empty() ? "" : ", ") + (own.empty() ? std::string("(unnamed)") : own);
  }
  throw UsageError("--camera " + name + ": " + run_dir + " has no camera of that name" + (names.empty() ? " (it has none)" : " (its cameras: " + names + ")"));
}

ReportArgs parse_report_args(const std::vector<std::string>& args) {
  ReportArgs r;
  std::vector<std::string> positional;
  for (ArgumentReader in(args); !in.done();) {
    const std::string& a = in.next();
    if (a == "--compare") r.compare = in.value();
    else if (a == "--every") r.every = parse_positive_int(a, in.value());
    else if (a == "--out") r.out = in.value();
    else if (a == "--camera") r.camera = in.value();
    else if (!a.empty() && a[0] == '-') throw UsageError("unknown option '" + a + "' for report (try vdcloth report --help)");
    else positional.push_back(a);
  }
  if (positional.size() != 1) throw UsageError("report expects one RUN_DIR (try vdcloth report --help)");
  r.run = positional[0];
  if (r.out.empty()) r.out = r.run + "/report";
  return r;
}

// The libraries the page loads, from Debian's packages, and their names in OUT/lib.
struct Library {
  const char* package;
  const char* path;  // under the JavaScript directory
  const char* name;
};
const Library kLibraries[] = {
    {"libjs-three", "three/three.min.js", "three.min.js"},
    {"libjs-three", "three/examples/js/controls/OrbitControls.js", "OrbitControls.js"},
    {"libjs-chart.js", "chart.js/chart.min.js", "chart.min.js"},
};

// The report's frames take about a third of their OBJ and PLY files (binary base64 against
// text at the micrometre); without --every, frames are kept one in N to stay near this.
constexpr double kReportBytesPerFileByte = 1.0 / 3.0;
constexpr double kDefaultReportBytes = 250e6;

// The bytes of a frame's mesh files (OBJ, and the PLY beside a cloth's).
double frame_file_bytes(const FrameFiles& files) {
  double bytes = 0;
  for (const auto& [name, path] : files) {
    std::error_code ec;
    const auto obj = fs::file_size(path, ec);
    bytes += ec ? 0.0 : static_cast<double>(obj);
    const auto ply = fs::file_size(fs::path(path).replace_extension(".ply"), ec);
    bytes += ec ? 0.0 : static_cast<double>(ply);
  }
  return bytes;
}

// A run's frames with meshes, none when it wrote none (--mesh-every 0): the report then has
// plots and tables only.
std::map<int, FrameFiles> frames_of(const std::string& run_dir) {
  std::error_code ec;
  if (!fs::is_directory(fs::path(run_dir) / "frames", ec)) return {};
  try {
    return read_frame_files(run_dir);
  } catch (const InputError&) {  // an empty frames/ directory
    return {};
  }
}

void write_text(const fs::path& path, std::string_view text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out.flush()) throw OutputError(path.string(), "cannot write");
}

// Whether `dir` may be replaced by a report: missing, empty, or a report written before.
bool replaceable(const fs::path& dir) {
  std::error_code ec;
  if (!fs::exists(dir, ec)) return true;
  if (!fs::is_directory(dir, ec)) return false;
  if (fs::is_empty(dir, ec)) return true;
  return fs::is_regular_file(dir / "index.html", ec) && fs::is_regular_file(dir / "report.js", ec) && fs::is_directory(dir / "data", ec);
}

// Writes the report of `runs` (records and frames to show, in order) into `dir`, which exists
// and is empty. Returns the bytes written.
std::uintmax_t write_report(const fs::path& dir, const std::vector<std::string>& run_dirs, std::vector<json>& records,
                            const std::vector<std::map<int, FrameFiles>>& frames, const std::vector<int>& shown,
                            const std::string& javascript_dir, std::ostream& out) {
  std::uintmax_t bytes = 0;
  fs::create_directories(dir / "lib");
  for (const Library& lib : kLibraries) {
    std::error_code ec;
    fs::copy_file(fs::path(javascript_dir) / lib.path, dir / "lib" / lib.name, ec);
    if (ec) throw OutputError((dir / "lib" / lib.name).string(), "cannot copy: " + ec.message());
    bytes += fs::file_size(dir / "lib" / lib.name);
  }
  for (const ReportAsset& asset : report_assets()) {
    write_text(dir / asset.name, asset.text);
    bytes += asset.text.size();
  }
  std::ostringstream runs_script;
  for (std::size_t r = 0; r < records.size(); ++r) {
    const std::string frame_dir = "data/run" + std::to_string(r);
    fs::create_directories(dir / frame_dir);
    json topology = json::object();
    for (std::size_t k = 0; k < shown.size(); ++k) {
      const int frame = shown[k];
      std::ostringstream name;
      name << std::setw(4) << std::setfill('0') << frame << ".js";
      std::ostringstream script;
      write_frame_script(script, static_cast<int>(r), frame, frames[r].at(frame), topology);
      write_text(dir / frame_dir / name.str(), script.str());
      bytes += script.str().size();
      if ((k + 1) % 25 == 0 || k + 1 == shown.size())
        out << "vdcloth report: " << run_dirs[r] << ": " << k + 1 << " of " << shown.size() << " frames\n" << std::flush;
    }
    records[r]["frames"] = shown;
    records[r]["frame_dir"] = frame_dir;
    records[r]["topology"] = topology;
    runs_script << "vdcloth.addRun(" << records[r].dump(-1, ' ', false, json::error_handler_t::replace) << ");\n";
  }
  write_text(dir / "data" / "runs.js", runs_script.str());
  return bytes + runs_script.str().size();
}

}  // namespace

int report_command(const std::vector<std::string>& args, std::ostream& out, const std::string& javascript_dir) {
  for (const std::string& a : args)
    if (a == "--help" || a == "-h") {
      out << kReportHelp;
      return kExitOk;
    }
  const ReportArgs r = parse_report_args(args);
  for (const Library& lib : kLibraries) {
    std::error_code ec;
    if (!fs::is_regular_file(fs::path(javascript_dir) / lib.path, ec))
      throw UsageError(std::string("report needs Debian's ") + lib.package + " (apt install " + lib.package + "): no " +
                       (fs::path(javascript_dir) / lib.path).string());
  }
  std::vector<std::string> run_dirs{r.run};
  if (!r.compare.empty()) run_dirs.push_back(r.compare);
  std::vector<json> records;
  std::vector<std::map<int, FrameFiles>> frames;
  std::vector<const std::map<int, FrameFiles>*> frame_sets;
  for (const std::string& dir : run_dirs) {
    records.push_back(read_run_record(dir));
    frames.push_back(frames_of(dir));
  }
  for (const auto& f : frames) frame_sets.push_back(&f);
  if (!r.camera.empty()) records.front()["initial_camera"] = camera_index(records.front()["cameras"], r.camera, r.run);
  const std::vector<int> common = frames_in_common(frame_sets);
  int every = r.every;
  if (every == 0) {
    double bytes = 0;
    for (const int frame : common)
      for (const auto& f : frames) bytes += kReportBytesPerFileByte * frame_file_bytes(f.at(frame));
    every = std::max(1, static_cast<int>(std::ceil(bytes / kDefaultReportBytes)));
    if (every > 1)
      out << "vdcloth report: one frame in " << every << " (" << std::fixed << std::setprecision(0) << bytes / 1e6
          << " MB for all of them); --every 1 keeps them all\n";
  }
  std::vector<int> shown;
  for (std::size_t k = 0; k < common.size(); k += static_cast<std::size_t>(every)) shown.push_back(common[k]);
  if (!common.empty() && shown.back() != common.back()) shown.push_back(common.back());

  if (shown.empty())
    out << "vdcloth report: "
        << (std::all_of(frames.begin(), frames.end(), [](const auto& f) { return f.empty(); })
                ? "no frame meshes (runs made with --mesh-every 0)"
                : "no frame meshes in common")
        << ": the report has its plots and tables, no 3D view\n";
  else if (records.front()["camera"].is_null())
    out << "vdcloth report: " << r.run << " has no camera.json (its scene has no camera): the 3D view has the orbit camera only\n";

  // Written aside and renamed into place: a report stopped part-way leaves no folder that looks whole.
  const fs::path target = fs::path(r.out).lexically_normal();
  if (!replaceable(target)) throw InputError(r.out, "", "exists and is not a vdcloth report: choose another --out");
  const fs::path partial = fs::path(target.string() + ".partial");
  std::error_code ec;
  fs::remove_all(partial, ec);
  const std::vector<fs::path> made = create_output_directory(partial.string());
  std::uintmax_t bytes = 0;
  try {
    bytes = write_report(partial, run_dirs, records, frames, shown, javascript_dir, out);
    fs::remove_all(target, ec);
    fs::rename(partial, target, ec);
    if (ec) throw OutputError(target.string(), "cannot rename " + partial.string() + " to it: " + ec.message());
  } catch (const std::exception&) {
    fs::remove_all(partial, ec);
    for (const fs::path& dir : made) fs::remove(dir, ec);  // parents made, only if empty
    throw;
  }
  out << "vdcloth report: " << shown.size() << " frame(s) of " << r.run;
  if (!r.compare.empty()) out << " beside " << r.compare;
  out << " (" << std::fixed << std::setprecision(1) << static_cast<double>(bytes) / 1e6 << " MB); open " << (target / "index.html").string()
      << " in a browser\n";
  return kExitOk;
}

}  // namespace vdc
