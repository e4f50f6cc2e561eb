// Running gnuplot for RenderFigure: finding it on PATH (GnuplotAvailable) and
// running it on a script in the script's folder, with its error output kept
// for the message when it fails.
#include "femup/reporting/plot.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "plot_internal.h"

extern char** environ;

namespace femup {
namespace plot_internal {
namespace {

bool IsExecutableFile(const std::string& path) {
  struct stat info;
  return ::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode) &&
         ::access(path.c_str(), X_OK) == 0;
}

std::string Trimmed(const std::string& text) {
  size_t begin = text.find_first_not_of(" \t\r\n");
  if (begin == std::string::npos) return "";
  size_t end = text.find_last_not_of(" \t\r\n");
  return text.substr(begin, end - begin + 1);
}

}  // namespace

std::string FindGnuplot() {
  const char* path_env = std::getenv("PATH");
  std::string path = path_env != nullptr ? path_env : "/bin:/usr/bin";
  size_t begin = 0;
  while (begin <= path.size()) {
    size_t end = path.find(':', begin);
    if (end == std::string::npos) end = path.size();
    std::string directory = path.substr(begin, end - begin);
    if (directory.empty()) directory = ".";  // POSIX: an empty entry is the cwd
    std::string candidate = directory + "/gnuplot";
    if (IsExecutableFile(candidate)) return candidate;
    begin = end + 1;
  }
  return "";
}

PlotStatus RunGnuplot(const std::string& gnuplot, const std::string& directory,
                      const std::string& script, const std::string& png) {
  PlotStatus status;
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0) {
    status.message = std::string("cannot start gnuplot: pipe: ") + std::strerror(errno);
    return status;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], 2);
  // The script names its files relative to its own folder, so it can be moved
  // with them and rerun there.
  posix_spawn_file_actions_addchdir_np(&actions, directory.c_str());

  std::vector<char*> argv;
  std::string arg0 = "gnuplot";
  std::string arg1 = script.substr(script.find_last_of('/') + 1);
  if (arg1[0] == '<' || arg1[0] == '-' || arg1[0] == '~' || arg1[0] == '|' ||
      arg1[0] == '+') {
    arg1 = "./" + arg1;
  }
  argv.push_back(arg0.data());
  argv.push_back(arg1.data());
  argv.push_back(nullptr);

  pid_t pid = 0;
  int spawn_error =
      ::posix_spawn(&pid, gnuplot.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(pipe_fds[1]);
  if (spawn_error != 0) {
    ::close(pipe_fds[0]);
    status.message = "cannot start " + gnuplot + ": " + std::strerror(spawn_error);
    return status;
  }

  std::string errors;
  char buffer[4096];
  for (;;) {
    ssize_t n = ::read(pipe_fds[0], buffer, sizeof(buffer));
    if (n > 0) {
      if (errors.size() < 16384) errors.append(buffer, static_cast<size_t>(n));
    } else if (n == 0 || errno != EINTR) {
      break;
    }
  }
  ::close(pipe_fds[0]);

  int wait_status = 0;
  while (::waitpid(pid, &wait_status, 0) < 0) {
    if (errno != EINTR) {
      status.message = std::string("waiting for gnuplot failed: ") + std::strerror(errno);
      return status;
    }
  }
  errors = Trimmed(errors);
  if (errors.size() > 4000) errors = errors.substr(0, 4000) + " ...";
  std::string detail = errors.empty() ? "" : ":\n" + errors;

  if (WIFSIGNALED(wait_status)) {
    status.message = "gnuplot was killed by signal " +
                     std::to_string(WTERMSIG(wait_status)) + " rendering '" + script +
                     "'" + detail;
  } else if (!WIFEXITED(wait_status) || WEXITSTATUS(wait_status) != 0) {
    status.message =
        "gnuplot failed (exit status " +
        std::to_string(WIFEXITED(wait_status) ? WEXITSTATUS(wait_status) : -1) +
        ") rendering '" + script + "'" + detail;
  } else {
    struct stat info;
    if (::stat(png.c_str(), &info) == 0 && S_ISREG(info.st_mode) && info.st_size > 0) {
      status.rendered = true;
      return status;
    }
    status.message =
        "gnuplot ran '" + script + "' but did not write '" + png + "'" + detail;
  }
  std::remove(png.c_str());  // a failed render may leave a truncated picture
  return status;
}

}  // namespace plot_internal

using plot_internal::FindGnuplot;

bool GnuplotAvailable() { return !FindGnuplot().empty(); }

}  // namespace femup
