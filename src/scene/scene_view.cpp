// The `view` block (docs/scene-format.md, "view"): the parameters of view-dependent sizing.
#include "scene/scene_blocks.hpp"

namespace vdc {

ViewParams parse_view(const JsonValue& j) {
  j.only_keys({"v_back", "v_out", "margin", "anticipation", "lead", "linger", "l_min", "l_max", "silhouette_threshold", "settle",
               "back_occlusion", "occlusion_scale", "occlusion_erosion", "occlusion_depth", "motion_anticipation", "defocus_scale",
               "motion_blur_scale", "occlusion", "v_occluded", "floor_in_frame", "fold_length", "fold_time", "gathering",
               "keep_compression", "coarse_damping", "far_remesh_every", "far_after"});
  ViewParams p;
  p.v_back = j.positive_or("v_back", p.v_back);
  p.v_out = j.positive_or("v_out", p.v_out);
  if (p.v_back > 1) j.at("v_back").fail("must be at most 1");
  if (p.v_out > p.v_back) j.at("v_out").fail("must be at most v_back");
  p.margin = j.positive_or("margin", p.margin);
  p.anticipation = j.non_negative_or("anticipation", p.anticipation);
  p.lead = j.non_negative_or("lead", p.lead);
  p.linger = j.non_negative_or("linger", p.linger);
  p.l_min = j.non_negative_or("l_min", p.l_min);
  p.l_max = j.non_negative_or("l_max", p.l_max);
  if (p.l_max > 0 && p.l_max < p.l_min) j.at("l_max").fail("must be 0 (no ceiling) or at least l_min");
  p.silhouette_threshold = j.positive_or("silhouette_threshold", p.silhouette_threshold);
  p.settle = j.non_negative_or("settle", p.settle);
  p.back_occlusion = j.boolean_or("back_occlusion", p.back_occlusion);
  p.occlusion_scale = j.positive_or("occlusion_scale", p.occlusion_scale);
  if (p.occlusion_scale > 1) j.at("occlusion_scale").fail("must be at most 1 (the camera's own image size)");
  const long long erosion = j.integer_or("occlusion_erosion", p.occlusion_erosion);
  if (erosion < 0 || erosion > 16) j.at("occlusion_erosion").fail("must be an integer from 0 to 16 (pixels)");
  p.occlusion_erosion = static_cast<int>(erosion);
  p.occlusion_depth = j.non_negative_or("occlusion_depth", p.occlusion_depth);
  p.occlusion = j.boolean_or("occlusion", p.occlusion);
  p.floor_in_frame = j.boolean_or("floor_in_frame", p.floor_in_frame);
  p.fold_length = j.non_negative_or("fold_length", p.fold_length);
  p.fold_time = j.non_negative_or("fold_time", p.fold_time);
  p.gathering = j.non_negative_or("gathering", p.gathering);
  if (p.gathering > 1) j.at("gathering").fail("must be at most 1 (the material's own stiffness)");
  p.keep_compression = j.boolean_or("keep_compression", p.keep_compression);
  p.coarse_damping = j.non_negative_or("coarse_damping", p.coarse_damping);
  if (p.coarse_damping > 10) j.at("coarse_damping").fail("must be at most 10 (time steps)");
  p.v_occluded = j.positive_or("v_occluded", p.v_back);
  if (p.v_occluded > 1) j.at("v_occluded").fail("must be at most 1");
  if (p.v_occluded < p.v_out) j.at("v_occluded").fail("must be at least v_out");
  p.motion_anticipation = j.boolean_or("motion_anticipation", p.motion_anticipation);
  p.defocus_scale = j.non_negative_or("defocus_scale", p.defocus_scale);
  p.motion_blur_scale = j.non_negative_or("motion_blur_scale", p.motion_blur_scale);
  const long long far_every = j.integer_or("far_remesh_every", p.far_remesh_every);
  if (far_every < 1 || far_every > 100) j.at("far_remesh_every").fail("must be an integer from 1 (every frame) to 100 (frames)");
  p.far_remesh_every = static_cast<int>(far_every);
  p.far_after = j.non_negative_or("far_after", p.far_after);
  return p;
}

}  // namespace vdc
