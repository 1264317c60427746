// Physical sizing field of adaptive remeshing (Narain et al. 2012, section 5): per face, a
// symmetric 2x2 tensor M in material space from curvature, velocity gradient and compression,
// clamped to [1/size_max^2, 1/size_min^2] with bounded anisotropy, then moved to verts by
// area-weighted averaging. A FaceSizingModifier may change the face tensors before that move
// (view-dependent sizing plugs in there) without the remesher knowing why.
#pragma once
#include "core/mesh.hpp"

namespace vdc {

struct SizingParams {
  double refine_angle = 0.3;          // rad: largest normal change across an edge
  double refine_velocity = 0.5;       // m/s: largest velocity difference across an edge
  double refine_compression = 0.01;   // m: resolution of buckles under compression
  double size_min = 0.01;             // m
  double size_max = 0.2;              // m
  double aspect_min = 0.2;            // smallest ratio of the short to the long axis of a face
  // Not a scene key: `vdcloth run --perturb-resolution E` sets it to 1 + E. Every vert's tensor
  // is divided by its square, so the remesher lets every edge be this many times as long as
  // the criteria ask (a perturbation of the discretisation, as --perturb is of the physics).
  double resolution_scale = 1.0;
};

// The obstacle point nearest to a node and the unit direction from it to the node (zero
// normal: no obstacle near), for the obstacle-proximity criterion; and whether the node is held:
// another surface lies within the hold distance on the far side of the node from that point, so
// that the cloth there is pressed between two and cannot buckle.
struct ObstaclePlane {
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::Zero();
  bool held = false;
};

// Face attribute holding the face tensors of the last compute_sizing.
inline constexpr const char* kFaceSizingAttr = "face_sizing";
// Face attribute (double) written by compute_sizing when a modifier changed the field: how much
// coarser than the physical criteria ask the face may be, as the largest eigenvalue of the
// physical tensor measured in the final one (the square of the length ratio; 1 or less where
// the modifier did not coarsen), or than the folds the modifier says it cannot show
// (FaceSizingModifier::fold_coarsening), whichever is larger.
inline constexpr const char* kCoarseningAttr = "coarsening";
// Face attribute (double) written beside kCoarseningAttr: 1 where the folds the modifier cannot
// show set the coarsening (they asked for more than the physical tensor), 0 elsewhere.
inline constexpr const char* kFoldLedAttr = "fold_led";

class FaceSizingModifier {
 public:
  virtual ~FaceSizingModifier() = default;
  // Called with the clamped physical tensors, which it may rewrite, and, by face index, the
  // clamped tensors of the criterion that resolves the cloth's motion (velocity, see
  // motion_sizing), which a modifier trading visual detail keeps.
  virtual void modify(const Mesh& mesh, const std::vector<Mat2>& motion, Attribute<FaceTag, Mat2>& face_sizing) const = 0;
  // Where the modifier knows the cloth folds finer than its final tensor `sizing` lets it show
  // (squared length ratio as in kCoarseningAttr): how much coarser than those folds the face is;
  // compute_sizing records the larger of this and the coarsening against the physical tensor.
  // 0 (the default): nothing known beyond the physical tensor.
  virtual double fold_coarsening(const Mesh& /*mesh*/, FaceId /*f*/, const Mat2& /*sizing*/) const { return 0.0; }
  // Whether the motion tensors it is given include the compression criterion (where the face
  // is not held, as in the physical tensor), not velocity alone.
  virtual bool keeps_compression() const { return false; }
};

// The criteria of one face (Narain et al. 2012, section 5), unclamped: curvature resolves the
// shape, velocity and compression (the buckles compression would form) the motion.
struct SizingCriteria {
  Mat2 curvature, velocity, compression;
};
SizingCriteria sizing_criteria(const Mesh& mesh, FaceId f, const std::vector<Vec3>& node_normals, const SizingParams& p);
// The clamped tensor of the motion criterion: velocity, and with `compression` the larger of it
// and the compression criterion. (Without it, a face coarsened below its compression criterion
// gives up compression instead, membrane.hpp.)
Mat2 motion_sizing(const SizingCriteria& c, const SizingParams& p, bool compression = false);

// The physical tensor of one face before clamping: the largest of the criteria, but for
// compression where all three nodes are held (ObstaclePlane::held: no room for the buckles it
// resolves). `planes`, by node index, may be empty (no obstacles).
Mat2 face_sizing_unclamped(const Mesh& mesh, FaceId f, const std::vector<Vec3>& node_normals, const SizingParams& p,
                           const std::vector<ObstaclePlane>& planes = {});
// Obstacle-proximity criterion (Narain et al. 2012, section 5): with h_v the heights of the
// face's nodes over the obstacle plane nearest node v, the mean over v of dh dh^T / h_v^2, so
// that along any edge the gap changes by less than the gap itself.
Mat2 obstacle_metric(const Mesh& mesh, FaceId f, const std::vector<ObstaclePlane>& planes);
// Eigenvalues clamped to [1/size_max^2, 1/size_min^2], then the smaller raised to at least
// aspect_min^2 times the larger.
Mat2 clamp_sizing(const Mat2& m, const SizingParams& p);
// The "max" of two tensors: in the eigenbasis of their sum, the larger of their quadratic
// forms along each axis (exact when they share eigenvectors, and never below either along
// those axes).
Mat2 tensor_max(const Mat2& a, const Mat2& b);
// The largest eigenvalue of m measured in the metric `in` (of in^-1/2 m in^-1/2): how many times
// longer, squared, an edge `in` allows is than the longest m allows, in the worst direction.
double metric_ratio(const Mat2& m, const Mat2& in);

// Computes face tensors (kFaceSizingAttr), lets `modifier` change them (then also writing
// kCoarseningAttr), and averages them onto verts by material area (kSizingAttr, read by remesh()),
// divided there by p.resolution_scale^2. Each face and vert on its own, on `threads` threads (the
// same field on any number).
void compute_sizing(Mesh& mesh, const SizingParams& p, const FaceSizingModifier* modifier = nullptr,
                    const std::vector<ObstaclePlane>& planes = {}, int threads = 1);

// A constant isotropic field of size h on every vert (the fixed-resolution baseline).
void set_uniform_sizing(Mesh& mesh, double h);

}  // namespace vdc
