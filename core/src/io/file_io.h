// Private to femup_core: reading a whole file, and writing one all at once
// (AtomicFile: the text goes to a temporary file next to the target, with a
// unique name, and is renamed into place, so a failure leaves neither a partial
// file nor a stray temporary).
#pragma once

#include <string>

namespace femup::internal {

class AtomicFile {
 public:
  // Throws InputError(path) when the temporary cannot be created.
  explicit AtomicFile(std::string path);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();  // removes the temporary unless committed

  // Writes `text` and empties it; throws InputError(path) on failure.
  void Write(std::string* text);
  // Closes and renames into place; throws InputError(path) on failure.
  void Commit();

 private:
  std::string path_;
  std::string temp_;
  int fd_ = -1;
  bool committed_ = false;
};

// The whole of `text` as the file `path`, through an AtomicFile.
void WriteFileAtomically(const std::string& path, std::string text);

// The whole file; `kind` names it in errors ("UFF file"): InputError(path,
// "<kind> not found"), "cannot open the <kind> for reading", "error while
// reading the <kind>".
std::string ReadFileText(const std::string& path, const std::string& kind);

// strerror-style text for an errno value.
std::string ErrnoText(int error);

}  // namespace femup::internal
