#include "fe/cantilever_geometry.h"

#include <array>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "femup/core/errors.h"
#include "text_util.h"

namespace femup::internal {
namespace {

std::string Str(double v) { return internal::ShortestDecimal(v); }

const char kNotCantilever[] = "not a vertical cantilever from BuildCantilever: ";

}  // namespace

std::vector<Node> CantileverNodes(const Structure& s) {
  const std::size_t n = s.dof_labels.size();
  const std::size_t num_elements = s.elements.size();
  if (num_elements == 0) {
    throw InputError("structure.elements", std::string(kNotCantilever) + "no elements");
  }
  if (s.dof_positions.size() != n) {
    throw InputError("structure.dof_positions",
                     std::string(kNotCantilever) + "has " +
                         std::to_string(s.dof_positions.size()) + " entries for " +
                         std::to_string(n) + " DOF labels");
  }
  if (static_cast<std::size_t>(s.stiffness.rows()) != n) {
    throw InputError("structure.dof_labels",
                     std::string(kNotCantilever) + "has " + std::to_string(n) +
                         " labels for " + std::to_string(s.stiffness.rows()) + " DOFs");
  }
  static const char* kNames[3] = {"ux", "uy", "rz"};
  std::vector<Node> nodes(num_elements + 1);
  for (std::size_t i = 0; i < n; ++i) {
    const std::string& label = s.dof_labels[i];
    const std::string where = "structure.dof_labels[" + std::to_string(i + 1) + "]";
    const std::size_t colon = label.find(':');
    int kind = -1;
    long node = -1;
    if (label.size() > 1 && label[0] == 'n' && colon != std::string::npos && colon > 1) {
      const std::string digits = label.substr(1, colon - 1);
      if (digits.find_first_not_of("0123456789") == std::string::npos &&
          digits.size() < 9) {
        node = std::stol(digits);
      }
      for (int k = 0; k < 3; ++k) {
        if (label.compare(colon + 1, std::string::npos, kNames[k]) == 0) kind = k;
      }
    }
    if (node < 0 || kind < 0) {
      throw InputError(where, std::string(kNotCantilever) + "label '" + label +
                                  "' is not 'n<k>:ux', 'n<k>:uy' or 'n<k>:rz'");
    }
    if (static_cast<std::size_t>(node) > num_elements) {
      throw InputError(where, std::string(kNotCantilever) + "label '" + label +
                                  "' names a node beyond the " +
                                  std::to_string(num_elements) + " elements");
    }
    Node& nd = nodes[node];
    const double z = s.dof_positions[i];
    if (nd.dof[kind] >= 0 || (nd.seen && nd.z != z)) {
      throw InputError(where, std::string(kNotCantilever) + "label '" + label +
                                  "' repeats a DOF or disagrees on the node height");
    }
    nd.seen = true;
    nd.z = z;
    nd.dof[kind] = static_cast<int>(i);
  }
  for (std::size_t e = 0; e < num_elements; ++e) {
    const ElementMatrices& el = s.elements[e];
    const std::string where = "structure.elements[" + std::to_string(e + 1) + "]";
    const double expected_x0 = e == 0 ? 0.0 : s.elements[e - 1].x1;
    if (!(el.x1 > el.x0) || !std::isfinite(el.x1) || el.x0 != expected_x0) {
      throw InputError(where, std::string(kNotCantilever) + "x0 = " + Str(el.x0) +
                                  ", x1 = " + Str(el.x1) +
                                  "; expected increasing heights from 0, each element "
                                  "starting where the one below ends");
    }
    const Node& lower = nodes[e];
    const Node& upper = nodes[e + 1];
    if ((e > 0 && !lower.seen) || !upper.seen || (lower.seen && lower.z != el.x0) ||
        upper.z != el.x1) {
      throw InputError(where, std::string(kNotCantilever) + "nodes n" +
                                  std::to_string(e) + " and n" + std::to_string(e + 1) +
                                  " do not have DOFs at x0 = " + Str(el.x0) +
                                  " and x1 = " + Str(el.x1));
    }
  }
  return nodes;
}

}  // namespace femup::internal
