#pragma once
// A virtual X display for driving the viewer's window as a user would: Xvfb (scripts/setup.sh
// installs it) with its screen mapped to a file (-fbdir), a command started in the background on
// it, xdotool pressing keys, moving and clicking the mouse, and the screen's pixels read back
// from the file (XWD, the format Xvfb writes). No dependency on the library.
#include <signal.h>
#include <sys/types.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "support/run_command.hpp"

namespace ibl::test {

// The screen as 8-bit sRGB pixels.
struct Screen {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // row-major, 3 bytes per pixel
  // The mean of the three channels over the rectangle [x0, x1) x [y0, y1), in [0, 255].
  double mean(int x0, int y0, int x1, int y1) const {
    double sum = 0.0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x)
        for (int c = 0; c < 3; ++c) sum += rgb[3 * (static_cast<std::size_t>(y) * width + x) + c];
    return sum / (3.0 * (x1 - x0) * (y1 - y0));
  }
  // The mean absolute difference from `other` over a rectangle, in [0, 255].
  double difference(const Screen& other, int x0, int y0, int x1, int y1) const {
    double sum = 0.0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x)
        for (int c = 0; c < 3; ++c) {
          const std::size_t i = 3 * (static_cast<std::size_t>(y) * width + x) + c;
          sum += std::abs(int(rgb[i]) - int(other.rgb[i]));
        }
    return sum / (3.0 * (x1 - x0) * (y1 - y0));
  }
};

class VirtualDisplay {
 public:
  // Starts Xvfb with one screen of width x height x 24 bits, mapped to a file in a new folder.
  // The server picks a free display number itself and writes it to a file (-displayfd): tests
  // that run side by side, each with its own server, never race for a number.
  VirtualDisplay(int width, int height) {
    dir_ = std::filesystem::temp_directory_path() /
           ("ibl-display-" + std::to_string(::getpid()) + "-" + std::to_string(counter()++));
    std::filesystem::create_directories(dir_);
    const auto numberFile = dir_ / "display";
    const CliRun r = runCommand("Xvfb -displayfd 3 -screen 0 " + std::to_string(width) + "x" +
                                std::to_string(height) + "x24 -fbdir " + dir_.string() +
                                " -nolisten tcp -nocursor 3> " + numberFile.string() + " > " +
                                (dir_ / "xvfb.log").string() + " 2>&1 & echo $!");
    xvfb_ = std::atoi(r.output.c_str());
    // The number, then the screen's file, then a client that connects.
    const bool started = waitFor(
        [&] {
          if (::kill(xvfb_, 0) != 0) return true;  // exited: the log says why
          const std::string text = fileText(numberFile);
          if (text.empty() || text.back() != '\n') return false;
          number_ = std::atoi(text.c_str());
          return std::filesystem::exists(dir_ / "Xvfb_screen0") &&
                 xdotool("getmouselocation").status == 0;
        },
        30.0);
    if (!started || ::kill(xvfb_, 0) != 0) {
      if (xvfb_ > 0) ::kill(xvfb_, SIGTERM);
      const std::string log = fileText(dir_ / "xvfb.log");
      std::error_code ignored;
      std::filesystem::remove_all(dir_, ignored);
      throw std::runtime_error("Xvfb did not start: " + log);
    }
  }
  ~VirtualDisplay() {
    if (app_ > 0) ::kill(-app_, SIGKILL);  // the command's process group
    if (xvfb_ > 0) ::kill(xvfb_, SIGTERM);
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
  }
  VirtualDisplay(const VirtualDisplay&) = delete;
  VirtualDisplay& operator=(const VirtualDisplay&) = delete;

  // Starts `command` on the display in the background, its output to a log (log()) and its exit
  // status to a file (exitStatus()).
  void launch(const std::string& command) {
    // setsid: the command leads a process group of its own, which the destructor kills.
    const CliRun r =
        runCommand("DISPLAY=:" + std::to_string(number_) + " setsid sh -c '" + command + " > " +
                   (dir_ / "app.log").string() + " 2>&1; echo $? > " +
                   (dir_ / "app.status").string() + "' > /dev/null 2>&1 & echo $!");
    app_ = std::atoi(r.output.c_str());
  }
  // Waits for a window whose title contains `name` and gives it the keyboard's focus.
  bool focusWindow(const std::string& name, double seconds) {
    return waitFor(
        [&] { return xdotool("search --name '" + name + "' windowfocus --sync").status == 0; },
        seconds);
  }
  // Runs the shell command line `command` on the display.
  CliRun onDisplay(const std::string& command) const {
    return runCommand("DISPLAY=:" + std::to_string(number_) + " " + command);
  }
  // Runs xdotool with `arguments` on the display.
  CliRun xdotool(const std::string& arguments) const { return onDisplay("xdotool " + arguments); }
  // The screen now.
  Screen screen() const {
    const std::string bytes = fileText(dir_ / "Xvfb_screen0");
    const auto word = [&](std::size_t i) {  // XWD's header: big-endian 32-bit fields
      return static_cast<std::uint32_t>(static_cast<std::uint8_t>(bytes[4 * i]) << 24 |
                                        static_cast<std::uint8_t>(bytes[4 * i + 1]) << 16 |
                                        static_cast<std::uint8_t>(bytes[4 * i + 2]) << 8 |
                                        static_cast<std::uint8_t>(bytes[4 * i + 3]));
    };
    Screen s;
    if (bytes.size() < 100) return s;
    const std::uint32_t headerSize = word(0), bitsPerPixel = word(11), bytesPerLine = word(12),
                        colors = word(19);
    s.width = static_cast<int>(word(4));
    s.height = static_cast<int>(word(5));
    const std::size_t pixels = headerSize + 12u * colors;
    if (bitsPerPixel != 32 || bytes.size() < pixels + bytesPerLine * s.height)
      throw std::runtime_error("unexpected XWD layout from Xvfb");
    s.rgb.resize(static_cast<std::size_t>(s.width) * s.height * 3);
    for (int y = 0; y < s.height; ++y)
      for (int x = 0; x < s.width; ++x) {
        const std::size_t i = pixels + y * bytesPerLine + 4 * x;  // B, G, R, X (LSB first)
        std::uint8_t* out = &s.rgb[3 * (static_cast<std::size_t>(y) * s.width + x)];
        out[0] = static_cast<std::uint8_t>(bytes[i + 2]);
        out[1] = static_cast<std::uint8_t>(bytes[i + 1]);
        out[2] = static_cast<std::uint8_t>(bytes[i]);
      }
    return s;
  }
  // Polls the screen until `condition` holds of it (true) or `seconds` pass (false).
  bool waitForScreen(const std::function<bool(const Screen&)>& condition, double seconds) const {
    return waitFor([&] { return condition(screen()); }, seconds);
  }
  // The launched command's exit status once it has exited within `seconds`; -1 otherwise.
  int exitStatus(double seconds) const {
    const auto path = dir_ / "app.status";
    if (!waitFor([&] { return std::filesystem::exists(path) && !fileText(path).empty(); }, seconds))
      return -1;
    return std::atoi(fileText(path).c_str());
  }
  std::string log() const { return fileText(dir_ / "app.log"); }

  static bool waitFor(const std::function<bool()>& condition, double seconds) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    for (;;) {
      if (condition()) return true;
      if (std::chrono::steady_clock::now() > end) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  }

 private:
  static int& counter() {
    static int n = 0;
    return n;
  }
  static std::string fileText(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  std::filesystem::path dir_;
  int number_ = 0;
  pid_t xvfb_ = 0, app_ = 0;
};

}  // namespace ibl::test
