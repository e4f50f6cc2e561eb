#include "io/file_io.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "femup/core/errors.h"

namespace femup::internal {

std::string ErrnoText(int error) {
  return std::error_code(error, std::generic_category()).message();
}

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  static std::atomic<unsigned> counter{0};
  int error = 0;
  for (int attempt = 0; attempt < 100 && fd_ < 0; ++attempt) {
    temp_ = path_ + ".tmp." + std::to_string(::getpid()) + "." +
            std::to_string(counter.fetch_add(1));
    fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    error = fd_ < 0 ? errno : 0;
    if (error != 0 && error != EEXIST) break;
  }
  if (fd_ < 0) {
    throw InputError(path_,
                     "cannot create a temporary file next to it: " + ErrnoText(error));
  }
}

AtomicFile::~AtomicFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!committed_) ::unlink(temp_.c_str());
}

void AtomicFile::Write(std::string* text) {
  const char* data = text->data();
  size_t left = text->size();
  while (left > 0) {
    const ssize_t n = ::write(fd_, data, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      throw InputError(path_, "error while writing: " + ErrnoText(n < 0 ? errno : EIO));
    }
    data += n;
    left -= static_cast<size_t>(n);
  }
  text->clear();
}

void AtomicFile::Commit() {
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0)
    throw InputError(path_, "error while writing: " + ErrnoText(errno));
  if (std::rename(temp_.c_str(), path_.c_str()) != 0) {
    throw InputError(path_, "cannot replace the file: " + ErrnoText(errno));
  }
  committed_ = true;
}

std::string ReadFileText(const std::string& path, const std::string& kind) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    std::error_code ec;
    const bool exists = std::filesystem::exists(path, ec);
    throw InputError(
        path, exists ? "cannot open the " + kind + " for reading" : kind + " not found");
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw InputError(path, "error while reading the " + kind);
  return buffer.str();
}

void WriteFileAtomically(const std::string& path, std::string text) {
  AtomicFile file(path);
  file.Write(&text);
  file.Commit();
}

}  // namespace femup::internal
