// The default bake as a whole process sees it, stage by stage: read the file, decode, replace
// invalid pixels, the bake's own stages (source cube and mips, specular, irradiance, SH9, DFG;
// the last runs beside the others), encode and write the outputs. Prints wall time per stage,
// the total, and the process's CPU time (all threads), for each input and repetition.
//   ibl_process [--runs N] [input ...]     (default: the bundled HDRIs as 1024x512 HDR files)
#include <sys/resource.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "ibl/bake/bake.hpp"
#include "ibl/env/environment.hpp"
#include "ibl/env/export.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// User + system time of the whole process so far, in ms.
double cpuMs() {
  rusage u{};
  ::getrusage(RUSAGE_SELF, &u);
  const auto ms = [](const timeval& t) { return t.tv_sec * 1e3 + t.tv_usec / 1e3; };
  return ms(u.ru_utime) + ms(u.ru_stime);
}

// A 1024x512 Radiance HDR of a bundled HDRI, the reference input.
fs::path referenceInput(const std::string& name, const fs::path& dir) {
  const fs::path out = dir / (name + "_1024.hdr");
  ibl::ExportOptions e;
  e.output = out;
  e.size = 1024;
  const auto env = ibl::loadEnvironment(std::string(IBL_BENCH_DATA) + "/hdri/" + name + ".exr");
  ibl::writeFilesTogether(ibl::encodeEnvironment(env.environment, e));
  return out;
}

void bakeOnce(const fs::path& input, const fs::path& outDir) {
  const double cpu0 = cpuMs();
  const auto start = Clock::now();
  auto t = Clock::now();
  const std::vector<std::uint8_t> bytes = ibl::readFileBytes(input);
  const double read = msSince(t);
  t = Clock::now();
  ibl::DecodedFile decoded = ibl::decodeImageFile(bytes, input.string());
  const double decode = msSince(t);
  t = Clock::now();
  ibl::Environment env = ibl::environmentFromFile(std::move(decoded), {}, input.string());
  ibl::sanitizeEnvironment(env);
  const double sanitize = msSince(t);
  const ibl::BakeOptions options;
  const ibl::BakeResult result = ibl::bakeEnvironment(env, options);
  t = Clock::now();
  ibl::BakeOutputOptions output;
  output.force = true;
  ibl::BakeSource source;
  source.path = input.string();
  source.format = "hdr";
  source.layout = "equirect";
  source.width = env.equirect.width;
  source.height = env.equirect.height;
  ibl::writeBakeOutputs(result, options, output, source, outDir);
  const double write = msSince(t);
  const double total = msSince(start), cpu = cpuMs() - cpu0;
  const auto& s = result.timingsMs;
  fmt::print(
      "{:24} {:7.1f} {:7.1f} {:7.1f} | {:7.1f} {:7.1f} {:7.1f} {:5.1f} {:5.1f} {:7.1f} | {:7.1f} | "
      "{:7.1f} {:7.1f}\n",
      input.filename().string(), read, decode, sanitize, s.at("source"), s.at("specular"),
      s.at("irradiance"), s.at("sh"), s.at("dfg"), s.at("total"), write, total, cpu);
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 3;
  std::vector<fs::path> inputs;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--runs" && i + 1 < argc) {
      runs = std::atoi(argv[++i]);
    } else {
      inputs.emplace_back(argv[i]);
    }
  }
  const fs::path dir = fs::temp_directory_path() / "ibl_process_bench";
  fs::create_directories(dir);
  if (inputs.empty())
    for (const char* name : {"sunset", "park"}) inputs.push_back(referenceInput(name, dir));
  fmt::print(
      "{:24} {:>7} {:>7} {:>7} | {:>7} {:>7} {:>7} {:>5} {:>5} {:>7} | {:>7} | {:>7} {:>7}\n",
      "input (ms)", "read", "decode", "clean", "source", "specul.", "irrad.", "sh", "dfg", "bake",
      "write", "wall", "cpu");
  for (const auto& input : inputs)
    for (int r = 0; r < runs; ++r) bakeOnce(input, dir / "out");
  fs::remove_all(dir);
}
