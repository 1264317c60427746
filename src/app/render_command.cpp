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

#include "app/camera_choice.hpp"
#include "app/cli.hpp"
#include "app/run_frames.hpp"
#include "app/video_writer.hpp"
#include "core/error.hpp"
#include "io/png.hpp"
#include "output/run_output.hpp"
#include "render/compare.hpp"
#include "scene/scene.hpp"

namespace vdc {

namespace fs = std::filesystem;

namespace {

const char* kRenderHelp =
    "usage: vdcloth render SCENE.json RUN_DIR [--compare OTHER_RUN_DIR] [--colour garment|view] [--wireframe]\n"
    "                      [--video] [--every N] [--scale S] [--camera NAME] [--out DIR]\n"
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
    "  --colour C      garment: each garment in its own colour (default); view: each cloth face\n"
    "                  by its view factor, red at 1 (full resolution), green at 0.1, blue at 0.01\n"
    "                  (from the frames' PLY files; a run without them, fixed or adaptive, is red)\n"
    "  --wireframe     the cloth's mesh edges drawn over it (the remeshing made visible)\n"
    "  --video         also OUT/render.mp4 (OUT/compare.mp4 with --compare): the pictures as an\n"
    "                  H.264 video at the shot's speed, made by ffmpeg (Debian package ffmpeg)\n"
    "  --every N       every Nth frame that has meshes (default: 1, all)\n"
    "  --scale S       image size relative to the camera's, 0.05 to 4 (default: 0.5)\n"
    "  --camera NAME   the scene's camera to look through (a scene with a \"cameras\" list, or a\n"
    "                  stereo camera's eyes: NAME_left, NAME_right); default: its first\n"
    "  --out DIR       output directory (default: RUN_DIR/render, or RUN_DIR/compare with --compare;\n"
    "                  with --camera, RUN_DIR/render_NAME or RUN_DIR/compare_NAME)\n";

struct RenderArgs {
  std::string scene, run, compare, out, camera;
  int every = 1;
  double scale = 0.5;
  DrawStyle style;
  bool video = false;
};

RenderArgs parse_render_args(const std::vector<std::string>& args) {
  RenderArgs r;
  std::vector<std::string> positional;
  for (ArgumentReader in(args); !in.done();) {
    const std::string& a = in.next();
    if (a == "--compare") r.compare = in.value();
    else if (a == "--every") r.every = parse_positive_int(a, in.value());
    else if (a == "--out") r.out = in.value();
    else if (a == "--camera") r.camera = in.value();
    else if (a == "--scale") r.scale = parse_number(a, in.value(), 0.05, 4);
    else if (a == "--wireframe") r.style.wireframe = true;
    else if (a == "--video") r.video = true;
    else if (a == "--colour" || a == "--color") {
      const std::string& c = in.value();
      if (c != "garment" && c != "view") throw UsageError(a + " expects garment or view, got '" + c + "'");
      r.style.view_colours = c == "view";
    }
    else if (!a.empty() && a[0] == '-') throw UsageError("unknown option '" + a + "' for render (try vdcloth render --help)");
    else positional.push_back(a);
  }
  if (positional.size() != 2) throw UsageError("render expects SCENE.json and RUN_DIR (try vdcloth render --help)");
  r.scene = positional[0];
  r.run = positional[1];
  if (r.out.empty()) r.out = r.run + (r.compare.empty() ? "/render" : "/compare") + (r.camera.empty() ? "" : "_" + r.camera);
  return r;
}

std::string numbered(const std::string& dir, const std::string& stem, int frame, const std::string& ext) {
  std::ostringstream s;
  s << dir << "/" << stem << "_" << std::setw(4) << std::setfill('0') << frame << ext;
  return s.str();
}

// Adds a picture to the video, started at the first one (its size is the pictures').
void add_to_video(std::optional<VideoWriter>& video, const std::string& path, const RgbImage& picture, double fps) {
  if (!video) video.emplace(path, picture.width, picture.height, fps);
  video->add(picture);
}

// Draws the frames `to_draw` of the run (beside those of the compared run) into r.out, listing
// each picture in `pictures` as it is written, and the comparison's table in `csv`.
void draw_frames(const RenderArgs& r, const Scene& scene, const std::map<int, FrameFiles>& frames, const std::map<int, FrameFiles>& other,
                 const std::vector<int>& to_draw, std::optional<PartialTable>& csv, std::vector<std::string>& pictures, std::ostream& out) {
  if (!r.compare.empty()) {
    csv.emplace(r.out + "/compare.csv");
    csv->stream() << "frame,time,cloth_pixels_a,cloth_pixels_b,cloth_iou,mean_abs_diff\n";
  }
  std::vector<int> chosen;
  for (std::size_t i = 0; i < to_draw.size(); i += static_cast<std::size_t>(r.every)) chosen.push_back(to_draw[i]);
  // The video plays the shot at its speed: the drawn frames' mean spacing, in frame times.
  const double spacing = chosen.size() > 1 ? double(chosen.back() - chosen.front()) / double(chosen.size() - 1) : 1.0;
  const double fps = 1.0 / (scene.frame_time * spacing);
  std::optional<VideoWriter> video;
  const std::string video_path = r.out + (r.compare.empty() ? "/render.mp4" : "/compare.mp4");
  int drawn = 0;
  double iou_sum = 0, iou_min = 1, diff_sum = 0;
  for (const int frame : chosen) {
    const double time = frame * scene.frame_time;
    const Camera camera = scene.cameras.front().path.at(time);
    const DrawnFrame a = draw_frame(camera, frames.at(frame), r.scale, r.style);
    std::string written;
    if (r.compare.empty()) {
      written = numbered(r.out, "frame", frame, ".png");
      pictures.push_back(written);
      if (!write_png(a.pixels.image, written)) throw OutputError(written, "cannot write");
      if (r.video) add_to_video(video, video_path, a.pixels.image, fps);
    } else {
      const DrawnFrame b = draw_frame(camera, other.at(frame), r.scale, r.style);
      const RenderComparison c = compare_renders(a.pixels, a.cloth, b.pixels, b.cloth);
      csv->stream() << frame << "," << time << "," << c.cloth_pixels_a << "," << c.cloth_pixels_b << "," << std::setprecision(4) << c.cloth_iou
                    << "," << c.mean_abs_diff << "\n";
      iou_sum += c.cloth_iou;
      iou_min = std::min(iou_min, c.cloth_iou);
      diff_sum += c.mean_abs_diff;
      written = numbered(r.out, "compare", frame, ".png");
      pictures.push_back(written);
      const RgbImage both = side_by_side(a.pixels.image, b.pixels.image);
      if (!write_png(both, written)) throw OutputError(written, "cannot write");
      if (r.video) add_to_video(video, video_path, both, fps);
    }
    ++drawn;
    out << "vdcloth render: frame " << frame << " -> " << written << "\n" << std::flush;
  }
  if (video) {
    video->finish();
    out << "vdcloth render: " << video_path << "\n";
  }
  out << "vdcloth render: " << drawn << " frame(s) in " << r.out;
  if (!r.compare.empty())
    out << "; cloth silhouette overlap mean " << std::fixed << std::setprecision(3) << iou_sum / drawn << ", min " << iou_min
        << "; mean pixel difference on cloth " << std::setprecision(1) << diff_sum / drawn << " of 255";
  out << "\n";
  if (csv) csv->finish();
}

}  // namespace

int render_command(const std::vector<std::string>& args, std::ostream& out) {
  for (const std::string& a : args)
    if (a == "--help" || a == "-h") {
      out << kRenderHelp;
      return kExitOk;
    }
  const RenderArgs r = parse_render_args(args);
  if (r.video && !ffmpeg_available()) throw UsageError("--video needs ffmpeg (Debian package ffmpeg), which cannot be started");
  Scene scene = load_scene(r.scene);
  choose_camera(scene, r.camera, "to render through");
  const std::map<int, FrameFiles> frames = read_frame_files(r.run);
  std::map<int, FrameFiles> other;
  std::vector<int> to_draw;
  for (const auto& [frame, files] : frames) to_draw.push_back(frame);
  if (!r.compare.empty()) {
    other = read_frame_files(r.compare);
    to_draw = frames_in_common({&frames, &other});
    if (to_draw.empty()) throw InputError(r.compare, "", "no frame in common with " + r.run);
  }
  // A frame that cannot be read stops the command with what it drew taken back: nothing written.
  const std::vector<fs::path> made = create_output_directory(r.out);
  std::vector<std::string> pictures;
  std::optional<PartialTable> csv;
  try {
    draw_frames(r, scene, frames, other, to_draw, csv, pictures, out);
  } catch (const std::exception&) {
    if (csv) csv->discard();
    std::error_code ec;
    for (const std::string& p : pictures) fs::remove(p, ec);
    for (const fs::path& dir : made) fs::remove(dir, ec);  // only if empty
    throw;
  }
  return kExitOk;
}

}  // namespace vdc
