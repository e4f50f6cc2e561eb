"""femup: finite element model updating from vibration measurements.

The C++ library's pipelines for Python (docs/python.md). Numbers cross as
numpy arrays (dense results are views of the C++ objects where they can be),
sparse matrices as ``scipy.sparse.csc_matrix`` views of the model's own
storage. Long computations release the GIL.

Areas:

* models: :func:`chain`, :func:`build_cantilever`, :func:`build_plane_frame`,
  :func:`build_plane_frame_structure`, :func:`build_space_frame`,
  :func:`import_matrix_market`, :func:`model_from_dict` (any study ``model:``),
  :func:`build_model`; :func:`solve_modes`, :func:`mac`, :func:`mac_matrix`,
  :func:`pair_modes_by_mac`, :func:`pair_modes_by_mac_and_misfit`,
  :func:`pair_modes_in_order`, :func:`predict_modes`;
* measurements: :class:`ModalData`, :func:`read_uff`, :func:`read_csv_series`,
  :func:`era`, :func:`stabilisation_diagram` (``.arrays()``),
  :func:`pick_stable_modes`, :func:`identify`, :func:`run_simulate`;
* solvers: :func:`correction_system` (Z d = F), :func:`solve_linear` (lstsq,
  tsvd, tikhonov, bvls, ceres, ipopt), :class:`NonlinearProblem`,
  :func:`eigen_sensitivity_problem`, :func:`solve_nonlinear` (ceres, ipopt);
* studies: :func:`load_study`, :func:`study_from_dict`, :func:`parse_study`,
  :func:`prepare_measurements`, :func:`solve_factors`;
* pipelines: :func:`run_update`, :func:`run_noise_study`, :func:`diagnose`
  (:func:`run_diagnosis`, :func:`run_structure_diagnosis`), :func:`run_modes`.

Bad input raises :class:`InputError` (a ``ValueError``) with the C++ message,
which names the file, line and field, e.g.
``<dict>:5:3: model.masses[2]: expected a positive number, found -1``. A numerical
method that fails on valid input (an eigensolver that does not converge) raises
:class:`NumericalError` (a ``RuntimeError``).
"""

import json as _json
import math as _math
import os as _os

from ._femup import *  # noqa: F401,F403  (the compiled module's functions and classes)
from ._femup import InputError, NumericalError, build_chain, parse_study, parse_study_model

__version__ = "0.1.0"


def chain(masses, springs, wet=(), shear_building=False):
    """The paper's spring-mass chain, fixed at mass 1's end.

    masses (kg) and springs (N/m, spring 1 joins the ground and mass 1) have
    one entry per element; ``wet`` lists the 1-based masses in water, as the
    study's ``model.wet``; ``shear_building`` says, as the study's
    ``model.shear_building``, that the chain idealises a building's storeys
    (its flexural deformation is then carried as two form variants). Returns a
    :class:`Structure`; DOF k is ``x<k>``.
    """
    spec = ChainSpec()  # noqa: F405
    spec.masses = [float(m) for m in masses]
    spec.springs = [float(k) for k in springs]
    flags = [False] * len(spec.masses)
    for k in wet:
        if not isinstance(k, int) or k < 1 or k > len(flags):
            raise InputError(
                f"model.wet: mass {k!r} is not one of 1..{len(flags)}")
        flags[k - 1] = True
    spec.wet = flags
    spec.shear_building = bool(shear_building)
    return build_chain(spec)


def _yaml_safe(value, field="study"):
    """The dict as JSON-compatible data, infinities as the study's 'inf'."""
    if isinstance(value, dict):
        out = {}
        for key, item in value.items():
            if not isinstance(key, str):
                raise InputError(f"{field}: keys must be text, found {key!r}")
            out[key] = _yaml_safe(item, f"{field}.{key}" if field != "study" else key)
        return out
    if isinstance(value, (list, tuple)):
        return [_yaml_safe(v, f"{field}[{i + 1}]") for i, v in enumerate(value)]
    if hasattr(value, "tolist") and not isinstance(value, (str, bytes)):
        return _yaml_safe(value.tolist(), field)  # numpy arrays and scalars
    if isinstance(value, bool) or value is None or isinstance(value, (int, str)):
        return value
    if isinstance(value, float):
        if _math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return value
    raise InputError(f"{field}: cannot be written in a study: {type(value).__name__}")


def study_text(study):
    """The study dict as the text :func:`study_from_dict` reads (JSON, one key
    per line): line numbers in error messages refer to it."""
    if not isinstance(study, dict):
        raise InputError(f"study: expected a dict, found {type(study).__name__}")
    return _json.dumps(_yaml_safe(study), indent=1)


def study_from_dict(study, base_dir=".", name="<dict>"):
    """A study from a Python dict with the study file's schema.

    The dict is checked by the same reader as a study file, so unknown keys,
    wrong types, missing fields and names that match no parameter raise
    :class:`InputError` naming the field (``model.masses[2]``). File names in
    it (records, modes files, Matrix Market files) are relative to
    ``base_dir``. ``name`` stands for the file in messages; the study's name
    defaults to ``name`` too. numpy arrays are accepted wherever lists are;
    float infinities become the study's ``inf`` / ``-inf``.
    """
    text = study_text(study)
    base = str(base_dir)
    path = name if base in ("", ".") else _os.path.join(base, name)
    return parse_study(text, path)


def model_from_dict(model, parameters=None, base_dir="."):
    """Any model a study's ``model:`` can describe (chain, cantilever,
    plane_frame, space_frame, matrix_market), with the factors of its
    ``parameters:`` (default: the study's). Returns (structure, model): a
    :class:`Structure` and its :class:`ParametrisedModel`. Errors name the
    field as for a study file (``model.section.E``)."""
    study = {"model": model}
    if parameters is not None:
        study["parameters"] = parameters
    base = str(base_dir)
    path = "<model>" if base in ("", ".") else _os.path.join(base, "<model>")
    s = parse_study_model(study_text(study), path)
    return s.structure, s.model


def factor_table(result):
    """An update's factors as a dict name -> (estimate, preset, error,
    standard_error, fixed), for printing or pandas."""
    return {f.name: (f.estimate, f.preset, f.error, f.standard_error, f.fixed)
            for f in result.factors}
