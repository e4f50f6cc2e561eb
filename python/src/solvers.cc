// The correction-factor system Z d = F and every solver: the linear ones
// (lstsq, tsvd, tikhonov with its parameter choice, bvls, ceres, ipopt) on a
// LinearProblem, the nonlinear ones (ceres, ipopt) on a NonlinearProblem whose
// residuals come from C++ (eigen-sensitivity updating, a linear problem) or
// from a Python function; with their summaries, identifiability and
// uncertainty.
#include <memory>
#include <string>
#include <vector>

#include "common.h"
#include "femup/core/errors.h"
#include "femup/problems/correction_system.h"
#include "femup/problems/eigen_sensitivity.h"
#include "femup/problems/linear_problem.h"
#include "femup/problems/nonlinear_problem.h"
#include "femup/solvers/identifiability.h"
#include "femup/solvers/linear_solver.h"
#include "femup/solvers/nonlinear_solver.h"

namespace femup_python {

namespace {

void BindSummaries(py::module_& m) {
  py::class_<femup::SolverSummary>(m, "SolverSummary",
                                   "A solver's outcome: a status, never an exception.")
      .def_property_readonly(
          "status",
          [](const femup::SolverSummary& s) { return femup::ToString(s.status); },
          "solved, minimum_norm, no_convergence, infeasible or failed")
      .def_readonly("message", &femup::SolverSummary::message)
      .def_readonly("iterations", &femup::SolverSummary::iterations)
      .def_readonly("cost", &femup::SolverSummary::cost)
      .def_readonly("time_seconds", &femup::SolverSummary::time_seconds)
      .def_readonly("kkt_residual", &femup::SolverSummary::kkt_residual)
      .def_readonly("warnings", &femup::SolverSummary::warnings)
      .def_property_readonly("usable", &femup::SolverSummary::usable)
      .def("__repr__", [](const femup::SolverSummary& s) {
        return std::string("<femup.SolverSummary ") + femup::ToString(s.status) + ": " +
               s.message + ">";
      });

  py::class_<femup::NullDirection>(m, "NullDirection")
      .def_readonly("coefficients", &femup::NullDirection::coefficients)
      .def_readonly("singular_value", &femup::NullDirection::singular_value)
      .def_readonly("description", &femup::NullDirection::description)
      .def_readonly("common_scaling", &femup::NullDirection::common_scaling)
      .def_readonly("best_to_fix", &femup::NullDirection::best_to_fix);
  py::class_<femup::Identifiability>(m, "Identifiability")
      .def_readonly("singular_values", &femup::Identifiability::singular_values)
      .def_readonly("tolerance", &femup::Identifiability::tolerance)
      .def_readonly("rank", &femup::Identifiability::rank)
      .def_readonly("condition_number", &femup::Identifiability::condition_number)
      .def_readonly("condition_number_in_rank",
                    &femup::Identifiability::condition_number_in_rank)
      .def_readonly("condition_number_unscaled",
                    &femup::Identifiability::condition_number_unscaled)
      .def_readonly("null_directions", &femup::Identifiability::null_directions)
      .def_readonly("unseen", &femup::Identifiability::unseen)
      .def_readonly("warnings", &femup::Identifiability::warnings);
  m.def("analyse_identifiability",
        py::overload_cast<const Eigen::MatrixXd&, const std::vector<std::string>&,
                          const std::vector<std::string>&, double, bool>(
            &femup::AnalyseIdentifiability),
        py::arg("a"), py::arg("names") = std::vector<std::string>(),
        py::arg("groups") = std::vector<std::string>(),
        py::arg("relative_tolerance") = 1e-10, py::arg("scale_columns") = true,
        py::call_guard<py::gil_scoped_release>(),
        "Singular values, rank and null directions (in words) of A.");

  py::class_<femup::RegularisationOptions>(m, "RegularisationOptions")
      .def(py::init<>())
      .def_readwrite("parameter_choice", &femup::RegularisationOptions::parameter_choice,
                     "gcv, lcurve, discrepancy, quasi_optimality or fixed")
      .def_readwrite("lambda_", &femup::RegularisationOptions::lambda,
                     "fixed rule: lambda")
      .def_readwrite("noise_norm", &femup::RegularisationOptions::noise_norm)
      .def_readwrite("discrepancy_factor",
                     &femup::RegularisationOptions::discrepancy_factor)
      .def_readwrite("operator", &femup::RegularisationOptions::op,
                     "identity, first_difference, second_difference or problem")
      .def_readwrite("grid_points", &femup::RegularisationOptions::grid_points)
      .def_readwrite("lambda_min", &femup::RegularisationOptions::lambda_min)
      .def_readwrite("lambda_max", &femup::RegularisationOptions::lambda_max)
      .def("validate", &ValidateText<femup::RegularisationOptions>);
  py::class_<femup::RegularisationReport>(m, "RegularisationReport")
      .def_readonly("parameter_choice", &femup::RegularisationReport::parameter_choice)
      .def_readonly("lambda_", &femup::RegularisationReport::lambda)
      .def_readonly("truncation", &femup::RegularisationReport::truncation)
      .def_readonly("at_range_end", &femup::RegularisationReport::at_range_end)
      .def_readonly("note", &femup::RegularisationReport::note)
      .def_readonly("lambda_lcurve", &femup::RegularisationReport::lambda_lcurve)
      .def_readonly("lambda_gcv", &femup::RegularisationReport::lambda_gcv)
      .def_readonly("lambda_discrepancy",
                    &femup::RegularisationReport::lambda_discrepancy)
      .def_readonly("lambda_quasi", &femup::RegularisationReport::lambda_quasi)
      .def_readonly("grid_lambda", &femup::RegularisationReport::grid_lambda)
      .def_readonly("grid_residual_norm",
                    &femup::RegularisationReport::grid_residual_norm)
      .def_readonly("grid_solution_norm",
                    &femup::RegularisationReport::grid_solution_norm)
      .def_readonly("grid_gcv", &femup::RegularisationReport::grid_gcv)
      .def_readonly("grid_curvature", &femup::RegularisationReport::grid_curvature)
      .def_readonly("grid_quasi", &femup::RegularisationReport::grid_quasi);
}

void BindLinear(py::module_& m) {
  py::class_<femup::LinearProblem>(
      m, "LinearProblem",
      "A x ~ b in the weighted least-squares sense with optional fixed values, "
      "equalities C x = d, bounds and a regulariser ||L (x - prior)||.")
      .def(py::init([](const Eigen::MatrixXd& a, const Eigen::VectorXd& b,
                       std::vector<std::string> names) {
             femup::LinearProblem p;
             p.A = a;
             p.b = b;
             p.names = std::move(names);
             return p;
           }),
           py::arg("A"), py::arg("b"), py::arg("names") = std::vector<std::string>())
      .def_readwrite("A", &femup::LinearProblem::A)
      .def_readwrite("b", &femup::LinearProblem::b)
      .def_readwrite("names", &femup::LinearProblem::names)
      .def_readwrite("groups", &femup::LinearProblem::groups)
      .def_readwrite("row_labels", &femup::LinearProblem::row_labels)
      .def_readwrite("fixed", &femup::LinearProblem::fixed, "[(index, value), ...]")
      .def_readwrite("row_weights", &femup::LinearProblem::row_weights)
      .def_readwrite("data_covariance", &femup::LinearProblem::data_covariance)
      .def_readwrite("lower", &femup::LinearProblem::lower)
      .def_readwrite("upper", &femup::LinearProblem::upper)
      .def_readwrite("equality_matrix", &femup::LinearProblem::equality_matrix)
      .def_readwrite("equality_rhs", &femup::LinearProblem::equality_rhs)
      .def_readwrite("regulariser", &femup::LinearProblem::regulariser)
      .def_readwrite("prior", &femup::LinearProblem::prior)
      .def_property_readonly("num_rows", &femup::LinearProblem::num_rows)
      .def_property_readonly("num_unknowns", &femup::LinearProblem::num_unknowns)
      .def("validate", &ValidateText<femup::LinearProblem>,
           "'' when consistent, else why not")
      .def("fix", &femup::LinearProblem::Fix, py::arg("name"), py::arg("value"),
           "Fixes the unknown called `name` (InputError when none is).")
      .def("free_unknowns", &femup::LinearProblem::FreeUnknowns)
      .def("index_of", &femup::LinearProblem::IndexOf, py::arg("name"));
  m.def("difference_operator", &femup::DifferenceOperator, py::arg("n"), py::arg("order"),
        py::arg("groups") = std::vector<std::string>());

  m.def(
      "correction_system",
      [](const femup::ParametrisedModel& model, const femup::Modes& fem_modes,
         const std::vector<femup::ModalData>& states, const std::string& form,
         int num_fem_modes) {
        femup::CorrectionSystemOptions options;
        if (!femup::SystemFormFromString(form, &options.form)) {
          throw femup::InputError("system.form",
                                  "expected stacked or summed, got '" + form + "'");
        }
        options.num_fem_modes = num_fem_modes;
        py::gil_scoped_release release;
        return femup::BuildCorrectionSystem(model, fem_modes, states, options);
      },
      py::arg("model"), py::arg("fem_modes"), py::arg("states"),
      py::arg("form") = "stacked", py::arg("num_fem_modes") = -1,
      "Z d = F (the paper's Eq. 20-31 when form='summed') from measured states with "
      "shapes on every DOF and M-normalised FEM modes of the nominal model.");

  py::class_<femup::LinearSolverOptions>(m, "LinearSolverOptions")
      .def(py::init<>())
      .def_readwrite("relative_rank_tolerance",
                     &femup::LinearSolverOptions::relative_rank_tolerance)
      .def_readwrite("scale_columns", &femup::LinearSolverOptions::scale_columns)
      .def_readwrite("truncation", &femup::LinearSolverOptions::truncation,
                     "tsvd: singular values kept; 0 = by the parameter choice")
      .def_readwrite("regularisation", &femup::LinearSolverOptions::regularisation)
      .def_readwrite("max_iterations", &femup::LinearSolverOptions::max_iterations)
      .def_readwrite("kkt_tolerance", &femup::LinearSolverOptions::kkt_tolerance)
      .def_readwrite("confidence_level", &femup::LinearSolverOptions::confidence_level)
      .def_readwrite("diagnostics", &femup::LinearSolverOptions::diagnostics)
      .def("validate", &ValidateText<femup::LinearSolverOptions>);

  py::class_<femup::LinearSolution>(m, "LinearSolution")
      .def_readonly("x", &femup::LinearSolution::x,
                    "every unknown, fixed ones at their values")
      .def_readonly("residual", &femup::LinearSolution::residual, "A x - b")
      .def_readonly("identifiability", &femup::LinearSolution::identifiability)
      .def_readonly("covariance", &femup::LinearSolution::covariance)
      .def_readonly("standard_error", &femup::LinearSolution::standard_error)
      .def_readonly("interval_lower", &femup::LinearSolution::interval_lower)
      .def_readonly("interval_upper", &femup::LinearSolution::interval_upper)
      .def_readonly("confidence_level", &femup::LinearSolution::confidence_level)
      .def_readonly("noise_estimated", &femup::LinearSolution::noise_estimated)
      .def_readonly("resolution", &femup::LinearSolution::resolution)
      .def_readonly("bias_estimate", &femup::LinearSolution::bias_estimate)
      .def_readonly("regularisation", &femup::LinearSolution::regularisation)
      .def_readonly("summary", &femup::LinearSolution::summary);

  m.def("available_linear_solvers", &femup::AvailableLinearSolvers);
  m.def(
      "solve_linear",
      [](const femup::LinearProblem& problem, const std::string& solver,
         const femup::LinearSolverOptions& options) {
        py::gil_scoped_release release;
        return femup::CreateLinearSolver(solver, options)->Solve(problem);
      },
      py::arg("problem"), py::arg("solver") = "lstsq",
      py::arg("options") = femup::LinearSolverOptions(),
      "Solves with lstsq, tsvd, tikhonov, bvls, ceres or ipopt; the outcome is in "
      "solution.summary (InputError only for unusable input or options).");
}

// A Python function as a NonlinearProblem's residuals. The function is held
// through a shared pointer whose deleter takes the GIL, so the problem can be
// copied by a solver that runs without it.
struct PythonResiduals {
  std::shared_ptr<py::object> function;
  std::shared_ptr<std::string> error;  // the first exception the function raised

  bool operator()(const Eigen::VectorXd& x, Eigen::VectorXd* r, Eigen::MatrixXd* j,
                  std::string* why) const {
    py::gil_scoped_acquire gil;
    try {
      py::object out = (*function)(x, j != nullptr);
      if (out.is_none()) {
        if (why) *why = "the Python residual function returned None at this x";
        return false;
      }
      auto pair = out.cast<py::tuple>();
      if (pair.size() != 2) throw py::value_error("expected (residuals, jacobian)");
      *r = pair[0].cast<Eigen::VectorXd>();
      if (j != nullptr) *j = pair[1].cast<Eigen::MatrixXd>();
      return true;
    } catch (py::error_already_set& e) {
      if (error->empty()) *error = e.what();
    } catch (const std::exception& e) {
      if (error->empty()) *error = e.what();
    }
    if (why) *why = "the Python residual function raised: " + *error;
    return false;
  }
};

void BindNonlinear(py::module_& m) {
  py::class_<femup::NonlinearProblem>(
      m, "NonlinearProblem",
      "min 0.5 ||r(x)||^2 with optional fixed values, equalities and bounds.")
      .def(py::init([](py::object residuals, const Eigen::VectorXd& initial,
                       int num_residuals, std::vector<std::string> names) {
             femup::NonlinearProblem p;
             p.initial = initial;
             p.num_residuals = num_residuals;
             p.names = std::move(names);
             PythonResiduals f;
             f.function = std::shared_ptr<py::object>(
                 new py::object(std::move(residuals)), [](py::object* o) {
                   py::gil_scoped_acquire gil;
                   delete o;
                 });
             f.error = std::make_shared<std::string>();
             p.evaluate = f;
             return p;
           }),
           py::arg("residuals"), py::arg("initial"), py::arg("num_residuals"),
           py::arg("names") = std::vector<std::string>(),
           "residuals(x, want_jacobian) -> (r, J) (J may be None when not wanted), "
           "or None where the model cannot be evaluated.")
      .def_readwrite("num_residuals", &femup::NonlinearProblem::num_residuals)
      .def_readwrite("initial", &femup::NonlinearProblem::initial)
      .def_readwrite("names", &femup::NonlinearProblem::names)
      .def_readwrite("groups", &femup::NonlinearProblem::groups)
      .def_readwrite("fixed", &femup::NonlinearProblem::fixed)
      .def_readwrite("lower", &femup::NonlinearProblem::lower)
      .def_readwrite("upper", &femup::NonlinearProblem::upper)
      .def_readwrite("equality_matrix", &femup::NonlinearProblem::equality_matrix)
      .def_readwrite("equality_rhs", &femup::NonlinearProblem::equality_rhs)
      .def_readwrite("residuals_whitened", &femup::NonlinearProblem::residuals_whitened)
      .def_property_readonly("num_parameters", &femup::NonlinearProblem::num_parameters)
      .def("validate", &ValidateText<femup::NonlinearProblem>)
      .def(
          "evaluate",
          [](const femup::NonlinearProblem& p, const Eigen::VectorXd& x) -> py::object {
            if (!p.evaluate) throw femup::InputError("evaluate", "the problem has none");
            Eigen::VectorXd r;
            Eigen::MatrixXd j;
            std::string why;
            bool ok = false;
            {
              py::gil_scoped_release release;
              ok = p.evaluate(x, &r, &j, &why);
            }
            if (!ok) return py::none();
            return py::make_tuple(r, j);
          },
          py::arg("x"), "(r, J) at x, or None where the model cannot be evaluated.");

  m.def("as_nonlinear", &femup::AsNonlinear, py::arg("problem"),
        py::arg("start") = Eigen::VectorXd(),
        "r(x) = W (A x - b) with the linear problem's constraints.");

  py::class_<femup::EigenSensitivityOptions>(m, "EigenSensitivityOptions")
      .def(py::init<>())
      .def_readwrite("use_shapes", &femup::EigenSensitivityOptions::use_shapes)
      .def_readwrite("frequency_sigma", &femup::EigenSensitivityOptions::frequency_sigma)
      .def_readwrite("shape_sigma", &femup::EigenSensitivityOptions::shape_sigma)
      .def_readwrite("shape_noise", &femup::EigenSensitivityOptions::shape_noise)
      .def_readwrite("entry_floor", &femup::EigenSensitivityOptions::entry_floor)
      .def_readwrite("shape_scaling", &femup::EigenSensitivityOptions::shape_scaling)
      .def_readwrite("extra_modes", &femup::EigenSensitivityOptions::extra_modes)
      .def_readwrite("pair_by_mac", &femup::EigenSensitivityOptions::pair_by_mac)
      .def_readwrite("min_mac", &femup::EigenSensitivityOptions::min_mac)
      .def_readwrite("prior_mean", &femup::EigenSensitivityOptions::prior_mean)
      .def_readwrite("prior_sigma", &femup::EigenSensitivityOptions::prior_sigma)
      .def_readwrite("tikhonov_lambda", &femup::EigenSensitivityOptions::tikhonov_lambda)
      .def_readwrite("threads", &femup::EigenSensitivityOptions::threads)
      .def("validate", &ValidateText<femup::EigenSensitivityOptions>);
  m.def("eigen_sensitivity_problem", &femup::BuildEigenSensitivityProblem,
        py::arg("model"), py::arg("states"),
        py::arg("options") = femup::EigenSensitivityOptions(),
        py::arg("start") = Eigen::VectorXd(), py::call_guard<py::gil_scoped_release>(),
        "The output-error problem of iterative eigen-sensitivity updating over the "
        "model's factors (whitened residuals of eigenvalues and shapes).");

  py::class_<femup::NonlinearSolverOptions>(m, "NonlinearSolverOptions")
      .def(py::init<>())
      .def_readwrite("max_iterations", &femup::NonlinearSolverOptions::max_iterations)
      .def_readwrite("function_tolerance",
                     &femup::NonlinearSolverOptions::function_tolerance)
      .def_readwrite("gradient_tolerance",
                     &femup::NonlinearSolverOptions::gradient_tolerance)
      .def_readwrite("parameter_tolerance",
                     &femup::NonlinearSolverOptions::parameter_tolerance)
      .def_readwrite("trust_region", &femup::NonlinearSolverOptions::trust_region)
      .def_readwrite("initial_trust_region",
                     &femup::NonlinearSolverOptions::initial_trust_region)
      .def_readwrite("max_restarts", &femup::NonlinearSolverOptions::max_restarts)
      .def_readwrite("hessian", &femup::NonlinearSolverOptions::hessian)
      .def_readwrite("kkt_tolerance", &femup::NonlinearSolverOptions::kkt_tolerance)
      .def_readwrite("max_outer_iterations",
                     &femup::NonlinearSolverOptions::max_outer_iterations)
      .def_readwrite("equality_tolerance",
                     &femup::NonlinearSolverOptions::equality_tolerance)
      .def("validate", &ValidateText<femup::NonlinearSolverOptions>);
  py::class_<femup::NonlinearSolution>(m, "NonlinearSolution")
      .def_readonly("x", &femup::NonlinearSolution::x)
      .def_readonly("residual", &femup::NonlinearSolution::residual)
      .def_readonly("jacobian", &femup::NonlinearSolution::jacobian)
      .def_readonly("covariance", &femup::NonlinearSolution::covariance)
      .def_readonly("summary", &femup::NonlinearSolution::summary);
  m.def("available_nonlinear_solvers", &femup::AvailableNonlinearSolvers);
  m.def(
      "solve_nonlinear",
      [](const femup::NonlinearProblem& problem, const std::string& solver,
         const femup::NonlinearSolverOptions& options) {
        femup::NonlinearSolution solution;
        {
          py::gil_scoped_release release;
          solution = femup::CreateNonlinearSolver(solver, options)->Solve(problem);
        }
        if (const auto* f = problem.evaluate.target<PythonResiduals>()) {
          if (!f->error->empty()) {
            const std::string what = *f->error;
            f->error->clear();
            throw std::runtime_error("the residual function raised: " + what);
          }
        }
        return solution;
      },
      py::arg("problem"), py::arg("solver") = "ceres",
      py::arg("options") = femup::NonlinearSolverOptions(),
      "Solves with ceres or ipopt; the outcome is in solution.summary. An exception "
      "raised by a Python residual function is raised again here.");
}

}  // namespace

void InitSolvers(py::module_& m) {
  BindSummaries(m);
  BindLinear(m);
  BindNonlinear(m);
}

}  // namespace femup_python
