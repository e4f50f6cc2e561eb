// Private to femup_studies: a node of a study file with its field path
// (Field), through which every study reader reads, checks types and ranges and
// reports errors as "file:line:column: path: message".
#pragma once

#include <yaml-cpp/yaml.h>

#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

namespace femup::study_reader {

// A YAML node with its field path, for messages like
// "study.yaml:12:5: model.section.E: expected a number, found 'abc'".
class Field {
 public:
  Field(YAML::Node node, std::string file, std::string path)
      : node_(std::move(node)), file_(std::move(file)), path_(std::move(path)) {}

  const YAML::Node& node() const { return node_; }
  const std::string& path() const { return path_; }
  bool IsMap() const { return node_.IsMap(); }
  bool IsSequence() const { return node_.IsSequence(); }
  bool IsScalar() const { return node_.IsScalar(); }

  std::string Where() const;
  [[noreturn]] void Fail(const std::string& what) const;

  // Keys must be among `allowed`.
  void ExpectKeys(std::initializer_list<const char*> allowed) const;
  // The text of `key`, a key of this mapping. A key that is not a plain value
  // (YAML allows null, a list or a mapping as a key: "? [a, b]: 1", "[a]: 1")
  // fails with this field's path.
  std::string Key(const YAML::Node& key) const;
  bool Has(const std::string& key) const { return node_.IsMap() && node_[key]; }
  Field operator[](const std::string& key) const;
  std::vector<Field> Items() const;

  std::string Str() const;
  double Num() const;
  double Positive() const;
  double NonNegative() const;
  int Int() const;
  // A random seed: a whole number from 0 to 2^53 (the integers a double holds
  // exactly), so that a seed is read as written and never converted out of
  // range (found by fuzzing: 2.2e29 overflowed unsigned long long).
  unsigned long long Seed() const;
  bool Bool() const;
  std::vector<double> Numbers() const;
  const std::string& file() const { return file_; }

 private:
  std::string Join(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
  }
  YAML::Node node_;
  std::string file_;
  std::string path_;
};

}  // namespace femup::study_reader
