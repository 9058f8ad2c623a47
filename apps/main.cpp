// `ibl`: command-line front end of the ibl library.
#include <pthread.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <fmt/core.h>
#include <tbb/global_control.h>

#include "commands.hpp"
#include "ibl/core/error.hpp"
#include "ibl/core/version.hpp"
#include "ibl/io/file_io.hpp"
#include "manual.hpp"
#include "usage.hpp"

namespace {

// Interrupts (Ctrl-C, SIGTERM, SIGHUP) end the process through one thread that first removes
// its temporary files (ibl::removeTemporariesOfThisProcess, which waits for a rename phase in
// progress): the signals are blocked in every thread (the task scheduler's start later and
// inherit the mask) and waited for in that one.
void removeTemporariesOnInterrupt() {
  sigset_t signals;
  sigemptyset(&signals);
  for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&signals, s);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  std::thread([signals] {
    int signal = 0;
    if (sigwait(&signals, &signal) != 0) return;
    ibl::removeTemporariesOfThisProcess();
    fmt::print(stderr, "\nibl: interrupted ({}); no output was left half-written\n",
               strsignal(signal));
    std::_Exit(128 + signal);
  }).detach();
}

}  // namespace

int main(int argc, char** argv) {
  removeTemporariesOnInterrupt();
  CLI::App app{"ibl: image-based lighting toolkit (bake, convert and inspect HDR environments)"};
  app.set_version_flag("--version", std::string("ibl ") + ibl::kVersion);
  app.require_subcommand(1);
  app.fallthrough();  // global options may follow the subcommand
  ibl::cli::GlobalOptions global;
  int threads = 0;
  app.add_option("--threads", threads, "Worker threads (default: all cores)")
      ->check(ibl::cli::numberIn(1, 4096));
  app.add_flag("-q,--quiet", global.quiet, "Print nothing but errors");
  std::unique_ptr<tbb::global_control> threadLimit;
  app.parse_complete_callback([&] {
    if (threads > 0)
      threadLimit = std::make_unique<tbb::global_control>(
          tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  });
  ibl::cli::addBakeCommand(app, global);
  ibl::cli::addConvertCommand(app, global);
  ibl::cli::addRenderCommand(app, global);
  ibl::cli::addProbeCommand(app, global);
  ibl::cli::addSkyCommand(app, global);
  ibl::cli::addCompareCommand(app, global);
  ibl::cli::addViewCommand(app, global);
  ibl::cli::addInfoCommand(app, global);
  ibl::cli::addManualCommands(app);  // last: it describes the commands above
  try {
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {
    return e.get_exit_code();  // a command's own status (compare above its threshold)
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    // Usage errors: one line in the project's words with the same prefix as every other error
    // (the nearest option or command for a misspelling), and status 2.
    fmt::print(
        stderr, "ibl: error: {}\n",
        ibl::cli::usageErrorMessage(app, e, std::vector<std::string>(argv + 1, argv + argc)));
    return 2;
  } catch (const ibl::UsageError& e) {  // a request found wrong before any work
    fmt::print(stderr, "ibl: error: {}\n", e.what());
    return 2;
  } catch (const ibl::Error& e) {
    fmt::print(stderr, "ibl: error: {}\n", e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "ibl: error: out of memory\n");
    return 1;
  } catch (const std::exception& e) {
    fmt::print(stderr, "ibl: error: {}\n", e.what());
    return 1;
  }
  return 0;
}
