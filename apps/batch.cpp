#include "batch.hpp"

#include <glob.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>

#include <fmt/core.h>

#include "ibl/core/error.hpp"
#include "ibl/core/parallel.hpp"

namespace ibl::cli {

namespace {

bool isPattern(const std::string& arg) {
  return arg.find_first_of("*?[") != std::string::npos;
}

// The files a shell pattern matches, sorted (glob(3)).
std::vector<std::string> expandPattern(const std::string& pattern) {
  glob_t g{};
  const int status = ::glob(pattern.c_str(), 0, nullptr, &g);
  std::vector<std::string> files;
  if (status == 0)
    for (std::size_t i = 0; i < g.gl_pathc; ++i) files.emplace_back(g.gl_pathv[i]);
  ::globfree(&g);
  if (files.empty()) fail(pattern, "matches no file");
  return files;
}

}  // namespace

std::string batchName(const std::string& input) {
  std::string name = std::filesystem::path(input).stem().string();
  const auto at = name.find("{face}");
  if (at != std::string::npos) {
    std::size_t begin = at, end = at + 6;
    while (begin > 0 &&
           (name[begin - 1] == '_' || name[begin - 1] == '-' || name[begin - 1] == '.'))
      --begin;
    while (end < name.size() && (name[end] == '_' || name[end] == '-' || name[end] == '.')) ++end;
    name = name.substr(0, begin) + (begin > 0 && end < name.size() ? "_" : "") + name.substr(end);
  }
  return name.empty() ? "environment" : name;
}

std::vector<std::string> expandInputs(const std::vector<std::string>& args,
                                      const std::string& listFile) {
  std::vector<std::string> inputs;
  for (const std::string& arg : args) {
    if (isPattern(arg) && !std::filesystem::exists(arg)) {
      for (auto& f : expandPattern(arg)) inputs.push_back(std::move(f));
    } else {
      inputs.push_back(arg);
    }
  }
  if (!listFile.empty()) {
    std::ifstream in(listFile);
    if (!in) fail(listFile, "cannot read the list");
    std::string line;
    while (std::getline(in, line)) {
      while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
      if (line.empty() || line[0] == '#') continue;
      inputs.push_back(line);
    }
    if (inputs.empty()) fail(listFile, "lists no input");
  }
  std::map<std::string, std::string> names;
  for (const std::string& input : inputs) {
    const auto [it, inserted] = names.emplace(batchName(input), input);
    if (!inserted)
      failUsage(input, fmt::format("has the same name '{}' as {}: the outputs would collide",
                                   it->first, it->second));
  }
  return inputs;
}

void runBatch(const std::vector<std::string>& inputs,
              const std::function<std::string(const std::string&)>& one, bool parallel,
              const GlobalOptions& global) {
  const auto start = std::chrono::steady_clock::now();
  std::mutex printing;
  std::vector<std::string> failed(inputs.size());
  int done = 0;
  const auto run = [&](std::size_t i) {
    std::string line;
    try {
      line = one(inputs[i]);
    } catch (const std::exception& e) {
      failed[i] = e.what();
    }
    const std::lock_guard lock(printing);
    ++done;
    if (!failed[i].empty())
      fmt::print(stderr, "[{}/{}] ibl: error: {}\n", done, inputs.size(), failed[i]);
    else if (!global.quiet)
      fmt::print(stderr, "[{}/{}] {}\n", done, inputs.size(), line);
  };
  if (parallel) {
    parallelFor(std::size_t{0}, inputs.size(), run);
  } else {
    for (std::size_t i = 0; i < inputs.size(); ++i) run(i);
  }
  std::vector<std::string> names;
  for (std::size_t i = 0; i < inputs.size(); ++i)
    if (!failed[i].empty()) names.push_back(inputs[i]);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!global.quiet || !names.empty())
    fmt::print(stderr, "{} of {} inputs done in {:.2f} s{}\n", inputs.size() - names.size(),
               inputs.size(), seconds,
               names.empty() ? "" : fmt::format(", {} failed", names.size()));
  if (!names.empty()) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    fail("batch", fmt::format("{} of {} inputs failed: {}", names.size(), inputs.size(), list));
  }
}

}  // namespace ibl::cli
