// Fitting the procedural garments, whose sizes are given for the project's figure, to the figure
// that wears them: heights carried by the skeleton's landmarks (soles, knees, hip joints,
// shoulders, head), radii changed so the garment keeps the ease (its radius beyond the body's)
// it has on the project's figure at every height, the garment placed on the figure's axis.
#pragma once
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/mesh_build.hpp"
#include "scene/garments.hpp"
#include "scene/skeleton.hpp"

namespace vdc {

// A figure as a garment sees it, in the pose the garment is put on in, in the figure's own frame:
// its root's vertical axis at x = z = 0, facing +z.
struct FigureMeasure {
  // Heights (m): the lowest joint, the knees, the hip joints, the shoulders and the head (the
  // mean of the left and right joints), increasing.
  std::array<double, 5> landmarks{};
  double shoulder_half_width = 0;  // m: the shoulder joints' mean distance from the axis
  Vec3 axis = Vec3::Zero();        // the root where the figure stands (y = 0), in the skeleton's space
  double heading = 0;              // radians about +y from +z to where the figure faces
  // Girth: the farthest point of the body's cross-section (arms from the collarbones and head
  // left out) from the axis, at heights kGirthStep apart from girth_base up.
  double girth_base = 0;
  std::vector<double> girth;
  static constexpr double kGirthStep = 0.005;
  double girth_at(double y) const;  // the larger of the two nearest heights'; 0 outside the body
  // Reach: the nearest the arms' cross-section comes to the axis at those heights, over the
  // poses of the figure's motion (each in its own root's frame, heights as the root stands in
  // the dressing pose); infinite where the arms never are.
  std::vector<double> reach;
  double reach_at(double y) const;  // the smaller of the two nearest heights' reach
};

// Measures a figure in `pose`: the humanoid's landmark joints (by the skeleton's shape, so any
// naming scheme works) and the body (`body_mesh`'s faces, `body` its vertices in that pose,
// `main_joints` the joint moving each most: Body::main_joints). Throws std::invalid_argument
// saying why the skeleton is not a humanoid's, or that its landmarks are out of order (a figure
// not standing upright).
FigureMeasure measure_figure(const Motion& motion, const Pose& pose, const MeshSource& body_mesh, const std::vector<Vec3>& body,
                             const std::vector<int>& main_joints);

// Adds the arms' reach to a figure measured in `pose`: over the `moving` poses, whose body
// vertices `skin` gives.
void measure_arm_reach(FigureMeasure& m, const Motion& motion, const Pose& pose, const MeshSource& body_mesh, const std::vector<int>& main_joints,
                       const std::vector<Pose>& moving, const std::function<std::vector<Vec3>(const Pose&)>& skin);

using GarmentPattern = std::variant<DressParams, TubeParams>;

// A procedural garment's radius at height y (its straps left out); none where it does not reach.
std::optional<double> garment_radius(const TubeParams& tube, double y);
std::optional<double> garment_radius(const DressParams& dress, double y);
std::optional<double> garment_radius(const GarmentPattern& pattern, double y);

// A procedural garment and the nodes its handles hold (indices of make_garment's positions).
struct HeldGarment {
  GarmentPattern pattern;
  std::vector<int> held;
};

// The map from a garment's sizes on the reference figure to the figure it is put on.
class GarmentFit {
 public:
  GarmentFit(FigureMeasure reference, FigureMeasure figure);
  // The figure is the reference (landmarks within a micrometre, girth within 2 mm, on the
  // reference's axis and heading): garments are made as specified.
  bool identity() const { return identity_; }
  // A reference height on the figure: piecewise linear through the landmarks, extended beyond
  // them by the end pieces.
  double height(double y) const;
  // The garment's sizes on the figure, cut in the same rows (with_rows) as on the reference, its
  // ease (radius beyond the body) at every height at least `ease` times what it is on the
  // reference.
  TubeParams fit(const TubeParams& p, double ease = 1.0) const;
  DressParams fit(const DressParams& p, double ease = 1.0) const;
  // The garments one figure wears, fitted together: at every height each keeps at least `ease`
  // times its ease beyond the body and beyond every garment it is worn over there on the
  // reference (one of smaller radius), measured on that garment as fitted, so layers keep their
  // order (a belt fitted to a slender waist stays outside a tunic the chest makes wide).
  std::vector<GarmentPattern> fit(const std::vector<GarmentPattern>& worn, double ease = 1.0) const;
  // The largest share of their ease, 1 at most and kLeastEase at least, that a figure's garments
  // can keep with every node a handle holds at least `clearance` inside the arms' reach (needs
  // measure_arm_reach): cloth a handle holds cannot make way, so a held waistband the arms
  // pass through would hold the arms. All garments of a figure take the same share, so layers
  // stay in their order.
  double ease_clearing_arms(const std::vector<HeldGarment>& garments, double clearance) const;
  static constexpr double kLeastEase = 0.2;
  // No garment is made narrower than this share of its given radius.
  static constexpr double kNarrowest = 0.3;
  // From the figure's frame (where fitted garments are made) to the skeleton's space.
  Vec3 place(const Vec3& x) const;

 private:
  // A garment worn under the one being fitted: as on the reference, and as fitted so far.
  struct Under {
    const GarmentPattern* reference;
    const GarmentPattern* fitted;
  };
  TubeParams fit(const TubeParams& p, double ease, const std::vector<Under>& under) const;
  DressParams fit(const DressParams& p, double ease, const std::vector<Under>& under) const;
  double needed(double y, double radius, double ease, const std::vector<Under>& under) const;
  FigureMeasure reference_, figure_;
  bool identity_ = false;
};

}  // namespace vdc
