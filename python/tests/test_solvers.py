"""The correction-factor system and every linear and nonlinear solver,
checked against numpy/scipy answers to the same problems."""

import numpy as np
import pytest
import scipy.optimize

import femup
from conftest import paper_study_dict

RNG = np.random.default_rng(20140613)
A = RNG.standard_normal((30, 5))
X_TRUE = np.array([1.0, -2.0, 0.5, 3.0, -1.0])
B = A @ X_TRUE + 0.01 * RNG.standard_normal(30)
NAMES = [f"x{i}" for i in range(5)]


def problem():
    return femup.LinearProblem(A, B, NAMES)


def test_available_solvers():
    assert femup.available_linear_solvers() == ["lstsq", "tsvd", "tikhonov", "bvls",
                                                "ceres", "ipopt"]
    assert femup.available_nonlinear_solvers() == ["ceres", "ipopt"]


@pytest.mark.parametrize("solver", ["lstsq", "bvls", "ceres", "ipopt"])
def test_unbounded_solvers_match_numpy_lstsq(solver):
    reference = np.linalg.lstsq(A, B, rcond=None)[0]
    solution = femup.solve_linear(problem(), solver)
    assert solution.summary.usable, solution.summary
    np.testing.assert_allclose(solution.x, reference, rtol=1e-6, atol=1e-8)
    np.testing.assert_allclose(solution.residual, A @ solution.x - B, atol=1e-9)


def test_lstsq_diagnostics():
    solution = femup.solve_linear(problem())
    assert solution.summary.status == "solved"
    assert solution.identifiability.rank == 5
    assert solution.covariance.shape == (5, 5)
    # Standard errors from the residual: s^2 (A'A)^-1, s^2 = ||r||^2 / (m - n).
    r = A @ solution.x - B
    s2 = r @ r / (30 - 5)
    np.testing.assert_allclose(solution.standard_error,
                               np.sqrt(np.diag(s2 * np.linalg.inv(A.T @ A))), rtol=1e-8)
    assert np.all(solution.interval_lower < solution.x)


@pytest.mark.parametrize("solver", ["bvls", "ceres", "ipopt"])
def test_bounded_solvers_match_scipy_lsq_linear(solver):
    p = problem()
    p.lower = np.full(5, -1.5)
    p.upper = np.full(5, 2.0)
    reference = scipy.optimize.lsq_linear(A, B, bounds=(-1.5, 2.0), tol=1e-12).x
    solution = femup.solve_linear(p, solver)
    assert solution.summary.status == "solved", solution.summary
    np.testing.assert_allclose(solution.x, reference, atol=1e-6)


def test_fixed_values_and_equalities():
    p = problem()
    p.fix("x0", 1.0)
    p.equality_matrix = np.array([[0.0, 1.0, 1.0, 0.0, 0.0]])
    p.equality_rhs = np.array([-1.5])
    assert p.validate() == "" and p.free_unknowns() == [1, 2, 3, 4] and p.index_of("x3") == 3
    solution = femup.solve_linear(p)
    assert solution.x[0] == 1.0
    assert solution.x[1] + solution.x[2] == pytest.approx(-1.5, abs=1e-12)
    with pytest.raises(femup.InputError, match="nope"):
        p.fix("nope", 0.0)


def test_tikhonov_fixed_lambda_is_the_closed_form():
    options = femup.LinearSolverOptions()
    options.regularisation.parameter_choice = "fixed"
    options.regularisation.lambda_ = 0.7
    options.scale_columns = False
    solution = femup.solve_linear(problem(), "tikhonov", options)
    closed = np.linalg.solve(A.T @ A + 0.7 ** 2 * np.eye(5), A.T @ B)
    np.testing.assert_allclose(solution.x, closed, rtol=1e-9)
    assert solution.regularisation.lambda_ == 0.7
    assert solution.resolution.shape == (5, 5)


def ill_posed():
    # A discrete ill-posed problem: the 12 x 12 Hilbert matrix, a smooth answer,
    # noise 1e-4 (seeded).
    n = 12
    h = 1.0 / (np.arange(n)[:, None] + np.arange(n)[None, :] + 1.0)
    x = np.sin(np.linspace(0, np.pi, n))
    e = 1e-4 * np.random.default_rng(11).standard_normal(n)
    return h, h @ x + e, np.linalg.norm(e)


def gcv(a, b, lam):
    h = a @ np.linalg.solve(a.T @ a + lam ** 2 * np.eye(a.shape[1]), a.T)
    r = b - h @ b
    return (r @ r) / (a.shape[0] - np.trace(h)) ** 2


@pytest.mark.parametrize("rule", ["gcv", "lcurve", "quasi_optimality", "discrepancy"])
def test_tikhonov_parameter_choice(rule):
    a, b, noise = ill_posed()
    options = femup.LinearSolverOptions()
    options.scale_columns = False
    options.regularisation.parameter_choice = rule
    options.regularisation.noise_norm = noise
    solution = femup.solve_linear(femup.LinearProblem(a, b), "tikhonov", options)
    report = solution.regularisation
    lam = report.lambda_
    assert report.parameter_choice == rule and not report.at_range_end, report.note
    assert len(report.grid_lambda) == len(report.grid_gcv) > 0
    closed = np.linalg.solve(a.T @ a + lam ** 2 * np.eye(12), a.T @ b)
    np.testing.assert_allclose(solution.x, closed, rtol=1e-6, atol=1e-8)
    if rule == "gcv":  # a local minimum of the GCV function, computed here
        assert gcv(a, b, lam) <= min(gcv(a, b, lam * 1.2), gcv(a, b, lam / 1.2))
    if rule == "discrepancy":  # ||A x - b|| = ||e||
        assert np.linalg.norm(a @ closed - b) == pytest.approx(noise, rel=1e-6)


def test_tsvd_truncation_matches_numpy_svd():
    options = femup.LinearSolverOptions()
    options.truncation = 3
    solution = femup.solve_linear(problem(), "tsvd", options)
    u, s, vt = np.linalg.svd(A, full_matrices=False)
    expected = vt[:3].T @ ((u[:, :3].T @ B) / s[:3])
    np.testing.assert_allclose(solution.x, expected, rtol=1e-9)
    assert solution.regularisation.truncation == 3


def test_solver_errors_name_the_field():
    with pytest.raises(femup.InputError, match=r"solver\.name"):
        femup.solve_linear(problem(), "magic")
    options = femup.LinearSolverOptions()
    options.regularisation.parameter_choice = "guess"
    assert "parameter_choice" in options.regularisation.validate()
    with pytest.raises(femup.InputError, match="parameter_choice"):
        femup.solve_linear(problem(), "tikhonov", options)


def test_identifiability_and_difference_operator():
    a = np.column_stack([A[:, 0], A[:, 0], A[:, 1]])
    ident = femup.analyse_identifiability(a, ["p", "q", "r"])
    assert ident.rank == 2 and len(ident.null_directions) == 1
    np.testing.assert_allclose(abs(ident.null_directions[0].coefficients),
                               [2 ** -0.5, 2 ** -0.5, 0], atol=1e-12)
    np.testing.assert_array_equal(femup.difference_operator(3, 1),
                                  [[-1.0, 1.0, 0.0], [0.0, -1.0, 1.0]])


@pytest.mark.parametrize("solver", ["ceres", "ipopt"])
def test_nonlinear_python_residuals_match_scipy(solver):
    # Exponential decay y = a exp(-k t) fitted to noisy samples.
    t = np.linspace(0, 2, 25)
    y = 2.5 * np.exp(-1.3 * t) + 0.01 * RNG.standard_normal(25)

    def residuals(x, want_jacobian):
        e = np.exp(-x[1] * t)
        r = x[0] * e - y
        j = np.column_stack([e, -x[0] * t * e]) if want_jacobian else None
        return r, j

    problem = femup.NonlinearProblem(residuals, np.array([1.0, 1.0]), 25, ["a", "k"])
    solution = femup.solve_nonlinear(problem, solver)
    assert solution.summary.usable, solution.summary
    reference = scipy.optimize.least_squares(lambda x: residuals(x, False)[0], [1.0, 1.0],
                                             xtol=1e-14, ftol=1e-14, gtol=1e-14).x
    np.testing.assert_allclose(solution.x, reference, rtol=1e-7)
    r, j = problem.evaluate(solution.x)
    np.testing.assert_allclose(r, solution.residual, atol=1e-12)
    problem.lower = np.array([0.0, 1.5])
    problem.upper = np.array([10.0, 5.0])
    problem.initial = np.array([1.0, 2.0])
    bounded = femup.solve_nonlinear(problem, solver)
    assert bounded.x[1] == pytest.approx(1.5, abs=1e-6)


def test_nonlinear_residual_exceptions_are_raised_again():
    def broken(x, want_jacobian):
        raise ZeroDivisionError("on purpose")

    problem = femup.NonlinearProblem(broken, np.array([1.0]), 1)
    with pytest.raises(RuntimeError, match="on purpose"):
        femup.solve_nonlinear(problem, "ceres")
    assert problem.evaluate(np.array([1.0])) is None


def test_as_nonlinear_matches_lstsq():
    nl = femup.as_nonlinear(problem())
    solution = femup.solve_nonlinear(nl, "ceres")
    np.testing.assert_allclose(solution.x, np.linalg.lstsq(A, B, rcond=None)[0], rtol=1e-8)


def test_paper_correction_system_and_eigen_sensitivity():
    study = femup.study_from_dict(paper_study_dict())
    states = femup.measured_states(study)
    fem = femup.fem_modes_for(study)
    z = femup.correction_system(study.model, fem, states, form="stacked")
    summed = femup.correction_system(study.model, fem, states, form="summed")
    assert z.A.shape == (20, 13) and summed.A.shape == (20, 13)
    assert z.names == study.model.parameter_names and len(z.row_labels) == 20
    with pytest.raises(femup.InputError, match=r"system\.form"):
        femup.correction_system(study.model, fem, states, form="folded")
    # Iterative eigen-sensitivity updating of the same data: with mass[4] fixed,
    # the residuals vanish at the paper's factors.
    options = femup.EigenSensitivityOptions()
    nl = femup.eigen_sensitivity_problem(study.model, states, options)
    nl.fixed = [(study.model.find_parameter("mass[4]"), 0.0058)]
    for solver in ("ceres", "ipopt"):
        solution = femup.solve_nonlinear(nl, solver)
        assert solution.summary.usable, solution.summary
        np.testing.assert_allclose(solution.x, study.truth, atol=1e-6)
