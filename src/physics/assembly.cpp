// Backward-Euler system assembly (Baraff and Witkin 1998, eq. 18), gathered in parallel.
#include "physics/assembly.hpp"

#include <algorithm>
#include <array>
#include <memory>
#include <span>

#include "core/task_order.hpp"

namespace vdc {

namespace {

constexpr int64_t kFaceMat = 81, kBendMat = 144, kFaceVec = 9, kBendVec = 12;

template <int N>
std::array<Vec3, N / 3> gather_positions(const Eigen::VectorXd& x, const std::array<int32_t, N / 3>& nodes) {
  std::array<Vec3, N / 3> out;
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = x.segment<3>(3 * nodes[i]);
  return out;
}

template <int N>
VecN<N> gather(const Eigen::VectorXd& v, const std::array<int32_t, N / 3>& nodes) {
  VecN<N> out;
  for (std::size_t i = 0; i < nodes.size(); ++i) out.template segment<3>(3 * static_cast<int>(i)) = v.segment<3>(3 * nodes[i]);
  return out;
}

// A local matrix of k x k nodes stored block by block (SystemAssembler::Contribution).
template <int K>
void store_blocks(const MatN<3 * K>& local, double* out) {
  for (int b = 0; b < K; ++b)
    for (int a = 0; a < K; ++a) Eigen::Map<Mat3>(out + 9 * (b * K + a)) = local.template block<3, 3>(3 * a, 3 * b);
}

}  // namespace

SystemAssembler::SystemAssembler(const ClothModel& model, int threads) : model_(model) {
  const int32_t slots = build_neighbours(threads);
  build_pattern(slots);
  build_gather_lists(slots, threads);
}

int32_t SystemAssembler::build_neighbours(int threads) {
  const ClothModel& model = model_;
  const int32_t n = model.num_nodes;
  // Each node's neighbours (itself and the nodes it shares an element with) in one flat array:
  // counted, filled, then each node's run sorted, made unique and packed forward in place.
  slot_start_.assign(static_cast<std::size_t>(n) + 1, 1);
  slot_start_[0] = 0;
  auto count = [&](const auto& nodes) {
    for (int32_t a : nodes) slot_start_[static_cast<std::size_t>(a) + 1] += static_cast<int32_t>(nodes.size()) - 1;
  };
  for (const auto& f : model.face_nodes) count(f);
  for (const auto& b : model.bend_nodes) count(b);
  for (int32_t i = 0; i < n; ++i) slot_start_[static_cast<std::size_t>(i) + 1] += slot_start_[static_cast<std::size_t>(i)];
  slot_node_.resize(static_cast<std::size_t>(slot_start_.back()));
  std::vector<int32_t> next(slot_start_.begin(), slot_start_.end() - 1);
  for (int32_t i = 0; i < n; ++i) slot_node_[static_cast<std::size_t>(next[static_cast<std::size_t>(i)]++)] = i;
  auto link = [&](const auto& nodes) {
    for (int32_t a : nodes)
      for (int32_t b : nodes)
        if (a != b) slot_node_[static_cast<std::size_t>(next[static_cast<std::size_t>(a)]++)] = b;
  };
  for (const auto& f : model.face_nodes) link(f);
  for (const auto& b : model.bend_nodes) link(b);
  std::vector<int32_t> kept(static_cast<std::size_t>(n));
  auto sort_run = [&](int32_t i) {
    const auto begin = slot_node_.begin() + slot_start_[static_cast<std::size_t>(i)];
    const auto end = slot_node_.begin() + slot_start_[static_cast<std::size_t>(i) + 1];
    std::sort(begin, end);
    kept[static_cast<std::size_t>(i)] = static_cast<int32_t>(std::unique(begin, end) - begin);
  };
  for_each_index(n, threads, [&](int64_t i) { sort_run(static_cast<int32_t>(i)); });
  int32_t packed = 0;
  for (int32_t i = 0; i < n; ++i) {
    const auto begin = slot_node_.begin() + slot_start_[static_cast<std::size_t>(i)];
    const auto to = slot_node_.begin() + packed;
    if (to != begin) std::copy(begin, begin + kept[static_cast<std::size_t>(i)], to);  // packs forward: `to` is never after `begin`
    slot_start_[static_cast<std::size_t>(i)] = packed;
    packed += kept[static_cast<std::size_t>(i)];
  }
  slot_start_[static_cast<std::size_t>(n)] = packed;
  slot_node_.resize(static_cast<std::size_t>(packed));
  slot_node_.shrink_to_fit();
  return packed;
}

// Matrix pattern: scalar column 3j+c holds rows 3i+r for each neighbour i of j.
void SystemAssembler::build_pattern(int32_t slots) {
  const int32_t n = model_.num_nodes;
  const int64_t dim = 3 * static_cast<int64_t>(n);
  a_.resize(dim, dim);
  a_.resizeNonZeros(9 * static_cast<int64_t>(slots));
  auto* outer = a_.outerIndexPtr();
  auto* inner = a_.innerIndexPtr();
  int64_t pos = 0;
  for (int32_t j = 0; j < n; ++j)
    for (int c = 0; c < 3; ++c) {
      outer[3 * j + c] = static_cast<int>(pos);
      for (int32_t i : neighbours(j))
        for (int r = 0; r < 3; ++r) inner[pos++] = 3 * i + r;
    }
  outer[dim] = static_cast<int>(pos);
  std::fill(a_.valuePtr(), a_.valuePtr() + pos, 0.0);
  b_.setZero(dim);
}

// Gather lists: which element blocks and vectors land in each slot and node.
void SystemAssembler::build_gather_lists(int32_t slots, int threads) {
  const ClothModel& model = model_;
  const int32_t n = model.num_nodes;
  const auto nf = static_cast<int64_t>(model.face_nodes.size());
  const auto ne = static_cast<int64_t>(model.bend_nodes.size());
  // Left uninitialised: assemble() writes every element's local matrix and vector in full, and its
  // threads touch the pages first.
  matrix_buffer_ = std::make_unique_for_overwrite<double[]>(static_cast<std::size_t>(nf * kFaceMat + ne * kBendMat));
  rhs_buffer_ = std::make_unique_for_overwrite<double[]>(static_cast<std::size_t>(nf * kFaceVec + ne * kBendVec));
  // Each element block (a, b) lands in one slot, each element vector part in one node; the
  // lists are bucketed by slot and node in element order (a counting sort: stable and linear).
  slot_contrib_start_.assign(static_cast<std::size_t>(slots) + 1, 0);
  node_force_start_.assign(static_cast<std::size_t>(n) + 1, 0);
  auto for_each_element = [&](auto&& visit) {
    for (int64_t f = 0; f < nf; ++f) visit(model.face_nodes[static_cast<std::size_t>(f)], f * kFaceMat, f * kFaceVec);
    for (int64_t e = 0; e < ne; ++e)
      visit(model.bend_nodes[static_cast<std::size_t>(e)], nf * kFaceMat + e * kBendMat, nf * kFaceVec + e * kBendVec);
  };
  // The slot of every block, in visiting order (9 a face, then 16 a bending element), looked up
  // in parallel.
  std::vector<int32_t> element_slots(static_cast<std::size_t>(9 * nf + 16 * ne));
  auto find_slots = [&](const auto& nodes, int32_t* out) {
    for (int32_t a : nodes)
      for (int32_t b : nodes) *out++ = slot_of(a, b);
  };
  auto find_element_slots = [&](int64_t k) {
    if (k < nf) find_slots(model.face_nodes[static_cast<std::size_t>(k)], element_slots.data() + 9 * k);
    else find_slots(model.bend_nodes[static_cast<std::size_t>(k - nf)], element_slots.data() + 9 * nf + 16 * (k - nf));
  };
  for_each_index(nf + ne, threads, find_element_slots);
  for (const int32_t s : element_slots) ++slot_contrib_start_[static_cast<std::size_t>(s) + 1];
  for_each_element([&](const auto& nodes, int64_t, int64_t) {
    for (int32_t a : nodes) ++node_force_start_[static_cast<std::size_t>(a) + 1];
  });
  for (int32_t s = 0; s < slots; ++s) slot_contrib_start_[static_cast<std::size_t>(s) + 1] += slot_contrib_start_[static_cast<std::size_t>(s)];
  for (int32_t i = 0; i < n; ++i) node_force_start_[static_cast<std::size_t>(i) + 1] += node_force_start_[static_cast<std::size_t>(i)];
  contributions_.resize(element_slots.size());
  force_parts_.resize(static_cast<std::size_t>(node_force_start_.back()));
  std::vector<int32_t> slot_fill(slot_contrib_start_.begin(), slot_contrib_start_.end() - 1);
  std::vector<int32_t> node_fill(node_force_start_.begin(), node_force_start_.end() - 1);
  std::size_t visited = 0;
  for_each_element([&](const auto& nodes, int64_t mat_offset, int64_t vec_offset) {
    const int k = static_cast<int>(nodes.size());
    for (int a = 0; a < k; ++a) {
      force_parts_[static_cast<std::size_t>(node_fill[static_cast<std::size_t>(nodes[static_cast<std::size_t>(a)])]++)] = vec_offset + 3 * a;
      for (int b = 0; b < k; ++b) {
        const int32_t s = element_slots[visited++];
        contributions_[static_cast<std::size_t>(slot_fill[static_cast<std::size_t>(s)]++)] = mat_offset + 9 * static_cast<int64_t>(b * k + a);
      }
    }
  });
}

int32_t SystemAssembler::slot_of(int32_t row_node, int32_t col_node) const {
  const std::span<const int32_t> nb = neighbours(col_node);
  auto it = std::lower_bound(nb.begin(), nb.end(), row_node);
  if (it == nb.end() || *it != row_node) return -1;
  return slot_start_[static_cast<std::size_t>(col_node)] + static_cast<int32_t>(it - nb.begin());
}

int64_t SystemAssembler::value_index(int32_t i, int32_t j, int r, int c) const {
  int32_t s = slot_of(i, j);
  if (s < 0) return -1;
  int32_t k = s - slot_start_[static_cast<std::size_t>(j)];
  return a_.outerIndexPtr()[3 * j + c] + 3 * k + r;
}

// How many contributions ahead the gather fetches element blocks.
constexpr int32_t kGatherAhead = 12;

void SystemAssembler::assemble(const Eigen::VectorXd& x, const Eigen::VectorXd& v, const StepParams& p) {
  const double h = p.h, h2 = p.h * p.h;
  const auto nf = static_cast<int64_t>(model_.face_nodes.size());
  const auto ne = static_cast<int64_t>(model_.bend_nodes.size());
  double energy = 0;

#pragma omp parallel num_threads(p.threads) reduction(+ : energy)
  {
#pragma omp for schedule(static)
    for (int64_t f = 0; f < nf; ++f) {
      const auto& nodes = model_.face_nodes[static_cast<std::size_t>(f)];
      TriStencil xs = gather_positions<9>(x, nodes);
      MembraneEval m = membrane_eval(xs, model_.membranes[static_cast<std::size_t>(f)]);
      energy += m.energy;
      VecN<9> vl = gather<9>(v, nodes);
      MatN<9> local = h2 * m.hessian;
      const VecN<9> kv = m.hessian * vl;
      VecN<9> rhs = -h * m.gradient - h2 * kv;
      const double compression = model_.membranes[static_cast<std::size_t>(f)].compression;
      if (p.coarse_damping > 0 && compression < 1) {
        // StepParams::coarse_damping: D = beta K in (M + h D + h^2 K) dv = h (f - D v) - h^2 K v.
        const double beta = p.coarse_damping * h * (1 - compression);
        local += h * beta * m.hessian;
        rhs -= h * beta * kv;
      }
      if (p.drag > 0) {
        // Air drag on the face normal, linear in the face's mean velocity relative to the wind.
        Vec3 an = area_normal(xs[0], xs[1], xs[2]);
        double area = 0.5 * an.norm();
        if (area > 0) {
          Vec3 nrm = an / (2 * area);
          Vec3 vmean = (vl.segment<3>(0) + vl.segment<3>(3) + vl.segment<3>(6)) / 3.0;
          Vec3 force = -p.drag * area * (vmean - p.wind).dot(nrm) * nrm / 3.0;
          Mat3 d = (p.drag * area / 9.0) * nrm * nrm.transpose();
          for (int a = 0; a < 3; ++a) {
            rhs.segment<3>(3 * a) += h * force;
            for (int b = 0; b < 3; ++b) local.block<3, 3>(3 * a, 3 * b) += h * d;
          }
        }
      }
      store_blocks<3>(local, matrix_buffer_.get() + f * kFaceMat);
      std::copy(rhs.data(), rhs.data() + kFaceVec, rhs_buffer_.get() + f * kFaceVec);
    }
#pragma omp for schedule(static)
    for (int64_t e = 0; e < ne; ++e) {
      const auto& nodes = model_.bend_nodes[static_cast<std::size_t>(e)];
      BendingEval b = bending_eval(gather_positions<12>(x, nodes), model_.bends[static_cast<std::size_t>(e)]);
      energy += b.energy;
      VecN<12> vl = gather<12>(v, nodes);
      MatN<12> local = h2 * b.hessian;
      VecN<12> rhs = -h * b.gradient - h2 * (b.hessian * vl);
      store_blocks<4>(local, matrix_buffer_.get() + nf * kFaceMat + e * kBendMat);
      std::copy(rhs.data(), rhs.data() + kBendVec, rhs_buffer_.get() + nf * kFaceVec + e * kBendVec);
    }
    // The gather: each slot's blocks (each node's force parts) lie scattered over the element
    // buffers, so those a few contributions ahead are fetched while these are summed (the same
    // sums in the same order).
    const auto num_contributions = static_cast<int32_t>(contributions_.size());
    const auto num_force_parts = static_cast<int32_t>(force_parts_.size());
    auto fetch_ahead = [&](int32_t q) {
      if (q + kGatherAhead < num_contributions) {
        const double* block = matrix_buffer_.get() + contributions_[static_cast<std::size_t>(q + kGatherAhead)];
        __builtin_prefetch(block);
        __builtin_prefetch(block + 8);
      }
    };
#pragma omp for schedule(static)
    for (int32_t j = 0; j < model_.num_nodes; ++j) {
      const std::span<const int32_t> nb = neighbours(j);
      for (std::size_t k = 0; k < nb.size(); ++k) {
        const int32_t s = slot_start_[static_cast<std::size_t>(j)] + static_cast<int32_t>(k);
        Mat3 block = Mat3::Zero();
        for (int32_t q = slot_contrib_start_[static_cast<std::size_t>(s)]; q < slot_contrib_start_[static_cast<std::size_t>(s) + 1]; ++q) {
          fetch_ahead(q);
          block += Eigen::Map<const Mat3>(matrix_buffer_.get() + contributions_[static_cast<std::size_t>(q)]);
        }
        if (nb[k] == j) block.diagonal().array() += model_.node_mass[static_cast<std::size_t>(j)] * (1.0 + h * p.damping);
        for (int c = 0; c < 3; ++c)
          for (int r = 0; r < 3; ++r) a_.valuePtr()[a_.outerIndexPtr()[3 * j + c] + 3 * static_cast<int64_t>(k) + r] = block(r, c);
      }
      const double mass = model_.node_mass[static_cast<std::size_t>(j)];
      Vec3 rhs = h * mass * (p.gravity - p.damping * v.segment<3>(3 * j));
      for (int32_t q = node_force_start_[static_cast<std::size_t>(j)]; q < node_force_start_[static_cast<std::size_t>(j) + 1]; ++q) {
        if (q + kGatherAhead < num_force_parts) __builtin_prefetch(rhs_buffer_.get() + force_parts_[static_cast<std::size_t>(q + kGatherAhead)]);
        rhs += Eigen::Map<const Vec3>(rhs_buffer_.get() + force_parts_[static_cast<std::size_t>(q)]);
      }
      b_.segment<3>(3 * j) = rhs;
    }
  }
  elastic_energy_ = energy;
}

void SystemAssembler::add_contacts(const std::vector<ContactTerm>& terms) {
  double* val = a_.valuePtr();
  const auto* outer = a_.outerIndexPtr();
  for (const ContactTerm& t : terms) {
    // Each block's slot looked up once (block (i, j) is column j's neighbour i).
    std::array<int32_t, 16> slot{};
    bool coupled = true;
    for (std::size_t a = 0; a < 4; ++a)
      for (std::size_t b = 0; b < 4; ++b)
        if (t.nodes[a] >= 0 && t.nodes[b] >= 0) {
          slot[4 * a + b] = slot_of(t.nodes[a], t.nodes[b]);
          if (slot[4 * a + b] < 0) coupled = false;
        }
    for (std::size_t a = 0; a < 4; ++a) {
      const int32_t i = t.nodes[a];
      if (i < 0) continue;
      b_.segment<3>(3 * i) += t.weights[a] * t.rhs;
      for (std::size_t b = 0; b < 4; ++b) {
        const int32_t j = t.nodes[b];
        if (j < 0 || (!coupled && j != i)) continue;
        const Mat3 block = t.weights[a] * t.weights[b] * t.block;
        const int64_t k = slot[4 * a + b] - slot_start_[static_cast<std::size_t>(j)];
        for (int c = 0; c < 3; ++c)
          for (int r = 0; r < 3; ++r) val[outer[3 * j + c] + 3 * k + r] += block(r, c);
      }
    }
  }
}

void SystemAssembler::constrain(const std::vector<VelocityConstraint>& constraints) {
  double* val = a_.valuePtr();
  for (const auto& con : constraints) {
    const int32_t c = con.node;
    for (int32_t i : neighbours(c)) {
      for (int cc = 0; cc < 3; ++cc)
        for (int r = 0; r < 3; ++r) {
          int64_t below = value_index(i, c, r, cc);  // block (i, c)
          int64_t right = value_index(c, i, cc, r);  // its mirror (c, i)
          if (i != c) b_[3 * i + r] -= val[below] * con.dv[cc];
          val[below] = 0.0;
          val[right] = 0.0;
        }
    }
    for (int r = 0; r < 3; ++r) {
      val[value_index(c, c, r, r)] = 1.0;
      b_[3 * c + r] = con.dv[r];
    }
  }
}

}  // namespace vdc
