#include "femup/studies/solve_study.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "femup/core/errors.h"
#include "femup/core/io/matrix_market.h"

namespace femup {

namespace {

bool EndsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() &&
         s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// `allow_infinite`: bounds may be -inf/inf (written inf, -inf, Inf, -Infinity
// by numpy, MATLAB and by hand); NaN is refused everywhere.
Eigen::MatrixXd ReadCsv(const std::string& path, std::vector<std::string>* names,
                        bool allow_infinite) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot open the file");
  std::vector<std::vector<double>> rows;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) cells.push_back(cell);
    std::vector<double> values;
    bool header = false;
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const std::string t = cells[c];
      std::size_t used = 0;
      double v = 0;
      try {
        v = std::stod(t, &used);
      } catch (...) {
        used = 0;
      }
      while (used < t.size() && (t[used] == ' ' || t[used] == '\t')) ++used;
      if (used == 0 || used != t.size()) {
        if (rows.empty() && values.empty() && number == 1) {
          header = true;
          break;
        }
        throw InputError(
            path + ":" + std::to_string(number),
            "field " + std::to_string(c + 1) + ": expected a number, found '" + t + "'");
      }
      if (std::isnan(v) || (!allow_infinite && !std::isfinite(v)))
        throw InputError(path + ":" + std::to_string(number),
                         "field " + std::to_string(c + 1) + ": '" + t + "' is " +
                             (std::isnan(v) ? "NaN (not a number)" : "not finite") +
                             (allow_infinite ? "" : "; only bounds may be -inf or inf"));
      values.push_back(v);
    }
    if (header) {
      if (names) {
        for (auto& c : cells) {
          const auto b = c.find_first_not_of(" \t\"");
          const auto e = c.find_last_not_of(" \t\"");
          names->push_back(b == std::string::npos ? "" : c.substr(b, e - b + 1));
        }
      }
      continue;
    }
    if (!rows.empty() && values.size() != rows.front().size())
      throw InputError(path + ":" + std::to_string(number),
                       "expected " + std::to_string(rows.front().size()) +
                           " fields, found " + std::to_string(values.size()));
    rows.push_back(values);
  }
  if (rows.empty()) throw InputError(path, "no numbers in the file");
  Eigen::MatrixXd m(rows.size(), rows.front().size());
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t j = 0; j < rows[i].size(); ++j) m(i, j) = rows[i][j];
  return m;
}

Eigen::VectorXd ReadVector(const std::string& path, const std::string& what,
                           bool allow_infinite = false) {
  const Eigen::MatrixXd m = ReadMatrixFile(path, nullptr, allow_infinite);
  if (m.cols() != 1 && m.rows() != 1)
    throw InputError(path, what + ": expected a vector (one row or one column), found " +
                               std::to_string(m.rows()) + " x " +
                               std::to_string(m.cols()));
  return m.cols() == 1 ? Eigen::VectorXd(m.col(0))
                       : Eigen::VectorXd(m.row(0).transpose());
}

}  // namespace

Eigen::MatrixXd ReadMatrixFile(const std::string& path, std::vector<std::string>* names,
                               bool allow_infinite) {
  if (EndsWith(path, ".mtx")) return ReadMatrixMarketDense(path);
  if (EndsWith(path, ".csv")) return ReadCsv(path, names, allow_infinite);
  throw InputError(path, "unknown file type: expected .mtx (Matrix Market) or .csv");
}

SolveResult RunSolve(const SolveFiles& files, const std::string& solver,
                     const LinearSolverOptions& options) {
  SolveResult r;
  r.solver = solver;
  const auto s = CreateLinearSolver(solver, options);  // bad names fail before reading
  LinearProblem& p = r.problem;
  p.A = ReadMatrixFile(files.a, &p.names);
  p.b = ReadVector(files.b, "b");
  if (p.b.size() != p.A.rows())
    throw InputError(files.b, "b has " + std::to_string(p.b.size()) + " entries but A (" +
                                  files.a + ") has " + std::to_string(p.A.rows()) +
                                  " rows");
  if (!p.names.empty() && static_cast<Eigen::Index>(p.names.size()) != p.A.cols())
    throw InputError(files.a, "the header names " + std::to_string(p.names.size()) +
                                  " columns but rows have " + std::to_string(p.A.cols()));
  if (p.names.empty()) {
    for (Eigen::Index j = 0; j < p.A.cols(); ++j)
      p.names.push_back("x" + std::to_string(j + 1));
  }
  auto read_n = [&](const std::string& path, const std::string& what, bool bound) {
    Eigen::VectorXd v = ReadVector(path, what, bound);
    if (v.size() != p.A.cols())
      throw InputError(path, what + " has " + std::to_string(v.size()) + " entries for " +
                                 std::to_string(p.A.cols()) + " unknowns");
    return v;
  };
  if (!files.lower.empty()) p.lower = read_n(files.lower, "lower", true);
  if (!files.upper.empty()) p.upper = read_n(files.upper, "upper", true);
  if (!files.truth.empty()) r.truth = read_n(files.truth, "truth", false);
  if (files.data_sigma > 0)
    p.row_weights = Eigen::VectorXd::Constant(p.A.rows(), 1.0 / files.data_sigma);
  if (const Invalid bad = p.Validate()) throw InputError(files.a, bad.ToString());
  r.solution = s->Solve(p);
  return r;
}

}  // namespace femup
