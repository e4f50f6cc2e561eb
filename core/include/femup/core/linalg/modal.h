// Modal analysis: the generalised symmetric eigenproblem K phi = lambda M phi,
// mass normalisation, the modal assurance criterion (MAC) and mode pairing.
#pragma once

#include <string>
#include <vector>

#include "femup/core/fe/model.h"
#include "femup/core/invalid.h"

namespace femup {

struct Modes {
  Eigen::VectorXd eigenvalues;  // lambda = omega^2 (rad^2/s^2), ascending
  Eigen::MatrixXd shapes;       // num_dofs x num_modes, columns M-normalised
  int size() const { return static_cast<int>(eigenvalues.size()); }
  Eigen::VectorXd FrequenciesHz() const;  // sqrt(lambda) / 2 pi (0 for lambda < 0)
};

struct EigenOptions {
  enum class Method { kAuto, kDense, kSparseShiftInvert };
  Method method = Method::kAuto;
  int num_modes = -1;        // -1: all (dense only); sparse needs 1 <= k < n
  int dense_limit = 1500;    // kAuto uses dense at or below this many DOFs
  double shift = 0.0;        // sparse: modes nearest this eigenvalue (rad^2/s^2)
  double tolerance = 1e-10;  // sparse: Krylov convergence tolerance
  int max_iterations = 1000;
  // sparse: threads for the two factorisations that are independent of each
  // other (M's, which checks that it is positive definite, and K - shift*M's)
  // on models of 10^4 DOFs or more; 0 = DefaultThreadCount(),
  // 1 = one after the other. The modes are the same bits whatever it is.
  int threads = 0;
  // sparse: empty, or the node of each DOF (ParametrisedModel::DofNodes()): the
  // fill-reducing ordering is then a nested dissection of the node graph,
  // several times faster than one of the DOF graph for about the same fill.
  // A size other than the matrices' or a negative entry: InputError.
  std::vector<int> dof_groups;
  // Ok when valid, otherwise the field and what is wrong. The messages name
  // the field too ("num_modes must be ..."): callers show the message alone.
  Invalid Validate() const;
};

// What became of an eigen-solve on valid input: the modes, or why the
// numerical method failed (the dense solver or shift-invert Lanczos did not
// converge, a mode came out with no positive modal mass), with what to change.
struct EigenSolution {
  Modes modes;          // empty unless ok()
  std::string failure;  // empty when ok
  bool ok() const { return failure.empty(); }
};

// Lowest modes of (K, M), M-normalised, with the sign fixed so that the entry of
// largest magnitude is positive. Throws InputError for unusable input (sizes
// differ, invalid options, a non-finite entry, M not positive definite, K -
// shift*M singular at the shift); a numerical failure is the solution's status.
EigenSolution TrySolveModes(const SparseMatrix& stiffness, const SparseMatrix& mass,
                            const EigenOptions& options = {});

// TrySolveModes for callers that cannot go on without the modes: a numerical
// failure throws NumericalError (errors.h), input errors InputError.
Modes SolveModes(const SparseMatrix& stiffness, const SparseMatrix& mass,
                 const EigenOptions& options = {});

// Scales each column of `shapes` so that phi' M phi = 1.
void MassNormalise(const SparseMatrix& mass, Eigen::MatrixXd* shapes);

// MAC(a, b) = (a'b)^2 / ((a'a)(b'b)), in [0, 1]; 0 when either is zero.
double Mac(const Eigen::VectorXd& a, const Eigen::VectorXd& b);
// MAC of every column of a against every column of b.
Eigen::MatrixXd MacMatrix(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b);

struct ModePair {
  int reference = -1;  // column in the reference set
  int candidate = -1;  // matched column in the candidate set
  double mac = 0;
};
// Pairs each reference mode with a distinct candidate, taking the largest
// remaining MAC first; pairs with MAC below `min_mac` are left unpaired
// (candidate = -1). Result is in reference order.
std::vector<ModePair> PairModesByMac(const Eigen::MatrixXd& reference,
                                     const Eigen::MatrixXd& candidate,
                                     double min_mac = 0.0);
// As PairModesByMac, on a MAC matrix already computed (references x
// candidates), except where the shapes cannot tell candidates apart: when a
// reference's best remaining candidate is taken, every remaining candidate
// whose shape misfit (shape_misfit, in noise units squared, e.g. the weighted
// least-squares residual of the scaled shapes) is within `tie` of that one's
// competes, and the one of least shape_misfit + frequency_misfit is paired.
// Two modes a few sensors see alike (two vertical beam modes read at one
// point) are paired by their frequencies, not by the noise in their MACs.
// `tie` >= 0; 0 is PairModesByMac. Result in reference order; ModePair::mac
// is the pair's MAC.
std::vector<ModePair> PairModesByMacAndMisfit(const Eigen::MatrixXd& mac,
                                              const Eigen::MatrixXd& shape_misfit,
                                              const Eigen::MatrixXd& frequency_misfit,
                                              double min_mac, double tie);
// Eigenvalues this close (relative) are one repeated eigenvalue: a symmetric
// structure's pairs (a square jacket's sway modes in x and y) come out of the
// eigensolver equal to about 1e-12, with eigenvectors in an arbitrary rotation
// of their eigenspace that depends on the machine's rounding.
constexpr double kRepeatedEigenvalueTolerance = 1e-6;

// The last mode of the repeated eigenvalue that starts at mode `first`:
// `first` itself where the next eigenvalue is not within `tolerance`
// (relative) of it.
Eigen::Index LastOfRepeated(const Modes& modes, Eigen::Index first,
                            double tolerance = kRepeatedEigenvalueTolerance);

// Before pairing `modes` with the columns of `reference` by MAC: within each
// repeated eigenvalue's eigenspace, the eigensolver's vectors are replaced by
// the combinations that best match the reference shapes that eigenspace
// reproduces best (at least as well as any single mode outside it), up to its
// dimension, and the rest of the eigenspace completes the set. An orthogonal
// turn within each eigenspace, so the shapes stay M-orthonormal eigenvectors.
// `seen` is modes->shapes where `reference` is read (at sensors, on another
// model's DOFs): one column per mode, reference.rows() rows. Without this,
// MAC pairing meets an arbitrary rotation of each pair (MAC about 0.5 each at
// 45 degrees), and modes go to other modes. An eigenspace that may extend
// beyond the modes given (it holds the last one) is left as it is.
void AlignRepeatedModes(const Eigen::MatrixXd& reference, const Eigen::MatrixXd& seen,
                        Modes* modes, double tolerance = kRepeatedEigenvalueTolerance);

// Pairs each reference mode with a distinct candidate keeping the order: when
// reference i < j are both paired, candidate(i) < candidate(j). Among such
// pairings it pairs as many as it can and, of those, maximises the sum of MACs
// (dynamic programming, O(references x candidates)). For structures whose modes
// keep their order under any change of mass and stiffness, such as a beam in
// bending (each mode has one more node than the one below), with the reference
// modes listed in ascending frequency. Result is in reference order.
std::vector<ModePair> PairModesInOrder(const Eigen::MatrixXd& reference,
                                       const Eigen::MatrixXd& candidate);

}  // namespace femup
