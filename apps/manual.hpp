#pragma once
// Manual pages and shell completions of `ibl`, written from the same CLI11 definitions as its
// --help: the generator walks the App tree the command parses with (its visible subcommands and
// options: names, descriptions, value types, defaults, and the allowed values of IsMember
// checks, read from the type name --help prints, "TEXT:{a,b,c}").
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace ibl::cli {

// One man page: ibl.1 (`command` null) or ibl-<command>.1.
std::string manPage(const CLI::App& top, const CLI::App* command);
// The file names and texts of every page: ibl.1 and ibl-<command>.1 per visible subcommand.
std::vector<std::pair<std::string, std::string>> manPages(const CLI::App& top);
// Completion scripts: bash (`complete -F _ibl ibl`) and zsh (`#compdef ibl`).
std::string bashCompletion(const CLI::App& top);
std::string zshCompletion(const CLI::App& top);

// Registers `ibl completion bash|zsh` (prints a script) and the hidden `ibl manual --man-dir DIR
// --bash FILE --zsh FILE` the build runs (cmake/manual_pages.cmake). Call after every other
// command is added: the texts describe the tree as it is when they are written.
void addManualCommands(CLI::App& app);

}  // namespace ibl::cli
