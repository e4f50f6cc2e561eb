#include "femup/reporting/output_dir.h"

#include <filesystem>
#include <fstream>
#include <random>
#include <vector>

#include "femup/core/errors.h"

namespace femup {

namespace fs = std::filesystem;

OutputDir::OutputDir(const std::string& directory) : directory_(directory) {
  std::error_code ec;
  if (directory_.empty()) throw InputError("-o", "the output folder's name is empty");
  // The folders that do not exist yet, outermost first: they are created here
  // and removed again (when still empty) if the job fails.
  std::vector<fs::path> missing;
  for (fs::path p = fs::path(directory_).lexically_normal(); !p.empty();
       p = p.parent_path()) {
    if (fs::exists(p, ec)) break;
    missing.insert(missing.begin(), p);
    if (p == p.parent_path()) break;
  }
  for (const fs::path& p : missing) {
    if (!fs::create_directory(p, ec) && !fs::is_directory(p)) {
      RemoveCreatedFolders();
      throw InputError(directory_, "cannot create the output folder: " + p.string() +
                                       " (" + ec.message() + ")");
    }
    created_.push_back(p.string());
  }
  if (!fs::is_directory(directory_, ec)) {
    throw InputError(directory_,
                     "cannot create the output folder (" +
                         std::string(fs::exists(directory_) ? "a file of that name exists"
                                                            : ec.message()) +
                         ")");
  }
  std::random_device rd;
  for (int attempt = 0; attempt < 100; ++attempt) {
    const fs::path candidate =
        fs::path(directory_) / (".femup-staging-" + std::to_string(rd() % 1000000));
    if (fs::create_directory(candidate, ec)) {
      staging_ = candidate.string();
      return;
    }
  }
  RemoveCreatedFolders();
  throw InputError(directory_, "cannot create a staging folder inside the output folder");
}

OutputDir::~OutputDir() {
  std::error_code ec;
  if (!staging_.empty()) fs::remove_all(staging_, ec);
  if (!committed_) RemoveCreatedFolders();
}

void OutputDir::RemoveCreatedFolders() {
  // Innermost first; fs::remove leaves a folder that is not empty alone.
  std::error_code ec;
  for (auto it = created_.rbegin(); it != created_.rend(); ++it) fs::remove(*it, ec);
  created_.clear();
}

std::string OutputDir::Stage(const std::string& name) {
  if (name.empty() || name.find('/') != std::string::npos) {
    throw InputError(directory_,
                     "output file name '" + name + "' is not a plain file name");
  }
  for (const auto& f : files_) {
    if (f == name) return (fs::path(staging_) / name).string();
  }
  files_.push_back(name);
  return (fs::path(staging_) / name).string();
}

void OutputDir::WriteText(const std::string& name, const std::string& text) {
  const std::string path = Stage(name);
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw InputError(path, "could not be written");
}

void OutputDir::Commit() {
  for (const auto& name : files_) {
    const fs::path from = fs::path(staging_) / name;
    if (!fs::exists(from)) continue;  // e.g. a plot gnuplot could not render
    std::error_code ec;
    fs::rename(from, fs::path(directory_) / name, ec);
    if (ec) {
      throw InputError((fs::path(directory_) / name).string(),
                       "could not be moved into place (" + ec.message() + ")");
    }
  }
  committed_ = true;
}

}  // namespace femup
