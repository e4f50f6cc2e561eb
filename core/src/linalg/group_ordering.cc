#include "linalg/group_ordering.h"

#include <algorithm>
#include <cstddef>
#include <utility>

namespace femup::internal {

cholmod_sparse CholmodLowerView(int rows, int* p, int* i, double* x) {
  cholmod_sparse a{};
  a.nrow = a.ncol = static_cast<std::size_t>(rows);
  a.nzmax = std::max<std::size_t>(static_cast<std::size_t>(p[rows]), 1);
  a.p = p;
  a.i = i;
  a.x = x;
  a.stype = -1;
  a.itype = CHOLMOD_INT;
  a.xtype = x == nullptr ? CHOLMOD_PATTERN : CHOLMOD_REAL;
  a.dtype = CHOLMOD_DOUBLE;
  a.sorted = 1;
  a.packed = 1;
  return a;
}

std::mutex& MetisMutex() {
  static std::mutex mutex;
  return mutex;
}

std::vector<int> GroupOrdering(const SparseMatrix& lower, const std::vector<int>& groups,
                               cholmod_common* common) {
  const int n = static_cast<int>(lower.rows());
  const int count =
      groups.empty() ? 0 : *std::max_element(groups.begin(), groups.end()) + 1;
  // The groups' graph: an edge (lower group, higher group) per coupling.
  std::vector<std::pair<int, int>> edges;
  edges.reserve(static_cast<std::size_t>(lower.nonZeros()));
  for (int j = 0; j < n; ++j) {
    for (SparseMatrix::InnerIterator it(lower, j); it; ++it) {
      const int a = groups[static_cast<std::size_t>(it.row())];
      const int b = groups[static_cast<std::size_t>(j)];
      if (a != b) edges.emplace_back(std::max(a, b), std::min(a, b));
    }
  }
  std::sort(edges.begin(), edges.end(), [](const auto& x, const auto& y) {
    return x.second != y.second ? x.second < y.second : x.first < y.first;
  });
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  // Compressed columns of the strictly lower triangle, pattern only.
  std::vector<int> p(static_cast<std::size_t>(count) + 1, 0), i(edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e) {
    ++p[static_cast<std::size_t>(edges[e].second) + 1];
    i[e] = edges[e].first;
  }
  for (int c = 0; c < count; ++c) p[c + 1] += p[c];
  cholmod_sparse graph = CholmodLowerView(count, p.data(), i.data(), nullptr);
  std::vector<int> group_order(static_cast<std::size_t>(count));
  if (count == 0) return {};
  {
    const std::lock_guard<std::mutex> lock(MetisMutex());
    if (!cholmod_metis(&graph, nullptr, 0, 0, group_order.data(), common)) return {};
  }
  // Rows by group, ascending within each.
  std::vector<int> start(static_cast<std::size_t>(count) + 1, 0);
  for (int g : groups) ++start[static_cast<std::size_t>(g) + 1];
  for (int c = 0; c < count; ++c) start[c + 1] += start[c];
  std::vector<int> by_group(static_cast<std::size_t>(n));
  {
    std::vector<int> next(start.begin(), start.end() - 1);
    for (int r = 0; r < n; ++r) by_group[next[groups[r]]++] = r;
  }
  std::vector<int> perm;
  perm.reserve(static_cast<std::size_t>(n));
  for (int g : group_order) {
    perm.insert(perm.end(), by_group.begin() + start[g], by_group.begin() + start[g + 1]);
  }
  return perm;
}

}  // namespace femup::internal
