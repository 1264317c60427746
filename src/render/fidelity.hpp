// How like a reference a run looks through the shot camera: per frame, the overlap of the cloth
// silhouettes, the on-screen wrinkle detail and the popping (image change from the frame
// before) of each run; per shot and over the whole run, these summed up and judged against
// targets set relative to the reference and to the chaos floor (the reference against a run of
// it perturbed below any physical meaning).
#pragma once
#include <limits>
#include <string>
#include <vector>

#include "render/rasterizer.hpp"

namespace vdc {

inline constexpr double kNotMeasured = std::numeric_limits<double>::quiet_NaN();

// Mean angle in degrees between the shading normals of horizontally and vertically neighbouring
// pixels that both show cloth of the same mesh and are not across a depth discontinuity (their
// depths differ by more than 4 pixel footprints, a footprint being depth /
// pixels_per_metre_at_unit_depth at their mean depth); 0 when no pair. It is how much the shading
// varies across the cloth on screen: folds and wrinkles raise it, a coarse smooth mesh lowers it.
// `cloth[m]` says whether mesh m is cloth; pixels_per_metre_at_unit_depth is the camera's
// focal_pixels() times the render's scale.
double wrinkle_detail(const RenderedFrame& frame, const std::vector<char>& cloth, double pixels_per_metre_at_unit_depth);

// One measured frame. Floor values are kNotMeasured without a floor run, and the means over the
// floor runs with several; popping is kNotMeasured on the first frame of a shot and where the
// frame before was not written by every run.
struct FrameFidelity {
  int frame = 0;
  double time = 0;
  int shot = 0;
  int cloth_pixels_run = 0, cloth_pixels_reference = 0;
  double overlap = 1;                    // cloth silhouette IoU, run against reference
  double floor_overlap = kNotMeasured;   // the same, floor run against reference
  // Each floor run's overlap, in the order given (a record with floor_overlap alone counts as one
  // floor run).
  std::vector<double> floor_overlaps;
  double detail_run = 0, detail_reference = 0, detail_floor = kNotMeasured;  // wrinkle_detail, degrees
  double popping_run = kNotMeasured, popping_reference = kNotMeasured, popping_floor = kNotMeasured;  // 0 to 255
};

// What a run must reach to look like its reference (`vdcloth fidelity`'s options).
struct FidelityTargets {
  double overlap_margin = 0.02;  // overlap mean >= floor overlap mean - this
  double min_margin = 0.05;      // overlap min >= floor overlap min - this
  double detail = 0.9;           // detail ratio >= this
  double popping = 1.2;          // popping ratio <= this
};

// A shot's frames (or the whole run's) summed up and judged.
struct ShotFidelity {
  int shot = -1;  // -1: the whole run
  int first_frame = 0, last_frame = 0, frames = 0;
  double overlap_mean = 0, overlap_min = 0;
  // The floor: the mean of the floor runs' overlap means and the mean of their minima (with
  // several, what one perturbed run is expected to give, where one alone is one sample of it).
  double floor_overlap_mean = kNotMeasured, floor_overlap_min = kNotMeasured;
  std::vector<double> floor_overlap_means, floor_overlap_mins;  // each floor run's, in order
  double detail_run_mean = 0, detail_reference_mean = 0;
  double detail_ratio = 1;  // detail_run_mean / detail_reference_mean: 1 for 0/0, +infinity for x/0
  int popping_pairs = 0;    // frame pairs with popping measured in both runs
  double popping_run_mean = kNotMeasured, popping_reference_mean = kNotMeasured;
  // popping_run_mean / popping_reference_mean: 1 for 0/0, +infinity for x/0, kNotMeasured
  // without pairs (then not judged).
  double popping_ratio = kNotMeasured;
  // The floor run's own detail and popping over the reference's, on the frames (pairs) it was
  // measured on: what a tiny perturbation already does to them, beside the run's ratios. Not
  // judged; kNotMeasured without a floor.
  double detail_floor_ratio = kNotMeasured;
  double popping_floor_ratio = kNotMeasured;
  // With several runs of the judged method (summarise_samples), each one's overlap mean and
  // minimum, in order; the figures above are then their means. Empty for one run.
  std::vector<double> sample_overlap_means, sample_overlap_mins;
  std::vector<std::string> failed;  // the targets missed: "overlap mean", "overlap min", "detail", "popping"
  bool pass() const { return failed.empty(); }
};

// The record's frames summed up over each shot in shot order, then over the whole run (shot -1)
// and judged against `targets`; overlap is judged only where floor overlaps were measured.
std::vector<ShotFidelity> summarise_shots(const std::vector<FrameFidelity>& frames, const FidelityTargets& targets);

// Several runs of the same method (the run and its twins perturbed below any meaning, against
// the same reference and floor), each summed up by summarise_shots, as one judged sample of the
// method: by shot, the mean of their overlap means and of their minima (as the floor is taken
// over several floor runs), and their mean detail and popping over the reference's, judged
// again. The reference's and the floor's figures are the first run's (the same in all). One run
// is returned as it is.
std::vector<ShotFidelity> summarise_samples(const std::vector<std::vector<ShotFidelity>>& runs, const FidelityTargets& targets);

// One garment at one measured frame: its own silhouette (where it is the nearest surface)
// against the reference's, to tell which garment of a scene departs.
struct GarmentFrame {
  int frame = 0;
  int shot = 0;
  std::string garment;
  int pixels_run = 0, pixels_reference = 0;
  int pixels_either = 0;                // showing it in the run or the reference
  double overlap = 1;                   // IoU of the garment's pixels, run against reference
  // The same for the floor run against the reference; with several floor runs, summed over
  // them (pixels either) and pooled (their pixels in both over their pixels in either).
  int floor_pixels_either = 0;
  double floor_overlap = kNotMeasured;
};

// A garment over the measured frames: the pixels showing it in both runs over those showing it
// in either, summed over the frames (each frame weighed by how much of it shows, so that a
// sliver at the edge of the frame or behind a body counts for little).
struct GarmentFidelity {
  std::string garment;
  int frames = 0;  // showing it in the run or the reference
  double overlap = 1;
  double floor_overlap = kNotMeasured;  // over the frames with a floor overlap
  long long pixels = 0;                 // showing it in the run or the reference, over the frames
  // The pixels it loses beyond the floor's rate, (floor_overlap - overlap) x pixels: its part of
  // the shot's departure, where a small far garment's low overlap counts for few pixels (not
  // measured without a floor overlap).
  double departure() const { return (floor_overlap - overlap) * static_cast<double>(pixels); }
};

// Each garment's frames summed up, the lowest overlap first (ties by name); a garment no frame
// shows is left out.
std::vector<GarmentFidelity> summarise_garments(const std::vector<GarmentFrame>& frames);

// A run's mean over its reference's, as the summaries take it: 1 for 0/0 (alike), +infinity
// for x/0 with x > 0.
double ratio_of_means(double run_mean, double reference_mean);

}  // namespace vdc
