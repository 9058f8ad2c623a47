// The Python module `ibl` (docs/python.md): NumPy arrays in and out of the command's own code.
// Every function parses its keyword arguments as the command's long options (size=32 is
// `--size 32`) with the command's own option definitions (apps/*.hpp), so that the defaults,
// the checks and the messages are the command's, and then runs the same functions the command
// runs. Long work runs without the GIL; a progress callback is called with it.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <mutex>
#include <optional>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include <fmt/core.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "bake.hpp"
#include "commands.hpp"
#include "compare.hpp"
#include "ibl/core/error.hpp"
#include "ibl/core/version.hpp"
#include "ibl/env/export.hpp"
#include "ibl/gpu/compute.hpp"
#include "ibl/io/file_io.hpp"
#include "ibl/io/image_io.hpp"
#include "render.hpp"
#include "sky.hpp"
#include "usage.hpp"

namespace py = pybind11;

namespace {

using namespace ibl;
using namespace ibl::cli;

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

// ---- Keyword arguments as the command's options ----------------------------------------------

std::string textOf(const py::handle& value) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::hasattr(value, "__fspath__"))
    return py::module_::import("os").attr("fspath")(value).cast<std::string>();
  return py::str(value).cast<std::string>();  // numbers: Python's shortest exact repr
}

// A NumPy scalar as Python's own bool, int or float (np.int64(48) is the option value 48); an
// array is no option value: a TypeError naming the keyword.
py::object plainValue(const std::string& key, const py::handle& value) {
  const py::module_ np = py::module_::import("numpy");
  if (py::isinstance(value, np.attr("ndarray")))
    throw py::type_error(key + ": an array is not an option value (pass a file path)");
  if (py::isinstance(value, np.attr("bool_"))) return py::bool_(value.cast<bool>());
  const py::object object = py::reinterpret_borrow<py::object>(value);
  if (py::isinstance(value, np.attr("integer"))) return py::int_(object);
  if (py::isinstance(value, np.attr("floating"))) return py::float_(object);
  return object;
}

bool isNumber(const py::handle& value) {
  return !py::isinstance<py::bool_>(value) &&
         (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value));
}

// `name=value` as the command line's `--name value`: True is a bare flag, False and None leave
// the option out, a sequence of numbers is joined ("1,2,3"; a size "WxH"), one of strings gives
// the option once per item.
void addOption(std::vector<std::string>& args, const std::string& key, const py::handle& given) {
  std::string option = "--" + key;
  for (char& c : option)
    if (c == '_') c = '-';
  const py::object value = plainValue(key, given);
  if (value.is_none()) return;
  if (py::isinstance<py::bool_>(value)) {
    if (value.cast<bool>()) args.push_back(option);
    return;
  }
  if ((py::isinstance<py::tuple>(value) || py::isinstance<py::list>(value))) {
    std::vector<py::object> items;
    for (const py::handle item : value) items.push_back(plainValue(key, item));
    bool numbers = !items.empty();
    for (const py::object& item : items) numbers = numbers && isNumber(item);
    if (numbers) {
      std::string joined;
      for (const py::object& item : items)
        joined += (joined.empty() ? "" : (key == "size" ? "x" : ",")) + textOf(item);
      args.push_back(option);
      args.push_back(joined);
    } else {
      for (const py::object& item : items) {
        args.push_back(option);
        args.push_back(textOf(item));
      }
    }
    return;
  }
  args.push_back(option);
  args.push_back(textOf(value));
}

// The command's option names in a message as Python spells them: `--input-layout` is
// `input_layout=` (a long option after a space, a parenthesis, a quote or at the start).
std::string pythonSpelling(const std::string& message) {
  static const std::regex option(R"((^|[\s(\[{,;'"`])--([A-Za-z][A-Za-z0-9]*(?:-[A-Za-z0-9]+)*))");
  std::string out;
  auto last = message.cbegin();
  for (std::sregex_iterator it(message.begin(), message.end(), option), end; it != end; ++it) {
    const std::smatch& m = *it;
    out.append(last, m[2].first - 2);
    std::string name = m[2].str();
    std::replace(name.begin(), name.end(), '-', '_');
    out += name + "=";
    last = m[2].second;
  }
  out.append(last, message.cend());
  return out;
}

// A keyword that is none of the command's long options: a UsageError naming it, with the
// nearest keyword when it looks like a misspelling (the command's rule, nearestName).
void checkKeywords(CLI::App* cmd, const std::vector<std::string>& keywords,
                   const std::string& function) {
  std::vector<std::string> known;
  for (const CLI::Option* option : cmd->get_options())
    for (std::string name : option->get_lnames()) {
      std::replace(name.begin(), name.end(), '-', '_');
      known.push_back(name);
    }
  for (const std::string& keyword : keywords) {
    if (std::find(known.begin(), known.end(), keyword) != known.end()) continue;
    const std::string near = nearestName(keyword, known);
    throw UsageError(fmt::format("{}=: not a keyword of ibl.{}(){}", keyword, function,
                                 near.empty() ? "" : fmt::format("; did you mean {}=?", near)));
  }
}

// Parses `args` (after the subcommand's name) with the subcommand that `add` registers, as the
// command does: a mistake is a UsageError with the command's message; a keyword (of `keywords`,
// those the caller passed as options) that is no option of the command, one naming it.
template <typename AddOptions>
CLI::App* parseOptions(CLI::App& app, const std::string& command, std::vector<std::string> args,
                       AddOptions add, const std::vector<std::string>& keywords) {
  CLI::App* cmd = add(app);
  checkKeywords(cmd, keywords, command);
  app.require_subcommand(1);
  args.insert(args.begin(), command);
  const std::vector<std::string> given = args;
  std::reverse(args.begin(), args.end());  // CLI11 takes them last first
  try {
    app.parse(args);
  } catch (const CLI::ParseError& e) {
    throw UsageError(usageErrorMessage(app, e, given));  // the command's words
  }
  return cmd;
}

std::vector<std::string> optionArgs(const py::kwargs& options) {
  std::vector<std::string> args;
  for (const auto& [key, value] : options) addOption(args, key.cast<std::string>(), value);
  return args;
}

std::vector<std::string> keywordsOf(const py::kwargs& options) {
  std::vector<std::string> keywords;
  for (const auto& item : options) keywords.push_back(item.first.cast<std::string>());
  return keywords;
}

// The options of a subcommand as a docstring's list: name=default: description.
std::string optionsDoc(CLI::App* cmd, const std::vector<std::string>& skip) {
  std::string doc;
  for (const CLI::Option* option : cmd->get_options()) {
    std::string name =
        option->get_lnames().empty() ? option->get_name(true) : option->get_lnames()[0];
    if (name.empty() || name == "help") continue;
    if (std::find(skip.begin(), skip.end(), name) != skip.end()) continue;
    for (char& c : name)
      if (c == '-') c = '_';
    doc += "    " + name;
    const std::string def = option->get_default_str();
    if (!def.empty()) doc += "=" + def;
    doc += ": " + option->get_description() + "\n";
  }
  return doc;
}

// ---- Progress and the GIL --------------------------------------------------------------------

// A Python callable progress(stage, fraction) that one progress bar can follow
// (docs/python.md): called with the GIL, one call at a time, one stage after another in the
// order the work started them. A stage that runs beside the one being reported (the DFG table
// beside the convolutions) is held back and reported when that one ends. Each stage's first call
// has the fraction 0 and its last 1 (finish() ends the stages still open when the work is done),
// and the fractions in between never decrease. The first exception the callable raises is kept
// (it is not called again) and raised after the work.
class PythonProgress {
 public:
  explicit PythonProgress(py::object callback) : callback_(std::move(callback)) {}
  ~PythonProgress() {
    py::gil_scoped_acquire gil;
    error_.reset();
  }
  PythonProgress(const PythonProgress&) = delete;
  PythonProgress& operator=(const PythonProgress&) = delete;

  // From the library's threads, without the GIL.
  void report(const std::string& stage, double fraction) {
    const std::lock_guard<std::mutex> lock(mutex_);
    auto it = std::find_if(stages_.begin(), stages_.end(),
                           [&](const Stage& s) { return s.name == stage; });
    if (it == stages_.end()) it = stages_.insert(stages_.end(), Stage{stage});
    // Workers report as they finish parts: a smaller fraction may come after a larger one.
    it->done = std::max(it->done, std::clamp(fraction, 0.0, 1.0));
    show();
  }
  // After the work, without the GIL: the stages it left open end at 1.
  void finish() {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (Stage& s : stages_) s.done = 1.0;
    show();
  }
  ProgressFn fn() {
    if (callback_.is_none()) return {};
    return [this](const std::string& stage, double fraction) { report(stage, fraction); };
  }
  // With the GIL held, after the work: the callback's exception, if it raised one.
  void raiseIfFailed() {
    if (!error_) return;
    py::error_already_set e = std::move(*error_);
    error_.reset();
    throw std::move(e);
  }

 private:
  struct Stage {
    std::string name;
    double done = 0.0;    // the largest fraction reported
    double shown = -1.0;  // the last fraction passed to the callback; -1: none yet
  };

  // Under mutex_: the calls the stages' reports allow, from the first stage not yet ended.
  void show() {
    for (; current_ < stages_.size(); ++current_) {
      Stage& s = stages_[current_];
      if (s.shown < 0.0) call(s, 0.0);
      if (s.done > s.shown) call(s, s.done);
      if (s.shown < 1.0) return;
    }
  }
  void call(Stage& stage, double fraction) {
    stage.shown = fraction;
    if (error_ || callback_.is_none()) return;
    py::gil_scoped_acquire gil;
    try {
      callback_(stage.name, fraction);
    } catch (py::error_already_set& e) {
      error_ = std::make_unique<py::error_already_set>(std::move(e));
    }
  }

  py::object callback_;
  std::mutex mutex_;
  std::unique_ptr<py::error_already_set> error_;
  std::vector<Stage> stages_;  // in the order they first reported
  std::size_t current_ = 0;    // the stage being shown
};

// Runs `work` without the GIL; the callback's exception comes first (the work may have failed
// because of it).
template <typename Work>
auto withoutGil(PythonProgress& progress, Work work) {
  try {
    const py::gil_scoped_release release;
    auto result = work();
    progress.finish();
    return result;
  } catch (...) {
    progress.raiseIfFailed();
    throw;
  }
}

// ---- Arrays ----------------------------------------------------------------------------------

py::array_t<float> arrayOf(const Image& image, const std::vector<float>* alpha = nullptr) {
  const py::ssize_t channels = alpha ? 4 : 3;
  py::array_t<float> a(
      {static_cast<py::ssize_t>(image.height), static_cast<py::ssize_t>(image.width), channels});
  float* out = a.mutable_data();
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    const glm::vec3& p = image.pixels[i];
    out[0] = p.x;
    out[1] = p.y;
    out[2] = p.z;
    if (alpha) out[3] = (*alpha)[i];
    out += channels;
  }
  return a;
}

// Six faces of one size, in the order +X, -X, +Y, -Y, +Z, -Z: (6, size, size, 3).
template <typename Faces>
py::array_t<float> arrayOfFaces(const Faces& faces) {
  const py::ssize_t n = faces[0].width;
  py::array_t<float> a({static_cast<py::ssize_t>(faces.size()), n, n, py::ssize_t{3}});
  float* out = a.mutable_data();
  for (const Image& face : faces)
    for (const glm::vec3& p : face.pixels) {
      out[0] = p.x;
      out[1] = p.y;
      out[2] = p.z;
      out += 3;
    }
  return a;
}

py::list levelsOf(const CubeMap& cube) {
  py::list levels;
  for (const auto& level : cube.levels) levels.append(arrayOfFaces(level));
  return levels;
}

// A (height, width, 3 or 4) array as an image (a fourth channel, alpha, is left out).
Image imageOf(const py::handle& value, const char* what) {
  const FloatArray a = FloatArray::ensure(value);
  if (!a || a.ndim() != 3 || (a.shape(2) != 3 && a.shape(2) != 4) || a.shape(0) < 1 ||
      a.shape(1) < 1)
    throw py::value_error(std::string(what) +
                          ": expected a float array of shape (height, width, 3 or 4)");
  const py::ssize_t channels = a.shape(2);
  Image image(static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)));
  const float* in = a.data();
  for (glm::vec3& p : image.pixels) {
    p = glm::vec3(in[0], in[1], in[2]);
    in += channels;
  }
  return image;
}

bool isPath(const py::handle& value) {
  return py::isinstance<py::str>(value) || py::hasattr(value, "__fspath__");
}

py::object parseJson(const std::string& text) {
  return py::module_::import("json").attr("loads")(text);
}

std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path.string(), "cannot be read");
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// ---- The functions ---------------------------------------------------------------------------

py::object readImage(const py::object& path, int level, const std::string& layer) {
  const std::string file = textOf(path);
  DecodedFile d = [&] {
    const py::gil_scoped_release release;
    return readImageFile(file, {layer});
  }();
  if (level < 0 || level >= static_cast<int>(d.levels.size()))
    throw py::index_error(
        fmt::format("{}: has {} level(s), not level {}", file, d.levels.size(), level));
  const auto& faces = d.levels[static_cast<std::size_t>(level)];
  if (faces.size() == 1) return arrayOf(faces[0]);
  return arrayOfFaces(faces);
}

void writeImage(const py::object& path, const py::object& array, const std::string& exrType,
                const std::string& format, float exposure) {
  Image image = imageOf(array, "array");
  ExportOptions e;
  e.output = textOf(path);
  if (exrType != "half" && exrType != "float")
    failUsage("--exr-type", fmt::format("'{}' is not half or float", exrType));
  e.exrType = exrType == "float" ? ExrPixelType::Float : ExrPixelType::Half;
  const std::optional<PixelFormat> pixelFormat = parsePixelFormat(format);
  if (!pixelFormat) failUsage("--format", fmt::format("'{}' is not a KTX2 pixel format", format));
  e.ktx2Format = *pixelFormat;
  e.pngExposure = exposure;
  checkExportOptions(e);
  const py::gil_scoped_release release;
  sanitizePixels(image);  // as `ibl convert` writes it: NaN, infinite and negative values are 0
  writeFilesTogether(encodeFlatImage(image, e));
}

GlobalOptions globalOf(bool quiet) {
  GlobalOptions g;
  g.quiet = quiet;
  return g;
}

py::dict bake(const py::object& environment, const py::object& output, bool force,
              const py::object& progressCallback, bool quiet, const py::kwargs& options) {
  std::vector<std::string> args = optionArgs(options);
  addOption(args, "output", output);
  addOption(args, "force", py::bool_(force));
  const bool inMemory = !environment.is_none() && !isPath(environment);
  std::optional<Image> pixels;
  std::string input;
  if (inMemory) {
    pixels = imageOf(environment, "environment");
    input = "(array)";
  } else if (!environment.is_none()) {
    input = textOf(environment);
    args.insert(args.begin(), input);  // the positional input
  }
  CLI::App app;
  BakeCliOptions o;
  CLI::App* cmd = parseOptions(
      app, "bake", args, [&](CLI::App& a) { return addBakeOptions(a, o); }, keywordsOf(options));
  noteGivenOptions(cmd, o);
  if (!o.list.empty() || !o.shard.empty() || o.listDevices)
    failUsage(!o.list.empty()    ? "--list"
              : !o.shard.empty() ? "--shard"
                                 : "--list-devices",
              "is the command's (batches, devices); call ibl.bake() once per environment");
  const GlobalOptions global = globalOf(quiet);
  PythonProgress progress(progressCallback);
  struct Baked {
    BakeRun run;
    std::string manifest;
  };
  const Baked baked = withoutGil(progress, [&] {
    checkSingleBake(o, inMemory ? std::string() : input, o.output, global);
    const std::unique_ptr<gpu::Context> device = gpu::openComputeDevice(deviceChoice(o.device));
    SourceEnvironment source = loadBakeInput(o, input, device.get(), global, std::move(pixels));
    Baked b{bakeSource(o, std::move(source), input, progress.fn(), device.get(), global), {}};
    if (o.output.empty()) {
      b.manifest = bakeManifestJson(b.run.result, b.run.options, b.run.output, b.run.facts, "bake");
    } else {
      writeBakeOutputs(b.run.result, b.run.options, b.run.output, b.run.facts, o.output);
      b.manifest = readText(std::filesystem::path(o.output) / "manifest.json");
    }
    return b;
  });
  progress.raiseIfFailed();
  const BakeResult& r = baked.run.result;
  py::dict out;
  out["specular"] = levelsOf(r.specular);
  out["irradiance"] = arrayOfFaces(r.irradiance.levels.at(0));
  out["source"] = levelsOf(r.source);
  py::array_t<float> sh({py::ssize_t{9}, py::ssize_t{3}});
  for (std::size_t k = 0; k < 9; ++k)
    for (int c = 0; c < 3; ++c) sh.mutable_at(k, c) = r.sh[k][c];
  out["sh"] = sh;
  out["dfg"] = arrayOf(r.dfg);
  if (r.specularF0Zero) out["specular_f0_0"] = levelsOf(*r.specularF0Zero);
  if (r.specularF0One) out["specular_f0_1"] = levelsOf(*r.specularF0One);
  if (r.sheen) out["sheen"] = levelsOf(*r.sheen);
  if (r.sheenDfg) out["sheen_dfg"] = arrayOf(*r.sheenDfg);
  out["manifest"] = parseJson(baked.manifest);
  return out;
}

// A command whose --output Python may leave out: the result is returned instead.
CLI::App* outputOptional(CLI::App* command) {
  command->get_option("--output")->required(false);
  return command;
}

py::array_t<float> render(const py::object& scene, const py::object& output,
                          const py::object& progressCallback, bool quiet, py::kwargs options) {
  // env= as an array: the environment's pixels, laid out by their shape as bake()'s are.
  std::shared_ptr<const Image> envPixels;
  if (options.contains("env") && !options["env"].is_none() && !isPath(options["env"])) {
    envPixels = std::make_shared<const Image>(imageOf(options["env"], "env"));
    PyDict_DelItemString(options.ptr(), "env");
  }
  std::vector<std::string> args = optionArgs(options);
  addOption(args, "output", output);
  args.insert(args.begin(), textOf(scene));
  CLI::App app;
  RenderCliOptions o;
  parseOptions(
      app, "render", args, [&](CLI::App& a) { return outputOptional(addRenderOptions(a, o)); },
      keywordsOf(options));
  if (envPixels) {
    o.scene.env = "(array)";  // the name in messages; --env with --bake is refused as the file's
    o.scene.envPixels = std::move(envPixels);
  }
  const GlobalOptions global = globalOf(quiet);
  PythonProgress progress(progressCallback);
  const ProgressFn report = progress.fn();
  const RenderedImage image = withoutGil(progress, [&] {
    RenderedImage rendered = renderImage(o, global, [&](float f) {
      if (report) report("rendering", f);
    });
    if (!o.output.empty()) writeRenderOutput(o, rendered);
    return rendered;
  });
  progress.raiseIfFailed();
  return arrayOf(image.result.color, &image.result.alpha);
}

py::object compare(const py::object& a, const py::object& b, const py::object& mask,
                   const py::kwargs& options) {
  const bool files = isPath(a) && isPath(b) && (mask.is_none() || isPath(mask));
  std::vector<std::string> args = optionArgs(options);
  args.insert(args.begin(), {files ? textOf(a) : "a", files ? textOf(b) : "b"});
  if (files) addOption(args, "mask", mask);
  CLI::App app;
  CompareOptions o;
  parseOptions(
      app, "compare", args, [&](CLI::App& cli) { return addCompareOptions(cli, o); },
      keywordsOf(options));
  if (o.maxRelError >= 0.0)
    failUsage("--max-rel-error", "is the command's exit status; compare the returned numbers");
  if (files) {
    const ImageComparison c = [&] {
      const py::gil_scoped_release release;
      return compareFiles(o);
    }();
    return parseJson(comparisonJson(c).dump());
  }
  // Arrays, converted with the GIL held; a path among them is read (as `ibl compare` reads a
  // flat image) without it.
  const auto arrayOrNothing = [](const py::object& value, const char* name) {
    return value.is_none() || isPath(value) ? Image() : imageOf(value, name);
  };
  const auto pathOrName = [](const py::object& value, const char* name) {
    return isPath(value) ? textOf(value) : std::string(name);
  };
  Image ia = arrayOrNothing(a, "a"), ib = arrayOrNothing(b, "b"), im = arrayOrNothing(mask, "mask");
  const std::string nameA = pathOrName(a, "a"), nameB = pathOrName(b, "b"),
                    nameMask = pathOrName(mask, "mask");
  const bool readA = isPath(a), readB = isPath(b), readMask = !mask.is_none() && isPath(mask);
  const ImageComparison c = [&] {
    const py::gil_scoped_release release;
    if (readA) ia = readFlatImage(nameA);
    if (readB) ib = readFlatImage(nameB);
    if (readMask) im = readFlatImage(nameMask);
    std::vector<float> maskValues;
    for (const glm::vec3& p : im.pixels) maskValues.push_back(p.x);
    return compareLoaded(o, ia, ib, maskValues, nameA, nameB, nameMask);
  }();
  return parseJson(comparisonJson(c).dump());
}

py::array_t<float> sky(const py::object& output, bool quiet, const py::kwargs& options) {
  std::vector<std::string> args = optionArgs(options);
  addOption(args, "output", output);
  CLI::App app;
  SkyCliOptions o;
  parseOptions(
      app, "sky", args, [&](CLI::App& a) { return outputOptional(addSkyOptions(a, o)); },
      keywordsOf(options));
  const GlobalOptions global = globalOf(quiet);
  const Image panorama = [&] {
    const py::gil_scoped_release release;
    const SkyRequest request = checkSkyRequest(o, global);
    Image image = computeSky(o, request);
    if (!o.output.empty()) writeSkyOutputs(o, request, image, global);
    return image;
  }();
  return arrayOf(panorama);
}

// The options of a subcommand, for the docstrings.
template <typename Options, typename AddOptions>
std::string docOf(AddOptions add, const std::vector<std::string>& skip) {
  CLI::App app;
  Options o;
  return optionsDoc(add(app, o), skip);
}

}  // namespace

PYBIND11_MODULE(ibl, m) {
  m.doc() =
      "Image-based lighting: bake HDR environments, render, compare, compute skies "
      "(docs/python.md). Arrays are float32, linear Rec.709 radiance (cd/m^2 where the input "
      "is in physical units), row 0 at the top; keyword arguments are the `ibl` command's long "
      "options (size=32 is --size 32) with the same defaults and checks.";
  m.attr("__version__") = kVersion;

  // ibl::Error and ibl::UsageError with their messages (the command prints them after
  // "ibl: error: "), the options named as Python's keywords; translators are tried last
  // registered first.
  auto& error = py::register_exception<Error>(m, "Error", PyExc_RuntimeError);
  auto& usageError = py::register_exception<UsageError>(m, "UsageError", error.ptr());
  error.doc() =
      "A failure of ibl: the command's message, without 'ibl: error: ', its options named as "
      "keywords (input_layout=, not --input-layout).";
  usageError.doc() =
      "A request found wrong before any work (a bad option value, contradicting options, an "
      "unknown keyword): the command exits with status 2 for it.";
  static PyObject* errorType = error.ptr();
  static PyObject* usageErrorType = usageError.ptr();
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const UsageError& e) {
      PyErr_SetString(usageErrorType, pythonSpelling(e.what()).c_str());
    } catch (const Error& e) {
      PyErr_SetString(errorType, pythonSpelling(e.what()).c_str());
    }
  });

  m.def("read_image", &readImage, py::arg("path"), py::kw_only(), py::arg("level") = 0,
        py::arg("layer") = "",
        "read_image(path, *, level=0, layer='') -> numpy.ndarray\n\n"
        "Reads any image `ibl` reads (.exr, .hdr, .png, .jpg, .ktx2, .ktx, .dds, .env) as "
        "float32: a flat image as (height, width, 3), a cube map as (6, size, size, 3) with the "
        "faces +X, -X, +Y, -Y, +Z, -Z. Linear radiance for HDR formats; PNG and JPEG values "
        "are decoded from sRGB to linear [0, 1]. level: the mip level (0 the largest); layer: "
        "the EXR layer (e.g. 'ViewLayer.Combined'). Alpha is not read.");
  m.def("write_image", &writeImage, py::arg("path"), py::arg("array"), py::kw_only(),
        py::arg("exr_type") = "half", py::arg("format") = "rgba16f", py::arg("exposure") = 0.0f,
        "write_image(path, array, *, exr_type='half', format='rgba16f', exposure=0.0)\n\n"
        "Writes a (height, width, 3 or 4) float array (linear radiance; a fourth channel is "
        "ignored) as `ibl convert` writes a flat image, the format from the extension: .exr "
        "(exr_type 'half' or 'float'), .hdr, .png (8-bit sRGB of the values scaled by "
        "2^exposure, exposure in stops), .ktx2 (format rgba16f, rgba32f, b10g11r11 or "
        "e5b9g9r9). NaN, infinite and negative values are written as 0. Written atomically.");

  const std::string bakeDoc =
      "bake(environment=None, *, output=None, force=False, progress=None, quiet=False, "
      "**options) -> dict\n\n"
      "Bakes an environment as `ibl bake` does. environment: a file path, a sky description "
      "('sky:elevation=30'), None for the bundled sunset.exr, or a float (height, width, 3 or "
      "4) array of linear radiance laid out by its shape (2:1 equirect, crosses, strips; or "
      "input_layout=...). output: also write the files `ibl bake -o output` writes; force: "
      "write into a non-empty directory. progress(stage: str, fraction: float) is called "
      "from worker threads, one stage after another, each from 0 to 1; quiet: no notes or "
      "warnings on stderr.\n\n"
      "Returns a dict of float32 arrays of radiance in the environment's units (cube maps "
      "(6, size, size, 3), faces +X, -X, +Y, -Y, +Z, -Z): 'specular' (list, one per mip "
      "level, roughness by the manifest's mapping), 'source' (list of the resampled source's "
      "levels), 'irradiance' (E / pi), 'sh' ((9, 3) radiance SH9 coefficients), 'dfg' ((n, "
      "n, 3): A, B, diffuse; u = n.v, v = roughness), with fresnel_weighted "
      "'specular_f0_0'/'specular_f0_1', with sheen 'sheen' (list) and 'sheen_dfg', and "
      "'manifest' (manifest.json as a dict). Arrays hold the bake's float values (the files "
      "hold them in `format`).\n\nOptions (the command's; sizes in texels, angles in "
      "degrees):\n" +
      docOf<BakeCliOptions>(addBakeOptions,
                            {"inputs", "output", "force", "list", "shard", "list-devices"});
  m.def("bake", &bake, py::arg("environment") = py::none(), py::kw_only(),
        py::arg("output") = py::none(), py::arg("force") = false, py::arg("progress") = py::none(),
        py::arg("quiet") = false, bakeDoc.c_str());

  const std::string renderDoc =
      "render(scene='grid', *, output=None, progress=None, quiet=False, **options) -> "
      "numpy.ndarray\n\n"
      "Renders as `ibl render` does: scene is a glTF file (.gltf, .glb), 'sphere' or 'grid'. "
      "Returns a float32 (height, width, 4) array: linear radiance in nits (cd/m^2, before "
      "exposure and tone mapping; bloom applied with bloom=...) and the coverage in [0, 1], "
      "the numbers `ibl render -o x.exr` writes. size=(width, height) in pixels; "
      "mode='split-sum' or 'reference'; spp, seed, bounces; env (a file or a sky: description, "
      "as `ibl render --env` takes, or a float (height, width, 3 or 4) array of linear radiance "
      "laid out by its shape, as bake() takes one) or bake (a bake's directory). output: also "
      "write the image (.exr or .png) as the command does. progress('rendering', fraction) "
      "from worker threads, from 0 to 1.\n\nOptions "
      "(the command's):\n" +
      docOf<RenderCliOptions>(addRenderOptions, {"scene", "output"});
  m.def("render", &render, py::arg("scene") = "grid", py::kw_only(), py::arg("output") = py::none(),
        py::arg("progress") = py::none(), py::arg("quiet") = false, renderDoc.c_str());

  const std::string compareDoc =
      "compare(a, b, *, mask=None, **options) -> dict\n\n"
      "Measures the error of image a against the reference b as `ibl compare --json` does; "
      "each of a, b and mask is a path or a float (height, width, 3 or 4) array (a mask "
      "counts where its first channel is > 0.5). Returns {'pixels': n, 'overall': {...}, "
      "'r': {...}, 'g': {...}, 'b': {...}}, each with 'rmse', 'relative_mse', "
      "'mean_relative_error', 'max_error' (in the images' units) and 'psnr_db' (decibels), and "
      "'frame': the luminance's 'frame_error', 'median_block_error' (4 x 4 blocks), "
      "'off_by_2x', 'blocks' and 'black_blocks'."
      "\n\nOptions (the command's; max_rel_error is its exit status, not taken here):\n" +
      docOf<CompareOptions>(addCompareOptions,
                            {"image", "reference", "mask", "json", "max-rel-error"});
  m.def("compare", &compare, py::arg("a"), py::arg("b"), py::kw_only(),
        py::arg("mask") = py::none(), compareDoc.c_str());

  const std::string skyDoc =
      "sky(*, output=None, quiet=False, **options) -> numpy.ndarray\n\n"
      "A physical clear sky as `ibl sky` computes it: a float32 (height, width, 3) "
      "equirect panorama of linear Rec.709 radiance in cd/m^2 (the panorama `ibl sky -o "
      "x.exr` writes; docs/sky.md); size=(width, height) in pixels, angles in degrees, "
      "altitude in meters. output: also write the files the command writes.\n\nOptions "
      "(the command's):\n" +
      docOf<SkyCliOptions>(addSkyOptions, {"output"});
  m.def("sky", &sky, py::kw_only(), py::arg("output") = py::none(), py::arg("quiet") = false,
        skyDoc.c_str());
}
