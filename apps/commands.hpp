#pragma once
// The subcommands of the `ibl` executable: each registers its options and a callback.
#include <CLI/CLI.hpp>

namespace ibl::cli {

struct GlobalOptions {
  bool quiet = false;
};

void addConvertCommand(CLI::App& app, const GlobalOptions& global);
void addInfoCommand(CLI::App& app, const GlobalOptions& global);
void addBakeCommand(CLI::App& app, const GlobalOptions& global);
void addRenderCommand(CLI::App& app, const GlobalOptions& global);
void addCompareCommand(CLI::App& app, const GlobalOptions& global);
void addViewCommand(CLI::App& app, const GlobalOptions& global);

}  // namespace ibl::cli
