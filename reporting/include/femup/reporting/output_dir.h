// All-or-nothing output: files are written into a staging folder and moved into
// the output folder only when the whole job has succeeded, so a failed run
// leaves no partial result behind.
#pragma once

#include <string>
#include <vector>

namespace femup {

class OutputDir {
 public:
  // Creates `directory` and any missing parent folders, and a private staging
  // folder inside it. Throws InputError when that is impossible. The folders it
  // created are removed again (when empty) unless the output is committed, so a
  // failed job leaves nothing behind.
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
  void RemoveCreatedFolders();

  std::string directory_;
  std::string staging_;
  std::vector<std::string> files_;
  std::vector<std::string> created_;  // folders this object created, outermost first
  bool committed_ = false;
};

}  // namespace femup
