// The documentation is tested as a user would use it (docs/testing.md, "The documentation"):
// every fenced ```sh block of README.md and docs/*.md runs with bash, each in a fresh scratch
// folder that has `ibl` on its PATH and links `data` and `examples` to the repository's data/
// and examples/ and `build` to the build folder, as the docs tell users to run them (from the
// repository root, `ibl` on the PATH). A ```console block is a transcript: its `$ ` lines run the
// same way, its other lines are output and are not compared. A block that must not run here says
// why just above it: `<!-- not run: REASON -->`. Every relative link of those pages must name an
// existing file, and each #anchor a heading.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/run_command.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path kSource = IBL_SOURCE_DIR;

// The most blocks that may be left out, all pages together: the README's set-up and test
// commands (CI runs them) and what needs a person at a window.
constexpr int kMaxExcluded = 6;

struct Block {
  fs::path page;
  int line = 0;           // of the opening fence, 1-based
  std::string info;       // the fence's info string
  std::string text;       // the contents, the fence's indentation removed
  std::string notRun;     // the reason of a `<!-- not run: REASON -->` just before it, or ""
  bool excluded = false;  // such a comment was there
};

std::vector<fs::path> pages() {
  std::vector<fs::path> out{kSource / "README.md"};
  std::vector<fs::path> docs;
  for (const auto& e : fs::directory_iterator(kSource / "docs"))
    if (e.path().extension() == ".md") docs.push_back(e.path());
  std::sort(docs.begin(), docs.end());
  out.insert(out.end(), docs.begin(), docs.end());
  return out;
}

std::vector<std::string> readLines(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

bool startsWith(const std::string& s, const std::string& p) {
  return s.rfind(p, 0) == 0;
}

// Fenced blocks (``` only; the pages use no ~~~ fences), and the lines outside them.
struct Parsed {
  std::vector<Block> blocks;
  std::vector<std::pair<int, std::string>> prose;  // (line, text) outside fences
};

Parsed parse(const fs::path& page) {
  Parsed p;
  const auto lines = readLines(page);
  for (size_t i = 0; i < lines.size(); ++i) {
    const std::string t = trim(lines[i]);
    if (!startsWith(t, "```")) {
      p.prose.emplace_back(int(i) + 1, lines[i]);
      continue;
    }
    Block b;
    b.page = page;
    b.line = int(i) + 1;
    b.info = trim(t.substr(3));
    const size_t indent = lines[i].find_first_not_of(" ");
    // The nearest non-blank line before the fence may carry the exclusion and its reason.
    for (size_t k = i; k-- > 0;) {
      const std::string prev = trim(lines[k]);
      if (prev.empty()) continue;
      const std::string open = "<!-- not run:";
      if (startsWith(prev, open) && prev.size() >= open.size() + 3 &&
          prev.substr(prev.size() - 3) == "-->") {
        b.excluded = true;
        b.notRun = trim(prev.substr(open.size(), prev.size() - open.size() - 3));
      }
      break;
    }
    size_t j = i + 1;
    for (; j < lines.size() && trim(lines[j]) != "```"; ++j)
      b.text += (lines[j].size() >= indent ? lines[j].substr(indent) : trim(lines[j])) + "\n";
    EXPECT_LT(j, lines.size()) << page.filename() << ":" << b.line << ": the fence is not closed";
    p.blocks.push_back(b);
    i = j;
  }
  return p;
}

// The commands a block runs: a sh block whole, the `$ ` lines of a console transcript.
std::string commandsOf(const Block& b) {
  if (b.info == "sh") return b.text;
  std::istringstream in(b.text);
  std::string out;
  for (std::string l; std::getline(in, l);)
    if (startsWith(l, "$ ")) out += l.substr(2) + "\n";
  return out;
}

bool runs(const Block& b) {
  return !b.excluded && (b.info == "sh" || b.info == "console");
}

std::string where(const Block& b) {
  return b.page.lexically_relative(kSource).string() + ":" + std::to_string(b.line);
}

// GitHub's anchor for a heading: lower case; letters, marks, digits, '-', '_' and spaces kept
// (spaces as '-'), everything else dropped. Beyond ASCII, the punctuation and symbol blocks are
// dropped (dashes, quotes, '·', '×', arrows, math operators, box drawing) and the rest kept
// (letters such as 'α' and 'é', numbers such as '²').
bool unicodeSymbol(unsigned cp) {
  if (cp >= 0xA0 && cp <= 0xBF)  // Latin-1 punctuation and signs, but for its letters and numbers
    return cp != 0xAA && cp != 0xB2 && cp != 0xB3 && cp != 0xB5 && cp != 0xB9 && cp != 0xBA &&
           cp < 0xBC;
  return cp == 0xD7 || cp == 0xF7 || (cp >= 0x2000 && cp <= 0x206F) ||
         (cp >= 0x20A0 && cp <= 0x20CF) || (cp >= 0x2190 && cp <= 0x23FF) ||
         (cp >= 0x2500 && cp <= 0x27BF) || (cp >= 0x2900 && cp <= 0x2BFF) ||
         (cp >= 0x3000 && cp <= 0x303F);
}

std::string slug(const std::string& heading) {
  std::string s;
  for (size_t i = 0; i < heading.size();) {
    const unsigned char c = heading[i];
    if (c < 0x80) {
      if (std::isalnum(c))
        s += char(std::tolower(c));
      else if (c == ' ')
        s += '-';
      else if (c == '-' || c == '_')
        s += char(c);
      ++i;
      continue;
    }
    const int n = c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : 2;
    unsigned cp = c & (n == 2 ? 0x1F : n == 3 ? 0x0F : 0x07);
    for (int k = 1; k < n && i + k < heading.size(); ++k) cp = (cp << 6) | (heading[i + k] & 0x3F);
    if (!unicodeSymbol(cp)) s += heading.substr(i, n);
    i += n;
  }
  return s;
}

std::set<std::string> anchorsOf(const fs::path& page) {
  std::set<std::string> anchors;
  std::map<std::string, int> seen;
  for (const auto& [line, text] : parse(page).prose) {
    if (!startsWith(text, "#")) continue;
    const auto space = text.find(' ');
    if (space == std::string::npos || text.find_first_not_of('#') != space) continue;
    const std::string base = slug(trim(text.substr(space + 1)));
    const int k = seen[base]++;
    anchors.insert(k == 0 ? base : base + "-" + std::to_string(k));
  }
  return anchors;
}

// Prose with its inline code spans removed (a `](x)` inside code is not a link).
std::string withoutCode(const std::string& line) {
  std::string out;
  bool code = false;
  for (char c : line) {
    if (c == '`')
      code = !code;
    else if (!code)
      out += c;
  }
  return out;
}

class DocsPage : public testing::TestWithParam<fs::path> {};

// Each runnable block of the page, in order, each in its own fresh scratch folder.
TEST_P(DocsPage, ShBlocksRunAsWritten) {
  const fs::path page = GetParam();
  int ran = 0;
  for (const Block& b : parse(page).blocks) {
    if (!runs(b)) continue;
    const std::string commands = commandsOf(b);
    if (trim(commands).empty()) continue;
    static int counter = 0;
    const fs::path dir = fs::temp_directory_path() / ("ibl_docs_" + std::to_string(::getpid()) +
                                                      "_" + std::to_string(counter++));
    fs::remove_all(dir);
    fs::create_directories(dir / ".bin");
    fs::create_directory_symlink(kSource / "data", dir / "data");
    // What the pages on installing and embedding use from the repository root: the build
    // folder (cmake --install, cpack, the Python module) and the example program.
    fs::create_directory_symlink(fs::path(IBL_CLI).parent_path(), dir / "build");
    fs::create_directory_symlink(kSource / "examples", dir / "examples");
    fs::create_symlink(IBL_CLI, dir / ".bin" / "ibl");
#ifdef IBL_PYTHON
    // `python3` is the interpreter the module was built for (python/CMakeLists.txt).
    fs::create_symlink(IBL_PYTHON, dir / ".bin" / "python3");
#endif
    std::ofstream(dir / ".block.sh") << "set -e -o pipefail\n" << commands;
    const auto start = std::chrono::steady_clock::now();
    const ibl::test::CliRun r =
        ibl::test::runCommand("cd '" + dir.string() + "' && PATH='" + (dir / ".bin").string() +
                              "':\"$PATH\" timeout 300 bash .block.sh");
    EXPECT_EQ(r.status, 0) << where(b) << ": this block failed:\n"
                           << commands << "--- its output:\n"
                           << r.output;
    const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
    std::cout << where(b) << ": " << took.count() << " s\n";  // for whoever sizes the examples
    fs::remove_all(dir);
    ++ran;
  }
  std::cout << page.filename().string() << ": " << ran << " blocks ran\n";
  // Counted apart from the parser: every ```sh or ```console fence, less the exclusions.
  int fences = 0, notRun = 0;
  for (const std::string& l : readLines(page)) {
    fences += trim(l) == "```sh" || trim(l) == "```console";
    notRun += startsWith(trim(l), "<!-- not run:");
  }
  EXPECT_EQ(ran, fences - notRun) << page.filename() << ": a block was not run";
}

INSTANTIATE_TEST_SUITE_P(Pages, DocsPage, testing::ValuesIn(pages()),
                         [](const testing::TestParamInfo<fs::path>& p) {
                           std::string name = p.param.stem().string();
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

// Blocks are left out only visibly and with a reason, and few; commands are never hidden in
// blocks that do not run; the examples of every page, run in order in one folder, never write
// the same output twice (a bake into an existing, non-empty folder fails) unless they say
// --force (or --shard, whose parts share their grid's folder).
TEST(DocsExamples, ExclusionsAreFewWithReasonsAndOutputsDoNotCollide) {
  const std::set<std::string> known{"sh", "console", "json", "text", "synopsis", ""};
  int excluded = 0, run = 0;
  std::map<std::string, std::string> written;  // -o target -> where, over every page
  for (const fs::path& page : pages()) {
    for (const Block& b : parse(page).blocks) {
      EXPECT_TRUE(known.count(b.info)) << where(b) << ": info string '" << b.info
                                       << "' (use sh, console, json, text, synopsis or none)";
      if (b.excluded) {
        ++excluded;
        EXPECT_GE(b.notRun.size(), 10u) << where(b) << ": give the reason it does not run";
        EXPECT_TRUE(b.info == "sh" || b.info == "console") << where(b);
        std::cout << where(b) << ": not run: " << b.notRun << "\n";
        continue;
      }
      if (b.info == "synopsis") continue;
      if (b.info != "sh" && b.info != "console") {
        std::istringstream in(b.text);
        for (std::string l; std::getline(in, l);)
          EXPECT_FALSE(startsWith(l, "ibl ") || startsWith(l, "$ "))
              << where(b) << ": a command in a '" << b.info
              << "' block; put it in a sh or console block: " << l;
        continue;
      }
      ++run;
      std::istringstream in(commandsOf(b));
      for (std::string l; std::getline(in, l);) {
        std::istringstream words(l);
        std::vector<std::string> w;
        for (std::string x; words >> x;) w.push_back(x);
        if (std::find(w.begin(), w.end(), "ibl") == w.end()) continue;
        const bool again =
            std::count(w.begin(), w.end(), "--force") || std::count(w.begin(), w.end(), "--shard");
        for (size_t k = 0; k + 1 < w.size(); ++k) {
          if (w[k] != "-o" && w[k] != "--output") continue;
          const auto [it, fresh] = written.emplace(w[k + 1], where(b));
          EXPECT_TRUE(fresh || again)
              << where(b) << ": -o " << w[k + 1] << " was written by the example at " << it->second
              << " already: run in order, they collide (another name, or --force)";
        }
      }
    }
  }
  std::cout << run << " blocks run, " << excluded << " left out\n";
  EXPECT_LE(excluded, kMaxExcluded);
  EXPECT_GE(run, 20);
}

// Every relative link of README.md and docs/*.md names an existing file, and each #anchor a
// heading of its page; every page of docs/ is linked from the README or another page.
TEST(DocsLinks, EveryRelativeLinkAndAnchorResolves) {
  std::set<fs::path> linked;
  int links = 0;
  for (const fs::path& page : pages()) {
    for (const auto& [line, raw] : parse(page).prose) {
      const std::string text = withoutCode(raw);
      for (size_t at = text.find("]("); at != std::string::npos; at = text.find("](", at + 2)) {
        const size_t end = text.find(')', at + 2);
        if (end == std::string::npos) break;
        const std::string target = text.substr(at + 2, end - at - 2);
        if (startsWith(target, "http://") || startsWith(target, "https://") ||
            startsWith(target, "mailto:"))
          continue;
        ++links;
        const std::string here = page.lexically_relative(kSource).string() + ":" +
                                 std::to_string(line) + ": link " + target;
        const auto hash = target.find('#');
        const std::string file = target.substr(0, hash);
        const fs::path dest = file.empty() ? page : (page.parent_path() / file).lexically_normal();
        if (!fs::exists(dest)) {
          ADD_FAILURE() << here << ": no such file";
          continue;
        }
        if (dest != page) linked.insert(fs::weakly_canonical(dest));
        if (hash != std::string::npos) {
          EXPECT_EQ(dest.extension(), ".md")
              << here << ": an anchor into a file that is not a page";
          EXPECT_TRUE(anchorsOf(dest).count(target.substr(hash + 1)))
              << here << ": no heading with that anchor in " << dest.filename();
        }
      }
    }
  }
  for (const fs::path& page : pages()) {
    if (page.filename() == "README.md") continue;
    EXPECT_TRUE(linked.count(fs::weakly_canonical(page)))
        << page.filename() << " is linked from no page";
  }
  EXPECT_GT(links, 20);
}

// The slug rule against anchors GitHub gives these headings.
TEST(DocsLinks, AnchorsAreGitHubs) {
  EXPECT_EQ(slug("Sheen: the Charlie lobe (`--sheen`)"), "sheen-the-charlie-lobe---sheen");
  EXPECT_EQ(slug("`ibl bake [INPUT] -o OUTDIR [options]`"), "ibl-bake-input--o-outdir-options");
  EXPECT_EQ(slug("Errors and exit codes"), "errors-and-exit-codes");
  EXPECT_EQ(slug("Time of day — in the viewer"), "time-of-day--in-the-viewer");
  EXPECT_EQ(slug("Cube maps: 6 × n²"), "cube-maps-6--n²");
  EXPECT_EQ(slug("Roughness · α ≤ 1 (“perceptual”)"), "roughness--α--1-perceptual");
}

}  // namespace
