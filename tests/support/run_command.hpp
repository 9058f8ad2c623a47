#pragma once
// Running a shell command from a test: its exit status and combined output. No dependency on the
// library, so that every test executable can use it.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace ibl::test {

// What a command did: exit status and combined output.
struct CliRun {
  int status;
  std::string output;  // stdout and stderr
};

// Runs a shell command; status (-1 if it did not exit) and combined output.
inline CliRun runCommand(const std::string& command) {
  const std::string cmd = command + " 2>&1";
  CliRun r{-1, ""};
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf;
  while (fgets(buf.data(), buf.size(), pipe)) r.output += buf.data();
  const int status = pclose(pipe);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

}  // namespace ibl::test
