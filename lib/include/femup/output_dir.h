// All-or-nothing output: files are written into a staging folder and moved into
// the output folder only when the whole job has succeeded, so a failed run
// leaves no partial result behind.
#pragma once

#include <string>
#include <vector>

namespace femup {

class OutputDir {
 public:
  // Creates `directory` if needed (its parent must exist) and a private
  // staging folder inside it. Throws InputError when that is impossible.
  explicit OutputDir(const std::string& directory);
  ~OutputDir();  // removes the staging folder unless committed
  OutputDir(const OutputDir&) = delete;
  OutputDir& operator=(const OutputDir&) = delete;

  // Where to write the file `name` now (inside the staging folder).
  std::string Stage(const std::string& name);
  // Writes `text` to the staged file `name`; throws InputError on failure.
  void WriteText(const std::string& name, const std::string& text);
  // Moves every staged file into the output folder (replacing older ones).
  void Commit();
  const std::string& directory() const { return directory_; }
  const std::vector<std::string>& files() const { return files_; }

 private:
  std::string directory_;
  std::string staging_;
  std::vector<std::string> files_;
  bool committed_ = false;
};

}  // namespace femup
