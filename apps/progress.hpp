#pragma once
// The progress of a long command on a terminal: one line per stage, "[  5.11 s] specular level
// 2/9 (1024x1024, roughness 0.125)", rewritten in place with the fraction of the stage done
// ("... 37 %") when the stage reports one, or else, every second, with the seconds the stage has
// run, so that no stage that takes long is silent.
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace ibl::cli {

class ProgressLine {
 public:
  // Prints nothing unless `enabled` (stderr is a terminal and the command is not --quiet).
  explicit ProgressLine(bool enabled);
  ~ProgressLine();  // ends the last line
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  // Stage `stage` has done `fraction` (0 when it starts) of its work. From any thread: a stage
  // other than the current one starts a new line.
  void report(const std::string& stage, double fraction);
  // The same as a callable for the library's ProgressFn.
  auto callback() {
    return [this](const std::string& stage, double fraction) { report(stage, fraction); };
  }

 private:
  void print(bool newLine);  // under mutex_
  void tick();

  bool enabled_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point stageStart_ = start_;
  std::string stage_;
  int percent_ = -1;  // last printed; -1: none reported
  bool stopping_ = false;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread ticker_;
};

}  // namespace ibl::cli
