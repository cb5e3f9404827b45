#pragma once
// Progress of a running case: simulated time against the end time, with an ETA from wall-clock
// time. On a terminal (isatty(stderr)) one line is redrawn as a bar; otherwise plain lines are
// printed every `interval` wall-clock seconds (logs stay readable).
#include <chrono>
#include <functional>
#include <string>

namespace demfit::cases {

// Called by case runners: stage name ("settle", "compress", "rotate"...), simulated time [s]
// and the stage's end time [s]. May be empty.
using ProgressCallback = std::function<void(const std::string& stage, double time, double end_time)>;

class ProgressPrinter {
 public:
  explicit ProgressPrinter(double interval_seconds = 1.0);
  // Updates the display; cheap when called often (prints at most every ~0.1 s on a terminal).
  void update(const std::string& stage, double time, double end_time);
  // Ends the current line (terminal mode) so later output starts on a fresh line.
  void finish();
  ProgressCallback callback();

 private:
  using Clock = std::chrono::steady_clock;
  bool terminal_;
  double interval_;
  std::string stage_;
  Clock::time_point stage_start_;
  Clock::time_point last_print_;
  bool line_open_ = false;
};

}  // namespace demfit::cases
