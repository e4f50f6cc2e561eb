// Field (study_reader_field.h): a study file's node read as a text, a number,
// a whole number, a seed, a flag, a list or a mapping of known keys, with every
// failure an InputError naming the file, line, column and field path.
#include "study_reader_field.h"

#include <cmath>
#include <sstream>

#include "femup/core/errors.h"

namespace femup::study_reader {

std::string Field::Where() const {
  std::ostringstream w;
  w << file_;
  if (!node_.Mark().is_null())
    w << ":" << node_.Mark().line + 1 << ":" << node_.Mark().column + 1;
  return w.str();
}

void Field::Fail(const std::string& what) const {
  throw InputError(Where(), (path_.empty() ? std::string("") : path_ + ": ") + what);
}

void Field::ExpectKeys(std::initializer_list<const char*> allowed) const {
  if (!node_.IsMap()) Fail("expected a mapping of keys to values");
  for (const auto& kv : node_) {
    const std::string key = Key(kv.first);
    bool ok = false;
    for (const char* a : allowed) ok = ok || key == a;
    if (!ok) {
      std::string list;
      for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      Field(kv.first, file_, Join(key))
          .Fail("unknown key (expected one of: " + list + ")");
    }
  }
}

std::string Field::Key(const YAML::Node& key) const {
  if (key.IsScalar()) return key.Scalar();
  const char* found = key.IsNull()       ? "an empty (null) key"
                      : key.IsSequence() ? "a list"
                      : key.IsMap()      ? "a mapping"
                                         : "an undefined key";
  Field(key, file_, path_)
      .Fail(std::string("expected each key to be a name, found ") + found +
            (key.IsNull() ? " (quote it, \"null\", to mean the word)" : ""));
}

Field Field::operator[](const std::string& key) const {
  if (!Has(key)) Fail("missing required key '" + key + "'");
  return Field(node_[key], file_, Join(key));
}

std::vector<Field> Field::Items() const {
  if (!node_.IsSequence()) Fail("expected a list");
  std::vector<Field> out;
  for (std::size_t i = 0; i < node_.size(); ++i) {
    out.emplace_back(node_[i], file_, path_ + "[" + std::to_string(i + 1) + "]");
  }
  return out;
}

std::string Field::Str() const {
  if (!node_.IsScalar()) Fail("expected a text value");
  return node_.Scalar();
}

double Field::Num() const {
  if (!node_.IsScalar()) Fail("expected a number");
  const std::string s = node_.Scalar();
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(s, &used);
  } catch (...) {
    used = 0;
  }
  if (used == 0 || used != s.size()) Fail("expected a number, found '" + s + "'");
  if (!std::isfinite(v)) Fail("expected a finite number, found '" + s + "'");
  return v;
}

double Field::Positive() const {
  const double v = Num();
  if (!(v > 0)) Fail("expected a positive number, found " + node_.Scalar());
  return v;
}

double Field::NonNegative() const {
  const double v = Num();
  if (!(v >= 0)) Fail("expected a number >= 0, found " + node_.Scalar());
  return v;
}

int Field::Int() const {
  const double v = Num();
  if (v != std::floor(v) || std::abs(v) > 1e9) Fail("expected a whole number");
  return static_cast<int>(v);
}

unsigned long long Field::Seed() const {
  const double v = Num();
  if (!(v >= 0 && v <= 9007199254740992.0) || v != std::floor(v))
    Fail("expected a whole number from 0 to 2^53 = 9007199254740992, found " +
         node_.Scalar());
  return static_cast<unsigned long long>(v);
}

bool Field::Bool() const {
  const std::string s = Str();
  if (s == "true" || s == "yes" || s == "on") return true;
  if (s == "false" || s == "no" || s == "off") return false;
  Fail("expected true or false, found '" + s + "'");
}

std::vector<double> Field::Numbers() const {
  std::vector<double> out;
  for (const Field& f : Items()) out.push_back(f.Num());
  return out;
}

}  // namespace femup::study_reader
