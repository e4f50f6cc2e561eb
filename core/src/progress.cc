#include "femup/core/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace femup {

namespace {

// "0.4 s", "12 s", "3 min 05 s", "2 h 07 min".
std::string Duration(double seconds) {
  char buffer[48];
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  if (seconds < 10) {
    std::snprintf(buffer, sizeof buffer, "%.1f s", seconds);
  } else if (seconds < 60) {
    std::snprintf(buffer, sizeof buffer, "%.0f s", seconds);
  } else if (seconds < 3600) {
    const long s = std::lround(seconds);
    std::snprintf(buffer, sizeof buffer, "%ld min %02ld s", s / 60, s % 60);
  } else {
    const long m = std::lround(seconds / 60);
    std::snprintf(buffer, sizeof buffer, "%ld h %02ld min", m / 60, m % 60);
  }
  return buffer;
}

}  // namespace

ProgressBar::ProgressBar(std::string label, std::ostream* out, bool is_terminal,
                         double min_interval_seconds)
    : label_(std::move(label)),
      out_(out),
      enabled_(is_terminal && out != nullptr),
      min_interval_(min_interval_seconds),
      start_(std::chrono::steady_clock::now()) {}

ProgressBar::~ProgressBar() { Finish(); }

std::string ProgressBar::Format(const std::string& label, int done, int total,
                                double elapsed_seconds, int bar_width) {
  total = std::max(total, 0);
  done = std::clamp(done, 0, total);
  const double fraction = total > 0 ? static_cast<double>(done) / total : 1.0;
  const int filled = static_cast<int>(std::floor(fraction * bar_width));
  const int percent = static_cast<int>(std::floor(fraction * 100));
  const double eta = done > 0 ? elapsed_seconds * (total - done) / done : std::nan("");
  char numbers[96];
  std::snprintf(numbers, sizeof numbers, "%3d%%  %d/%d", percent, done, total);
  std::string line = label;
  if (!line.empty()) line += " ";
  line += "[" + std::string(static_cast<std::size_t>(filled), '#') +
          std::string(static_cast<std::size_t>(bar_width - filled), '-') + "] " +
          numbers + "  elapsed " + Duration(elapsed_seconds) + "  ETA " +
          (done == total ? Duration(0) : Duration(eta));
  return line;
}

void ProgressBar::Update(int done, int total) {
  if (!enabled_) return;
  const double now =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::lock_guard<std::mutex> lock(mutex_);
  if (finished_) return;
  if (done <= best_done_) return;  // out of order: a newer count was shown
  best_done_ = done;
  if (done < total && now - last_draw_ < min_interval_) return;
  last_draw_ = now;
  const std::string line = Format(label_, done, total, now);
  // Blank out what is left of a longer previous line.
  const std::size_t pad = last_length_ > line.size() ? last_length_ - line.size() : 0;
  *out_ << '\r' << line << std::string(pad, ' ') << std::flush;
  last_length_ = line.size();
  drawn_ = true;
}

void ProgressBar::Finish() {
  if (!enabled_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (finished_) return;
  finished_ = true;
  if (drawn_) *out_ << '\n' << std::flush;
}

ProgressCallback ProgressBar::Callback() {
  return [this](int done, int total) { Update(done, total); };
}

bool StderrIsTerminal() { return ::isatty(STDERR_FILENO) == 1; }

}  // namespace femup
