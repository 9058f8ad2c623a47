#pragma once
// The checks every command runs before its work, so that a mistake costs no computation: the
// inputs exist and can be read, no output is an input, the job fits in memory and on disk.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace ibl::cli {

// The files an input argument names: the file itself, or the six files of a "{face}" pattern;
// none for a sky description ("sky:...") or the bundled default ("").
std::vector<std::filesystem::path> filesOfInput(const std::string& input);

// Fails, naming the file, unless every file of `input` exists, is a regular file and can be
// opened for reading. A sky description is parsed (its mistakes are usage errors).
void requireReadable(const std::string& input);

// Refuses (a usage error, before anything is read) an output that is one of the inputs: the
// same file by any path, through symbolic or hard links, "." and "..".
void refuseOverwritingInputs(const std::vector<std::filesystem::path>& outputs,
                             const std::vector<std::filesystem::path>& inputs);

// Refuses (before any work) an output file that cannot be written: the command creates its
// missing folders when it writes, so its nearest existing folder must be a writable directory;
// an existing output must not be a directory. Fails naming `output`.
void requireWritableFile(const std::filesystem::path& output);

// Refuses an input inside `outDir` when a command writes that directory as a whole (a bake, a
// probe): its files may be replaced or removed.
void refuseInputsInside(const std::filesystem::path& outDir,
                        const std::vector<std::filesystem::path>& inputs);

// The memory this process can still allocate: the system's available memory, or less where a
// control group limits the process.
std::uint64_t availableMemoryBytes();

// Refuses a job whose estimated peak memory (`bytes`) exceeds availableMemoryBytes(), with the
// estimate and what would make it smaller: "the bake needs about 9.1 GB (...); 6.0 GB are free:
// try a smaller --size". IBL_MEMORY_LIMIT (bytes) replaces the machine's figure (tests).
void requireMemory(std::uint64_t bytes, std::string_view job, std::string_view hint);

// Refuses writing about `bytes` under `where` (a file or directory, existing or not) when the
// file system holding it has less space free.
void requireDiskSpace(const std::filesystem::path& where, std::uint64_t bytes,
                      std::string_view job);

// "9.1 GB", "512 MB", "12 kB".
std::string formatBytes(double bytes);

}  // namespace ibl::cli
