// What every peer comparison program (bench/*_peer_compare.cc) shares: running
// a Python peer script and reading the JSON it prints, running femup's side in
// a fork()ed child so that its peak resident set is its own, and reading and
// resetting the peak resident set of the calling process; and the command-line
// options, the working directory and the clock they have in common.
#pragma once

#include <malloc.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace femup_bench {

using Clock = std::chrono::steady_clock;

// Seconds from `since` to now.
inline double Seconds(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
}

// The options every peer program has: --python (an interpreter that has
// `needs`), --script (the peer script, `script_name`) and --markdown.
inline void AddPeerOptions(CLI::App& app, std::string& python, std::string& script,
                           std::string& markdown, const std::string& needs,
                           const std::string& script_name) {
  app.add_option("--python", python, "python interpreter that has " + needs);
  app.add_option("--script", script, "the peer script (" + script_name + ")");
  app.add_option("--markdown", markdown, "also write the tables to this file");
}

// Prints `tables` to stdout and, when `markdown` is not empty, writes them to
// that file; false, with a message on stderr, when the file cannot be written.
inline bool PrintTables(const std::string& tables, const std::string& markdown) {
  std::cout << tables;
  if (markdown.empty()) return true;
  std::ofstream file(markdown);
  file << tables;
  if (!file) {
    std::cerr << "cannot write " << markdown << "\n";
    return false;
  }
  return true;
}

// `keep` when it is not empty; otherwise a fresh temporary directory
// (femup-`name`-XXXXXX in the system's temporary directory). Empty, with a
// message on stderr, when that cannot be created.
inline std::filesystem::path WorkDirectory(const std::string& keep,
                                           const std::string& name) {
  if (!keep.empty()) return keep;
  std::string pattern =
      (std::filesystem::temp_directory_path() / ("femup-" + name + "-XXXXXX")).string();
  if (::mkdtemp(pattern.data()) == nullptr) {
    std::cerr << "cannot create a temporary directory from " << pattern << "\n";
    return {};
  }
  return pattern;
}

// What one side returned; `error` says why not when it is not empty.
struct PeerResult {
  nlohmann::json json;
  std::string error;
};

// Single quotes for /bin/sh.
inline std::string ShellQuote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

inline std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// printf of one number.
inline std::string Format(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

// Runs `python script dir arguments` with one BLAS thread (femup's side uses
// one thread too), its stderr to dir/peer.stderr, and parses its stdout as
// JSON. `arguments` is appended as it is: quote what needs quoting.
inline PeerResult RunPeerScript(const std::string& python, const std::string& script,
                                const std::filesystem::path& dir,
                                const std::string& arguments) {
  const std::filesystem::path err = dir / "peer.stderr";
  const std::string command =
      "OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1 " + ShellQuote(python) +
      " " + ShellQuote(script) + " " + ShellQuote(dir.string()) + " " + arguments +
      " 2>" + ShellQuote(err.string());
  PeerResult out;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) {
    out.error = "could not start " + python;
    return out;
  }
  std::string text;
  char buffer[1 << 16];
  for (std::size_t got; (got = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) {
    text.append(buffer, got);
  }
  const int status = ::pclose(pipe);
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (code != 0) {
    std::string why = ReadFile(err);
    while (!why.empty() && why.back() == '\n') why.pop_back();
    if (code == 127) why = python + " not found (" + why + ")";
    out.error =
        why.empty() ? "the script exited with status " + std::to_string(code) : why;
    return out;
  }
  try {
    out.json = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    out.error = std::string("unreadable output of the script: ") + e.what();
  }
  return out;
}

// VmRSS / VmHWM (MB) from /proc/self/status; -1 when unreadable.
inline double StatusMb(const char* field) {
  std::ifstream status("/proc/self/status");
  std::string line;
  const std::string key = std::string(field) + ":";
  while (std::getline(status, line)) {
    if (line.compare(0, key.size(), key) == 0) {
      return std::stod(line.substr(key.size())) / 1024.0;  // kB
    }
  }
  return -1;
}

// Resets VmHWM to the current resident set (Linux >= 4.0).
inline bool ResetPeakRss() {
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
  clear.flush();
  return static_cast<bool>(clear);
}

// Runs `work` in a fork()ed child and reads the JSON it returns through a
// pipe, so that the child's peak resident set is the work's own (plus what it
// inherits). An exception in the child comes back as `error`; so does a child
// killed by a signal (out of memory, say).
inline PeerResult RunInChild(const std::function<nlohmann::json()>& work) {
  PeerResult out;
  int fds[2];
  if (::pipe(fds) != 0) {
    out.error = std::string("pipe: ") + std::strerror(errno);
    return out;
  }
  std::cout.flush();
  std::cerr.flush();
  const pid_t pid = ::fork();
  if (pid < 0) {
    out.error = std::string("fork: ") + std::strerror(errno);
    ::close(fds[0]);
    ::close(fds[1]);
    return out;
  }
  if (pid == 0) {
    ::close(fds[0]);
    std::string text;
    int code = 0;
    try {
      text = work().dump();
    } catch (const std::exception& e) {
      text = nlohmann::json{{"error", e.what()}}.dump();
      code = 1;
    }
    for (std::size_t done = 0; done < text.size();) {
      const ssize_t wrote = ::write(fds[1], text.data() + done, text.size() - done);
      if (wrote <= 0) break;
      done += static_cast<std::size_t>(wrote);
    }
    ::close(fds[1]);
    ::_exit(code);
  }
  ::close(fds[1]);
  std::string text;
  char buffer[1 << 16];
  for (ssize_t got; (got = ::read(fds[0], buffer, sizeof buffer)) > 0;) {
    text.append(buffer, static_cast<std::size_t>(got));
  }
  ::close(fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (WIFSIGNALED(status)) {
    out.error = "the femup child died of signal " + std::to_string(WTERMSIG(status));
    return out;
  }
  try {
    out.json = nlohmann::json::parse(text);
    if (out.json.contains("error")) out.error = out.json["error"].get<std::string>();
  } catch (const nlohmann::json::exception& e) {
    out.error = std::string("unreadable output of the femup child: ") + e.what();
  }
  return out;
}

}  // namespace femup_bench
