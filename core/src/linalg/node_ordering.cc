#include "femup/core/linalg/node_ordering.h"

#include <algorithm>
#include <string>
#include <unordered_map>

namespace femup {

std::vector<int> DofNodesFromLabels(const std::vector<std::string>& dof_labels) {
  std::unordered_map<std::string, int> ids;
  std::vector<int> node(dof_labels.size());
  for (std::size_t i = 0; i < dof_labels.size(); ++i) {
    const std::string& label = dof_labels[i];
    const std::size_t colon = label.find(':');
    // '\n' cannot appear in a node's name: a label without ':' never shares.
    const std::string key = colon == std::string::npos ? label + "\n" + std::to_string(i)
                                                       : label.substr(0, colon);
    node[i] = ids.emplace(key, static_cast<int>(ids.size())).first->second;
  }
  return node;
}

EigenOptions WithNodeOrdering(EigenOptions options,
                              const std::vector<std::string>& dof_labels, int min_dofs) {
  if (dof_labels.size() < static_cast<std::size_t>(std::max(min_dofs, 0))) return options;
  std::vector<int> nodes = DofNodesFromLabels(dof_labels);
  int distinct = 0;
  for (int n : nodes) distinct = std::max(distinct, n + 1);
  if (distinct < static_cast<int>(nodes.size())) options.dof_groups = std::move(nodes);
  return options;
}

}  // namespace femup
