// femup info (file_info.h): a file's format told by its extension and described:
// a UFF file by its datasets (file_info_uff.cc), a CSV time series by its
// columns, a Matrix Market file by its header; as text or as JSON.
#include "femup/studies/file_info.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "femup/core/errors.h"
#include "femup/core/io/matrix_market.h"
#include "file_info_uff.h"

namespace femup {

using file_info::DescribeUff;
using file_info::Num;

std::string file_info::Num(double v, int digits) {
  std::ostringstream s;
  s.precision(digits);
  s << v;
  return s.str();
}

namespace {

std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string Trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

// --- Matrix Market header -------------------------------------------------------

MatrixMarketInfo DescribeMatrixMarket(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!std::filesystem::exists(path)) throw InputError(path, "file not found");
  if (!in) throw InputError(path, "cannot open the Matrix Market file for reading");
  MatrixMarketInfo m;
  std::string line;
  long long number = 0;
  auto where = [&] { return path + ": line " + std::to_string(number); };
  if (!std::getline(in, line))
    throw InputError(path, "empty file; expected a Matrix Market banner");
  ++number;
  std::istringstream banner(line);
  std::string tag;
  banner >> tag >> m.object >> m.format >> m.field >> m.symmetry;
  m.object = Lower(m.object);
  m.format = Lower(m.format);
  m.field = Lower(m.field);
  m.symmetry = Lower(m.symmetry);
  if (tag != "%%MatrixMarket" || m.symmetry.empty()) {
    throw InputError(where(),
                     "expected the banner '%%MatrixMarket matrix coordinate|array "
                     "<field> <symmetry>', found '" +
                         Trim(line) + "'");
  }
  if (m.format != "coordinate" && m.format != "array") {
    throw InputError(where(), "format '" + m.format + "': expected coordinate or array");
  }
  bool sized = false;
  while (std::getline(in, line)) {
    ++number;
    const std::string t = Trim(line);
    if (t.empty() || t[0] == '%') continue;
    std::istringstream size(t);
    if (!(size >> m.rows >> m.cols) || m.rows < 0 || m.cols < 0 ||
        (m.format == "coordinate" && !(size >> m.entries))) {
      throw InputError(where(),
                       "expected the size line (" +
                           std::string(m.format == "coordinate" ? "rows, columns, entries"
                                                                : "rows, columns") +
                           "), found '" + t + "'");
    }
    if (m.format == "array") {
      m.entries = m.symmetry == "general"          ? m.rows * m.cols
                  : m.symmetry == "skew-symmetric" ? m.rows * (m.rows - 1) / 2
                                                   : m.rows * (m.rows + 1) / 2;
    }
    sized = true;
    break;
  }
  if (!sized) {
    throw InputError(path + ": line " + std::to_string(number + 1),
                     "the file ends before the size line");
  }
  const bool supported = m.object == "matrix" &&
                         (m.field == "real" || m.field == "integer") &&
                         (m.symmetry == "general" || m.symmetry == "symmetric");
  if (!supported) {
    m.problem = "femup reads real or integer matrices, general or symmetric; this is " +
                m.object + " " + m.field + " " + m.symmetry;
    return m;
  }
  try {
    m.nonzeros = ReadMatrixMarket(path).nonZeros();
    m.readable = true;
  } catch (const InputError& e) {
    m.problem = e.what();
  }
  return m;
}

}  // namespace

void SplitNameAndUnits(const std::string& column, std::string* name, std::string* units) {
  const std::string t = Trim(column);
  *name = t;
  units->clear();
  if (t.size() < 3) return;
  const char close = t.back();
  const char open = close == ']' ? '[' : close == ')' ? '(' : '\0';
  if (!open) return;
  const auto at = t.rfind(open);
  if (at == std::string::npos || at == 0) return;
  const std::string inside = Trim(t.substr(at + 1, t.size() - at - 2));
  if (inside.empty()) return;
  *units = inside;
  *name = Trim(t.substr(0, at));
}

FileInfo DescribeFile(const std::string& path) {
  FileInfo info;
  info.path = path;
  const std::string ext = Lower(std::filesystem::path(path).extension().string());
  if (ext == ".uff" || ext == ".unv") {
    info.format = "uff";
    info.uff = ReadUff(path);
  } else if (ext == ".csv") {
    info.format = "csv";
    CsvInfo c;
    c.series = ReadCsvSeries(path);
    std::string name;
    SplitNameAndUnits(c.series.time_name, &name, &c.time_units);
    for (const std::string& column : c.series.channel_names) {
      std::string units;
      SplitNameAndUnits(column, &name, &units);
      c.names.push_back(name);
      c.units.push_back(units);
    }
    info.csv = std::move(c);
  } else if (ext == ".mtx") {
    info.format = "matrix_market";
    info.matrix = DescribeMatrixMarket(path);
  } else {
    throw InputError(path, "cannot tell the kind of file from the extension '" + ext +
                               "': expected .uff or .unv (Universal File Format), .csv "
                               "(time series) or .mtx (Matrix Market)");
  }
  return info;
}

std::string FileInfoReport(const FileInfo& info) {
  std::ostringstream o;
  if (info.uff) {
    const UffFile& u = *info.uff;
    std::size_t read = 0;
    for (const UffDatasetHeader& h : u.headers) read += h.index >= 0 ? 1 : 0;
    o << info.path << ": Universal File Format, " << u.headers.size() << " dataset(s), "
      << read << " read, " << u.headers.size() - read << " skipped\n";
    std::vector<std::string> lines;
    nlohmann::json unused = nlohmann::json::array();
    DescribeUff(u, &lines, &unused);
    for (const std::string& l : lines) o << "  " << l << "\n";
    const std::size_t modes = u.ModeShapes().size();
    if (modes > 0 && u.Functions().empty()) {
      o << "  the mode shapes can be a study measurement's modes_file (with uff_dofs or "
           "geometry_file)\n";
    }
    // Notes, but not those that repeat a skipped dataset's line above.
    for (const std::string& n : u.notes) {
      bool repeated = false;
      for (const UffDatasetHeader& h : u.headers) {
        const std::string prefix = info.path + ": line " + std::to_string(h.line) + ": ";
        repeated = repeated || (h.index < 0 && n.compare(0, prefix.size(), prefix) == 0);
      }
      if (!repeated) o << "  note: " << n << "\n";
    }
  } else if (info.csv) {
    const CsvInfo& c = *info.csv;
    o << info.path << ": CSV time series, " << c.series.time.size() << " rows, "
      << c.names.size() << " channel(s), sample rate " << Num(c.series.sample_rate_hz)
      << " Hz (step " << Num(c.series.time_step) << (c.time_units.empty() ? "" : " ")
      << c.time_units << ")\n";
    o << "  time column: " << c.series.time_name << "\n";
    for (std::size_t k = 0; k < c.names.size(); ++k) {
      o << "  channel " << k + 1 << ": " << c.names[k];
      if (!c.units[k].empty()) o << " [" << c.units[k] << "]";
      o << "\n";
    }
  } else if (info.matrix) {
    const MatrixMarketInfo& m = *info.matrix;
    o << info.path << ": Matrix Market " << m.object << ", " << m.rows << " x " << m.cols
      << ", " << m.format << ", " << m.field << ", " << m.symmetry << ", " << m.entries
      << " stored entries\n";
    if (m.readable) {
      o << "  femup reads it: " << m.nonzeros << " nonzeros in the whole matrix\n";
    } else {
      o << "  femup does not read it: " << m.problem << "\n";
    }
  }
  return o.str();
}

std::string FileInfoJson(const FileInfo& info) {
  nlohmann::json j;
  j["file"] = info.path;
  j["format"] = info.format;
  if (info.uff) {
    std::vector<std::string> lines;
    nlohmann::json datasets = nlohmann::json::array();
    DescribeUff(*info.uff, &lines, &datasets);
    j["datasets"] = datasets;
    j["notes"] = info.uff->notes;
  } else if (info.csv) {
    const CsvInfo& c = *info.csv;
    j["rows"] = c.series.time.size();
    j["sample_rate_hz"] = c.series.sample_rate_hz;
    j["time_step"] = c.series.time_step;
    j["time"] = {{"column", c.series.time_name}, {"units", c.time_units}};
    j["delimiter"] = std::string(1, c.series.delimiter);
    nlohmann::json channels = nlohmann::json::array();
    for (std::size_t k = 0; k < c.names.size(); ++k) {
      channels.push_back({{"column", c.series.channel_names[k]},
                          {"name", c.names[k]},
                          {"units", c.units[k]}});
    }
    j["channels"] = channels;
  } else if (info.matrix) {
    const MatrixMarketInfo& m = *info.matrix;
    j["object"] = m.object;
    j["storage"] = m.format;
    j["field"] = m.field;
    j["symmetry"] = m.symmetry;
    j["rows"] = m.rows;
    j["cols"] = m.cols;
    j["entries"] = m.entries;
    j["readable"] = m.readable;
    if (m.readable) {
      j["nonzeros"] = m.nonzeros;
    } else {
      j["problem"] = m.problem;
    }
  }
  return j.dump(2) + "\n";
}

}  // namespace femup
