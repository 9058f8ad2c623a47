#pragma once
// Batches: one command over many inputs (`ibl bake a.exr b.hdr -o DIR`, `ibl convert ...`).
#include <functional>
#include <string>
#include <vector>

#include "commands.hpp"

namespace ibl::cli {

// The inputs a user named: each argument (a pattern with * ? [ ] that names no file is
// expanded, sorted; one that matches nothing is an error), then the lines of `listFile` if
// given (one path per line, relative to the working directory; blank lines and lines starting
// with # are skipped). Fails on an empty result and on two inputs with the same batchName.
std::vector<std::string> expandInputs(const std::vector<std::string>& args,
                                      const std::string& listFile);

// The name of an input's own output in a batch: its file name without the extension, with a
// "{face}" placeholder and the separators around it removed (sky_{face}.exr -> sky).
std::string batchName(const std::string& input);

// Runs `one(input)` for every input, several at once when `parallel` (each one uses every core
// too; the task scheduler shares them), and prints a line per input as it ends: its result,
// or its error. Throws Error naming the failed inputs after all have run.
void runBatch(const std::vector<std::string>& inputs,
              const std::function<std::string(const std::string&)>& one, bool parallel,
              const GlobalOptions& global);

}  // namespace ibl::cli
