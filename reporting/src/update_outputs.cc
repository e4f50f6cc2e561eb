// The outputs of femup run (update_study.h): result.json, the updated matrices
// and the system as Matrix Market files, the plots (factors, frequencies, mode
// shapes, L-curve and GCV) and the terminal report.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "femup/core/fe/dof_labels.h"
#include "femup/core/io/matrix_market.h"
#include "femup/reporting/outputs.h"
#include "femup/reporting/plot.h"
#include "json_util.h"
#include "regularisation_output.h"
#include "render_staged.h"

namespace femup {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

nlohmann::json IdentifiabilityJson(const Identifiability& id) {
  nlohmann::json j;
  j["singular_values"] = json_util::Vector(id.singular_values);
  j["rank"] = id.rank;
  j["rank_tolerance"] = id.tolerance;
  j["condition_number"] = json_util::Number(id.condition_number);
  j["condition_number_in_rank"] = json_util::Number(id.condition_number_in_rank);
  j["condition_number_unscaled"] = json_util::Number(id.condition_number_unscaled);
  j["null_directions"] = nlohmann::json::array();
  for (const auto& nd : id.null_directions) {
    j["null_directions"].push_back(
        {{"description", nd.description},
         {"common_scaling", nd.common_scaling},
         {"best_to_fix", nd.best_to_fix},
         {"singular_value", nd.singular_value},
         {"coefficients", json_util::Vector(nd.coefficients)}});
  }
  j["unseen"] = id.unseen;
  j["warnings"] = id.warnings;
  return j;
}

double ErrorPercent(double model, double measured) {
  return std::isfinite(model) ? (model - measured) / measured * 100.0 : kNaN;
}

std::vector<double> Positions(const UpdateResult& r, const std::vector<int>& dofs) {
  std::vector<double> x;
  for (int d : dofs) {
    x.push_back(d < static_cast<int>(r.dof_positions.size()) ? r.dof_positions[d]
                                                             : d + 1);
  }
  return x;
}

}  // namespace

void RenderStaged(const Figure& figure, const std::string& name, OutputDir* out,
                  std::vector<std::string>* warnings) {
  out->Stage(name + ".dat");
  out->Stage(name + ".gp");
  const std::string png = out->Stage(name + ".png");
  const PlotStatus st = RenderFigure(figure, png.substr(0, png.size() - 4));
  if (!st.rendered) warnings->push_back(name + ".png: " + st.message);
}

std::vector<int> TransverseRows(const std::vector<std::string>& dof_labels,
                                const std::vector<int>& dofs) {
  std::vector<int> rows;
  for (std::size_t i = 0; i < dofs.size(); ++i) {
    if (internal::IsTransverseDof(dof_labels[dofs[i]]))
      rows.push_back(static_cast<int>(i));
  }
  if (rows.empty()) {
    for (std::size_t i = 0; i < dofs.size(); ++i) rows.push_back(static_cast<int>(i));
  }
  return rows;
}

void WriteUpdateOutputs(const UpdateResult& r, bool plots, OutputDir* out,
                        std::vector<std::string>* warnings) {
  nlohmann::json j;
  j["femup_version"] = "0.1.0";
  j["command"] = "run";
  j["study"] = r.study_name;
  j["model"] = {{"description", r.model_description}, {"dofs", r.num_dofs}};
  j["parameters"] = nlohmann::json::array();
  for (std::size_t i = 0; i < r.parameters.size(); ++i) {
    const Parameter& p = r.parameters[i];
    nlohmann::json pj = {{"name", p.name},
                         {"kind", ToString(p.kind)},
                         {"tags", p.tags},
                         {"elements", p.elements},
                         {"estimate", json_util::Number(r.solution.x[i])},
                         {"fixed", static_cast<bool>(r.fixed[i])}};
    if (r.solution.standard_error.size() ==
        static_cast<Eigen::Index>(r.parameters.size())) {
      pj["standard_error"] = json_util::Number(r.solution.standard_error[i]);
      pj["interval"] = {json_util::Number(r.solution.interval_lower[i]),
                        json_util::Number(r.solution.interval_upper[i])};
    }
    if (r.solution.bias_estimate.size() ==
        static_cast<Eigen::Index>(r.parameters.size())) {
      pj["resolution"] = json_util::Number(r.solution.resolution(i, i));
      pj["bias_estimate"] = json_util::Number(r.solution.bias_estimate[i]);
    }
    if (r.preset) {
      pj["preset"] = (*r.preset)[i];
      pj["error"] = json_util::Number(r.solution.x[i] - (*r.preset)[i]);
    }
    j["parameters"].push_back(pj);
  }
  j["system"] = {{"form", ToString(r.form)},
                 {"rows", r.problem.num_rows()},
                 {"unknowns", r.problem.num_unknowns()},
                 {"fem_modes", r.num_fem_modes},
                 {"weighted_by_inverse_mass", r.normal_system},
                 {"unconstrained", IdentifiabilityJson(r.identifiability_unconstrained)},
                 {"solved", IdentifiabilityJson(r.solution.identifiability)}};
  j["rank"] = r.identifiability_unconstrained.rank;
  j["singular_values"] =
      json_util::Vector(r.identifiability_unconstrained.singular_values);
  j["solver"] = {{"status", ToString(r.solution.summary.status)},
                 {"message", r.solution.summary.message},
                 {"iterations", r.solution.summary.iterations},
                 {"cost", r.solution.summary.cost},
                 {"time_seconds", r.solution.summary.time_seconds},
                 {"residual_norm", r.solution.residual.norm()},
                 {"rhs_norm", r.problem.b.norm()},
                 {"method", r.method},
                 {"name", r.solver_name},
                 {"kkt_residual", json_util::Number(r.solution.summary.kkt_residual)},
                 {"warnings", r.solution.summary.warnings},
                 {"confidence_level", r.solution.confidence_level},
                 {"noise_estimated_from_residual", r.solution.noise_estimated}};
  const RegularisationReport& reg = r.solution.regularisation;
  if (!reg.parameter_choice.empty()) {
    j["regularisation"] = RegularisationJson(reg);
  }
  j["states"] = nlohmann::json::array();
  for (const StateComparison& c : r.states) {
    nlohmann::json sj = {{"state", c.state}, {"immersion", ToString(c.immersion)}};
    sj["measured_hz"] = json_util::Vector(c.measured_hz);
    sj["model_hz"] = json_util::Vector(c.model_hz);
    sj["updated_hz"] = json_util::Vector(c.updated_hz);
    Eigen::VectorXd e0(c.measured_hz.size()), e1(c.measured_hz.size());
    for (Eigen::Index k = 0; k < c.measured_hz.size(); ++k) {
      e0[k] = ErrorPercent(c.model_hz[k], c.measured_hz[k]);
      e1[k] = ErrorPercent(c.updated_hz[k], c.measured_hz[k]);
    }
    sj["model_error_percent"] = json_util::Vector(e0);
    sj["updated_error_percent"] = json_util::Vector(e1);
    sj["model_mac"] = json_util::Vector(c.model_mac);
    sj["updated_mac"] = json_util::Vector(c.updated_mac);
    j["states"].push_back(sj);
  }
  if (r.added_mass_summary.present) {
    const AddedMassSummary& a = r.added_mass_summary;
    j["added_mass_summary"] = {{"sa", a.sa},
                               {"wet_elements", a.wet_elements},
                               {"total_kg", a.total_kg},
                               {"wet_length_m", a.wet_length_m},
                               {"per_length_kg_per_m", a.per_length},
                               {"eq2_coefficients", a.eq2_coefficients}};
  }
  j["measurements"] = nlohmann::json::array();
  for (std::size_t s = 0; s < r.sources.size(); ++s) {
    const PreparedState& p = r.sources[s];
    nlohmann::json mj = {{"state", p.data.state},
                         {"modes", p.data.num_modes()},
                         {"sensors", p.at_sensors.sensor_dofs.empty() &&
                                             !p.at_sensors.HasInterpolatedSensors()
                                         ? r.num_dofs
                                         : static_cast<int>(p.at_sensors.shapes.rows())}};
    if (!p.source.empty()) {
      mj["source"] = p.source;
      mj["identified_modes_used"] = p.identified_modes;
    }
    if (p.identified) {
      mj["identification"] = p.data.state + "_modes.json";
      nlohmann::json used = nlohmann::json::array();
      for (int k : p.identified_modes) {
        const StableMode& m = p.identified->modes[k - 1];
        used.push_back({{"frequency_hz", m.mode.frequency_hz},
                        {"damping_ratio", m.mode.damping_ratio},
                        {"mpc", m.mode.mpc},
                        {"emac", m.mode.emac}});
      }
      mj["identified"] = used;
    }
    if (p.uff) {
      // Modes read from UFF dataset 55: where each came from, and each sensor.
      nlohmann::json modes = nlohmann::json::array(), sensors = nlohmann::json::array();
      for (std::size_t k = 0; k < p.uff->modes.size(); ++k) {
        const UffMode& m = p.uff->modes[k];
        modes.push_back({{"mode", p.uff->used[k]},
                         {"line", m.line},
                         {"mode_number", m.mode_number},
                         {"analysis_type", static_cast<int>(m.analysis_type)},
                         {"complex", m.analysis_type != UffAnalysisType::kNormalMode},
                         {"frequency_hz", m.frequency_hz},
                         {"damping_ratio", m.damping_ratio},
                         {"mpc", m.mpc},
                         {"imaginary_fraction", m.imaginary_fraction}});
      }
      for (const UffSensor& sensor : p.uff->sensors) {
        sensors.push_back({{"node", sensor.node},
                           {"direction", UffDirectionName(sensor.direction)},
                           {"dof", sensor.label},
                           {"from", sensor.source}});
      }
      mj["uff"] = {{"modes_in_file", p.uff->all_frequencies_hz.size()},
                   {"modes", modes},
                   {"sensors", sensors}};
    }
    if (!p.expansion_method.empty()) {
      mj["expansion"] = {{"method", p.expansion_method},
                         {"model_modes", p.expansion_modes},
                         {"sensor_mac", json_util::Vector(p.expansion_sensor_mac)},
                         {"condition_number", json_util::Vector(p.expansion_condition)}};
    }
    j["measurements"].push_back(mj);
  }
  // A dry study (no added-mass factor) has no added-mass matrix to write.
  const bool has_added_mass =
      std::any_of(r.parameters.begin(), r.parameters.end(),
                  [](const Parameter& p) { return p.kind == ParameterKind::kAddedMass; });
  j["files"] = nlohmann::json::array();
  if (has_added_mass) j["files"].push_back("added_mass.mtx");
  for (const char* f :
       {"updated_stiffness.mtx", "updated_dry_mass.mtx", "system_Z.mtx", "system_F.mtx"})
    j["files"].push_back(f);
  for (const PreparedState& p : r.sources) {
    if (p.identified)
      WriteIdentifyOutputs(*p.identified, plots, out, warnings, p.data.state + "_");
  }
  out->WriteText("result.json", j.dump(2) + "\n");
  if (has_added_mass) WriteMatrixMarket(out->Stage("added_mass.mtx"), r.added_mass, true);
  WriteMatrixMarket(out->Stage("updated_stiffness.mtx"), r.updated_stiffness, true);
  WriteMatrixMarket(out->Stage("updated_dry_mass.mtx"), r.updated_dry_mass, true);
  WriteMatrixMarket(out->Stage("system_Z.mtx"), r.problem.A);
  WriteMatrixMarket(out->Stage("system_F.mtx"), Eigen::MatrixXd(r.problem.b));
  if (!plots) return;

  // Estimated vs preset factors (the paper's Figs. 2-3).
  Figure factors;
  factors.width_px = std::max(900, 40 * static_cast<int>(r.parameters.size()) + 200);
  Plot fp;
  fp.title = r.study_name + ": correction factors";
  fp.x_label = "parameter";
  fp.y_label = "factor";
  PlotSeries est{"estimated", PlotSeries::Style::kBars, {}, {}, {}, {}};
  PlotSeries pre{"preset", PlotSeries::Style::kBars, {}, {}, {}, {}};
  for (std::size_t i = 0; i < r.parameters.size(); ++i) {
    fp.x_tick_labels.push_back(r.parameters[i].name);
    est.x.push_back(i + 1.0);
    est.y.push_back(r.solution.x[i]);
    if (r.preset) {
      pre.x.push_back(i + 1.0);
      pre.y.push_back((*r.preset)[i]);
    }
  }
  fp.series.push_back(est);
  if (r.preset) fp.series.push_back(pre);
  if (r.solution.standard_error.size() ==
      static_cast<Eigen::Index>(r.parameters.size())) {
    std::ostringstream label;
    label << r.solution.confidence_level * 100 << " % interval";
    PlotSeries ci{label.str(), PlotSeries::Style::kErrorBars, {}, {}, {}, {}};
    for (std::size_t i = 0; i < r.parameters.size(); ++i) {
      ci.x.push_back(i + 1.0);
      ci.y.push_back(r.solution.x[i]);
      ci.y_low.push_back(r.solution.interval_lower[i]);
      ci.y_high.push_back(r.solution.interval_upper[i]);
    }
    fp.series.push_back(ci);
  }
  factors.panels.push_back(fp);
  std::vector<std::pair<std::string, Figure>> figures = {{"factors", factors}};

  // Frequencies per state: measured, nominal model, updated.
  Figure freq;
  freq.columns = static_cast<int>(r.states.size());
  freq.width_px = 450 * freq.columns + 100;
  for (const StateComparison& c : r.states) {
    Plot p;
    p.title = c.state + " (" + ToString(c.immersion) + ")";
    p.x_label = "mode";
    p.y_label = "frequency error vs measured (%)";
    PlotSeries m0{"nominal model", PlotSeries::Style::kBars, {}, {}, {}, {}};
    PlotSeries m1{"updated model", PlotSeries::Style::kBars, {}, {}, {}, {}};
    for (Eigen::Index k = 0; k < c.measured_hz.size(); ++k) {
      m0.x.push_back(k + 1.0);
      m0.y.push_back(ErrorPercent(c.model_hz[k], c.measured_hz[k]));
      m1.x.push_back(k + 1.0);
      m1.y.push_back(ErrorPercent(c.updated_hz[k], c.measured_hz[k]));
      std::ostringstream label;
      label << "mode " << k + 1 << " (" << std::fixed << std::setprecision(2)
            << c.measured_hz[k] << " Hz)";
      p.x_tick_labels.push_back(label.str());
    }
    p.series = {m0, m1};
    freq.panels.push_back(p);
  }
  figures.emplace_back("frequencies", freq);

  // Mode shapes per state with shapes: measured points, updated lines.
  for (const StateComparison& c : r.states) {
    // Sensors between nodes have no model DOF to place them on the plot.
    if (c.measured_shapes.cols() == 0 || c.shape_dofs.empty()) continue;
    Figure shapes;
    shapes.columns =
        static_cast<int>(std::min<Eigen::Index>(c.measured_shapes.cols(), 4));
    shapes.width_px = 380 * shapes.columns + 100;
    shapes.height_px = 500;
    std::vector<int> rows;
    for (int dof : r.plot_dofs) {
      const auto it = std::find(c.shape_dofs.begin(), c.shape_dofs.end(), dof);
      if (it != c.shape_dofs.end())
        rows.push_back(static_cast<int>(it - c.shape_dofs.begin()));
    }
    if (rows.empty()) rows = TransverseRows(r.dof_labels, c.shape_dofs);
    std::vector<int> dofs;
    for (int i : rows) dofs.push_back(c.shape_dofs[i]);
    const std::vector<double> x = Positions(r, dofs);
    for (Eigen::Index k = 0; k < c.measured_shapes.cols(); ++k) {
      Plot p;
      p.title = c.state + " mode " + std::to_string(k + 1);
      p.x_label = "position along the structure";
      p.y_label = "shape (measured scale)";
      PlotSeries meas{"measured", PlotSeries::Style::kPoints, x, {}, {}, {}};
      PlotSeries nom{"nominal model", PlotSeries::Style::kLines, x, {}, {}, {}};
      PlotSeries upd{"updated model", PlotSeries::Style::kLines, x, {}, {}, {}};
      for (int i : rows) {
        meas.y.push_back(c.measured_shapes(i, k));
        nom.y.push_back(c.model_shapes.rows() > i ? c.model_shapes(i, k) : kNaN);
        upd.y.push_back(c.updated_shapes.rows() > i ? c.updated_shapes(i, k) : kNaN);
      }
      p.series = {meas, nom, upd};
      shapes.panels.push_back(p);
    }
    figures.emplace_back("shapes_" + c.state, shapes);
  }
  // The L-curve and the GCV function of a regularised solve (tikhonov: lambda;
  // tsvd: the kept singular values), with the chosen point.
  if (!reg.grid_lambda.empty()) {
    Figure lf;
    lf.columns = 2;
    lf.width_px = 1100;
    lf.panels = RegularisationPlots(reg, "residual norm ||Z d - F||",
                                    "solution (semi)norm ||L (d - d0)||");
    figures.emplace_back("lcurve_gcv", lf);
  }
  for (const auto& [name, figure] : figures) {
    RenderStaged(figure, name, out, warnings);
  }
}

std::string UpdateReport(const UpdateResult& r) {
  std::ostringstream o;
  o << std::fixed;
  o << "study: " << r.study_name << "\nmodel: " << r.model_description << " ("
    << r.num_dofs << " DOFs)\n";
  const Identifiability& u = r.identifiability_unconstrained;
  if (r.problem.num_rows() > 0) {
    if (r.normal_system) {
      o << "system: " << ToString(r.form) << " form weighted by all " << r.num_fem_modes
        << " FEM modes (M^-1 by a sparse Cholesky factor, no eigenbasis), "
        << r.problem.data_rows() << " equations compressed to " << r.problem.num_rows()
        << " x " << r.problem.num_unknowns() << ", rank " << u.rank << " of "
        << r.problem.num_unknowns() << "\n";
    } else {
      o << "system: " << ToString(r.form) << " form, " << r.problem.num_rows() << " x "
        << r.problem.num_unknowns() << ", " << r.num_fem_modes << " FEM modes, rank "
        << u.rank << " of " << r.problem.num_unknowns() << "\n";
    }
  } else {
    o << "system: no Z d = F (incomplete shapes or frequencies only); the sensitivity "
         "Jacobian is analysed below\n";
  }
  for (const auto& nd : u.null_directions)
    o << "  null direction: " << nd.description << "\n";
  for (const auto& w : u.warnings) o << "  note: " << w << "\n";
  if (!r.problem.fixed.empty()) {
    o << "fixed:";
    for (const auto& f : r.problem.fixed) {
      o << " " << r.problem.names[f.first] << " = " << std::setprecision(6) << f.second;
    }
    o << "\n";
  }
  const Identifiability& s = r.solution.identifiability;
  o << "solver: " << ToString(r.solution.summary.status) << " (rank " << s.rank
    << ", condition " << std::setprecision(1) << s.condition_number_in_rank
    << "): " << r.method << " method, " << r.solver_name << ": "
    << r.solution.summary.message << "\n";
  for (const auto& w : r.solution.summary.warnings) o << "  warning: " << w << "\n";
  if (r.method == "sensitivity" &&
      r.solution.identifiability.singular_values.size() > 0) {
    const Identifiability& id = r.solution.identifiability;
    o << "sensitivity Jacobian at the answer: rank " << id.rank << " of "
      << id.singular_values.size() << " free parameters\n";
    for (const auto& nd : id.null_directions)
      o << "  not determined by the data: " << nd.description << "\n";
  }
  const bool has_se =
      r.solution.standard_error.size() == static_cast<Eigen::Index>(r.parameters.size());
  o << "\n";
  o << std::left << std::setw(22) << "parameter" << std::right << std::setw(14)
    << "estimate" << std::setw(14) << (r.preset ? "preset" : "") << std::setw(14)
    << (has_se ? "std_error" : "") << "\n";
  for (std::size_t i = 0; i < r.parameters.size(); ++i) {
    o << std::left << std::setw(22) << r.parameters[i].name << std::right << std::setw(14)
      << std::setprecision(6) << r.solution.x[i];
    o << std::setw(14);
    if (r.preset) {
      o << (*r.preset)[i];
    } else {
      o << "";
    }
    if (has_se) o << std::setw(14) << r.solution.standard_error[i];
    if (r.fixed[i]) o << "  (fixed)";
    o << "\n";
  }
  if (r.added_mass_summary.present) {
    const AddedMassSummary& a = r.added_mass_summary;
    o << "\nadded mass: Sa (mean factor over " << a.wet_elements
      << " wet elements) = " << std::setprecision(4) << a.sa << "; "
      << std::setprecision(3) << a.total_kg << " kg in transverse translation";
    if (a.wet_length_m > 0)
      o << " = " << std::setprecision(4) << a.per_length << " kg/m over "
        << std::setprecision(3) << a.wet_length_m << " m";
    o << "\n";
    if (!a.eq2_coefficients.empty()) {
      o << "  Eq. 2 from the measured frequencies, (f_air/f_water)^2 - 1:";
      for (double c : a.eq2_coefficients) o << " " << std::setprecision(4) << c;
      o << "\n";
    }
  }
  for (std::size_t si = 0; si < r.states.size(); ++si) {
    const StateComparison& c = r.states[si];
    o << "\nstate " << c.state << " (" << ToString(c.immersion) << ")\n";
    if (si < r.sources.size()) {
      const PreparedState& p = r.sources[si];
      if (p.identified) {
        o << "  identified by ERA in " << p.source << ": " << p.identified->modes.size()
          << " stable mode(s); used";
        for (int k : p.identified_modes) {
          const StableMode& m = p.identified->modes[k - 1];
          o << " " << std::setprecision(3) << m.mode.frequency_hz << " Hz (damping "
            << std::setprecision(2) << 100 * m.mode.damping_ratio << " %, MPC "
            << std::setprecision(3) << m.mode.mpc << ")";
        }
        o << "\n";
      } else if (p.uff) {
        o << "  " << p.uff->modes.size() << " of " << p.uff->all_frequencies_hz.size()
          << " mode(s) of UFF dataset 55 in " << p.source << " at "
          << p.uff->sensors.size() << " DOF(s);";
        for (const UffMode& m : p.uff->modes) {
          o << " " << std::setprecision(4) << m.frequency_hz << " Hz";
          if (m.analysis_type != UffAnalysisType::kNormalMode)
            o << " (complex, damping " << std::setprecision(2) << 100 * m.damping_ratio
              << " %, MPC " << std::setprecision(4) << m.mpc << ")";
        }
        o << "\n";
      } else if (!p.source.empty()) {
        o << "  modes read from " << p.source << "\n";
      }
      if (!p.expansion_method.empty()) {
        o << "  expanded from " << p.at_sensors.shapes.rows() << " sensors to "
          << r.num_dofs << " DOFs by " << p.expansion_method;
        if (p.expansion_modes > 0) o << " (" << p.expansion_modes << " model modes)";
        o << "; sensor MAC";
        for (Eigen::Index k = 0; k < p.expansion_sensor_mac.size(); ++k)
          o << " " << std::setprecision(4) << p.expansion_sensor_mac[k];
        if (p.expansion_modes > 0) {
          o << "; condition";
          for (Eigen::Index k = 0; k < p.expansion_condition.size(); ++k)
            o << " " << std::setprecision(1) << p.expansion_condition[k];
        }
        o << "\n";
      }
    }
    o << "  mode  measured_Hz   model_Hz  err_%   updated_Hz  err_%   MAC_mod   "
         "MAC_upd\n";
    for (Eigen::Index k = 0; k < c.measured_hz.size(); ++k) {
      o << "  " << std::setw(4) << k + 1 << std::setw(12) << std::setprecision(4)
        << c.measured_hz[k] << std::setw(11) << c.model_hz[k] << std::setw(7)
        << std::setprecision(2) << ErrorPercent(c.model_hz[k], c.measured_hz[k])
        << std::setw(13) << std::setprecision(4) << c.updated_hz[k] << std::setw(7)
        << std::setprecision(2) << ErrorPercent(c.updated_hz[k], c.measured_hz[k])
        << std::setw(10) << std::setprecision(4) << c.model_mac[k] << std::setw(10)
        << c.updated_mac[k] << "\n";
    }
  }
  return o.str();
}

}  // namespace femup
