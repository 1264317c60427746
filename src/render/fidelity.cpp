// The fidelity measures of one frame (wrinkle detail from the shading normals) and their
// summaries over shots, judged against the targets.
#include "render/fidelity.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace vdc {

namespace {

// Neighbours further apart in depth than this many pixel footprints are on different surfaces
// (a fold in front of the cloth behind it): a surface seen at up to atan(4) = 76 degrees from
// facing the camera still counts as one.
constexpr double kDiscontinuityFootprints = 4;

// Sums of a measure and the reference's over the frames (or frame pairs) where both were
// measured, for the ratio of their means.
struct PairedSums {
  double value = 0, reference = 0;
  int count = 0;
  void add(double x, double ref) {
    if (std::isnan(x) || std::isnan(ref)) return;
    ++count;
    value += x;
    reference += ref;
  }
  double mean() const { return value / count; }
  double reference_mean() const { return reference / count; }
  double ratio() const { return count > 0 ? ratio_of_means(mean(), reference_mean()) : kNotMeasured; }
};

// A frame's floor overlaps, one a floor run: the list, or the one floor run's, or none.
std::vector<double> floor_overlaps_of(const FrameFidelity& f) {
  if (!f.floor_overlaps.empty()) return f.floor_overlaps;
  if (std::isnan(f.floor_overlap)) return {};
  return {f.floor_overlap};
}

double mean_of(const std::vector<double>& xs) {
  double sum = 0;
  for (double x : xs) sum += x;
  return sum / static_cast<double>(xs.size());
}

// The targets a summary misses, into s.failed; the overlap only against a floor, the popping
// only where measured.
void judge(ShotFidelity& s, const FidelityTargets& targets) {
  s.failed.clear();
  if (!std::isnan(s.floor_overlap_mean)) {
    if (s.overlap_mean < s.floor_overlap_mean - targets.overlap_margin) s.failed.push_back("overlap mean");
    if (s.overlap_min < s.floor_overlap_min - targets.min_margin) s.failed.push_back("overlap min");
  }
  if (s.detail_ratio < targets.detail) s.failed.push_back("detail");
  if (!std::isnan(s.popping_ratio) && s.popping_ratio > targets.popping) s.failed.push_back("popping");
}

ShotFidelity summarise(int shot, const std::vector<const FrameFidelity*>& frames, const FidelityTargets& targets) {
  ShotFidelity s;
  s.shot = shot;
  s.frames = static_cast<int>(frames.size());
  s.first_frame = frames.front()->frame;
  s.last_frame = frames.front()->frame;
  s.overlap_min = std::numeric_limits<double>::infinity();
  double overlap_sum = 0;
  double detail_run = 0, detail_reference = 0;
  PairedSums popping, detail_floor, popping_floor;
  // Each floor run's sum, minimum and count of frames, in the order given.
  std::vector<double> floor_sums, floor_mins;
  std::vector<int> floor_counts;
  for (const FrameFidelity* f : frames) {
    s.first_frame = std::min(s.first_frame, f->frame);
    s.last_frame = std::max(s.last_frame, f->frame);
    overlap_sum += f->overlap;
    s.overlap_min = std::min(s.overlap_min, f->overlap);
    const std::vector<double> floors = floor_overlaps_of(*f);
    if (floors.size() > floor_sums.size()) {
      floor_sums.resize(floors.size(), 0.0);
      floor_mins.resize(floors.size(), std::numeric_limits<double>::infinity());
      floor_counts.resize(floors.size(), 0);
    }
    for (std::size_t k = 0; k < floors.size(); ++k) {
      floor_sums[k] += floors[k];
      floor_mins[k] = std::min(floor_mins[k], floors[k]);
      ++floor_counts[k];
    }
    detail_run += f->detail_run;
    detail_reference += f->detail_reference;
    popping.add(f->popping_run, f->popping_reference);
    detail_floor.add(f->detail_floor, f->detail_reference);
    popping_floor.add(f->popping_floor, f->popping_reference);
  }
  s.detail_floor_ratio = detail_floor.ratio();
  s.popping_floor_ratio = popping_floor.ratio();
  s.overlap_mean = overlap_sum / s.frames;
  s.detail_run_mean = detail_run / s.frames;
  s.detail_reference_mean = detail_reference / s.frames;
  s.detail_ratio = ratio_of_means(s.detail_run_mean, s.detail_reference_mean);
  for (std::size_t k = 0; k < floor_sums.size(); ++k) {
    s.floor_overlap_means.push_back(floor_sums[k] / floor_counts[k]);
    s.floor_overlap_mins.push_back(floor_mins[k]);
  }
  if (!s.floor_overlap_means.empty()) {
    s.floor_overlap_mean = mean_of(s.floor_overlap_means);
    s.floor_overlap_min = mean_of(s.floor_overlap_mins);
  }
  s.popping_pairs = popping.count;
  if (popping.count > 0) {
    s.popping_run_mean = popping.mean();
    s.popping_reference_mean = popping.reference_mean();
    s.popping_ratio = popping.ratio();
  }
  judge(s, targets);
  return s;
}

}  // namespace

// Mean angle between neighbouring cloth pixels' shading normals, each angle as atan2(|a x b|,
// a . b), which keeps its digits for the small angles of gentle wrinkles where acos loses half.
double wrinkle_detail(const RenderedFrame& frame, const std::vector<char>& cloth, double pixels_per_metre_at_unit_depth) {
  const auto width = static_cast<std::size_t>(frame.image.width), height = static_cast<std::size_t>(frame.image.height);
  if (frame.mesh.size() != width * height || frame.depth.size() != width * height || frame.normal.size() != width * height)
    throw std::invalid_argument("wrinkle_detail: the frame's buffers are not one value a pixel");
  auto is_cloth = [&](std::size_t i) {
    const int32_t m = frame.mesh[i];
    return m >= 0 && static_cast<std::size_t>(m) < cloth.size() && cloth[static_cast<std::size_t>(m)];
  };
  double sum = 0;
  long pairs = 0;
  auto add_pair = [&](std::size_t i, std::size_t j) {
    if (frame.mesh[i] != frame.mesh[j] || !is_cloth(i)) return;
    const double footprint = 0.5 * (frame.depth[i] + frame.depth[j]) / pixels_per_metre_at_unit_depth;
    if (std::abs(frame.depth[i] - frame.depth[j]) > kDiscontinuityFootprints * footprint) return;
    sum += std::atan2(frame.normal[i].cross(frame.normal[j]).norm(), frame.normal[i].dot(frame.normal[j]));
    ++pairs;
  };
  for (std::size_t y = 0; y < height; ++y)
    for (std::size_t x = 0; x < width; ++x) {
      const std::size_t i = y * width + x;
      if (x + 1 < width) add_pair(i, i + 1);
      if (y + 1 < height) add_pair(i, i + width);
    }
  return pairs > 0 ? sum / static_cast<double>(pairs) * 180.0 / M_PI : 0.0;
}

double ratio_of_means(double run_mean, double reference_mean) {
  if (reference_mean > 0) return run_mean / reference_mean;
  return run_mean > 0 ? std::numeric_limits<double>::infinity() : 1.0;
}

std::vector<ShotFidelity> summarise_shots(const std::vector<FrameFidelity>& frames, const FidelityTargets& targets) {
  std::map<int, std::vector<const FrameFidelity*>> by_shot;
  std::vector<const FrameFidelity*> all;
  for (const FrameFidelity& f : frames) {
    by_shot[f.shot].push_back(&f);
    all.push_back(&f);
  }
  std::vector<ShotFidelity> summaries;
  for (const auto& [shot, members] : by_shot) summaries.push_back(summarise(shot, members, targets));
  if (!all.empty()) summaries.push_back(summarise(-1, all, targets));
  return summaries;
}

std::vector<ShotFidelity> summarise_samples(const std::vector<std::vector<ShotFidelity>>& runs, const FidelityTargets& targets) {
  if (runs.size() < 2) return runs.empty() ? std::vector<ShotFidelity>{} : runs.front();
  std::vector<ShotFidelity> out = runs.front();
  for (std::size_t k = 0; k < out.size(); ++k) {
    ShotFidelity& s = out[k];
    std::vector<double> details, poppings;
    for (const auto& run : runs) {
      if (run.size() != out.size() || run[k].shot != s.shot)
        throw std::invalid_argument("summarise_samples: the runs' summaries are not of the same shots");
      s.sample_overlap_means.push_back(run[k].overlap_mean);
      s.sample_overlap_mins.push_back(run[k].overlap_min);
      details.push_back(run[k].detail_run_mean);
      poppings.push_back(run[k].popping_run_mean);
    }
    s.overlap_mean = mean_of(s.sample_overlap_means);
    s.overlap_min = mean_of(s.sample_overlap_mins);
    s.detail_run_mean = mean_of(details);
    s.detail_ratio = ratio_of_means(s.detail_run_mean, s.detail_reference_mean);
    if (s.popping_pairs > 0) {
      s.popping_run_mean = mean_of(poppings);
      s.popping_ratio = ratio_of_means(s.popping_run_mean, s.popping_reference_mean);
    }
    judge(s, targets);
  }
  return out;
}

std::vector<GarmentFidelity> summarise_garments(const std::vector<GarmentFrame>& frames) {
  struct Sums {
    int frames = 0;
    double both = 0, either = 0, floor_both = 0, floor_either = 0;
  };
  std::map<std::string, Sums> by_garment;
  for (const GarmentFrame& f : frames) {
    if (f.pixels_either == 0) continue;
    Sums& s = by_garment[f.garment];
    ++s.frames;
    s.both += f.overlap * f.pixels_either;
    s.either += f.pixels_either;
    if (std::isnan(f.floor_overlap)) continue;
    s.floor_both += f.floor_overlap * f.floor_pixels_either;
    s.floor_either += f.floor_pixels_either;
  }
  std::vector<GarmentFidelity> out;
  for (const auto& [garment, s] : by_garment)
    out.push_back({garment, s.frames, s.both / s.either, s.floor_either > 0 ? s.floor_both / s.floor_either : kNotMeasured,
                   static_cast<long long>(s.either)});
  std::stable_sort(out.begin(), out.end(), [](const GarmentFidelity& a, const GarmentFidelity& b) { return a.overlap < b.overlap; });
  return out;
}

}  // namespace vdc
