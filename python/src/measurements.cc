// Measurements: measured modal data from arrays, UFF files (datasets 15, 55,
// 58 and 2411) and CSV time series; ERA at one order and the stabilisation
// analysis with its data as numpy arrays; identification from a record file.
#include <string>
#include <vector>

#include "common.h"
#include "femup/core/errors.h"
#include "femup/core/io/csv_series.h"
#include "femup/core/io/uff.h"
#include "femup/core/sysid/era.h"
#include "femup/core/sysid/frf_impulse.h"
#include "femup/core/sysid/measurement.h"
#include "femup/reporting/outputs.h"
#include "femup/studies/identify_study.h"

namespace femup_python {

namespace {

femup::Immersion ImmersionFrom(const std::string& text, const std::string& field) {
  if (text == "dry") return femup::Immersion::kDry;
  if (text == "wet") return femup::Immersion::kWet;
  throw femup::InputError(field, "expected dry or wet, got '" + text + "'");
}

void BindModalData(py::module_& m) {
  py::class_<femup::ModalData>(m, "ModalData",
                               "Measured modes of one state (in air, in water, ...).")
      .def(py::init([](const std::string& state, const std::string& immersion,
                       const Eigen::VectorXd& frequencies_hz,
                       const Eigen::MatrixXd& shapes, std::vector<int> sensor_dofs) {
             femup::ModalData d;
             d.state = state;
             d.immersion = ImmersionFrom(immersion, "immersion");
             d.frequencies_hz = frequencies_hz;
             d.shapes = shapes;
             d.sensor_dofs = std::move(sensor_dofs);
             return d;
           }),
           py::arg("state"), py::arg("immersion") = "dry", py::arg("frequencies_hz"),
           py::arg("shapes") = Eigen::MatrixXd(),
           py::arg("sensor_dofs") = std::vector<int>(),
           "frequencies_hz: one per mode (Hz); shapes: sensors x modes (any scaling), "
           "empty for frequencies only; sensor_dofs: 0-based model DOF of each shape row "
           "(empty: every model DOF in order).")
      .def_readwrite("state", &femup::ModalData::state)
      .def_property(
          "immersion",
          [](const femup::ModalData& d) { return femup::ToString(d.immersion); },
          [](femup::ModalData& d, const std::string& text) {
            d.immersion = ImmersionFrom(text, "immersion");
          })
      .def_readwrite("frequencies_hz", &femup::ModalData::frequencies_hz)
      .def_readwrite("shapes", &femup::ModalData::shapes)
      .def_readwrite("sensor_dofs", &femup::ModalData::sensor_dofs)
      .def_property_readonly("num_modes", &femup::ModalData::num_modes)
      .def_property_readonly("eigenvalues", &femup::ModalData::Eigenvalues,
                             "(2 pi f)^2, rad^2/s^2")
      .def("validate", &femup::ModalData::Validate, py::arg("num_dofs"),
           py::arg("where") = "measurement",
           "Raises InputError naming `where` for unusable data.")
      .def("full_shapes", &femup::ModalData::FullShapes, py::arg("num_dofs"),
           py::arg("where") = "measurement")
      .def("__repr__", [](const femup::ModalData& d) {
        return "<femup.ModalData " + d.state + " (" + femup::ToString(d.immersion) +
               "), " + std::to_string(d.num_modes()) + " modes>";
      });

  m.def(
      "predict_modes",
      [](const femup::ParametrisedModel& model, const Eigen::VectorXd& d,
         const std::string& immersion, int num_modes, const std::string& state) {
        const femup::Immersion im = ImmersionFrom(immersion, "immersion");
        py::gil_scoped_release release;
        return femup::PredictModes(model, d, im, num_modes, state);
      },
      py::arg("model"), py::arg("d"), py::arg("immersion"), py::arg("num_modes"),
      py::arg("state") = "",
      "The lowest modes of (K~, M~dry) or (K~, M~wet) for factors d, at every DOF.");
}

void BindUff(py::module_& m) {
  py::class_<femup::UffNode>(m, "UffNode")
      .def_readonly("label", &femup::UffNode::label)
      .def_readonly("definition_cs", &femup::UffNode::definition_cs)
      .def_readonly("displacement_cs", &femup::UffNode::displacement_cs)
      .def_readonly("xyz", &femup::UffNode::xyz)
      .def_readonly("line", &femup::UffNode::line);
  py::class_<femup::UffNodes>(m, "UffNodes", "Dataset 15 or 2411.")
      .def_readonly("dataset", &femup::UffNodes::dataset)
      .def_readonly("line", &femup::UffNodes::line)
      .def_property_readonly("nodes", [](py::object self) {
        return RefList(self.cast<const femup::UffNodes&>().nodes, self);
      });
  py::class_<femup::UffModeShape>(m, "UffModeShape", "Dataset 55: data at nodes.")
      .def_readonly("id_lines", &femup::UffModeShape::id_lines)
      .def_property_readonly(
          "analysis_type",
          [](const femup::UffModeShape& s) { return static_cast<int>(s.analysis_type); })
      .def_readonly("mode_number", &femup::UffModeShape::mode_number)
      .def_readonly("frequency_hz", &femup::UffModeShape::frequency_hz)
      .def_readonly("modal_mass", &femup::UffModeShape::modal_mass)
      .def_readonly("viscous_damping_ratio", &femup::UffModeShape::viscous_damping_ratio)
      .def_readonly("eigenvalue", &femup::UffModeShape::eigenvalue)
      .def_readonly("complex_data", &femup::UffModeShape::complex_data)
      .def_readonly("nodes", &femup::UffModeShape::nodes)
      .def_readonly("values", &femup::UffModeShape::values,
                    "nodes x values per node (complex)")
      .def_readonly("line", &femup::UffModeShape::line);
  py::class_<femup::UffFunction>(m, "UffFunction", "Dataset 58/58b: function at a DOF.")
      .def_readonly("id_lines", &femup::UffFunction::id_lines)
      .def_readonly("function_type", &femup::UffFunction::function_type,
                    "1 time response, 4 FRF, ...")
      .def_readonly("response_node", &femup::UffFunction::response_node)
      .def_readonly("response_direction", &femup::UffFunction::response_direction)
      .def_readonly("reference_node", &femup::UffFunction::reference_node)
      .def_readonly("reference_direction", &femup::UffFunction::reference_direction)
      .def_readonly("even_spacing", &femup::UffFunction::even_spacing)
      .def_readonly("abscissa_start", &femup::UffFunction::abscissa_start)
      .def_readonly("abscissa_increment", &femup::UffFunction::abscissa_increment)
      .def_readonly("x", &femup::UffFunction::x, "abscissa of every point")
      .def_readonly("y", &femup::UffFunction::y, "ordinates (complex)")
      .def_readonly("binary", &femup::UffFunction::binary)
      .def_property_readonly("is_complex", &femup::UffFunction::IsComplex)
      .def_readonly("line", &femup::UffFunction::line);
  py::class_<femup::UffFile>(m, "UffFile")
      .def_readonly("notes", &femup::UffFile::notes,
                    "skipped datasets and irregularities")
      .def_property_readonly(
          "nodes",
          [](py::object self) {
            py::list out;
            for (const auto* d : self.cast<const femup::UffFile&>().Nodes()) {
              out.append(py::cast(d, py::return_value_policy::reference_internal, self));
            }
            return out;
          })
      .def_property_readonly(
          "mode_shapes",
          [](py::object self) {
            py::list out;
            for (const auto* d : self.cast<const femup::UffFile&>().ModeShapes()) {
              out.append(py::cast(d, py::return_value_policy::reference_internal, self));
            }
            return out;
          })
      .def_property_readonly("functions", [](py::object self) {
        py::list out;
        for (const auto* d : self.cast<const femup::UffFile&>().Functions()) {
          out.append(py::cast(d, py::return_value_policy::reference_internal, self));
        }
        return out;
      });
  m.def(
      "read_uff", &femup::ReadUff, py::arg("path"),
      py::call_guard<py::gil_scoped_release>(),
      "Every dataset of a UFF file (15, 55, 58/58b, 2411; others skipped with a note).");
  m.def(
      "impulse_response_from_frf",
      [](const Eigen::MatrixXcd& frf, double df) {
        const femup::FrfImpulseResponse r = femup::ImpulseResponseFromFrf(frf, df);
        return py::make_tuple(r.data, r.sample_rate_hz);
      },
      py::arg("frf"), py::arg("frequency_step_hz"),
      "Impulse responses (channels x samples) and their sample rate from FRFs "
      "(channels x frequencies, evenly spaced from 0 Hz).");
}

void BindCsv(py::module_& m) {
  py::class_<femup::CsvSeries>(m, "CsvSeries", "A CSV time series.")
      .def_readonly("time_name", &femup::CsvSeries::time_name)
      .def_readonly("channel_names", &femup::CsvSeries::channel_names)
      .def_readonly("time", &femup::CsvSeries::time)
      .def_readonly("values", &femup::CsvSeries::values, "samples x channels")
      .def_readonly("time_step", &femup::CsvSeries::time_step)
      .def_readonly("sample_rate_hz", &femup::CsvSeries::sample_rate_hz);
  m.def(
      "read_csv_series",
      [](const std::string& path, double tolerance) {
        femup::CsvReadOptions options;
        options.relative_step_tolerance = tolerance;
        py::gil_scoped_release release;
        return femup::ReadCsvSeries(path, options);
      },
      py::arg("path"), py::arg("relative_step_tolerance") = 1e-6,
      "A CSV time series (time, then one column per channel); errors name line and "
      "column.");
  m.def(
      "write_csv_series",
      [](const std::string& path, const Eigen::VectorXd& time,
         const Eigen::MatrixXd& values, std::vector<std::string> channel_names,
         const std::string& time_name) {
        femup::CsvSeries s;
        s.time_name = time_name;
        s.channel_names = std::move(channel_names);
        s.time = time;
        s.values = values;
        femup::WriteCsvSeries(path, s);
      },
      py::arg("path"), py::arg("time"), py::arg("values"), py::arg("channel_names"),
      py::arg("time_name") = "time", "values: samples x channels.");
}

void BindEra(py::module_& m) {
  py::class_<femup::EraOptions>(m, "EraOptions")
      .def(py::init<>())
      .def_readwrite("order", &femup::EraOptions::order)
      .def_readwrite("block_rows", &femup::EraOptions::block_rows)
      .def_readwrite("block_columns", &femup::EraOptions::block_columns)
      .def_readwrite("max_hankel_size", &femup::EraOptions::max_hankel_size)
      .def_readwrite("first_sample", &femup::EraOptions::first_sample)
      .def_readwrite("max_damping_ratio", &femup::EraOptions::max_damping_ratio)
      .def_readwrite("min_emac", &femup::EraOptions::min_emac)
      .def_readwrite("min_mpc", &femup::EraOptions::min_mpc)
      .def("validate", &ValidateText<femup::EraOptions>);
  py::class_<femup::StabilisationOptions>(m, "StabilisationOptions")
      .def(py::init<>())
      .def_readwrite("era", &femup::StabilisationOptions::era)
      .def_readwrite("min_order", &femup::StabilisationOptions::min_order)
      .def_readwrite("max_order", &femup::StabilisationOptions::max_order)
      .def_readwrite("order_step", &femup::StabilisationOptions::order_step)
      .def_readwrite("frequency_tolerance",
                     &femup::StabilisationOptions::frequency_tolerance)
      .def_readwrite("damping_tolerance", &femup::StabilisationOptions::damping_tolerance)
      .def_readwrite("mac_tolerance", &femup::StabilisationOptions::mac_tolerance)
      .def("validate", &ValidateText<femup::StabilisationOptions>);

  py::class_<femup::IdentifiedMode>(m, "IdentifiedMode")
      .def_property_readonly(
          "status",
          [](const femup::IdentifiedMode& x) { return femup::ToString(x.status); })
      .def_readonly("pole", &femup::IdentifiedMode::pole,
                    "continuous-time lambda (rad/s)")
      .def_readonly("frequency_hz", &femup::IdentifiedMode::frequency_hz)
      .def_readonly("damping_ratio", &femup::IdentifiedMode::damping_ratio)
      .def_readonly("complex_shape", &femup::IdentifiedMode::complex_shape)
      .def_readonly("shape", &femup::IdentifiedMode::shape, "real, unit norm")
      .def_readonly("mpc", &femup::IdentifiedMode::mpc)
      .def_readonly("emac", &femup::IdentifiedMode::emac)
      .def_readonly("contribution", &femup::IdentifiedMode::contribution)
      .def("__repr__", [](const femup::IdentifiedMode& x) {
        return "<femup.IdentifiedMode " + std::to_string(x.frequency_hz) + " Hz, " +
               femup::ToString(x.status) + ">";
      });
  py::class_<femup::EraResult>(m, "EraResult")
      .def_readonly("order", &femup::EraResult::order)
      .def_readonly("sample_rate_hz", &femup::EraResult::sample_rate_hz)
      .def_readonly("block_rows", &femup::EraResult::block_rows)
      .def_readonly("block_columns", &femup::EraResult::block_columns)
      .def_readonly("singular_values", &femup::EraResult::singular_values)
      .def_readonly("a", &femup::EraResult::a)
      .def_readonly("b", &femup::EraResult::b)
      .def_readonly("c", &femup::EraResult::c)
      .def_readonly("modes", &femup::EraResult::modes, "accepted poles")
      .def_readonly("rejected", &femup::EraResult::rejected);
  m.def(
      "era",
      [](py::object records, double sample_rate_hz, const femup::EraOptions& options) {
        // One reference: a 2D array (channels x samples); several: a list of them.
        if (py::isinstance<py::list>(records) || py::isinstance<py::tuple>(records)) {
          auto refs = records.cast<std::vector<Eigen::MatrixXd>>();
          py::gil_scoped_release release;
          return femup::RunEra(refs, sample_rate_hz, options);
        }
        auto y = records.cast<Eigen::MatrixXd>();
        py::gil_scoped_release release;
        return femup::RunEra(y, sample_rate_hz, options);
      },
      py::arg("records"), py::arg("sample_rate_hz"), py::arg("options"),
      "ERA at options.order. records: channels x samples (one reference), or a list "
      "of such arrays (one per reference).");

  py::class_<femup::DiagramPole>(m, "DiagramPole")
      .def_readonly("mode", &femup::DiagramPole::mode)
      .def_readonly("previous", &femup::DiagramPole::previous)
      .def_readonly("stable_frequency", &femup::DiagramPole::stable_frequency)
      .def_readonly("stable_damping", &femup::DiagramPole::stable_damping)
      .def_readonly("stable_shape", &femup::DiagramPole::stable_shape)
      .def_readonly("stable_run", &femup::DiagramPole::stable_run)
      .def_property_readonly("stable", &femup::DiagramPole::stable);
  py::class_<femup::DiagramOrder>(m, "DiagramOrder")
      .def_readonly("order", &femup::DiagramOrder::order)
      .def_readonly("poles", &femup::DiagramOrder::poles);
  py::class_<femup::StabilisationDiagram>(m, "StabilisationDiagram")
      .def_readonly("sample_rate_hz", &femup::StabilisationDiagram::sample_rate_hz)
      .def_readonly("block_rows", &femup::StabilisationDiagram::block_rows)
      .def_readonly("block_columns", &femup::StabilisationDiagram::block_columns)
      .def_readonly("singular_values", &femup::StabilisationDiagram::singular_values)
      .def_readonly("orders", &femup::StabilisationDiagram::orders)
      .def(
          "arrays",
          [](const femup::StabilisationDiagram& d) {
            // One entry per pole of every order: what a stabilisation plot draws.
            std::size_t n = 0;
            for (const auto& o : d.orders) n += o.poles.size();
            const auto size = static_cast<py::ssize_t>(n);
            py::array_t<int> order(size), run(size), status(size);
            py::array_t<double> freq(size), damping(size), mpc(size), emac(size),
                contribution(size);
            py::array_t<bool> accepted(size), stable(size), stable_f(size),
                stable_d(size), stable_s(size);
            std::size_t k = 0;
            for (const auto& o : d.orders) {
              for (const auto& p : o.poles) {
                order.mutable_at(k) = o.order;
                freq.mutable_at(k) = p.mode.frequency_hz;
                damping.mutable_at(k) = p.mode.damping_ratio;
                mpc.mutable_at(k) = p.mode.mpc;
                emac.mutable_at(k) = p.mode.emac;
                contribution.mutable_at(k) = p.mode.contribution;
                status.mutable_at(k) = static_cast<int>(p.mode.status);
                accepted.mutable_at(k) = p.mode.status == femup::PoleStatus::kAccepted;
                stable.mutable_at(k) = p.stable();
                stable_f.mutable_at(k) = p.stable_frequency;
                stable_d.mutable_at(k) = p.stable_damping;
                stable_s.mutable_at(k) = p.stable_shape;
                run.mutable_at(k) = p.stable_run;
                ++k;
              }
            }
            py::dict out;
            out["order"] = order;
            out["frequency_hz"] = freq;
            out["damping_ratio"] = damping;
            out["mpc"] = mpc;
            out["emac"] = emac;
            out["contribution"] = contribution;
            out["status"] = status;
            out["accepted"] = accepted;
            out["stable"] = stable;
            out["stable_frequency"] = stable_f;
            out["stable_damping"] = stable_d;
            out["stable_shape"] = stable_s;
            out["stable_run"] = run;
            return out;
          },
          "Every pole of every order as flat numpy arrays (a dict): order, "
          "frequency_hz, damping_ratio, mpc, emac, contribution, status (the "
          "PoleStatus code, 0 = accepted), accepted, stable, stable_frequency, "
          "stable_damping, stable_shape, stable_run.");
  m.def(
      "stabilisation_diagram",
      [](py::object records, double sample_rate_hz,
         const femup::StabilisationOptions& options) {
        if (py::isinstance<py::list>(records) || py::isinstance<py::tuple>(records)) {
          auto refs = records.cast<std::vector<Eigen::MatrixXd>>();
          py::gil_scoped_release release;
          return femup::BuildStabilisationDiagram(refs, sample_rate_hz, options);
        }
        auto y = records.cast<Eigen::MatrixXd>();
        py::gil_scoped_release release;
        return femup::BuildStabilisationDiagram(y, sample_rate_hz, options);
      },
      py::arg("records"), py::arg("sample_rate_hz"), py::arg("options"),
      "ERA at every order from options.min_order to max_order from one SVD, each "
      "pole compared with the previous order's.");
  py::class_<femup::StableMode>(m, "StableMode")
      .def_readonly("mode", &femup::StableMode::mode)
      .def_readonly("order", &femup::StableMode::order)
      .def_readonly("stable_run", &femup::StableMode::stable_run)
      .def_readonly("num_poles", &femup::StableMode::num_poles)
      .def_readonly("frequency_std_hz", &femup::StableMode::frequency_std_hz)
      .def_readonly("damping_std", &femup::StableMode::damping_std)
      .def("__repr__", [](const femup::StableMode& s) {
        return "<femup.StableMode " + std::to_string(s.mode.frequency_hz) +
               " Hz, order " + std::to_string(s.order) + ">";
      });
  m.def("pick_stable_modes", &femup::PickStableModes, py::arg("diagram"),
        py::arg("options"), py::arg("min_consecutive") = 5,
        "The physical modes: poles stable over min_consecutive orders, one per group.");

  py::class_<femup::IdentifyOptions>(m, "IdentifyOptions")
      .def(py::init<>())
      .def_readwrite("file", &femup::IdentifyOptions::file)
      .def_readwrite("format", &femup::IdentifyOptions::format,
                     "uff, csv or '' (extension)")
      .def_readwrite("stabilisation", &femup::IdentifyOptions::stabilisation)
      .def_readwrite("min_consecutive", &femup::IdentifyOptions::min_consecutive)
      .def_readwrite("max_frequency_hz", &femup::IdentifyOptions::max_frequency_hz)
      .def("validate", &ValidateText<femup::IdentifyOptions>);
  py::class_<femup::IdentifyResult>(m, "IdentifyResult")
      .def_readonly("source", &femup::IdentifyResult::source)
      .def_readonly("data_kind", &femup::IdentifyResult::data_kind, "time or frf")
      .def_readonly("channels", &femup::IdentifyResult::channels)
      .def_readonly("sample_rate_hz", &femup::IdentifyResult::sample_rate_hz)
      .def_readonly("num_samples", &femup::IdentifyResult::num_samples)
      .def_readonly("diagram", &femup::IdentifyResult::diagram)
      .def_readonly("modes", &femup::IdentifyResult::modes)
      .def_readonly("notes", &femup::IdentifyResult::notes)
      .def("report", &femup::IdentifyReport);
  m.def("identify", &femup::RunIdentify, py::arg("options"),
        py::call_guard<py::gil_scoped_release>(),
        "`femup identify`: ERA with a stabilisation diagram on a UFF 58 or CSV file.");
}

}  // namespace

void InitMeasurements(py::module_& m) {
  BindModalData(m);
  BindUff(m);
  BindCsv(m);
  BindEra(m);
}

}  // namespace femup_python
