#pragma once
// API: stable
// Progress of long work, reported to a front end (apps/progress.hpp draws it on a terminal).

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

namespace ibl {

// Progress of long work: `stage` (a few words naming it, e.g. "irradiance 32x32") has done
// `fraction` (0 to 1) of its work: 0 when it starts, 1 when it ends (a front end keeps the largest
// fraction so far: the parallel workers' calls may arrive out of order). Called from any thread;
// stages may run at the same time (the DFG table beside the convolutions).
using ProgressFn = std::function<void(const std::string& stage, double fraction)>;

// Counts the parts of a stage as parallel workers finish them, and reports `stage` to
// `progress` (if any) each time another whole percent is done: at most 100 calls, whatever the
// number of parts. Thread-safe.
class ProgressCounter {
 public:
  // progress: kept by reference (it must outlive the counter), may be empty; parts: the number
  // of advance() calls that complete the stage (below 1 counts as 1).
  ProgressCounter(const ProgressFn& progress, std::string stage, std::int64_t parts)
      : progress_(progress), stage_(std::move(stage)), parts_(parts > 0 ? parts : 1) {}

  // One more part is done.
  void advance() {
    if (!progress_) return;
    const int percent = static_cast<int>(100 * (done_.fetch_add(1) + 1) / parts_);
    int reported = reported_.load();
    while (percent > reported && !reported_.compare_exchange_weak(reported, percent)) {
    }
    if (percent > reported) progress_(stage_, percent / 100.0);
  }

 private:
  const ProgressFn& progress_;
  std::string stage_;
  std::int64_t parts_;
  std::atomic<std::int64_t> done_{0};
  std::atomic<int> reported_{0};
};

}  // namespace ibl
