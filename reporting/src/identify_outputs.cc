#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "femup/core/errors.h"
#include "femup/core/io/csv_series.h"
#include "femup/core/io/uff.h"
#include "femup/core/sysid/frf_impulse.h"
#include "femup/reporting/outputs.h"
#include "json_util.h"
#include "render_staged.h"

namespace femup {

void WriteIdentifyOutputs(const IdentifyResult& r, bool plots, OutputDir* out,
                          std::vector<std::string>* warnings, const std::string& prefix) {
  nlohmann::json j;
  j["femup_version"] = "0.1.0";
  j["command"] = "identify";
  j["source"] = r.source;
  j["data"] = {{"kind", r.data_kind},
               {"channels", r.channels},
               {"sample_rate_hz", r.sample_rate_hz},
               {"samples", r.num_samples}};
  j["era"] = {{"block_rows", r.diagram.block_rows},
              {"block_columns", r.diagram.block_columns},
              {"singular_values", json_util::Vector(r.diagram.singular_values)}};
  j["modes"] = nlohmann::json::array();
  for (const StableMode& m : r.modes) {
    j["modes"].push_back({{"frequency_hz", m.mode.frequency_hz},
                          {"damping_ratio", m.mode.damping_ratio},
                          {"shape", json_util::Vector(m.mode.shape)},
                          {"mpc", m.mode.mpc},
                          {"emac", m.mode.emac},
                          {"contribution", m.mode.contribution},
                          {"order", m.order},
                          {"stable_run", m.stable_run},
                          {"frequency_std_hz", m.frequency_std_hz},
                          {"damping_std", m.damping_std}});
  }
  j["notes"] = r.notes;
  out->WriteText(prefix + "modes.json", j.dump(2) + "\n");
  if (!plots) return;

  // Stabilisation diagram: every pole by frequency and order, stable ones apart.
  Figure f;
  f.width_px = 1000;
  Plot p;
  p.title =
      "stabilisation diagram: " + std::filesystem::path(r.source).filename().string();
  p.x_label = "frequency (Hz)";
  p.y_label = "model order";
  PlotSeries all{"pole", PlotSeries::Style::kPoints, {}, {}, {}, {}};
  PlotSeries freq{"stable frequency", PlotSeries::Style::kPoints, {}, {}, {}, {}};
  PlotSeries stable{
      "stable frequency, damping and shape", PlotSeries::Style::kPoints, {}, {}, {}, {}};
  for (const DiagramOrder& o : r.diagram.orders) {
    for (const DiagramPole& q : o.poles) {
      PlotSeries& s = q.stable() ? stable : (q.stable_frequency ? freq : all);
      s.x.push_back(q.mode.frequency_hz);
      s.y.push_back(o.order);
    }
  }
  for (PlotSeries* s : {&all, &freq, &stable}) {
    if (!s->x.empty()) p.series.push_back(*s);
  }
  for (const StableMode& m : r.modes) {
    std::ostringstream t;
    t << std::fixed << std::setprecision(2) << m.mode.frequency_hz << " Hz";
    p.series.push_back({t.str(),
                        PlotSeries::Style::kLines,
                        {m.mode.frequency_hz, m.mode.frequency_hz},
                        {0.0, static_cast<double>(r.diagram.orders.back().order)},
                        {},
                        {}});
  }
  p.key_outside = true;
  f.panels.push_back(p);
  RenderStaged(f, prefix + "stabilisation", out, warnings);

  if (r.modes.empty()) return;
  Figure g;
  Plot s;
  s.title = "identified mode shapes at the sensors (largest entry 1)";
  s.x_label = "channel";
  s.y_label = "shape";
  s.key_outside = true;
  s.x_tick_labels = r.channels;
  for (std::size_t k = 0; k < r.modes.size() && k < 8; ++k) {
    const Eigen::VectorXd& v = r.modes[k].mode.shape;
    const double peak = v.cwiseAbs().maxCoeff();
    Eigen::Index imax = 0;
    v.cwiseAbs().maxCoeff(&imax);
    const double scale = peak > 0 ? (v[imax] < 0 ? -1.0 : 1.0) / peak : 1.0;
    std::ostringstream t;
    t << std::fixed << std::setprecision(2) << r.modes[k].mode.frequency_hz << " Hz";
    PlotSeries ser{t.str(), PlotSeries::Style::kLinesPoints, {}, {}, {}, {}};
    for (Eigen::Index i = 0; i < v.size(); ++i) {
      ser.x.push_back(static_cast<double>(i + 1));
      ser.y.push_back(scale * v[i]);
    }
    s.series.push_back(ser);
  }
  g.panels.push_back(s);
  RenderStaged(g, prefix + "identified_shapes", out, warnings);
}

std::string IdentifyReport(const IdentifyResult& r) {
  std::ostringstream o;
  o << "source: " << r.source << " (" << r.data_kind << ", " << r.channels.size()
    << " channels, " << r.num_samples << " samples at " << r.sample_rate_hz << " Hz)\n";
  o << "ERA: Hankel " << r.diagram.block_rows << " x " << r.diagram.block_columns
    << " blocks, orders " << r.diagram.orders.front().order << ".."
    << r.diagram.orders.back().order << "\n";
  o << "  mode  frequency_Hz  damping_%    MPC   EMAC  stable_orders\n" << std::fixed;
  for (std::size_t k = 0; k < r.modes.size(); ++k) {
    const StableMode& m = r.modes[k];
    o << "  " << std::setw(4) << k + 1 << std::setw(14) << std::setprecision(3)
      << m.mode.frequency_hz << std::setw(11) << std::setprecision(3)
      << 100 * m.mode.damping_ratio << std::setw(7) << std::setprecision(3) << m.mode.mpc
      << std::setw(7) << m.mode.emac << std::setw(15) << m.stable_run << "\n";
  }
  if (r.modes.empty()) o << "  no mode stayed stable over enough orders\n";
  for (const std::string& n : r.notes) o << "note: " << n << "\n";
  return o.str();
}

}  // namespace femup
