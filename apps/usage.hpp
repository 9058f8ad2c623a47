#pragma once
// The messages of command-line mistakes that CLI11 finds while parsing, in the project's words:
// one line naming the option or command, what was expected, and the nearest name for a
// misspelling.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

namespace ibl::cli {

// The Levenshtein distance: the fewest insertions, deletions and substitutions of one
// character that turn `a` into `b`.
std::size_t editDistance(std::string_view a, std::string_view b);

// Of `candidates`, the one nearest `word` by editDistance when it is near enough to be a
// misspelling of it (at most 2 edits, and fewer than half of `word`'s length); "" otherwise.
std::string nearestName(std::string_view word, const std::vector<std::string>& candidates);

// The line (without "ibl: error: ") that `e`, thrown by app.parse(args), stands for: "unknown
// option --sizee; did you mean --size?", "unknown command 'frobnicate'; the commands are
// bake, ...", "--size: '64x64' is not a whole number (...)", "--camera: 'fisheye' is not
// perspective or ortho", "scene: required (...)". `args`: the arguments after the program's
// name, as given.
std::string usageErrorMessage(const CLI::App& app, const CLI::ParseError& e,
                              const std::vector<std::string>& args);

}  // namespace ibl::cli
