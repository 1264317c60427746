#include "app/check_command.hpp"

#include "app/run_frames.hpp"

#include <filesystem>
#include <fstream>
#include <map>

#include "app/cli.hpp"
#include "app/run_frames.hpp"
#include "collision/intersection.hpp"
#include "core/error.hpp"
#include "io/obj.hpp"
#include "output/run_output.hpp"

namespace vdc {

namespace fs = std::filesystem;

namespace {

const char* kCheckHelp =
    "usage: vdcloth check RUN_DIR [--every N]\n"
    "\n"
    "Checks the meshes of RUN_DIR/frames/ (written by `vdcloth run`): at every frame, each garment\n"
    "against itself, every other garment and every obstacle, by the exact triangle-triangle test.\n"
    "Lists each crossing mesh pair with its count of crossing face pairs and writes RUN_DIR/check.csv\n"
    "(frame, mesh, other mesh, face pairs; one row per crossing pair of meshes) and\n"
    "RUN_DIR/check_status.txt (frames checked, frames with crossings, N), which `bench table1` shows.\n"
    "Exit status: 0 no crossing, 3 crossings found, 2 bad usage or input.\n"
    "\n"
    "options:\n"
    "  --every N   every Nth frame that has meshes (default: 1, all)\n";

struct TriangleSoup {
  std::vector<std::array<int32_t, 3>> faces;
  std::vector<Vec3> positions;
};

TriangleSoup read_soup(const std::string& path) {
  const MeshSource source = read_obj_source(path, false);
  return {position_triangles(source), source.positions};
}

}  // namespace

int check_command(const std::vector<std::string>& args, std::ostream& out) {
  std::string run;
  int every = 1;
  for (ArgumentReader in(args); !in.done();) {
    const std::string& a = in.next();
    if (a == "--help" || a == "-h") {
      out << kCheckHelp;
      return kExitOk;
    }
    if (a == "--every") {
      every = parse_positive_int(a, in.value());
    } else if (!a.empty() && a[0] == '-') {
      throw UsageError("unknown option '" + a + "' for check (try vdcloth check --help)");
    } else if (run.empty()) {
      run = a;
    } else {
      throw UsageError("check expects one RUN_DIR (try vdcloth check --help)");
    }
  }
  if (run.empty()) throw UsageError("check expects RUN_DIR (try vdcloth check --help)");
  const CheckSummary summary = check_run(run, every, out);
  return summary.frames_with_crossings == 0 ? kExitOk : kExitSimulationFailed;
}

CheckSummary check_run(const std::string& run, int every, std::ostream& out) {
  const std::map<int, FrameFiles> frames = read_frame_files(run);
  const std::string csv_path = run + "/check.csv", status_path = run + "/check_status.txt";
  std::error_code ec;
  fs::remove(status_path, ec);
  PartialTable table(csv_path);
  std::ofstream& csv = table.stream();
  csv << "frame,mesh,other,face_pairs\n";
  CheckSummary summary;
  try {
    int index = 0;
    for (const auto& [frame, files] : frames) {
      if (index++ % every != 0) continue;
      std::map<std::string, TriangleSoup> meshes;
      for (const auto& [key, path] : files) meshes.emplace(key, read_soup(path));
      bool bad = false;
      auto report = [&, frame = frame](const std::string& a, const std::string& b, int pairs) {
        if (pairs == 0) return;
        bad = true;
        csv << frame << "," << a << "," << b << "," << pairs << "\n";
        out << "vdcloth check: frame " << frame << ": " << a << (a == b ? " crosses itself" : " crosses " + b) << " (" << pairs
            << " face pairs)\n";
      };
      for (auto a = meshes.begin(); a != meshes.end(); ++a) {
        if (a->first.rfind("cloth_", 0) != 0) continue;
        report(a->first, a->first, count_self_intersections(a->second.faces, a->second.positions));
        for (auto b = meshes.begin(); b != meshes.end(); ++b) {
          // Each garment pair once (from its first garment); every obstacle from each garment.
          const bool cloth_b = b->first.rfind("cloth_", 0) == 0;
          if (b == a || (cloth_b && b->first < a->first)) continue;
          report(a->first, b->first, count_intersections_between(a->second.faces, a->second.positions, b->second.faces, b->second.positions));
        }
      }
      ++summary.frames_checked;
      summary.frames_with_crossings += bad;
    }
  } catch (const std::exception&) {  // a mesh that cannot be read: no table left behind
    table.discard();
    throw;
  }
  table.finish();
  std::ofstream status(status_path);
  status << summary.frames_checked << " " << summary.frames_with_crossings << " " << every << "\n";
  if (!status) throw OutputError(status_path, "cannot write");
  out << "vdcloth check: " << summary.frames_checked << " frame(s) of " << run << ", " << summary.frames_with_crossings
      << " with crossings; " << csv_path << "\n";
  return summary;
}

}  // namespace vdc
