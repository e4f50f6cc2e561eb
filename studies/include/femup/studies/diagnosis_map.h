// The diagnosis map: the structure drawn to scale with the probability of each
// local explanation where it lies — a stiffness loss on its element, an
// attached mass at its node, a softer support at the supports — so a reader
// sees at a glance where the gap is and how sure the diagnosis is. Global
// explanations (material scaling, added mass, none) are named in the title.
#pragma once

#include <string>
#include <vector>

#include "femup/core/fe/structure.h"
#include "femup/studies/effect_ranking.h"

namespace femup {

struct DiagnosisMap {
  struct Element {
    std::string region;  // as the ranking names it: "element s1:beam1"
    // Its segments, each from (x[2i], y[2i]) to (x[2i+1], y[2i+1]): the pairs
    // of nodes its stiffness couples (a member: node to node along it; a
    // group of members: each of them).
    std::vector<double> x, y;
  };
  struct Node {
    std::string region;  // "node n7"
    double x = 0, y = 0;
  };
  std::vector<Element> elements;
  std::vector<Node> nodes;
  std::vector<Node> supports;  // the nodes the support springs act on
  // true: drawn from the nodes' coordinates; false: a chain or a model without
  // coordinates, drawn as a column (element k from height k - 1 to k).
  bool to_scale = false;
  bool empty() const { return elements.empty(); }
};

// The geometry of `structure` as the map draws it: each element as the
// segments between the nodes its stiffness couples (coordinates in the x-y
// plane, or x-z when the model is 3D; a vertical member whose foot is a rigid
// support, which has no DOF, reaches down to its start height), each member's
// end connections (Structure::connections) as stubs from its joints a quarter
// of the way along its end elements, the nodes with DOFs, support nodes.
DiagnosisMap MapGeometry(const Structure& structure);

}  // namespace femup
