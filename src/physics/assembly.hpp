// Parallel assembly of the backward-Euler system (Baraff and Witkin 1998, eq. 18, one Newton step):
//   (M + h D + h^2 K) dv = h f - h^2 K v
// with K the PSD-projected Hessian of the elastic energies, D the damping Jacobian. Elements
// are evaluated in parallel into their own buffers, then each matrix block and force gathers
// its contributions, so no two threads write one place and the sum order never changes.
#pragma once
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include <Eigen/Sparse>

#include "physics/cloth_model.hpp"
#include "physics/contact.hpp"

namespace vdc {

using SparseMatrix = Eigen::SparseMatrix<double>;  // column-major, both triangles stored

struct StepParams {
  double h = 0.005;                     // s
  Vec3 gravity = Vec3(0, -9.8, 0);      // m/s^2
  double damping = 0;                   // 1/s: force -damping m v
  double drag = 0;                      // N s/m^3: face force -drag A ((v - wind).n) n
  Vec3 wind = Vec3::Zero();             // m/s
  // Coarse cloth's missing dissipation (an extension): a face whose compression is softened
  // (a coarse face standing for folds it cannot form, membrane.hpp) takes stiffness-proportional
  // damping -beta K v on its membrane, beta = coarse_damping h (1 - compression). Backward
  // Euler damps every resolved mode as Rayleigh damping of beta = h would (zeta = omega h / 2
  // for omega h << 1), the fine cloth's folds included; the coarse face has no such modes and
  // would keep their energy in its swing. 0: off.
  double coarse_damping = 0;
  int threads = 1;
};

// Velocity change prescribed for a node over the step (handles).
struct VelocityConstraint {
  int32_t node;
  Vec3 dv;
};

class SystemAssembler {
 public:
  // `threads`: for building the pattern (the same pattern on any number).
  explicit SystemAssembler(const ClothModel& model, int threads = 1);

  void assemble(const Eigen::VectorXd& x, const Eigen::VectorXd& v, const StepParams& p);
  // Adds contact terms after assemble(). A term whose movable nodes are all neighbours in the
  // pattern adds its full block; otherwise (cloth-cloth pairs across the mesh) only its diagonal
  // blocks, which keeps the pattern fixed and the matrix positive definite.
  void add_contacts(const std::vector<ContactTerm>& terms);
  // Eliminates constrained nodes: their rows and columns become identity, rhs the prescribed dv.
  void constrain(const std::vector<VelocityConstraint>& constraints);

  const SparseMatrix& matrix() const { return a_; }
  const Eigen::VectorXd& rhs() const { return b_; }
  double elastic_energy() const { return elastic_energy_; }
  // Position in the matrix value array of entry (3 i + r, 3 j + c), or -1 if not in the pattern.
  int64_t value_index(int32_t i, int32_t j, int r, int c) const;

 private:
  // The constructor's parts: each node's neighbours (returns the number of slots), the matrix's
  // pattern, and the lists that gather element blocks into slots and element vectors into nodes.
  int32_t build_neighbours(int threads);
  void build_pattern(int32_t slots);
  void build_gather_lists(int32_t slots, int threads);
  // Where an element's local 3x3 block (a, b) lies in matrix_buffer_: the element's blocks are
  // stored one after another (block (a, b) the (b k + a)-th of its k x k), each column-major, so
  // the gather reads each block from one or two cache lines.
  using Contribution = int64_t;
  int32_t slot_of(int32_t row_node, int32_t col_node) const;
  // Node j's neighbours, sorted, j included: the rows of its column's blocks, one per slot.
  std::span<const int32_t> neighbours(int32_t j) const {
    return {slot_node_.data() + slot_start_[static_cast<std::size_t>(j)], slot_node_.data() + slot_start_[static_cast<std::size_t>(j) + 1]};
  }

  const ClothModel& model_;
  std::vector<int32_t> slot_start_;               // per node: first block slot of its column
  std::vector<int32_t> slot_node_;                // per slot: the row node of its block
  std::vector<int32_t> slot_contrib_start_;       // per slot: range in contributions_
  std::vector<Contribution> contributions_;
  std::vector<int32_t> node_force_start_;         // per node: range in force_parts_
  std::vector<int64_t> force_parts_;              // offsets of local 3-vectors in rhs_buffer_
  std::unique_ptr<double[]> matrix_buffer_;       // per element local matrices
  std::unique_ptr<double[]> rhs_buffer_;          // per element local rhs
  SparseMatrix a_;
  Eigen::VectorXd b_;
  double elastic_energy_ = 0;
};

}  // namespace vdc
