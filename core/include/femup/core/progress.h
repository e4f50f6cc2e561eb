// Progress of long work: the callback a study reports through, and a text
// progress bar for a terminal that the command line wires to it. Studies never
// write to a terminal themselves; they call the callback they are given.
#pragma once

#include <chrono>
#include <functional>
#include <mutex>
#include <ostream>
#include <string>

namespace femup {

// Called as items of work finish: `done` of `total` (0 < done <= total). It may
// be called from several worker threads at once, and out of order (a smaller
// `done` after a larger one): implementations must be thread-safe. An empty
// function means nobody listens.
using ProgressCallback = std::function<void(int done, int total)>;

// A one-line bar, redrawn in place with '\r':
//   "noise [##########----------]  50%  500/1000  elapsed 1.2 s  ETA 1.2 s"
// Writes nothing at all when `is_terminal` is false (output piped or
// redirected to a file) so logs stay clean. Thread-safe: Update may be called
// from any thread; redraws are throttled to one per `min_interval_seconds`
// (the last item, done == total, is always drawn). `out` is not owned and must
// outlive the bar.
class ProgressBar {
 public:
  ProgressBar(std::string label, std::ostream* out, bool is_terminal,
              double min_interval_seconds = 0.1);
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;
  ~ProgressBar();  // calls Finish()

  void Update(int done, int total);
  // Ends the line (a newline) if anything was drawn; later updates draw nothing.
  void Finish();
  // A callback that forwards to Update; the bar must outlive its use.
  ProgressCallback Callback();

  // The line for `done` of `total` after `elapsed_seconds` (no '\r'); the ETA
  // is elapsed * (total - done) / done, "?" before the first item.
  static std::string Format(const std::string& label, int done, int total,
                            double elapsed_seconds, int bar_width = 24);

 private:
  const std::string label_;
  std::ostream* const out_;
  const bool enabled_;
  const double min_interval_;
  const std::chrono::steady_clock::time_point start_;
  std::mutex mutex_;             // guards the fields below and the stream
  int best_done_ = 0;            // largest `done` seen
  double last_draw_ = -1e300;    // seconds since start_ of the last redraw
  std::size_t last_length_ = 0;  // length of the last line drawn
  bool drawn_ = false, finished_ = false;
};

// True when standard error is a terminal (isatty(2)).
bool StderrIsTerminal();

}  // namespace femup
