// `vdcloth fidelity`: parsing, checking the input before anything is written, drawing each
// measured frame (and the frame before it, for popping) of every run, the tables and verdicts.
#include "app/fidelity_command.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "app/camera_choice.hpp"
#include "app/cli.hpp"
#include "app/run_frames.hpp"
#include "core/error.hpp"
#include "output/run_output.hpp"
#include "render/compare.hpp"
#include "render/fidelity.hpp"
#include "scene/scene.hpp"

namespace vdc {

namespace fs = std::filesystem;

namespace {

const char* kFidelityHelp =
    "usage: vdcloth fidelity SCENE.json RUN_DIR REFERENCE_DIR [--floor PERTURBED_REFERENCE_DIR ...]\n"
    "                        [--sample PERTURBED_RUN_DIR ...] [--every N] [--scale S] [--camera NAME] [--out DIR]\n"
    "                        [--overlap-margin X] [--min-margin X] [--detail X] [--popping X]\n"
    "\n"
    "Measures how like REFERENCE_DIR (an adaptive run, say) RUN_DIR (a view run of the same scene)\n"
    "looks through the scene's camera, at the frames all the runs given have meshes for: the overlap\n"
    "of the cloth silhouettes (intersection over union, bodies hiding cloth), the wrinkle detail on\n"
    "screen of each run (the mean angle in degrees between neighbouring cloth pixels' shading\n"
    "normals) and the popping of each (the mean pixel change on cloth from the frame before, 0 to\n"
    "255). With --floor, a run of the reference perturbed below any meaning is measured against the\n"
    "reference the same way: the floor, what a tiny perturbation already changes (`vdcloth run\n"
    "--perturb 1e-6`: gravity one part in a million stronger). `vdcloth run --perturb-resolution E`\n"
    "perturbs the discretisation instead (every edge may be 1 + E times as long): as a floor it\n"
    "says how far a change of the adaptive run's own resolution moves the shot (more, the larger\n"
    "E), to set a view run's departure beside. One perturbed run is one sample of what chaos does\n"
    "(karate's gravity twins at 1e-6, -1e-6 and 2e-6 give overlap means of 0.965 to 0.976); with\n"
    "--floor given several times the floor is the mean of the floor runs' means and the mean of\n"
    "their minima, what one perturbed run is expected to give. RUN_DIR is one sample too: with\n"
    "--sample (RUN_DIR made again with --perturb, as many times as given) the judged figures are\n"
    "the mean of the runs' overlap means, of their minima, and their mean detail and popping.\n"
    "\n"
    "Writes OUT/fidelity.csv (one row a frame), OUT/fidelity_garments.csv (one row a garment a\n"
    "frame: the overlap of that garment's own pixels, to tell which one departs) and\n"
    "OUT/fidelity_shots.csv (one row a shot between the camera's cuts, and a last row `all`),\n"
    "prints the garments with the lowest overlap over the run (with --floor also those that lose\n"
    "the most pixels beyond the floor's rate: a shot's departure, where a small far garment's low\n"
    "overlap counts for few pixels) and a verdict for each shot and for the whole run: pass when\n"
    "  overlap mean  >= floor overlap mean - X   (--overlap-margin, default 0.02)\n"
    "  overlap min   >= floor overlap min - X    (--min-margin, default 0.05)\n"
    "  detail ratio  >= X                        (--detail, default 0.9: run's mean over reference's)\n"
    "  popping ratio <= X                        (--popping, default 1.2: run's mean over reference's)\n"
    "The overlap is judged only with --floor; with it the verdicts also give the floor run's own\n"
    "detail and popping ratios (what a tiny perturbation already does to them), not judged.\n"
    "--camera NAME looks through that camera of the scene (a scene with a \"cameras\" list, or a\n"
    "stereo camera's eyes: NAME_left, NAME_right; default: its first), into RUN_DIR/fidelity_NAME.\n"
    "Exit status: 0 every verdict passes, 3 one fails,\n"
    "2 bad usage or input (nothing written).\n"
    "\n"
    "options:\n"
    "  --floor DIR           the reference run made again with `vdcloth run --perturb 1e-6` or\n"
    "                        `--perturb-resolution 0.01`; again for each further floor run\n"
    "  --sample DIR          RUN_DIR's method made again with `vdcloth run --perturb 1e-6` (another\n"
    "                        value each time); again for each further sample\n"
    "  --every N             every Nth frame the runs have in common (default: 1, all)\n"
    "  --scale S             image size relative to the camera's, 0.05 to 4 (default: 0.5)\n"
    "  --out DIR             output directory (default: RUN_DIR/fidelity)\n"
    "  --overlap-margin X    0 to 1 (default: 0.02)\n"
    "  --min-margin X        0 to 1 (default: 0.05)\n"
    "  --detail X            0 to 10 (default: 0.9)\n"
    "  --popping X           0 to 100 (default: 1.2)\n";

struct FidelityArgs {
  std::string scene, run, reference, out, camera;
  std::vector<std::string> floors, samples;
  int every = 1;
  double scale = 0.5;
  FidelityTargets targets;
};

FidelityArgs parse_fidelity_args(const std::vector<std::string>& args) {
  FidelityArgs f;
  std::vector<std::string> positional;
  for (ArgumentReader in(args); !in.done();) {
    const std::string& a = in.next();
    if (a == "--floor" || a == "--sample" || a == "--out") {
      const std::string& dir = in.value();
      if (dir.empty()) throw UsageError(a + " needs a directory");
      if (a == "--floor") f.floors.push_back(dir);
      else if (a == "--sample") f.samples.push_back(dir);
      else f.out = dir;
    } else if (a == "--camera") {
      f.camera = in.value();
    } else if (a == "--every") {
      f.every = parse_positive_int(a, in.value());
    } else if (a == "--scale") {
      f.scale = parse_number(a, in.value(), 0.05, 4);
    } else if (a == "--overlap-margin") {
      f.targets.overlap_margin = parse_number(a, in.value(), 0, 1);
    } else if (a == "--min-margin") {
      f.targets.min_margin = parse_number(a, in.value(), 0, 1);
    } else if (a == "--detail") {
      f.targets.detail = parse_number(a, in.value(), 0, 10);
    } else if (a == "--popping") {
      f.targets.popping = parse_number(a, in.value(), 0, 100);
    } else if (!a.empty() && a[0] == '-') {
      throw UsageError("unknown option '" + a + "' for fidelity (try vdcloth fidelity --help)");
    } else {
      positional.push_back(a);
    }
  }
  if (positional.size() != 3) throw UsageError("fidelity expects SCENE.json, RUN_DIR and REFERENCE_DIR (try vdcloth fidelity --help)");
  f.scene = positional[0];
  f.run = positional[1];
  f.reference = positional[2];
  if (f.out.empty()) f.out = f.run + "/fidelity" + (f.camera.empty() ? "" : "_" + f.camera);
  return f;
}

// The runs at one frame, drawn in the order run, reference, floor runs, samples (when given).
using DrawnRuns = std::vector<DrawnFrame>;

DrawnRuns draw_runs(const Scene& scene, const std::vector<std::map<int, FrameFiles>>& runs, int frame, double scale) {
  const Camera camera = scene.cameras.front().path.at(frame * scene.frame_time);
  DrawnRuns drawn;
  for (const auto& run : runs) drawn.push_back(draw_frame(camera, run.at(frame), scale));
  return drawn;
}

// The shot of a frame: the number of cuts at times up to the frame's.
int shot_of(const Scene& scene, int frame) {
  return static_cast<int>(scene.cameras.front().path.cuts_in(-std::numeric_limits<double>::infinity(), frame * scene.frame_time).size());
}

// Drawn run k's overlap with the reference (drawn run 1), its wrinkle detail, and its popping
// from the frame before: compare_renders' cloth silhouette IoU and mean pixel change on cloth.
double overlap_of(const DrawnRuns& now, std::size_t k) {
  return compare_renders(now[k].pixels, now[k].cloth, now[1].pixels, now[1].cloth).cloth_iou;
}
double detail_of(const DrawnRuns& now, std::size_t k, double pixels_per_metre_at_unit_depth) {
  return wrinkle_detail(now[k].pixels, now[k].cloth, pixels_per_metre_at_unit_depth);
}
double popping_of(const DrawnRuns& before, const DrawnRuns& now, std::size_t k) {
  return compare_renders(before[k].pixels, before[k].cloth, now[k].pixels, now[k].cloth).mean_abs_diff;
}

// `run` with drawn run k in the run's place (0: the run itself, beyond the floors: a sample):
// its overlap, cloth pixels (and the reference's), detail and popping; the rest as in `run`.
FrameFidelity with_run_measured(const FrameFidelity& run, const DrawnRuns& now, const DrawnRuns* before, std::size_t k,
                                double pixels_per_metre_at_unit_depth) {
  FrameFidelity m = run;
  const RenderComparison c = compare_renders(now[k].pixels, now[k].cloth, now[1].pixels, now[1].cloth);
  m.cloth_pixels_run = c.cloth_pixels_a;
  m.cloth_pixels_reference = c.cloth_pixels_b;
  m.overlap = c.cloth_iou;
  m.detail_run = detail_of(now, k, pixels_per_metre_at_unit_depth);
  if (before) m.popping_run = popping_of(*before, now, k);
  return m;
}

// The measures of one frame, the floor runs drawn at 2 to 2 + floors - 1. `before`: the runs
// drawn at the frame before, null when that frame is in another shot or not written by every run.
FrameFidelity measure(const DrawnRuns& now, const DrawnRuns* before, std::size_t floors, double pixels_per_metre_at_unit_depth) {
  FrameFidelity m = with_run_measured(FrameFidelity{}, now, before, 0, pixels_per_metre_at_unit_depth);
  m.detail_reference = detail_of(now, 1, pixels_per_metre_at_unit_depth);
  if (before) m.popping_reference = popping_of(*before, now, 1);
  // The floor runs: each one's overlap, their means of overlap, detail and popping.
  if (floors == 0) return m;
  double overlap = 0, detail_sum = 0, popping_sum = 0;
  for (std::size_t k = 2; k < 2 + floors; ++k) {
    m.floor_overlaps.push_back(overlap_of(now, k));
    overlap += m.floor_overlaps.back();
    detail_sum += detail_of(now, k, pixels_per_metre_at_unit_depth);
    if (before) popping_sum += popping_of(*before, now, k);
  }
  const auto n = static_cast<double>(floors);  // x / 1 is x: one floor run's values as they are
  m.floor_overlap = overlap / n;
  m.detail_floor = detail_sum / n;
  if (before) m.popping_floor = popping_sum / n;
  return m;
}

// The index of the mesh drawn from frame file `name`, -1 when the frame has none.
int32_t mesh_named(const DrawnFrame& frame, const std::string& name) {
  const auto at = std::find(frame.names.begin(), frame.names.end(), name);
  return at == frame.names.end() ? -1 : static_cast<int32_t>(at - frame.names.begin());
}

// Each garment of the run or the reference on its own (compare_mesh): which one departs; the
// floor runs drawn at 2 to 2 + floors - 1.
std::vector<GarmentFrame> measure_garments(const DrawnRuns& now, std::size_t floors) {
  std::set<std::string> names;  // in name order
  for (std::size_t k = 0; k < 2; ++k)
    for (std::size_t m = 0; m < now[k].names.size(); ++m)
      if (now[k].cloth[m]) names.insert(now[k].names[m]);
  std::vector<GarmentFrame> out;
  for (const std::string& name : names) {
    const int32_t reference = mesh_named(now[1], name);
    const MeshOverlap c = compare_mesh(now[0].pixels, mesh_named(now[0], name), now[1].pixels, reference);
    GarmentFrame g;
    g.garment = name.substr(std::string("cloth_").size());
    g.pixels_run = c.pixels_a;
    g.pixels_reference = c.pixels_b;
    g.pixels_either = c.either;
    g.overlap = c.iou;
    if (floors > 0) {  // pooled over the floor runs as compare_mesh pools pixels: both over either (1 for none)
      int both = 0;
      for (std::size_t k = 2; k < 2 + floors; ++k) {
        const MeshOverlap floor = compare_mesh(now[k].pixels, mesh_named(now[k], name), now[1].pixels, reference);
        g.floor_pixels_either += floor.either;
        both += floor.both;
      }
      g.floor_overlap = g.floor_pixels_either > 0 ? static_cast<double>(both) / g.floor_pixels_either : 1.0;
    }
    out.push_back(g);
  }
  return out;
}

// A table's cell: empty when not measured.
std::string cell(double x) {
  if (std::isnan(x)) return "";
  std::ostringstream s;
  s << std::setprecision(6) << x;
  return s.str();
}

std::string joined(const std::vector<std::string>& parts, const std::string& between) {
  std::string s;
  for (const std::string& p : parts) s += (s.empty() ? "" : between) + p;
  return s;
}

// One cell holding a value for each floor run, ';' between them.
std::string cells(const std::vector<double>& xs) {
  std::vector<std::string> parts;
  for (double x : xs) parts.push_back(cell(x));
  return joined(parts, ";");
}

const char* kFramesHeader =
    "frame,time,shot,cloth_pixels_run,cloth_pixels_reference,overlap,floor_overlap,detail_run,detail_reference,detail_floor,"
    "popping_run,popping_reference,popping_floor,floor_overlaps,sample_overlaps\n";

// `samples`: the frame measured with each sample in the run's place.
void write_frame_row(std::ostream& csv, const FrameFidelity& m, const std::vector<FrameFidelity>& samples) {
  std::vector<double> sample_overlaps;
  for (const FrameFidelity& s : samples) sample_overlaps.push_back(s.overlap);
  csv << m.frame << "," << cell(m.time) << "," << m.shot << "," << m.cloth_pixels_run << "," << m.cloth_pixels_reference << ","
      << cell(m.overlap) << "," << cell(m.floor_overlap) << "," << cell(m.detail_run) << "," << cell(m.detail_reference) << ","
      << cell(m.detail_floor) << "," << cell(m.popping_run) << "," << cell(m.popping_reference) << "," << cell(m.popping_floor) << ","
      << cells(m.floor_overlaps) << "," << cells(sample_overlaps) << "\n";
}

const char* kGarmentsHeader = "frame,shot,garment,pixels_run,pixels_reference,overlap,floor_overlap\n";

void write_garment_row(std::ostream& csv, const GarmentFrame& g) {
  csv << g.frame << "," << g.shot << "," << g.garment << "," << g.pixels_run << "," << g.pixels_reference << "," << cell(g.overlap) << ","
      << cell(g.floor_overlap) << "\n";
}

// "TITLE: a, b, c, d, e (N more)": the first five of `count` items, each written by `item`.
std::string first_five(const char* title, std::size_t count, const std::function<void(std::ostream&, std::size_t)>& item) {
  const std::size_t shown = std::min<std::size_t>(count, 5);
  std::ostringstream o;
  o << std::fixed << title << ":";
  for (std::size_t k = 0; k < shown; ++k) {
    o << (k == 0 ? " " : ", ");
    item(o, k);
  }
  if (shown < count) o << " (" << count - shown << " more)";
  return o.str();
}

// e.g. "garments by overlap over the run, lowest first: dress04 0.908 (floor 0.983), ..."; the
// lowest five of a crowd.
std::string garments_line(const std::vector<GarmentFidelity>& garments) {
  return first_five("garments by overlap over the run, lowest first", garments.size(), [&](std::ostream& o, std::size_t k) {
    const GarmentFidelity& g = garments[k];
    o << std::setprecision(3) << g.garment << " " << g.overlap;
    if (!std::isnan(g.floor_overlap)) o << " (floor " << g.floor_overlap << ")";
  });
}

// e.g. "garments by their part of the pixels lost beyond the floor, largest first: dress03 19%,
// ..."; the largest five; empty when no garment loses more than the floor does.
std::string departure_line(const std::vector<GarmentFidelity>& garments) {
  std::vector<const GarmentFidelity*> losing;
  double total = 0;
  for (const GarmentFidelity& g : garments)
    if (g.departure() > 0) {
      losing.push_back(&g);
      total += g.departure();
    }
  if (losing.empty()) return "";
  std::stable_sort(losing.begin(), losing.end(), [](const GarmentFidelity* a, const GarmentFidelity* b) { return a->departure() > b->departure(); });
  return first_five("garments by their part of the pixels lost beyond the floor, largest first", losing.size(), [&](std::ostream& o, std::size_t k) {
    o << std::setprecision(0) << losing[k]->garment << " " << 100 * losing[k]->departure() / total << "%";
  });
}

const char* kShotsHeader =
    "shot,first_frame,last_frame,frames,overlap_mean,overlap_min,floor_overlap_mean,floor_overlap_min,detail_run,detail_reference,"
    "detail_ratio,popping_pairs,popping_run,popping_reference,popping_ratio,verdict,failed,detail_floor_ratio,popping_floor_ratio,"
    "floors,floor_overlap_means,floor_overlap_mins,samples,sample_overlap_means,sample_overlap_mins\n";

void write_shot_row(std::ostream& csv, const ShotFidelity& s) {
  csv << (s.shot < 0 ? "all" : std::to_string(s.shot)) << "," << s.first_frame << "," << s.last_frame << "," << s.frames << ","
      << cell(s.overlap_mean) << "," << cell(s.overlap_min) << "," << cell(s.floor_overlap_mean) << "," << cell(s.floor_overlap_min) << ","
      << cell(s.detail_run_mean) << "," << cell(s.detail_reference_mean) << "," << cell(s.detail_ratio) << "," << s.popping_pairs << ","
      << cell(s.popping_run_mean) << "," << cell(s.popping_reference_mean) << "," << cell(s.popping_ratio) << ","
      << (s.pass() ? "pass" : "fail") << "," << joined(s.failed, ";") << "," << cell(s.detail_floor_ratio) << ","
      << cell(s.popping_floor_ratio) << "," << s.floor_overlap_means.size() << "," << cells(s.floor_overlap_means) << ","
      << cells(s.floor_overlap_mins) << "," << std::max<std::size_t>(1, s.sample_overlap_means.size()) << ","
      << cells(s.sample_overlap_means) << "," << cells(s.sample_overlap_mins) << "\n";
}

std::string progress_line(const FrameFidelity& m) {
  std::ostringstream o;
  o << std::fixed << "vdcloth fidelity: frame " << m.frame << ", shot " << m.shot << ": overlap " << std::setprecision(3) << m.overlap;
  if (!std::isnan(m.floor_overlap)) o << " (floor " << m.floor_overlap << ")";
  o << ", detail " << std::setprecision(2) << m.detail_run << " / " << m.detail_reference << " deg";
  if (!std::isnan(m.popping_run)) o << ", popping " << std::setprecision(1) << m.popping_run << " / " << m.popping_reference;
  return o.str();
}

// With several floor runs, e.g. ", mean of 3 floor runs, their means 0.965 to 0.976"; nothing
// with one.
std::string floor_runs(const ShotFidelity& s) {
  if (s.floor_overlap_means.size() < 2) return "";
  const auto [low, high] = std::minmax_element(s.floor_overlap_means.begin(), s.floor_overlap_means.end());
  std::ostringstream o;
  o << std::fixed << std::setprecision(3) << ", mean of " << s.floor_overlap_means.size() << " floor runs, their means " << *low << " to "
    << *high;
  return o.str();
}

// With several runs judged, e.g. " (mean of 4 runs, their means 0.949 to 0.955)"; nothing with one.
std::string sample_runs(const ShotFidelity& s) {
  if (s.sample_overlap_means.size() < 2) return "";
  const auto [low, high] = std::minmax_element(s.sample_overlap_means.begin(), s.sample_overlap_means.end());
  std::ostringstream o;
  o << std::fixed << std::setprecision(3) << " (mean of " << s.sample_overlap_means.size() << " runs, their means " << *low << " to "
    << *high << ")";
  return o.str();
}

// e.g. "shot 2 (frames 75-149): overlap 0.952 mean / 0.930 min (floor 0.968 / 0.941), detail 97%
// of reference (floor 99%), popping 1.05x (floor 1.01x): pass"
std::string verdict_line(const ShotFidelity& s) {
  std::ostringstream o;
  o << std::fixed << (s.shot < 0 ? std::string("all") : "shot " + std::to_string(s.shot)) << " (frames " << s.first_frame << "-"
    << s.last_frame << "): overlap " << std::setprecision(3) << s.overlap_mean << " mean / " << s.overlap_min << " min" << sample_runs(s);
  if (std::isnan(s.floor_overlap_mean)) o << " (no floor)";
  else o << " (floor " << s.floor_overlap_mean << " / " << s.floor_overlap_min << floor_runs(s) << ")";
  o << ", detail ";
  if (std::isinf(s.detail_ratio)) o << "where the reference has none";
  else o << std::setprecision(0) << 100 * s.detail_ratio << "% of reference";
  if (std::isfinite(s.detail_floor_ratio)) o << " (floor " << std::setprecision(0) << 100 * s.detail_floor_ratio << "%)";
  o << ", popping ";
  if (std::isnan(s.popping_ratio)) o << "not measured (no consecutive frames)";
  else if (std::isinf(s.popping_ratio)) o << "where the reference has none";
  else o << std::setprecision(2) << s.popping_ratio << "x";
  if (std::isfinite(s.popping_floor_ratio)) o << " (floor " << std::setprecision(2) << s.popping_floor_ratio << "x)";
  o << ": " << (s.pass() ? "pass" : "fail (" + joined(s.failed, ", ") + ")");
  return o.str();
}

}  // namespace

int fidelity_command(const std::vector<std::string>& args, std::ostream& out) {
  for (const std::string& a : args)
    if (a == "--help" || a == "-h") {
      out << kFidelityHelp;
      return kExitOk;
    }
  const FidelityArgs f = parse_fidelity_args(args);
  Scene scene = load_scene(f.scene);
  choose_camera(scene, f.camera, "to measure through");
  std::vector<std::string> dirs{f.run, f.reference};
  dirs.insert(dirs.end(), f.floors.begin(), f.floors.end());
  dirs.insert(dirs.end(), f.samples.begin(), f.samples.end());
  std::vector<std::map<int, FrameFiles>> runs;
  std::vector<const std::map<int, FrameFiles>*> listed;
  for (const std::string& dir : dirs) runs.push_back(read_frame_files(dir));
  for (const auto& run : runs) listed.push_back(&run);
  const std::vector<int> common = frames_in_common(listed);
  if (common.empty())
    throw InputError(f.run, "", "no frame in common with " + joined(std::vector<std::string>(dirs.begin() + 1, dirs.end()), " and "));
  std::vector<int> measured;
  for (std::size_t i = 0; i < common.size(); i += static_cast<std::size_t>(f.every)) measured.push_back(common[i]);
  const double pixels_per_metre = scene.cameras.front().path.lens().focal_pixels() * f.scale;

  // Everything given is valid: from here on only a mesh file that cannot be read (or results
  // that cannot be written) stops the command, and then it takes back what it wrote.
  const std::vector<fs::path> made = create_output_directory(f.out);
  std::optional<PartialTable> frames_csv, garments_csv, shots_csv;
  try {
    frames_csv.emplace(f.out + "/fidelity.csv");
    frames_csv->stream() << kFramesHeader;
    garments_csv.emplace(f.out + "/fidelity_garments.csv");
    garments_csv->stream() << kGarmentsHeader;
    std::vector<FrameFidelity> record;
    std::vector<std::vector<FrameFidelity>> sample_records(f.samples.size());  // by sample
    std::vector<GarmentFrame> garment_record;
    // The runs at the last measured frame, kept as the frame before of the next one.
    std::optional<int> kept_frame;
    DrawnRuns kept;
    for (const int frame : measured) {
      DrawnRuns now = draw_runs(scene, runs, frame, f.scale);
      const int shot = shot_of(scene, frame);
      const bool has_before = std::binary_search(common.begin(), common.end(), frame - 1) && shot_of(scene, frame - 1) == shot;
      DrawnRuns before;
      if (has_before) before = kept_frame == frame - 1 ? std::move(kept) : draw_runs(scene, runs, frame - 1, f.scale);
      FrameFidelity m = measure(now, has_before ? &before : nullptr, f.floors.size(), pixels_per_metre);
      m.frame = frame;
      m.time = frame * scene.frame_time;
      m.shot = shot;
      std::vector<FrameFidelity> samples;
      for (std::size_t k = 0; k < f.samples.size(); ++k) {
        samples.push_back(with_run_measured(m, now, has_before ? &before : nullptr, 2 + f.floors.size() + k, pixels_per_metre));
        sample_records[k].push_back(samples.back());
      }
      write_frame_row(frames_csv->stream(), m, samples);
      for (GarmentFrame& g : measure_garments(now, f.floors.size())) {
        g.frame = frame;
        g.shot = shot;
        write_garment_row(garments_csv->stream(), g);
        garment_record.push_back(std::move(g));
      }
      out << progress_line(m) << "\n" << std::flush;
      record.push_back(m);
      kept = std::move(now);
      kept_frame = frame;
    }
    std::vector<std::vector<ShotFidelity>> runs_summed{summarise_shots(record, f.targets)};
    for (const auto& sample : sample_records) runs_summed.push_back(summarise_shots(sample, f.targets));
    const std::vector<ShotFidelity> shots = summarise_samples(runs_summed, f.targets);
    shots_csv.emplace(f.out + "/fidelity_shots.csv");
    shots_csv->stream() << kShotsHeader;
    bool pass = true;
    for (const ShotFidelity& s : shots) {
      write_shot_row(shots_csv->stream(), s);
      pass = pass && s.pass();
    }
    frames_csv->finish();
    garments_csv->finish();
    shots_csv->finish();
    const std::vector<GarmentFidelity> garments = summarise_garments(garment_record);
    if (!garments.empty()) out << "vdcloth fidelity: " << garments_line(garments) << "\n";
    if (const std::string departing = departure_line(garments); !departing.empty()) out << "vdcloth fidelity: " << departing << "\n";
    for (const ShotFidelity& s : shots) out << "vdcloth fidelity: " << verdict_line(s) << "\n";
    out << "vdcloth fidelity: " << record.size() << " frame(s) of " << f.run << " against " << f.reference;
    if (!f.floors.empty()) out << " (floor " << joined(f.floors, ", ") << ")";
    if (!f.samples.empty()) out << " (samples " << joined(f.samples, ", ") << ")";
    out << "; " << f.out << "/fidelity.csv, " << f.out << "/fidelity_garments.csv, " << f.out << "/fidelity_shots.csv\n";
    return pass ? kExitOk : kExitSimulationFailed;
  } catch (const std::exception&) {  // nothing half-written stays behind, whatever stopped it
    if (frames_csv) frames_csv->discard();
    if (garments_csv) garments_csv->discard();
    if (shots_csv) shots_csv->discard();
    std::error_code ec;
    for (const fs::path& dir : made) fs::remove(dir, ec);  // only if empty
    throw;
  }
}

}  // namespace vdc
