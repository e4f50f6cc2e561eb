// UFF datasets 15 and 2411 (nodes: label, coordinate systems, colour,
// coordinates): their record layouts, reading (Reader::Read15, Read2411) and
// writing (Writer::Write(const UffNodes&)).
#include <string>
#include <vector>

#include "io/uff_internal.h"

namespace femup::uff_internal {
namespace {

// Dataset 15: a node.
const std::vector<Field> kNodeFields = {{"node label", 10, true},
                                        {"definition coordinate system", 10, true},
                                        {"displacement coordinate system", 10, true},
                                        {"color", 10, true},
                                        {"X coordinate", 13, false},
                                        {"Y coordinate", 13, false},
                                        {"Z coordinate", 13, false}};

// Dataset 2411: record 1 of a node (record 2 is three coordinates, 3D25.16).
const std::vector<Field> k2411Record1 = {{"node label", 10, true},
                                         {"export coordinate system", 10, true},
                                         {"displacement coordinate system", 10, true},
                                         {"color", 10, true}};
const std::vector<Field> k2411Record2 = {{"X coordinate", 25, false},
                                         {"Y coordinate", 25, false},
                                         {"Z coordinate", 25, false}};

}  // namespace

// --- Dataset 15 -------------------------------------------------------------

UffNodes Reader::Read15() {
  UffNodes out;
  std::string_view line;
  while (NextLineBeforeEnd(&line)) {
    const auto v = NumericRecord(line, kNodeFields, "node record");
    UffNode node;
    node.label = v[0].integer;
    node.definition_cs = v[1].integer;
    node.displacement_cs = v[2].integer;
    node.color = v[3].integer;
    node.xyz = {v[4].real, v[5].real, v[6].real};
    node.line = line_;
    out.nodes.push_back(node);
  }
  return out;
}

// --- Dataset 2411 -----------------------------------------------------------

UffNodes Reader::Read2411() {
  UffNodes out;
  out.dataset = 2411;
  std::string_view line;
  while (NextLineBeforeEnd(&line)) {
    const std::string r1 = "record 1 (node " + std::to_string(out.nodes.size() + 1) + ")";
    const auto v1 = NumericRecord(line, k2411Record1, r1);
    UffNode node;
    node.label = v1[0].integer;
    node.definition_cs = v1[1].integer;
    node.displacement_cs = v1[2].integer;
    node.color = v1[3].integer;
    node.line = line_;
    const std::string r2 =
        "record 2 (coordinates of node " + std::to_string(node.label) + ")";
    const auto v2 = NumericRecord(RecordLine(r2), k2411Record2, r2);
    node.xyz = {v2[0].real, v2[1].real, v2[2].real};
    out.nodes.push_back(node);
  }
  return out;
}

// --- 15 and 2411 ---
void Writer::Write(const UffNodes& d) {
  number_ = d.dataset;
  if (d.dataset != 15 && d.dataset != 2411) {
    Fail("dataset " + std::to_string(d.dataset) + ": nodes are written as 15 or 2411");
  }
  for (size_t k = 0; k < d.nodes.size(); ++k) {
    const UffNode& node = d.nodes[k];
    const std::string where = "node " + std::to_string(k + 1);
    Int(node.label, 10, where + " label");
    Int(node.definition_cs, 10, where + " definition coordinate system");
    Int(node.displacement_cs, 10, where + " displacement coordinate system");
    Int(node.color, 10, where + " color");
    for (int c = 0; c < 3; ++c)
      Real(node.xyz[static_cast<size_t>(c)], where + " coordinates");
  }
  Begin(d.dataset);
  out_ += std::string(74, ' ') + "\n";
  for (const UffNode& node : d.nodes) {
    if (d.dataset == 15) {
      AppendF(&out_, "%10d%10d%10d%10d%13.5E%13.5E%13.5E\n", node.label,
              node.definition_cs, node.displacement_cs, node.color, node.xyz[0],
              node.xyz[1], node.xyz[2]);
    } else {
      AppendF(&out_, "%10d%10d%10d%10d\n%25.16E%25.16E%25.16E\n", node.label,
              node.definition_cs, node.displacement_cs, node.color, node.xyz[0],
              node.xyz[1], node.xyz[2]);
    }
  }
  End();
}

}  // namespace femup::uff_internal
