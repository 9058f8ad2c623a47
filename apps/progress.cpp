#include "progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <fmt/core.h>

namespace ibl::cli {

namespace {

double seconds(std::chrono::steady_clock::duration d) {
  return std::chrono::duration<double>(d).count();
}

}  // namespace

ProgressLine::ProgressLine(bool enabled) : enabled_(enabled) {
  if (enabled_) ticker_ = std::thread([this] { tick(); });
}

ProgressLine::~ProgressLine() {
  if (!enabled_) return;
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
    if (!stage_.empty()) fmt::print(stderr, "\n");
  }
  wake_.notify_all();
  ticker_.join();
}

void ProgressLine::report(const std::string& stage, double fraction) {
  if (!enabled_) return;
  const std::lock_guard lock(mutex_);
  const int percent = static_cast<int>(std::floor(100.0 * std::clamp(fraction, 0.0, 1.0)));
  if (stage != stage_) {
    const bool first = stage_.empty();
    stage_ = stage;
    stageStart_ = std::chrono::steady_clock::now();
    percent_ = fraction > 0.0 ? percent : -1;
    print(!first);
  } else if (fraction > 0.0 && percent > percent_) {
    percent_ = percent;
    print(false);
  }
}

void ProgressLine::print(bool newLine) {
  const auto now = std::chrono::steady_clock::now();
  std::string status;
  if (percent_ >= 0)
    status = fmt::format(": {} %", percent_);
  else if (now - stageStart_ >= std::chrono::seconds(1))
    status = fmt::format(" ({:.0f} s)", seconds(now - stageStart_));
  // \x1b[K clears what a longer earlier text left on the line.
  fmt::print(stderr, "{}\r[{:7.2f} s] {}{}\x1b[K", newLine ? "\n" : "", seconds(now - start_),
             stage_, status);
  std::fflush(stderr);
}

void ProgressLine::tick() {
  std::unique_lock lock(mutex_);
  while (!stopping_) {
    wake_.wait_for(lock, std::chrono::seconds(1));
    if (!stopping_ && !stage_.empty() && percent_ < 0) print(false);
  }
}

}  // namespace ibl::cli
