#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "femup/core/errors.h"
#include "femup/core/fe/dof_labels.h"
#include "femup/core/fe/strip_theory.h"
#include "femup/core/io/csv_series.h"
#include "femup/core/io/uff.h"
#include "femup/core/linalg/modal.h"
#include "femup/reporting/outputs.h"
#include "femup/reporting/plot.h"
#include "json_util.h"
#include "render_staged.h"

namespace femup {
namespace {

// UFF node and direction of a DOF label: "n12:ux" -> node 12, +X; other labels
// -> node (DOF + 1), +X.
void NodeAndDirection(const std::string& label, int dof, int* node, int* direction) {
  *node = dof + 1;
  *direction = 1;
  const auto colon = label.find(':');
  if (label.size() > 1 && label[0] == 'n' && colon != std::string::npos) {
    try {
      *node = std::stoi(label.substr(1, colon - 1));
    } catch (...) {
      *node = dof + 1;
    }
    const std::string d = label.substr(colon + 1);
    *direction = d == "uy" ? 2 : (d == "rz" ? 6 : 1);
  }
}

}  // namespace

void WriteSimulateOutputs(const SimulateResult& r, bool plots, OutputDir* out,
                          std::vector<std::string>* warnings) {
  nlohmann::json j;
  j["femup_version"] = "0.1.0";
  j["command"] = "simulate";
  j["study"] = r.study_name;
  j["model"] = r.description;
  j["impulse_dof"] = r.impulse_label;
  j["states"] = nlohmann::json::array();
  for (const SimulatedState& st : r.states) {
    const TimeResponse& t = st.response;
    const std::string path = out->Stage(st.spec.file);
    const std::string ext = std::filesystem::path(st.spec.file).extension().string();
    if (ext == ".csv") {
      CsvSeries csv;
      csv.time_name = "time_s";
      csv.channel_names = st.sensors;
      csv.time = t.Times();
      csv.values = t.data.transpose();
      WriteCsvSeries(path, csv);
    } else {
      std::vector<UffDataset> sets;
      int ref_node = 0, ref_dir = 0;
      NodeAndDirection(r.impulse_label, r.impulse_dof, &ref_node, &ref_dir);
      for (int c = 0; c < t.num_channels(); ++c) {
        UffFunction f;
        f.id_lines[0] = r.study_name + " " + st.spec.state;
        f.id_lines[1] = "simulated by femup: impulse at " + r.impulse_label;
        f.id_lines[2] = "channel " + std::to_string(c + 1) + " " + st.sensors[c];
        f.function_type = 1;
        f.function_id = c + 1;
        NodeAndDirection(st.sensors[c], t.sensor_dofs[c], &f.response_node,
                         &f.response_direction);
        f.reference_node = ref_node;
        f.reference_direction = ref_dir;
        f.ordinate_type = UffOrdinateType::kRealDouble;
        f.even_spacing = true;
        f.abscissa_start = 0.0;
        f.abscissa_increment = 1.0 / t.sample_rate_hz;
        f.abscissa_axis = {17, 0, 0, 0, "Time", "s"};
        f.ordinate_axis = {12, 1, 0, 0, "Acceleration", "m/s^2"};
        f.x = t.Times();
        f.y = t.data.row(c).transpose().cast<std::complex<double>>();
        sets.emplace_back(std::move(f));
      }
      WriteUff(path, sets);
    }
    nlohmann::json sj = {{"state", st.spec.state},
                         {"immersion", ToString(st.spec.immersion)},
                         {"file", st.spec.file},
                         {"sensors", st.sensors},
                         {"sample_rate_hz", t.sample_rate_hz},
                         {"cutoff_hz", st.cutoff_hz},
                         {"samples", t.num_samples()},
                         {"noise_std", json_util::Vector(t.noise_std)},
                         {"frequencies_hz", json_util::Vector(st.frequencies_hz)},
                         {"damping_ratios", json_util::Vector(st.damping_ratios)}};
    nlohmann::json shapes = nlohmann::json::array();
    for (Eigen::Index c = 0; c < st.shapes.cols(); ++c)
      shapes.push_back(json_util::Vector(st.shapes.col(c)));
    sj["shapes_at_sensors"] = shapes;
    if (st.spec.water) {
      const StripTheoryWater& w = *st.spec.water;
      sj["water"] = {
          {"depth", w.depth},
          {"fluid_density", w.fluid_density},
          {"width", w.width},
          {"thickness", w.thickness},
          {"coefficient", st.added_mass_coefficient},
          {"fade", w.fade},
          {"added_mass_per_length", st.added_mass_per_length},
          {"structural_mass_per_length", st.structural_mass_per_length},
          {"ratio", st.structural_mass_per_length > 0
                        ? st.added_mass_per_length / st.structural_mass_per_length
                        : 0.0}};
    }
    j["states"].push_back(sj);
  }
  out->WriteText("truth.json", j.dump(2) + "\n");
  if (!plots) return;
  Figure fig;
  fig.columns = 1;
  fig.width_px = 1000;
  fig.height_px = 320 * static_cast<int>(r.states.size()) + 80;
  for (const SimulatedState& st : r.states) {
    Plot p;
    p.title = st.spec.state + ": acceleration at " + st.sensors.front() + " and " +
              st.sensors.back();
    p.x_label = "time (s)";
    p.y_label = "acceleration (m/s^2)";
    const Eigen::VectorXd time = st.response.Times();
    for (int c : {0, st.response.num_channels() - 1}) {
      PlotSeries s{st.sensors[c], PlotSeries::Style::kLines, {}, {}, {}, {}};
      s.x.assign(time.data(), time.data() + time.size());
      for (int k = 0; k < st.response.num_samples(); ++k)
        s.y.push_back(st.response.data(c, k));
      p.series.push_back(s);
      if (st.response.num_channels() == 1) break;
    }
    fig.panels.push_back(p);
  }
  RenderStaged(fig, "records", out, warnings);
}

std::string SimulateReport(const SimulateResult& r) {
  std::ostringstream o;
  o << std::fixed;
  o << "simulated records of " << r.study_name << ": " << r.description << "\n"
    << "impulse at " << r.impulse_label << ", " << r.sample_rate_hz << " Hz sampling\n";
  for (const SimulatedState& st : r.states) {
    o << "\nstate " << st.spec.state << " (" << ToString(st.spec.immersion) << ") -> "
      << st.spec.file << ": " << st.response.num_channels() << " channels x "
      << st.response.num_samples() << " samples\n";
    if (st.spec.water) {
      o << "  strip-theory water to " << std::setprecision(3) << st.spec.water->depth
        << " m: C_A " << std::setprecision(3) << st.added_mass_coefficient << ", "
        << std::setprecision(4) << st.added_mass_per_length << " kg/m";
      if (st.structural_mass_per_length > 0)
        o << " (" << std::setprecision(4)
          << st.added_mass_per_length / st.structural_mass_per_length
          << " of the beam's mass per length)";
      o << "\n";
    }
    o << "  modes below the " << std::setprecision(0) << st.cutoff_hz << " Hz cut-off:";
    for (Eigen::Index j = 0; j < st.frequencies_hz.size(); ++j)
      o << " " << std::setprecision(3) << st.frequencies_hz[j] << " Hz";
    o << "\n";
  }
  return o.str();
}

}  // namespace femup
