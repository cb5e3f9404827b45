// Progress bar / periodic progress lines on stderr (see progress.hpp).
#include "demfit/cases/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace demfit::cases {

ProgressPrinter::ProgressPrinter(double interval_seconds)
    : terminal_(isatty(STDERR_FILENO) != 0), interval_(interval_seconds) {}

void ProgressPrinter::update(const std::string& stage, double time, double end_time) {
  const auto now = Clock::now();
  if (stage != stage_) {
    if (line_open_) finish();
    stage_ = stage;
    stage_start_ = now;
    last_print_ = now - std::chrono::hours(1);
  }
  const double since_print = std::chrono::duration<double>(now - last_print_).count();
  const bool done = time >= end_time;
  if (since_print < (terminal_ ? 0.1 : interval_) && !done) return;
  last_print_ = now;
  const double fraction = end_time > 0.0 ? std::clamp(time / end_time, 0.0, 1.0) : 1.0;
  const double elapsed = std::chrono::duration<double>(now - stage_start_).count();
  const double eta = fraction > 1e-9 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  if (terminal_) {
    constexpr int width = 30;
    const int filled = static_cast<int>(fraction * width);
    std::string bar(filled, '#');
    bar.resize(width, '.');
    std::fprintf(stderr, "\r%-9s [%s] %5.1f%%  t = %.4f / %.4f s  ETA %4.0f s ", stage.c_str(), bar.c_str(),
                 100.0 * fraction, time, end_time, eta);
    line_open_ = true;
  } else {
    std::fprintf(stderr, "%s: t = %.4f / %.4f s (%.0f%%), elapsed %.0f s, ETA %.0f s\n", stage.c_str(), time, end_time,
                 100.0 * fraction, elapsed, eta);
  }
  std::fflush(stderr);
}

void ProgressPrinter::finish() {
  if (line_open_) std::fputc('\n', stderr);
  line_open_ = false;
}

ProgressCallback ProgressPrinter::callback() {
  return [this](const std::string& stage, double time, double end_time) { update(stage, time, end_time); };
}

}  // namespace demfit::cases
