#include "app/render_command.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <map>
#include <optional>
#include <sstream>

#include "app/cli.hpp"
#include "core/error.hpp"
#include "io/obj.hpp"
#include "io/png.hpp"
#include "io/run_output.hpp"
#include "render/compare.hpp"
#include "render/rasterizer.hpp"
#include "scene/scene.hpp"

namespace vdc {

namespace fs = std::filesystem;

namespace {

const char* kRenderHelp =
    "usage: vdcloth render SCENE.json RUN_DIR [--compare OTHER_RUN_DIR] [--every N] [--scale S] [--out DIR]\n"
    "\n"
    "Draws the meshes of RUN_DIR/frames/ (written by `vdcloth run`) through the scene's camera at\n"
    "each frame's time: OUT/frame_NNNN.png. With --compare, the frames both runs have are drawn\n"
    "side by side with their difference (OUT/compare_NNNN.png: RUN_DIR, OTHER_RUN_DIR, difference\n"
    "amplified four times, white where equal), and OUT/compare.csv lists per frame the cloth\n"
    "pixels of each, the overlap of the two cloth silhouettes (intersection over union) and the\n"
    "mean pixel difference where either shows cloth.\n"
    "\n"
    "options:\n"
    "  --compare DIR   a second run of the same scene (another mode, say)\n"
    "  --every N       every Nth frame that has meshes (default: 1, all)\n"
    "  --scale S       image size relative to the camera's, 0.05 to 4 (default: 0.5)\n"
    "  --out DIR       output directory (default: RUN_DIR/render, or RUN_DIR/compare with --compare)\n";

struct RenderArgs {
  std::string scene, run, compare, out;
  int every = 1;
  double scale = 0.5;
};

RenderArgs parse_render_args(const std::vector<std::string>& args) {
  RenderArgs r;
  std::vector<std::string> positional;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw UsageError(a + " needs a value");
      return args[++i];
    };
    if (a == "--compare") r.compare = value();
    else if (a == "--every") r.every = parse_positive_int(a, value());
    else if (a == "--out") r.out = value();
    else if (a == "--scale") {
      const std::string& v = value();
      std::size_t used = 0;
      double s = 0;
      try {
        s = std::stod(v, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != v.size() || !(s >= 0.05 && s <= 4)) throw UsageError("--scale expects a number from 0.05 to 4, got '" + v + "'");
      r.scale = s;
    } else if (!a.empty() && a[0] == '-') throw UsageError("unknown option '" + a + "' for render (try vdcloth render --help)");
    else positional.push_back(a);
  }
  if (positional.size() != 2) throw UsageError("render expects SCENE.json and RUN_DIR (try vdcloth render --help)");
  r.scene = positional[0];
  r.run = positional[1];
  if (r.out.empty()) r.out = r.run + (r.compare.empty() ? "/render" : "/compare");
  return r;
}

// Garment colours, given in name order, so that the same garment has the same colour in every
// run of a scene.
const Vec3 kClothPalette[] = {{0.80, 0.25, 0.22}, {0.93, 0.72, 0.20}, {0.22, 0.42, 0.78}, {0.30, 0.65, 0.38},
                              {0.60, 0.35, 0.70}, {0.90, 0.50, 0.25}, {0.25, 0.70, 0.75}, {0.85, 0.40, 0.60}};

struct LoadedFrame {
  std::vector<RenderMesh> meshes;
  std::vector<char> cloth;
};

LoadedFrame load_frame(const FrameFiles& files) {
  LoadedFrame f;
  std::size_t garments = 0;
  for (const auto& [key, path] : files) {
    const bool cloth = key.rfind("cloth_", 0) == 0;
    const MeshSource source = read_obj_source(path, false);
    RenderMesh mesh;
    mesh.positions = source.positions;
    mesh.faces = position_triangles(source);
    mesh.colour = cloth ? kClothPalette[garments++ % std::size(kClothPalette)] : Vec3(0.78, 0.74, 0.70);
    f.meshes.push_back(std::move(mesh));
    f.cloth.push_back(cloth);
  }
  return f;
}

std::string numbered(const std::string& dir, const std::string& stem, int frame, const std::string& ext) {
  std::ostringstream s;
  s << dir << "/" << stem << "_" << std::setw(4) << std::setfill('0') << frame << ext;
  return s.str();
}

}  // namespace

int render_command(const std::vector<std::string>& args, std::ostream& out) {
  for (const std::string& a : args)
    if (a == "--help" || a == "-h") {
      out << kRenderHelp;
      return kExitOk;
    }
  const RenderArgs r = parse_render_args(args);
  const Scene scene = load_scene(r.scene);
  if (!scene.camera) throw InputError(r.scene, "camera", "the scene has no camera to render through");
  std::map<int, FrameFiles> frames = read_frame_files(r.run);
  std::map<int, FrameFiles> other;
  if (!r.compare.empty()) {
    other = read_frame_files(r.compare);
    for (auto it = frames.begin(); it != frames.end();) it = other.count(it->first) ? std::next(it) : frames.erase(it);
    if (frames.empty()) throw InputError(r.compare, "", "no frame in common with " + r.run);
  }
  std::error_code ec;
  fs::create_directories(r.out, ec);
  if (ec) throw InputError(r.out, "", "cannot create output directory: " + ec.message());

  std::ofstream csv;
  if (!r.compare.empty()) {
    // Written under another name until the last frame is in, so a stopped render leaves no
    // table that looks complete.
    fs::remove(r.out + "/compare.csv", ec);
    csv.open(r.out + "/compare.csv.partial");
    if (!csv) throw InputError(r.out + "/compare.csv.partial", "", "cannot write");
    csv << "frame,time,cloth_pixels_a,cloth_pixels_b,cloth_iou,mean_abs_diff\n";
  }
  int drawn = 0, index = 0;
  double iou_sum = 0, iou_min = 1, diff_sum = 0;
  for (const auto& [frame, files] : frames) {
    if (index++ % r.every != 0) continue;
    const double time = frame * scene.frame_time;
    const Camera camera = scene.camera->at(time);
    const LoadedFrame a = load_frame(files);
    const RenderedFrame image_a = render(camera, a.meshes, r.scale);
    std::string written;
    if (r.compare.empty()) {
      written = numbered(r.out, "frame", frame, ".png");
      if (!write_png(image_a.image, written)) throw InputError(written, "", "cannot write");
    } else {
      const LoadedFrame b = load_frame(other.at(frame));
      const RenderedFrame image_b = render(camera, b.meshes, r.scale);
      const RenderComparison c = compare_renders(image_a, a.cloth, image_b, b.cloth);
      csv << frame << "," << time << "," << c.cloth_pixels_a << "," << c.cloth_pixels_b << "," << std::setprecision(4) << c.cloth_iou << ","
          << c.mean_abs_diff << "\n";
      iou_sum += c.cloth_iou;
      iou_min = std::min(iou_min, c.cloth_iou);
      diff_sum += c.mean_abs_diff;
      written = numbered(r.out, "compare", frame, ".png");
      if (!write_png(side_by_side(image_a.image, image_b.image), written)) throw InputError(written, "", "cannot write");
    }
    ++drawn;
    out << "vdcloth render: frame " << frame << " -> " << written << "\n" << std::flush;
  }
  out << "vdcloth render: " << drawn << " frame(s) in " << r.out;
  if (!r.compare.empty())
    out << "; cloth silhouette overlap mean " << std::fixed << std::setprecision(3) << iou_sum / drawn << ", min " << iou_min
        << "; mean pixel difference on cloth " << std::setprecision(1) << diff_sum / drawn << " of 255";
  out << "\n";
  if (csv.is_open()) {
    csv.close();
    fs::rename(r.out + "/compare.csv.partial", r.out + "/compare.csv", ec);
    if (ec) throw InputError(r.out + "/compare.csv", "", "cannot write: " + ec.message());
  }
  return kExitOk;
}

}  // namespace vdc
