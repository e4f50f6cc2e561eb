// femup info on a Universal File Format file: the names of the UFF codes and a
// line of text and a JSON object per dataset (nodes 15/2411, data at nodes 55,
// functions 58/58b).
#include "file_info_uff.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <variant>

#include "femup/core/errors.h"
#include "femup/core/io/uff_modes.h"

namespace femup::file_info {
namespace {

// --- Names of UFF codes -------------------------------------------------------

std::string FunctionTypeName(int type) {
  switch (type) {
    case 0:
      return "general or unknown";
    case 1:
      return "time response";
    case 2:
      return "auto spectrum";
    case 3:
      return "cross spectrum";
    case 4:
      return "frequency response function";
    case 5:
      return "transmissibility";
    case 6:
      return "coherence";
    case 7:
      return "auto correlation";
    case 8:
      return "cross correlation";
    case 9:
      return "power spectral density";
    case 10:
      return "energy spectral density";
    case 11:
      return "probability density function";
    case 12:
      return "spectrum";
    case 18:
      return "mode indicator function";
    case 26:
      return "multiple coherence";
    case 27:
      return "order function";
    default:
      return "function type " + std::to_string(type);
  }
}

std::string DataTypeName(int type) {
  switch (type) {
    case 0:
      return "unknown";
    case 1:
      return "general";
    case 2:
      return "stress";
    case 3:
      return "strain";
    case 5:
      return "temperature";
    case 6:
      return "heat flux";
    case 8:
      return "displacement";
    case 9:
      return "reaction force";
    case 11:
      return "velocity";
    case 12:
      return "acceleration";
    case 13:
      return "excitation force";
    case 15:
      return "pressure";
    case 16:
      return "mass";
    case 17:
      return "time";
    case 18:
      return "frequency";
    case 19:
      return "rpm";
    case 20:
      return "order";
    default:
      return "data type " + std::to_string(type);
  }
}

std::string AnalysisName(UffAnalysisType type) {
  switch (type) {
    case UffAnalysisType::kNormalMode:
      return "normal mode";
    case UffAnalysisType::kComplexFirstOrder:
      return "complex mode (first order)";
    case UffAnalysisType::kFrequencyResponse:
      return "frequency response shape";
    case UffAnalysisType::kComplexSecondOrder:
      return "complex mode (second order)";
  }
  return "analysis type " + std::to_string(static_cast<int>(type));
}

std::string CharacteristicName(int c) {
  switch (c) {
    case 1:
      return "scalar";
    case 2:
      return "translations";
    case 3:
      return "translations and rotations";
    case 4:
      return "symmetric tensor";
    case 5:
      return "general tensor";
    default:
      return "data characteristic " + std::to_string(c);
  }
}

std::string DirectionText(int direction) {
  return direction == 0 ? "scalar" : UffDirectionName(direction);
}

bool IsComplexMode(const UffModeShape& s) {
  return s.analysis_type == UffAnalysisType::kComplexFirstOrder ||
         s.analysis_type == UffAnalysisType::kComplexSecondOrder;
}

// The columns of 55 values as directions when they are nodal DOFs (3 or 6).
std::vector<std::string> ValueDirections(int per_node) {
  std::vector<std::string> out;
  if (per_node == 3 || per_node == 6) {
    for (int d = 1; d <= per_node; ++d) out.push_back(UffDirectionName(d));
  } else {
    for (int d = 1; d <= per_node; ++d) out.push_back("value " + std::to_string(d));
  }
  return out;
}

enum class Abscissa { kTime, kFrequency, kOther };

Abscissa AbscissaKind(const UffFunction& f) {
  if (f.abscissa_axis.specific_data_type == 17) return Abscissa::kTime;
  if (f.abscissa_axis.specific_data_type == 18) return Abscissa::kFrequency;
  switch (f.function_type) {
    case 1:
    case 7:
    case 8:
      return Abscissa::kTime;
    case 2:
    case 3:
    case 4:
    case 5:
    case 6:
    case 9:
    case 10:
    case 12:
      return Abscissa::kFrequency;
    default:
      return Abscissa::kOther;
  }
}

std::string OrdinateTypeName(const UffFunction& f) {
  return std::string(f.IsComplex() ? "complex" : "real") +
         (f.IsDoublePrecision() ? " double" : " single");
}

std::string AxisText(const UffAxis& a) {
  std::string out = a.label == "NONE" || a.label.empty()
                        ? DataTypeName(a.specific_data_type)
                        : "'" + a.label + "'";
  if (!a.units.empty() && a.units != "NONE") out += " [" + a.units + "]";
  return out;
}

nlohmann::json AxisJson(const UffAxis& a) {
  return {{"specific_data_type", a.specific_data_type},
          {"data", DataTypeName(a.specific_data_type)},
          {"label", a.label},
          {"units", a.units},
          {"exponents",
           {{"length", a.length_exponent},
            {"force", a.force_exponent},
            {"temperature", a.temperature_exponent}}}};
}

// --- Per-dataset descriptions -------------------------------------------------

void DescribeNodes(const UffNodes& d, std::string* text, nlohmann::json* j) {
  std::vector<int> labels;
  std::set<int> systems;
  std::array<double, 3> lo{0, 0, 0}, hi{0, 0, 0};
  for (std::size_t i = 0; i < d.nodes.size(); ++i) {
    const UffNode& n = d.nodes[i];
    labels.push_back(n.label);
    systems.insert(n.definition_cs);
    systems.insert(n.displacement_cs);
    for (std::size_t c = 0; c < 3; ++c) {
      lo[c] = i == 0 ? n.xyz[c] : std::min(lo[c], n.xyz[c]);
      hi[c] = i == 0 ? n.xyz[c] : std::max(hi[c], n.xyz[c]);
    }
  }
  std::ostringstream t;
  t << "nodes (" << (d.dataset == 15 ? "single" : "double")
    << " precision): " << d.nodes.size() << " (" << LabelRanges(labels) << ")";
  if (!d.nodes.empty()) {
    const char* axes[3] = {"X", "Y", "Z"};
    for (std::size_t c = 0; c < 3; ++c)
      t << (c ? ", " : "; ") << axes[c] << " " << Num(lo[c]) << " .. " << Num(hi[c]);
  }
  std::vector<int> cs(systems.begin(), systems.end());
  t << "; coordinate systems " << LabelRanges(cs);
  *text = t.str();
  (*j)["kind"] = "nodes";
  (*j)["nodes"] = d.nodes.size();
  (*j)["labels"] = labels;
  if (!d.nodes.empty()) (*j)["extent"] = {{"min", lo}, {"max", hi}};
  (*j)["coordinate_systems"] = cs;
}

void DescribeShape(const UffModeShape& s, std::string* text, nlohmann::json* j) {
  const int per_node = static_cast<int>(s.values.cols());
  const std::vector<std::string> dirs = ValueDirections(per_node);
  std::ostringstream t;
  t << AnalysisName(s.analysis_type) << " "
    << (s.analysis_type == UffAnalysisType::kFrequencyResponse ? "at step " : "")
    << s.mode_number << ": ";
  (*j)["kind"] = "data at nodes";
  (*j)["analysis_type"] = static_cast<int>(s.analysis_type);
  (*j)["analysis"] = AnalysisName(s.analysis_type);
  (*j)["mode_number"] = s.mode_number;
  (*j)["load_case"] = s.load_case;
  if (IsComplexMode(s)) {
    double f = 0, zeta = 0;
    try {
      ComplexEigenvalueModes(s.eigenvalue, &f, &zeta, "");
      t << Num(f) << " Hz, damping " << Num(100 * zeta, 4) << " % (eigenvalue "
        << Num(s.eigenvalue.real()) << (s.eigenvalue.imag() < 0 ? " - " : " + ")
        << Num(std::abs(s.eigenvalue.imag())) << "i rad/s)";
      (*j)["frequency_hz"] = f;
      (*j)["damping_ratio"] = zeta;
    } catch (const InputError&) {
      t << "eigenvalue 0 (no frequency)";
    }
    (*j)["eigenvalue"] = {s.eigenvalue.real(), s.eigenvalue.imag()};
    (*j)["modal_a"] = {s.modal_a.real(), s.modal_a.imag()};
    (*j)["modal_b"] = {s.modal_b.real(), s.modal_b.imag()};
  } else if (s.analysis_type == UffAnalysisType::kNormalMode) {
    t << Num(s.frequency_hz) << " Hz, damping " << Num(100 * s.viscous_damping_ratio, 4)
      << " %, modal mass " << Num(s.modal_mass);
    (*j)["frequency_hz"] = s.frequency_hz;
    (*j)["damping_ratio"] = s.viscous_damping_ratio;
    (*j)["hysteretic_damping_ratio"] = s.hysteretic_damping_ratio;
    (*j)["modal_mass"] = s.modal_mass;
  } else {
    t << Num(s.frequency_hz) << " Hz";
    (*j)["frequency_hz"] = s.frequency_hz;
  }
  t << "; " << s.nodes.size() << " nodes (" << LabelRanges(s.nodes) << ") x " << per_node
    << " values (";
  for (std::size_t k = 0; k < dirs.size(); ++k) t << (k ? " " : "") << dirs[k];
  t << "), " << CharacteristicName(s.data_characteristic) << ", "
    << DataTypeName(s.specific_data_type) << ", "
    << (s.complex_data ? "complex" : "real");
  *text = t.str();
  (*j)["data_characteristic"] = s.data_characteristic;
  (*j)["specific_data_type"] = s.specific_data_type;
  (*j)["data"] = DataTypeName(s.specific_data_type);
  (*j)["complex_data"] = s.complex_data;
  (*j)["values_per_node"] = per_node;
  (*j)["directions"] = dirs;
  (*j)["nodes"] = s.nodes;
}

void DescribeFunction(const UffFunction& f, std::string* text, nlohmann::json* j) {
  std::ostringstream t;
  t << FunctionTypeName(f.function_type) << ": response " << f.response_node << " "
    << DirectionText(f.response_direction) << ", reference " << f.reference_node << " "
    << DirectionText(f.reference_direction) << "; " << f.y.size() << " points, "
    << OrdinateTypeName(f) << (f.binary ? " (binary)" : "");
  (*j)["kind"] = "function";
  (*j)["function_type"] = f.function_type;
  (*j)["function"] = FunctionTypeName(f.function_type);
  (*j)["id"] = f.id_lines[0];
  (*j)["response"] = {{"entity", f.response_entity},
                      {"node", f.response_node},
                      {"direction", DirectionText(f.response_direction)}};
  (*j)["reference"] = {{"entity", f.reference_entity},
                       {"node", f.reference_node},
                       {"direction", DirectionText(f.reference_direction)}};
  (*j)["ordinate_type"] = static_cast<int>(f.ordinate_type);
  (*j)["ordinate"] = OrdinateTypeName(f);
  (*j)["binary"] = f.binary;
  (*j)["points"] = f.y.size();
  (*j)["even_spacing"] = f.even_spacing;
  const Abscissa kind = AbscissaKind(f);
  if (f.even_spacing) {
    (*j)["abscissa_start"] = f.abscissa_start;
    (*j)["abscissa_increment"] = f.abscissa_increment;
    if (kind == Abscissa::kTime && f.abscissa_increment > 0) {
      t << ", sample rate " << Num(1 / f.abscissa_increment) << " Hz (step "
        << Num(f.abscissa_increment) << " s from " << Num(f.abscissa_start) << " s)";
      (*j)["sample_rate_hz"] = 1 / f.abscissa_increment;
    } else if (kind == Abscissa::kFrequency) {
      t << ", frequency step " << Num(f.abscissa_increment) << " Hz from "
        << Num(f.abscissa_start) << " Hz";
      (*j)["frequency_step_hz"] = f.abscissa_increment;
    } else {
      t << ", abscissa step " << Num(f.abscissa_increment) << " from "
        << Num(f.abscissa_start);
    }
  } else if (f.x.size() > 0) {
    t << ", uneven abscissa " << Num(f.x[0]) << " .. " << Num(f.x[f.x.size() - 1]);
    (*j)["abscissa_range"] = {f.x[0], f.x[f.x.size() - 1]};
  }
  t << "; ordinate " << AxisText(f.ordinate_axis);
  if (f.function_type == 4 || f.function_type == 5 ||
      (f.denominator_axis.specific_data_type != 0 && f.denominator_axis.label != "NONE"))
    t << " / " << AxisText(f.denominator_axis);
  t << ", abscissa " << AxisText(f.abscissa_axis);
  (*j)["axes"] = {{"abscissa", AxisJson(f.abscissa_axis)},
                  {"ordinate", AxisJson(f.ordinate_axis)},
                  {"denominator", AxisJson(f.denominator_axis)},
                  {"z", AxisJson(f.z_axis)}};
  *text = t.str();
}

}  // namespace

// Text and JSON of every dataset of a UFF file, in file order.
void DescribeUff(const UffFile& uff, std::vector<std::string>* lines,
                 nlohmann::json* datasets) {
  for (const UffDatasetHeader& h : uff.headers) {
    nlohmann::json j = {{"dataset", h.number},
                        {"binary", h.binary},
                        {"line", h.line},
                        {"read", h.index >= 0}};
    std::string text;
    if (h.index < 0) {
      text =
          "not read (femup reads datasets 15, 55, 58/58b and 2411; 55 of analysis "
          "types 2, 3, 5, 7)";
    } else {
      const UffDataset& d = uff.datasets[static_cast<std::size_t>(h.index)];
      if (const auto* n = std::get_if<UffNodes>(&d)) DescribeNodes(*n, &text, &j);
      if (const auto* s = std::get_if<UffModeShape>(&d)) DescribeShape(*s, &text, &j);
      if (const auto* f = std::get_if<UffFunction>(&d)) DescribeFunction(*f, &text, &j);
    }
    lines->push_back("dataset " + std::to_string(h.number) + (h.binary ? "b" : "") +
                     " (line " + std::to_string(h.line) + "): " + text);
    datasets->push_back(j);
  }
}

}  // namespace femup::file_info
