// Measured modes from UFF dataset 55 at a model's DOFs: normal (real) and
// complex modes, each node component (node, direction) of the file mapped to a
// model DOF explicitly or by the node's coordinates (datasets 15 / 2411).
//
// Directions. Dataset 55 holds per node the components along +X, +Y, +Z (3
// values per node) and also about +X, +Y, +Z (6 values) of the node's
// displacement coordinate system: direction d = 1..6 (+X, +Y, +Z, +RX, +RY,
// +RZ) is value column d - 1. A negative direction is the reversed one: the
// model DOF is minus the component.
//
// Frequencies. A normal mode (analysis type 2) gives its frequency (Hz) and
// viscous damping ratio in record 8. A complex mode (analysis types 3 and 7)
// gives its eigenvalue lambda = sigma + i omega_d (rad/s): the undamped natural
// frequency |lambda| / (2 pi) is taken, the one an undamped model's eigenvalue
// (2 pi f)^2 stands for, and the damping ratio -sigma / |lambda|.
//
// Complex shapes (any shape with a nonzero imaginary part at the mapped DOFs)
// are made real as ERA does (femup/era.h): rotated by the e^{i theta} that
// maximises the norm of the real part (theta = -arg(psi^T psi) / 2, psi the
// shape at the mapped DOFs), the real part kept (the best real fit of psi up to
// a complex factor), its sign set so that the largest entry is positive. How
// far the shape was from real is reported: MPC = |psi^T psi|^2 / (psi^H psi)^2
// (1: monophase) and the share of |psi|^2 dropped with the imaginary part,
// (1 - sqrt(MPC)) / 2. Real shapes are kept as they are.
#pragma once

#include <Eigen/Core>
#include <complex>
#include <string>
#include <string_view>
#include <vector>

#include "femup/core/fe/structure.h"
#include "femup/core/io/uff.h"

namespace femup {

// Reads "X", "+Y", "-rz", "RX", and the UFF codes "1".."6", "-1".."-6"
// (case-insensitive) as a direction +-1..6. False when `text` is none of them.
bool ParseUffDirection(std::string_view text, int* direction);
// "+X", "-RZ", ... for +-1..6; the number otherwise.
std::string UffDirectionName(int direction);
// The DOF-label suffix of femup's frame models along direction |d| = 1..6:
// "ux", "uy", "uz", "rx", "ry", "rz".
const char* FrameDofName(int direction);

// One component of a UFF node measured as a model DOF: the DOF's value is the
// node's component along `direction` (the negative of the +component when the
// direction is negative).
struct UffSensor {
  int node = 0;
  int direction = 1;  // +-1..6
  int dof = -1;       // model DOF, 0-based
  // Where the mapping was given, for messages ("study.yaml:12:7:
  // measurements[1].uff_dofs.101:+Y"); for a node placed by coordinates, how:
  // "n3, 0.0004 m away".
  std::string source;
  std::string label;  // the DOF's label; set by ExtractUffModes
};

struct UffSkippedNode {
  int node = 0;
  std::string source;  // as UffSensor::source
};

// How the nodes of a UFF file map to model DOFs: explicit components and
// skipped nodes first; the other nodes by coordinates when `by_geometry`.
struct UffDofMap {
  std::vector<UffSensor> sensors;  // explicit: "node:direction" -> model DOF
  std::vector<UffSkippedNode> skipped;
  // Leave out the nodes that are neither mapped nor placed on a model node
  // (the study's "*": skip) rather than fail on them.
  bool skip_unmapped = false;
  // A node named by neither is matched to the model node within `tolerance`
  // (m) of its coordinates (the UFF coordinates are taken in the model's axes
  // and metres; coordinate systems are not transformed), and its components
  // along `directions` become the model DOFs "<model node>:<FrameDofName>".
  // Empty `directions`: every direction the modes hold, leaving out those the
  // model node has no DOF for (a 2D model's Z, a support).
  bool by_geometry = false;
  std::vector<UffNode> geometry;  // UffNodeCoordinates of the geometry file
  std::string geometry_file;      // for messages
  std::vector<ModelNode> model_nodes;
  double tolerance = 0;  // m, > 0
  std::vector<int> directions;
};

// One mode of dataset 55 as used.
struct UffMode {
  long long line = 0;   // line of its dataset number
  int mode_number = 0;  // record 7
  UffAnalysisType analysis_type = UffAnalysisType::kNormalMode;
  double frequency_hz = 0;
  double damping_ratio = 0;
  double mpc = 1;                 // 1 for real shapes
  double imaginary_fraction = 0;  // share of |psi|^2 dropped; 0 for real shapes
};

struct UffModes {
  std::vector<double> all_frequencies_hz;  // every mode of the file, ascending
  std::vector<int> used;                   // 1-based places in that order
  std::vector<UffMode> modes;              // the used modes, in `used` order
  std::vector<UffSensor> sensors;          // one per row of `shapes`
  Eigen::MatrixXd shapes;                  // sensors x used modes, real
};

// The real shape closest to a complex one (see above).
struct RealShape {
  Eigen::VectorXd shape;
  double mpc = 1;
  double imaginary_fraction = 0;
};
RealShape BestRealShape(const Eigen::VectorXcd& psi);

// Natural frequency (Hz) and damping ratio of a complex eigenvalue (rad/s).
// Throws InputError(where) for a zero eigenvalue.
void ComplexEigenvalueModes(std::complex<double> lambda, double* frequency_hz,
                            double* damping_ratio, const std::string& where);

// The nodes of datasets 15 and 2411 of a file, merged (a node given twice must
// have the same coordinates). Throws InputError naming `name` and the lines
// when the file has no nodes or a node is given twice at different places.
std::vector<UffNode> UffNodeCoordinates(const UffFile& file, const std::string& name);

// The modes of dataset 55 (analysis types 2, 3 and 7) of `file` (`name` in
// messages), numbered 1.. by ascending frequency, the `use`d ones (empty: all)
// at the DOFs `map` gives; `dof_labels` are the model's. Throws InputError
// naming the file, the line and what was expected when the file has no mode
// (no dataset 55, or only frequency-response shapes, analysis type 5), a used
// mode lacks a node or has other nodes than the first used one, a node of the
// modes is neither mapped nor skipped nor matched by coordinates (unless
// skip_unmapped), a node's coordinates are within the tolerance of two model
// nodes, a mapped node
// is not in the modes, a mapped direction is not in the data (3 values per
// node have no rotations), two components map to one model DOF, a frequency is
// not positive, a shape is zero at every mapped DOF, or `use` asks for a mode
// the file does not have.
UffModes ExtractUffModes(const UffFile& file, const std::string& name,
                         const UffDofMap& map, const std::vector<std::string>& dof_labels,
                         const std::vector<int>& use);

}  // namespace femup
