// The manual pages and shell completions the command writes (apps/manual.cpp, `ibl manual`,
// `ibl completion`) against what `ibl --help` and `ibl COMMAND --help` print, parsed here on their
// own: every command, option and allowed value that --help lists is in the pages and is what the
// completions offer; the pages format without a warning; the scripts parse and complete.
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/helpers.hpp"
#include "support/text_file.hpp"

using namespace ibl;
using namespace ibl::test;

namespace {

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::set<std::string> nonEmptyLines(const std::string& text) {
  std::set<std::string> out;
  for (const std::string& l : lines(text))
    if (!l.empty()) out.insert(l);
  return out;
}

std::vector<std::string> splitCommas(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string part; std::getline(in, part, ',');) out.push_back(part);
  return out;
}

// The commands `ibl --help` lists under "Subcommands:".
std::vector<std::string> commandsInHelp() {
  const CliRun help = runIbl("--help");
  std::vector<std::string> commands;
  bool inSection = false;
  const std::regex entry(R"(^  ([a-z][\w-]*)\s)");
  for (const std::string& line : lines(help.output)) {
    if (line.rfind("Subcommands:", 0) == 0) {
      inSection = true;
      continue;
    }
    std::smatch m;
    if (inSection && std::regex_search(line, m, entry)) commands.push_back(m[1].str());
  }
  return commands;
}

// An option as `--help` prints it: its names ("-o,--output") and the allowed values in its
// type ("TEXT:{cpu,gpu,auto}=cpu").
struct HelpOption {
  std::vector<std::string> names;
  std::vector<std::string> values;
};

std::vector<HelpOption> optionsInHelp(const std::string& command) {
  const CliRun help = runIbl(command + " --help");
  std::vector<HelpOption> options;
  const std::regex line(R"(^\s+(-[\w-]+(?:,-[\w-]+)*)(?:\s+(\S+))?)");
  for (const std::string& text : lines(help.output)) {
    std::smatch m;
    if (!std::regex_search(text, m, line)) continue;
    HelpOption o;
    o.names = splitCommas(m[1].str());
    const std::string type = m[2].matched ? m[2].str() : "";
    const std::size_t open = type.find(":{");
    if (open != std::string::npos)
      o.values = splitCommas(type.substr(open + 2, type.find('}', open) - open - 2));
    options.push_back(o);
  }
  return options;
}

std::set<std::string> namesOf(const std::vector<HelpOption>& options) {
  std::set<std::string> names;
  for (const HelpOption& o : options) names.insert(o.names.begin(), o.names.end());
  return names;
}

// The options of `ibl --help` that may also follow a command.
std::set<std::string> globalOptionNames() {
  std::set<std::string> names = namesOf(optionsInHelp(""));
  for (const char* n : {"-h", "--help", "--version"}) names.erase(n);
  return names;
}

std::string upper(std::string text) {
  for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

// An option name or value as roff writes it: each hyphen a minus, \-.
std::string roffDashes(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '-' ? std::string("\\-") : std::string(1, c);
  return out;
}

// What the command writes, once for the suite.
struct Generated {
  TempDir dir;
  std::filesystem::path man() const { return dir / "man1"; }
  std::filesystem::path bash() const { return dir / "ibl"; }
  std::filesystem::path zsh() const { return dir / "_ibl"; }
};

const Generated& generated() {
  static Generated* g = [] {
    auto* out = new Generated;
    const CliRun r = runIbl("manual --man-dir " + quote(out->man()) + " --bash " +
                            quote(out->bash()) + " --zsh " + quote(out->zsh()));
    EXPECT_EQ(r.status, 0) << r.output;
    return out;
  }();
  return *g;
}

// The words bash completes: runs the generated script's _ibl on COMP_WORDS = `words`, the last
// the one being completed, in `cwd` (for file names).
std::set<std::string> bashComplete(const std::vector<std::string>& words,
                                   const std::filesystem::path& cwd = {}) {
  TempDir scratch;
  std::string script = "source " + quote(generated().bash()) + "\nCOMP_WORDS=(";
  for (const std::string& w : words) script += " '" + w + "'";
  script += " )\nCOMP_CWORD=" + std::to_string(words.size() - 1) +
            "\n_ibl\nprintf '%s\\n' \"${COMPREPLY[@]}\"\n";
  std::ofstream(scratch / "complete.sh") << script;
  const std::string cd = cwd.empty() ? "" : "cd " + quote(cwd) + " && ";
  const CliRun r = runCommand(cd + "bash --norc --noprofile " + quote(scratch / "complete.sh"));
  EXPECT_EQ(r.status, 0) << r.output;
  return nonEmptyLines(r.output);
}

std::set<std::string> asSet(const std::vector<std::string>& v) {
  return {v.begin(), v.end()};
}

}  // namespace

TEST(Manual, PagesListEveryOptionAndValue) {
  const std::string version = runIbl("--version").output;  // "ibl 0.1.0"
  ASSERT_EQ(version.rfind("ibl ", 0), 0u) << version;
  const std::string versionText = version.substr(0, version.find('\n'));
  const std::vector<std::string> commands = commandsInHelp();
  ASSERT_GE(commands.size(), 8u);
  for (const std::string& command : commands) {
    const std::filesystem::path file = generated().man() / ("ibl-" + command + ".1");
    ASSERT_TRUE(std::filesystem::exists(file)) << file;
    const std::string page = readText(file);
    EXPECT_NE(
        page.find(".TH IBL\\-" + roffDashes(upper(command)) + " 1 \"\" \"" + versionText + "\""),
        std::string::npos)
        << command << ": no .TH with " << versionText;
    // The page as a reader sees it: every option as it is typed.
    const CliRun text = runCommand("groff -man -Tutf8 -P-cbou " + quote(file));
    for (const HelpOption& o : optionsInHelp(command)) {
      for (const std::string& n : o.names) {
        EXPECT_NE(page.find("\\fB" + roffDashes(n) + "\\fR"), std::string::npos)
            << "ibl-" << command << ".1 lacks " << n;
        EXPECT_NE(text.output.find(n), std::string::npos)
            << "ibl-" << command << ".1 does not show " << n << " as typed";
      }
      for (const std::string& v : o.values)
        EXPECT_NE(page.find("\\fB" + roffDashes(v) + "\\fR"), std::string::npos)
            << "ibl-" << command << ".1: " << o.names.back() << " lacks the value " << v;
    }
  }
  // The hidden command that writes them has no page.
  EXPECT_FALSE(std::filesystem::exists(generated().man() / "ibl-manual.1"));
}

TEST(Manual, TopPageListsCommandsAndGlobalOptions) {
  const std::string page = readText(generated().man() / "ibl.1");
  for (const std::string& command : commandsInHelp()) {
    EXPECT_NE(page.find(".TP\n\\fB" + roffDashes(command) + "\\fR\n"), std::string::npos)
        << command;
    EXPECT_NE(page.find(".BR ibl\\-" + roffDashes(command) + " (1)"), std::string::npos) << command;
  }
  for (const std::string& n : namesOf(optionsInHelp("")))
    EXPECT_NE(page.find("\\fB" + roffDashes(n) + "\\fR"), std::string::npos) << n;
  // Every page is listed here, and no other.
  std::set<std::string> pages;
  for (const auto& e : std::filesystem::directory_iterator(generated().man()))
    pages.insert(e.path().filename().string());
  std::set<std::string> expected{"ibl.1"};
  for (const std::string& command : commandsInHelp()) expected.insert("ibl-" + command + ".1");
  EXPECT_EQ(pages, expected);
}

TEST(Manual, PagesFormatWithoutWarnings) {
  for (const auto& e : std::filesystem::directory_iterator(generated().man())) {
    const CliRun r = runCommand("groff -man -Tutf8 -ww -z " + quote(e.path()));
    EXPECT_EQ(r.status, 0) << e.path();
    EXPECT_EQ(r.output, "") << e.path();
  }
}

// roff's special characters in the text: a line starting with '.' or ' is a request, a backslash
// an escape. Every control line is one the generator writes on purpose, every backslash one of
// the escapes it uses, and no option name is left with plain hyphens.
TEST(Manual, RoffSpecialsEscaped) {
  const std::regex request(
      R"(^(\.\\" |\.TH |\.SH |\.TP$|\.PP$|\.br$|\.B |\.BR |\.nf$|\.fi$|\.nh$|\.ad l$))");
  const std::regex escape(R"(\\([^-e&f]|f[^BIR]))");
  for (const auto& e : std::filesystem::directory_iterator(generated().man())) {
    const std::vector<std::string> pageLines = lines(readText(e.path()));
    for (std::size_t i = 0; i < pageLines.size(); ++i) {
      const std::string& l = pageLines[i];
      if (l.empty()) continue;
      if (l[0] == '.' || l[0] == '\'') {
        EXPECT_TRUE(std::regex_search(l, request))
            << e.path().filename() << ":" << i + 1 << ": " << l;
      }
      if (l.rfind(".\\\"", 0) == 0) continue;  // comment
      EXPECT_FALSE(std::regex_search(l, escape))
          << e.path().filename() << ":" << i + 1 << ": " << l;
      EXPECT_EQ(l.find(" --"), std::string::npos)
          << e.path().filename() << ":" << i + 1 << ": " << l;
      EXPECT_EQ(l.find("\\fB--"), std::string::npos)
          << e.path().filename() << ":" << i + 1 << ": " << l;
    }
  }
}

TEST(Manual, BashCompletesCommandsAndOptions) {
  const std::vector<std::string> commands = commandsInHelp();
  EXPECT_EQ(bashComplete({"ibl", ""}), asSet(commands));
  EXPECT_EQ(bashComplete({"ibl", "--threads", "4", "b"}), std::set<std::string>{"bake"});
  std::set<std::string> top = namesOf(optionsInHelp(""));
  EXPECT_EQ(bashComplete({"ibl", "-"}), top);
  const std::set<std::string> globals = globalOptionNames();
  for (const std::string& command : commands) {
    std::set<std::string> expected = namesOf(optionsInHelp(command));
    expected.insert(globals.begin(), globals.end());
    EXPECT_EQ(bashComplete({"ibl", command, "-"}), expected) << command;
    std::set<std::string> longs;
    for (const std::string& n : expected)
      if (n.rfind("--", 0) == 0) longs.insert(n);
    EXPECT_EQ(bashComplete({"ibl", "-q", command, "--"}), longs) << command;
  }
  // After a flag, the next word is no flag's value: commands, options and positionals as before.
  EXPECT_EQ(bashComplete({"ibl", "-q", ""}), asSet(commands));
  EXPECT_EQ(bashComplete({"ibl", "-q", "comp"}), (std::set<std::string>{"compare", "completion"}));
  EXPECT_EQ(bashComplete({"ibl", "bake", "--sheen", "--targ"}), std::set<std::string>{"--target"});
  EXPECT_EQ(bashComplete({"ibl", "completion", "-q", ""}), (std::set<std::string>{"bash", "zsh"}));
}

TEST(Manual, BashCompletesValues) {
  int enums = 0;
  for (const std::string& command : commandsInHelp()) {
    for (const HelpOption& o : optionsInHelp(command)) {
      if (o.values.empty()) continue;
      ++enums;
      const std::set<std::string> values = asSet(o.values);
      for (const std::string& n : o.names) {
        EXPECT_EQ(bashComplete({"ibl", command, n, ""}), values) << command << " " << n;
        if (n.rfind("--", 0) == 0) {  // --opt=VALUE: bash splits the words at '='
          EXPECT_EQ(bashComplete({"ibl", command, n, "="}), values) << command << " " << n << "=";
        }
      }
      // A prefix keeps the values that start with it.
      std::set<std::string> withPrefix;
      const std::string prefix = o.values.back().substr(0, 1);
      for (const std::string& v : o.values)
        if (v.rfind(prefix, 0) == 0) withPrefix.insert(v);
      EXPECT_EQ(bashComplete({"ibl", command, o.names.back(), "=", prefix}), withPrefix)
          << command << " " << o.names.back() << "=" << prefix;
    }
  }
  EXPECT_GE(enums, 30);
  // --target takes several, comma-separated.
  EXPECT_EQ(bashComplete({"ibl", "bake", "--target", "ibl,f"}),
            std::set<std::string>{"ibl,filament"});
  // A positional of allowed values, and file names for the others.
  EXPECT_EQ(bashComplete({"ibl", "completion", ""}), (std::set<std::string>{"bash", "zsh"}));
  TempDir dir;
  std::ofstream(dir / "scene.gltf") << "{}";
  std::ofstream(dir / "sunset.exr") << "";
  EXPECT_EQ(bashComplete({"ibl", "render", "sc"}, dir.path()), std::set<std::string>{"scene.gltf"});
  EXPECT_EQ(bashComplete({"ibl", "render", "sphere", "--env", "su"}, dir.path()),
            std::set<std::string>{"sunset.exr"});
  // A number: nothing to offer (no file names).
  EXPECT_TRUE(bashComplete({"ibl", "bake", "--size", ""}, dir.path()).empty());
}

TEST(Manual, ZshScriptParsesAndListsEveryOption) {
  const std::string script = readText(generated().zsh());
  EXPECT_EQ(script.rfind("#compdef ibl\n", 0), 0u);
  const CliRun syntax = runCommand("zsh -n " + quote(generated().zsh()));
  EXPECT_EQ(syntax.status, 0) << syntax.output;
  EXPECT_EQ(syntax.output, "");
  for (const std::string& command : commandsInHelp()) {
    // The command's function, up to the next one.
    const std::size_t begin = script.find("\n_ibl_" + command + "() {\n");
    ASSERT_NE(begin, std::string::npos) << command;
    const std::string body = script.substr(begin, script.find("\n}\n", begin) - begin);
    EXPECT_NE(script.find("'" + command + ":"), std::string::npos) << command << " not described";
    for (const HelpOption& o : optionsInHelp(command)) {
      for (const std::string& n : o.names) {
        const std::regex spec("['{,*)]" + std::regex_replace(n, std::regex("-"), "\\-") +
                              "[=+,}\\[]");
        EXPECT_TRUE(std::regex_search(body, spec)) << command << " " << n;
      }
      if (o.values.empty()) continue;
      std::string words;
      for (const std::string& v : o.values) words += (words.empty() ? "" : " ") + v;
      EXPECT_TRUE(body.find(":(" + words + ")'") != std::string::npos ||
                  body.find(" " + words + "'") != std::string::npos)
          << command << " " << o.names.back() << ": " << words;
    }
  }
}

// zsh itself completes with the script: an interactive zsh in a pseudo-terminal (zsh/zpty) loads
// it through compinit, a Tab is typed after each case's words (bound to complete-word and then a
// marker that completion ended), and a wrapper of compadd prints the candidates the script's
// _arguments and _describe add.
TEST(Manual, ZshCompletes) {
  TempDir dir;
  std::filesystem::copy_file(generated().zsh(), dir / "_ibl");
  const std::vector<std::pair<std::string, std::string>> cases{
      {"commands", "ibl "},
      {"target", "ibl bake --target "},
      {"tonemap", "ibl render sphere --tonemap="},
      {"spp", "ibl view sphere --spp "},
      {"sky", "ibl sky --"},
      {"shell", "ibl completion "},
  };
  // The folder's path in double quotes: TempDir's names have no '"', '$' or '\\'.
  std::string driver =
      "zmodload zsh/zpty\nzpty z zsh -f -i\n"
      "zpty -w z 'PS1=\"\" RPROMPT=\"\" LISTMAX=100000'\n"
      "zpty -w z \"fpath=(" +
      dir.path().string() + " \\$fpath); autoload -Uz compinit; compinit -u -d " +
      (dir / "zcompdump").string() + "\"\n";
  driver +=
      R"(zpty -w z 'compadd() { local -a hits; builtin compadd -A hits "$@"; local h; for h in $hits; do print -r -- "<HIT>$h</HIT>" >/dev/tty; done; builtin compadd "$@"; }'
zpty -w z 'zstyle ":completion:*" list-prompt ""; zstyle ":completion:*" menu no'
zpty -w z 'tab() { zle complete-word; print -r -- "<COMP""LETED>" >/dev/tty; }; zle -N tab; bindkey "^I" tab'
offer() {
  zpty -n -w z "$2"$'\t'
  local out
  zpty -r z out '*<COMPLETED>*'
  zpty -n -w z $'\C-u'
  print -r -- "$out" | grep -ao '<HIT>[^<]*</HIT>' | sed -e 's/<HIT>//' -e 's/<\/HIT>//' | grep -v '^\$h$' | sed "s/^/$1 /"
}
)";
  for (const auto& [name, words] : cases) driver += "offer " + name + " '" + words + "'\n";
  std::ofstream(dir / "driver.zsh") << driver;
  const CliRun r = runCommand("timeout 60 zsh -f " + quote(dir / "driver.zsh"));
  ASSERT_EQ(r.status, 0) << r.output;
  std::map<std::string, std::set<std::string>> hits;
  for (const std::string& line : lines(r.output)) {
    const std::size_t space = line.find(' ');
    if (space != std::string::npos) hits[line.substr(0, space)].insert(line.substr(space + 1));
  }
  EXPECT_EQ(hits["commands"], asSet(commandsInHelp()));
  auto valuesOf = [](const std::string& command, const std::string& option) {
    for (const HelpOption& o : optionsInHelp(command))
      if (o.names.back() == option) return asSet(o.values);
    return std::set<std::string>{};
  };
  EXPECT_EQ(hits["target"], valuesOf("bake", "--target"));
  EXPECT_EQ(hits["tonemap"], valuesOf("render", "--tonemap"));
  EXPECT_EQ(hits["spp"], valuesOf("view", "--spp"));
  EXPECT_EQ(hits["shell"], (std::set<std::string>{"bash", "zsh"}));
  std::set<std::string> skyOptions;
  for (const std::string& n : namesOf(optionsInHelp("sky")))
    if (n.rfind("--", 0) == 0) skyOptions.insert(n);
  for (const std::string& n : globalOptionNames())
    if (n.rfind("--", 0) == 0) skyOptions.insert(n);
  EXPECT_EQ(hits["sky"], skyOptions);
}

TEST(Manual, CompletionCommandPrintsTheScripts) {
  const CliRun bash = runCommand(std::string(IBL_CLI) + " completion bash 2>/dev/null");
  EXPECT_EQ(bash.status, 0);
  EXPECT_EQ(bash.output, readText(generated().bash()));
  const CliRun zsh = runCommand(std::string(IBL_CLI) + " completion zsh 2>/dev/null");
  EXPECT_EQ(zsh.status, 0);
  EXPECT_EQ(zsh.output, readText(generated().zsh()));
  const CliRun bashSyntax = runCommand("bash -n " + quote(generated().bash()));
  EXPECT_EQ(bashSyntax.status, 0) << bashSyntax.output;
}

// The build's copies (cmake/manual_pages.cmake) are those of the command it built.
TEST(Manual, BuildWroteCurrentFiles) {
  const std::filesystem::path build = std::filesystem::path(IBL_CLI).parent_path();
  const std::string cache = readText(build / "CMakeCache.txt");
  if (cache.find("IBL_SANITIZE:BOOL=ON") != std::string::npos ||
      cache.find("IBL_TSAN:BOOL=ON") != std::string::npos)
    GTEST_SKIP() << "not generated under the sanitizers";
  EXPECT_EQ(readText(build / "completions" / "ibl"), readText(generated().bash()));
  EXPECT_EQ(readText(build / "completions" / "_ibl"), readText(generated().zsh()));
  for (const auto& e : std::filesystem::directory_iterator(generated().man()))
    EXPECT_EQ(readText(build / "man" / "man1" / e.path().filename()), readText(e.path()))
        << e.path().filename();
}
