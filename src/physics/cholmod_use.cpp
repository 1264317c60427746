// METIS orderings of node graphs for CHOLMOD.
#include "physics/cholmod_use.hpp"

namespace vdc {

void node_graph(const Eigen::SparseMatrix<double>& a, Eigen::Index start, Eigen::Index size, std::vector<int>& col_start,
                std::vector<int>& rows) {
  const auto n = static_cast<std::size_t>(size / 3);
  const auto* outer = a.outerIndexPtr();
  const auto* inner = a.innerIndexPtr();
  col_start.assign(n + 1, 0);
  rows.clear();
  for (std::size_t j = 0; j < n; ++j) {
    const Eigen::Index column = start + 3 * static_cast<Eigen::Index>(j);
    for (auto k = outer[column]; k < (a.isCompressed() ? outer[column + 1] : outer[column] + a.innerNonZeroPtr()[column]); ++k)
      if ((inner[k] - start) % 3 == 0) rows.push_back(static_cast<int>((inner[k] - start) / 3));
    col_start[j + 1] = static_cast<int>(rows.size());
  }
}

cholmod_sparse node_graph_view(std::vector<int>& col_start, std::vector<int>& rows) {
  const std::size_t n = col_start.size() - 1;
  cholmod_sparse g{};
  g.nrow = g.ncol = n;
  g.nzmax = rows.size();
  g.p = col_start.data();
  g.i = rows.data();
  g.stype = 1;  // symmetric, upper part used
  g.itype = CHOLMOD_INT;
  g.xtype = CHOLMOD_PATTERN;
  g.dtype = CHOLMOD_DOUBLE;
  g.sorted = 1;
  g.packed = 1;
  return g;
}

bool metis_node_order(std::vector<int>& col_start, std::vector<int>& rows, std::vector<int>& node_perm, cholmod_common& common) {
  cholmod_sparse g = node_graph_view(col_start, rows);
  node_perm.assign(col_start.size() - 1, 0);
  const MetisTurn turn;
  return cholmod_metis(&g, nullptr, 0, 1, node_perm.data(), &common) != 0;
}

}  // namespace vdc
