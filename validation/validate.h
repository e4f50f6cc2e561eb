// Private to femup_validate: what its tables (validate_<table>.cc) and its
// driver (validate.cc) share: a report and its Markdown table, the number
// formats, the NIST folder check, and the tables themselves.
#pragma once

#include <Eigen/Core>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "femup/core/errors.h"
#include "femup/evaluation/nist_strd.h"

namespace femup_validate {

namespace fs = std::filesystem;
using femup::InputError;
using Json = nlohmann::ordered_json;

// ---------------------------------------------------------------------------
// Output: one Markdown table (with its heading and notes) and its numbers.

struct Report {
  std::string name;      // file stem: "nist_linear"
  std::string markdown;  // heading, table, notes
  Json json;
};

// "n/a" for NaN, else `value` printed with the printf `format`.
std::string Format(const char* format, double value);
// A log relative error with one decimal; a value in scientific notation.
std::string Digits(double lre);
std::string Sci(double value);

// A Markdown cell: no pipes or line breaks inside.
std::string Cell(const std::string& text);

class MarkdownTable {
 public:
  explicit MarkdownTable(std::vector<std::string> header) : header_(std::move(header)) {}
  void Add(std::vector<std::string> row) { rows_.push_back(std::move(row)); }
  std::string str() const {
    std::ostringstream out;
    const auto line = [&out](const std::vector<std::string>& cells) {
      out << "|";
      for (const auto& c : cells) out << " " << Cell(c) << " |";
      out << "\n";
    };
    line(header_);
    out << "|";
    for (std::size_t i = 0; i < header_.size(); ++i) out << " --- |";
    out << "\n";
    for (const auto& r : rows_) line(r);
    return out.str();
  }

 private:
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
};

// Seconds since `start`.
double Seconds(std::chrono::steady_clock::time_point start);

// Correct significant digits of an answer: the least, over the parameters, of
// NIST's log relative error against the certified values.
double MinLre(const femup::VectorLD& x, const femup::VectorLD& certified);
double MinLre(const Eigen::VectorXd& x, const femup::VectorLD& certified);

// `items` joined by `separator`.
std::string Join(const std::vector<std::string>& items, const std::string& separator);

// The NIST folder (with linear/ and nonlinear/ inside), checked before any work.
std::string NistFolder(const std::string& data, const std::string& kind);

// The tables: nist-linear (validate_nist_linear.cc), nist-nonlinear
// (validate_nist_nonlinear.cc), ill-posed (validate_ill_posed.cc) and
// paper-chain (validate_paper_chain.cc).
Report NistLinear(const std::string& data);
Report NistNonlinear(const std::string& data);

struct IllPosedSettings {
  int n = 64;
  double noise = 1e-3;
  std::uint64_t seed = 1;
};

// Throws InputError naming the option when the settings cannot be used.
void Check(const IllPosedSettings& settings);
Report IllPosed(const IllPosedSettings& settings);

Report PaperChain();

}  // namespace femup_validate
