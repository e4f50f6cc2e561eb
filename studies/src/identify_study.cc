#include "femup/studies/identify_study.h"

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

namespace femup {
namespace {

std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string FormatOf(const IdentifyOptions& o) {
  if (!o.format.empty()) return o.format;
  const std::string ext = Lower(std::filesystem::path(o.file).extension().string());
  if (ext == ".uff" || ext == ".unv") return "uff";
  if (ext == ".csv" || ext == ".txt") return "csv";
  throw InputError(o.file, "cannot tell the format from the extension '" + ext +
                               "': expected .uff, .unv or .csv (or give --format)");
}

std::string ChannelName(const UffFunction& f) {
  std::ostringstream s;
  s << f.response_node << ":" << f.response_direction;
  return s.str();
}

// Rows of `records` from the UFF file's function datasets.
void ReadUffRecords(const std::string& file, IdentifyResult* r,
                    Eigen::MatrixXd* records) {
  const UffFile uff = ReadUff(file);
  r->notes = uff.notes;
  const std::vector<const UffFunction*> all = uff.Functions();
  std::vector<const UffFunction*> fs;
  for (const UffFunction* f : all) {
    if (f->function_type == 1 || f->function_type == 4) fs.push_back(f);
  }
  if (fs.empty()) {
    const std::size_t shapes = uff.ModeShapes().size();
    if (shapes > 0 && all.empty()) {
      throw InputError(
          file, "holds " + std::to_string(shapes) +
                    " mode shape(s) (dataset 55) and no records (dataset 58): there is "
                    "nothing to identify. Use the modes directly as a study "
                    "measurement's modes_file (with uff_dofs or geometry_file to map "
                    "the nodes to model DOFs; README, Study files); femup info " +
                    file + " lists them");
    }
    throw InputError(file,
                     "no time history (function type 1) or FRF (type 4) in dataset 58" +
                         (shapes > 0 ? " (it holds " + std::to_string(shapes) +
                                           " mode shape(s), dataset 55: use them as a "
                                           "study measurement's modes_file)"
                                     : std::string()));
  }
  const int type = fs[0]->function_type;
  const Eigen::Index n = fs[0]->y.size();
  const double dx = fs[0]->abscissa_increment;
  for (std::size_t k = 0; k < fs.size(); ++k) {
    const UffFunction& f = *fs[k];
    std::ostringstream where;
    where << "dataset 58 number " << k + 1 << " (node " << ChannelName(f) << ")";
    if (f.function_type != type) {
      throw InputError(file, where.str() + ": mixes time histories and FRFs");
    }
    if (!f.even_spacing || !(f.abscissa_increment > 0)) {
      throw InputError(file, where.str() + ": needs evenly spaced abscissae");
    }
    if (f.y.size() != n || std::abs(f.abscissa_increment - dx) > 1e-9 * dx) {
      throw InputError(
          file, where.str() + ": length or spacing differs from the first function");
    }
    r->channels.push_back(ChannelName(f));
  }
  if (type == 1) {
    r->data_kind = "time";
    records->resize(static_cast<Eigen::Index>(fs.size()), n);
    for (std::size_t k = 0; k < fs.size(); ++k)
      records->row(k) = fs[k]->y.real().transpose();
    r->sample_rate_hz = 1.0 / dx;
    return;
  }
  if (std::abs(fs[0]->abscissa_start) > 1e-9 * dx) {
    throw InputError(file, "FRFs must start at 0 Hz for the inverse FFT");
  }
  r->data_kind = "frf";
  Eigen::MatrixXcd frf(static_cast<Eigen::Index>(fs.size()), n);
  for (std::size_t k = 0; k < fs.size(); ++k) frf.row(k) = fs[k]->y.transpose();
  const FrfImpulseResponse irf = ImpulseResponseFromFrf(frf, dx);
  *records = irf.data;
  r->sample_rate_hz = irf.sample_rate_hz;
}

}  // namespace

Invalid IdentifyOptions::Validate() const {
  if (file.empty()) return {"file", "no input file given"};
  if (!format.empty() && format != "uff" && format != "csv")
    return {"format", "expected uff or csv, got '" + format + "'"};
  if (min_consecutive < 1) return {"min_consecutive", "must be >= 1"};
  if (!(max_frequency_hz >= 0) || !std::isfinite(max_frequency_hz))
    return {"max_frequency_hz", "must be finite and >= 0"};
  return stabilisation.Validate().Under("stabilisation");
}

IdentifyResult RunIdentify(const IdentifyOptions& options) {
  ThrowIfInvalid(options.Validate(), "identify");
  IdentifyResult r;
  r.source = options.file;
  Eigen::MatrixXd records;
  if (FormatOf(options) == "uff") {
    ReadUffRecords(options.file, &r, &records);
  } else {
    const CsvSeries csv = ReadCsvSeries(options.file);
    r.data_kind = "time";
    r.channels = csv.channel_names;
    r.sample_rate_hz = csv.sample_rate_hz;
    records = csv.values.transpose();
  }
  r.num_samples = static_cast<int>(records.cols());
  if (!records.allFinite()) throw InputError(options.file, "a sample is NaN or infinite");
  r.diagram = BuildStabilisationDiagram(records, r.sample_rate_hz, options.stabilisation);
  const double top =
      options.max_frequency_hz > 0 ? options.max_frequency_hz : 0.5 * r.sample_rate_hz;
  for (const StableMode& m :
       PickStableModes(r.diagram, options.stabilisation, options.min_consecutive)) {
    if (m.mode.frequency_hz < top) r.modes.push_back(m);
  }
  std::sort(r.modes.begin(), r.modes.end(), [](const StableMode& a, const StableMode& b) {
    return a.mode.frequency_hz < b.mode.frequency_hz;
  });
  return r;
}

}  // namespace femup
