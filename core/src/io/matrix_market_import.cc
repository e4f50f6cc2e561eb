// Import of a model made of Matrix Market files (ImportMatrixMarketStructure):
// global and element matrices read and checked against each other, elements
// taken to global DOFs, missing global matrices summed from the elements.
#include <algorithm>
#include <array>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "femup/core/errors.h"
#include "femup/core/io/matrix_market.h"
#include "io/matrix_market_internal.h"

namespace femup {
namespace matrix_market_internal {

std::string SizeText(const SparseMatrix& a) {
  return std::to_string(a.rows()) + " x " + std::to_string(a.cols());
}

}  // namespace matrix_market_internal

namespace {

using Triplet = Eigen::Triplet<double>;
using matrix_market_internal::SizeText;

// ---------------------------------------------------------------------------
// Import helpers.

// An InputError from the reader, prefixed with the spec field that named the file.
[[noreturn]] void Rethrow(const InputError& error, const std::string& field) {
  std::string what = error.what();
  const std::string prefix = error.where() + ": ";
  if (what.compare(0, prefix.size(), prefix) == 0) what.erase(0, prefix.size());
  throw InputError(field + ": " + error.where(), what);
}

std::string Resolve(const std::string& file, const std::string& base_dir) {
  const std::filesystem::path path(file);
  if (path.is_absolute() || base_dir.empty()) return path.string();
  return (std::filesystem::path(base_dir) / path).string();
}

// Reads a symmetric square matrix named by `field`.
SparseMatrix ReadSymmetric(const std::string& path, const std::string& field) {
  SparseMatrix a;
  try {
    a = ReadMatrixMarket(path);
  } catch (const InputError& error) {
    Rethrow(error, field);
  }
  if (a.rows() != a.cols()) {
    throw InputError(field + ": " + path,
                     "matrix is " + SizeText(a) + ", expected a square matrix");
  }
  if (!IsSymmetric(a)) {
    throw InputError(field + ": " + path,
                     "matrix is not symmetric (to a relative tolerance of 1e-10)");
  }
  return a;
}

// One matrix file of an element, as stored (local or global DOFs).
struct ElementFile {
  const char* name;  // the spec field: "stiffness_file", ...
  std::string path;  // resolved; empty when the spec names no file
  SparseMatrix matrix;
  bool present() const { return !path.empty(); }
};
enum ElementSlot { kStiffnessSlot, kMassSlot, kAddedMassSlot, kNumSlots };

}  // namespace

// Element matrices absent from the spec become n x n zero matrices; an element
// with id 0 takes its position in the list (1-based) as id. Ids and labels must
// be unique, and so must DOF labels and each element's `dofs`.
Structure ImportMatrixMarketStructure(const MatrixMarketModelSpec& spec,
                                      const std::string& base_dir) {
  const int num_elements = static_cast<int>(spec.elements.size());
  auto element_field = [](int e, const std::string& name) {
    return "model.elements[" + std::to_string(e) + "]." + name;
  };

  // Global matrices.
  SparseMatrix stiffness;
  SparseMatrix mass;
  std::string stiffness_path;
  std::string mass_path;
  if (!spec.stiffness_file.empty()) {
    stiffness_path = Resolve(spec.stiffness_file, base_dir);
    stiffness = ReadSymmetric(stiffness_path, "model.stiffness_file");
  }
  if (!spec.mass_file.empty()) {
    mass_path = Resolve(spec.mass_file, base_dir);
    mass = ReadSymmetric(mass_path, "model.mass_file");
  }

  // Element files, as stored (local or global).
  std::vector<std::array<ElementFile, kNumSlots>> files(num_elements);
  for (int e = 0; e < num_elements; ++e) {
    const MatrixMarketElement& element = spec.elements[e];
    const std::string* names[kNumSlots] = {&element.stiffness_file, &element.mass_file,
                                           &element.added_mass_file};
    files[e] = {ElementFile{"stiffness_file", "", {}}, ElementFile{"mass_file", "", {}},
                ElementFile{"added_mass_file", "", {}}};
    for (int slot = 0; slot < kNumSlots; ++slot) {
      ElementFile& file = files[e][slot];
      if (names[slot]->empty()) continue;
      file.path = Resolve(*names[slot], base_dir);
      file.matrix = ReadSymmetric(file.path, element_field(e, file.name));
    }
  }

  // The number of DOFs: every source that fixes it must agree.
  long long n = -1;
  std::string n_source;
  auto fix_size = [&](long long size, const std::string& where, const std::string& what) {
    if (n < 0) {
      n = size;
      n_source = what;
      return;
    }
    if (size != n) {
      throw InputError(where, what + " gives " + std::to_string(size) + " DOFs, but " +
                                  n_source + " gives " + std::to_string(n));
    }
  };
  if (!spec.dof_labels.empty()) {
    fix_size(static_cast<long long>(spec.dof_labels.size()), "model.dof_labels",
             "model.dof_labels (" + std::to_string(spec.dof_labels.size()) + " labels)");
  }
  if (!spec.stiffness_file.empty()) {
    fix_size(stiffness.rows(), "model.stiffness_file: " + stiffness_path,
             "the global stiffness matrix (" + SizeText(stiffness) + ")");
  }
  if (!spec.mass_file.empty()) {
    fix_size(mass.rows(), "model.mass_file: " + mass_path,
             "the global mass matrix (" + SizeText(mass) + ")");
  }
  for (int e = 0; e < num_elements; ++e) {
    const std::vector<int>& dofs = spec.elements[e].dofs;
    for (const ElementFile& file : files[e]) {
      if (!file.present()) continue;
      const std::string field = element_field(e, file.name);
      const std::string where = field + ": " + file.path;
      if (dofs.empty()) {
        fix_size(file.matrix.rows(), where,
                 field + " (" + SizeText(file.matrix) + ", global DOFs)");
      } else if (file.matrix.rows() != static_cast<Eigen::Index>(dofs.size())) {
        const std::string d = std::to_string(dofs.size());
        throw InputError(where, "matrix is " + SizeText(file.matrix) + ", expected " + d +
                                    " x " + d + " (one row per entry of " +
                                    element_field(e, "dofs") + ")");
      }
    }
  }
  if (n < 0) {
    // Only local element matrices: the DOFs are those the elements reach.
    for (const MatrixMarketElement& element : spec.elements) {
      for (int dof : element.dofs) n = std::max<long long>(n, dof + 1LL);
    }
    n_source = "the largest DOF in the elements' dofs";
    // The size comes from one number of the study: checked as a Matrix Market
    // size line is (a model of 72,812,094 DOFs from one element reaching one
    // DOF allocated gigabytes of labels and indices; found by fuzzing).
    std::vector<int> reached;
    for (const MatrixMarketElement& element : spec.elements)
      reached.insert(reached.end(), element.dofs.begin(), element.dofs.end());
    std::sort(reached.begin(), reached.end());
    const long long distinct =
        std::unique(reached.begin(), reached.end()) - reached.begin();
    if (n >
        std::max(kMatrixMarketFreeDimension, kMatrixMarketDimensionPerEntry * distinct)) {
      throw InputError(
          "model.elements",
          "the largest DOF in the elements' dofs (" + std::to_string(n - 1) +
              ") makes a model of " + std::to_string(n) +
              " DOFs, of which the elements reach " + std::to_string(distinct) +
              "; expected at most " + std::to_string(kMatrixMarketFreeDimension) +
              " DOFs, or more only where the elements reach at least one DOF in " +
              std::to_string(kMatrixMarketDimensionPerEntry) +
              " (give model.dof_labels or a global matrix to set a larger size)");
    }
  }
  if (n < 0) {
    throw InputError(
        "model",
        "has no stiffness_file, no mass_file and no element matrices: nothing "
        "to import");
  }

  // Elements in global DOFs.
  Structure structure;
  structure.type = "matrix_market";
  std::map<int, int> ids;             // id -> position in spec.elements
  std::map<std::string, int> labels;  // label -> position
  for (int e = 0; e < num_elements; ++e) {
    const MatrixMarketElement& element = spec.elements[e];
    ElementMatrices out;
    out.id = element.id == 0 ? e + 1 : element.id;
    if (out.id < 0) {
      throw InputError(element_field(e, "id"),
                       "is " + std::to_string(element.id) + ", expected a positive id");
    }
    if (const auto [it, added] = ids.emplace(out.id, e); !added) {
      throw InputError(element_field(e, "id"), "id " + std::to_string(out.id) +
                                                   " is already used by model.elements[" +
                                                   std::to_string(it->second) + "]");
    }
    out.label = element.label.empty() ? "e" + std::to_string(out.id) : element.label;
    if (const auto [it, added] = labels.emplace(out.label, e); !added) {
      throw InputError(element_field(e, "label"),
                       "label '" + out.label + "' is already used by model.elements[" +
                           std::to_string(it->second) + "]");
    }
    std::set<int> seen;
    for (size_t k = 0; k < element.dofs.size(); ++k) {
      const int dof = element.dofs[k];
      const std::string where = element_field(e, "dofs[" + std::to_string(k) + "]");
      if (dof < 0 || dof >= n) {
        throw InputError(where, "global DOF " + std::to_string(dof) +
                                    " is out of range: the model has " +
                                    std::to_string(n) + " DOFs (0-based, 0.." +
                                    std::to_string(n - 1) + ")");
      }
      if (!seen.insert(dof).second) {
        throw InputError(where, "global DOF " + std::to_string(dof) + " is listed twice");
      }
    }
    auto to_global = [&](const ElementFile& file) {
      SparseMatrix global(n, n);
      if (!file.present()) return global;
      const SparseMatrix& local = file.matrix;
      if (element.dofs.empty()) return local;
      std::vector<Triplet> triplets;
      triplets.reserve(static_cast<size_t>(local.nonZeros()));
      for (Eigen::Index k = 0; k < local.outerSize(); ++k) {
        for (SparseMatrix::InnerIterator it(local, k); it; ++it) {
          triplets.emplace_back(element.dofs[it.row()], element.dofs[it.col()],
                                it.value());
        }
      }
      global.setFromTriplets(triplets.begin(), triplets.end());
      return global;
    };
    out.stiffness = to_global(files[e][kStiffnessSlot]);
    out.mass = to_global(files[e][kMassSlot]);
    out.added_mass_basis = files[e][kAddedMassSlot].present()
                               ? to_global(files[e][kAddedMassSlot])
                               : out.mass;
    out.wet = element.wet;
    structure.elements.push_back(std::move(out));
  }

  // Global matrices missing from the spec: sums of the elements.
  auto sum_of = [&](ElementSlot slot, const char* field, const char* kind) {
    SparseMatrix sum(n, n);
    bool any = false;
    for (int e = 0; e < num_elements; ++e) {
      if (!files[e][slot].present()) continue;
      const ElementMatrices& element = structure.elements[e];
      sum += slot == kStiffnessSlot ? element.stiffness : element.mass;
      any = true;
    }
    if (!any) {
      throw InputError(field, std::string("is empty and no element has a ") + kind +
                                  " file: nothing to form the global matrix from");
    }
    return sum;
  };
  structure.stiffness = spec.stiffness_file.empty()
                            ? sum_of(kStiffnessSlot, "model.stiffness_file", "stiffness")
                            : std::move(stiffness);
  structure.mass = spec.mass_file.empty() ? sum_of(kMassSlot, "model.mass_file", "mass")
                                          : std::move(mass);
  structure.stiffness.makeCompressed();
  structure.mass.makeCompressed();

  // DOF labels.
  if (spec.dof_labels.empty()) {
    for (long long i = 0; i < n; ++i) {
      structure.dof_labels.push_back("d" + std::to_string(i + 1));
    }
  } else {
    std::set<std::string> seen;
    for (size_t i = 0; i < spec.dof_labels.size(); ++i) {
      const std::string where = "model.dof_labels[" + std::to_string(i) + "]";
      if (spec.dof_labels[i].empty()) throw InputError(where, "is empty");
      if (!seen.insert(spec.dof_labels[i]).second) {
        throw InputError(where, "label '" + spec.dof_labels[i] + "' is used twice");
      }
    }
    structure.dof_labels = spec.dof_labels;
  }

  std::ostringstream description;
  description << "Matrix Market model: " << n << " DOFs, " << num_elements
              << " elements; K "
              << (spec.stiffness_file.empty() ? "= sum of element stiffnesses"
                                              : "from " + spec.stiffness_file)
              << ", M "
              << (spec.mass_file.empty() ? "= sum of element masses"
                                         : "from " + spec.mass_file);
  structure.description = description.str();
  return structure;
}

}  // namespace femup
