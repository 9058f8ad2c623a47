// Manual pages and bash/zsh completions from the command's CLI11 definitions (manual.hpp).
#include "manual.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <fmt/core.h>

#include "ibl/core/error.hpp"
#include "ibl/core/version.hpp"

namespace ibl::cli {

namespace {

// What the pages and the scripts say about one option or positional argument.
struct OptionInfo {
  std::vector<std::string> names;  // "-o", "--output"; a positional's name
  bool positional = false;
  bool flag = false;                // takes no value
  std::string type;                 // TEXT, INT, FLOAT, UINT
  std::vector<std::string> values;  // the allowed values (IsMember), if any
  std::string check;                // any other check, as --help words it ("1 to 4096")
  std::string defaultValue;
  std::string description;
  std::vector<std::string> excludes;
  bool required = false;
  bool several = false;    // takes several values
  bool commaList = false;  // ... separated by commas
  bool help = false;       // -h,--help (and --version)
};

std::vector<std::string> splitKeepingEmpty(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, separator)) parts.push_back(part);
  return parts;
}

OptionInfo describe(const CLI::Option& o) {
  OptionInfo info;
  info.positional = !o.nonpositional();
  if (info.positional) {
    info.names.push_back(o.get_name(true));
  } else {
    for (const std::string& s : o.get_snames()) info.names.push_back("-" + s);
    for (const std::string& l : o.get_lnames()) info.names.push_back("--" + l);
  }
  info.flag = !info.positional && (o.get_type_size_max() == 0 || o.get_expected_max() == 0);
  info.description = o.get_description();
  info.required = o.get_required();
  info.several = o.get_expected_max() >= CLI::detail::expected_max_vector_size;
  info.commaList = o.get_delimiter() != '\0';
  for (const CLI::Option* e : o.get_excludes()) info.excludes.push_back(e->get_name());
  if (info.flag) return info;
  // The type name --help prints: the type, then each check's description after a colon; a set
  // of allowed values reads "{a,b,c}" (a mapping "{a->1,b->2}").
  const std::string typeName = o.get_type_name();
  const std::size_t colon = typeName.find(':');
  info.type = typeName.substr(0, colon);
  if (colon != std::string::npos) {
    std::string rest = typeName.substr(colon + 1);
    const std::size_t open = rest.find('{');
    const std::size_t close = rest.find('}', open == std::string::npos ? 0 : open);
    if (open != std::string::npos && close != std::string::npos) {
      for (std::string v : splitKeepingEmpty(rest.substr(open + 1, close - open - 1), ',')) {
        v = v.substr(0, v.find("->"));
        if (!v.empty()) info.values.push_back(v);
      }
      rest.erase(open, close - open + 1);
    }
    while (!rest.empty() && (rest.front() == ':' || rest.front() == ' ')) rest.erase(0, 1);
    while (!rest.empty() && (rest.back() == ':' || rest.back() == ' ')) rest.pop_back();
    info.check = rest;
  }
  info.defaultValue = o.get_default_str();
  if (info.several && info.defaultValue.size() >= 2 && info.defaultValue.front() == '[' &&
      info.defaultValue.back() == ']')
    info.defaultValue = info.defaultValue.substr(1, info.defaultValue.size() - 2);
  return info;
}

bool visible(const CLI::App* app) {
  return !app->get_group().empty();
}

std::vector<const CLI::App*> commandsOf(const CLI::App& top) {
  return top.get_subcommands([](const CLI::App* s) { return visible(s); });
}

// The visible options of `app` (help first, as --help lists them), then its positionals.
std::vector<OptionInfo> optionsOf(const CLI::App& app) {
  std::vector<OptionInfo> options;
  for (const CLI::Option* o : app.get_options()) {
    if (o->get_group().empty()) continue;  // hidden
    OptionInfo info = describe(*o);
    info.help = o == app.get_help_ptr() || o == app.get_help_all_ptr() ||
                (!info.names.empty() && info.names.back() == "--version");
    options.push_back(std::move(info));
  }
  return options;
}

std::vector<OptionInfo> positionals(const std::vector<OptionInfo>& options) {
  std::vector<OptionInfo> out;
  for (const OptionInfo& o : options)
    if (o.positional) out.push_back(o);
  return out;
}

// The options of the top command that also follow a command (all but --help and --version).
std::vector<OptionInfo> globalOptions(const CLI::App& top) {
  std::vector<OptionInfo> out;
  for (const OptionInfo& o : optionsOf(top))
    if (!o.positional && !o.help) out.push_back(o);
  return out;
}

std::string join(const std::vector<std::string>& parts, const std::string& separator) {
  std::string out;
  for (std::size_t i = 0; i < parts.size(); ++i) out += (i ? separator : "") + parts[i];
  return out;
}

// --- roff ---

// Every hyphen a minus (option names, negative numbers), backslashes printable.
std::string roffName(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '-')
      out += "\\-";
    else if (c == '\\')
      out += "\\e";
    else
      out += c;
  }
  return out;
}

// Running text: backslashes printable; the hyphens of words that start with one (--option,
// -Z, -90) as minus signs, so that an option copied from the page is the one to type; a line
// that would start with a control character ('.' or ') made plain text.
std::string roffText(const std::string& text) {
  std::string out;
  bool wordStart = true, optionWord = false;
  for (char c : text) {
    if (c == ' ' || c == '\t' || c == '\n') {
      wordStart = true;
      optionWord = false;
      out += c;
      continue;
    }
    if (wordStart && c == '-') optionWord = true;
    if (wordStart && (c == '(' || c == '`' || c == '\'' || c == '"' || c == '[' || c == '{')) {
      out += c;
      continue;  // still at the start of the word
    }
    wordStart = false;
    if (c == '\\')
      out += "\\e";
    else if (c == '-' && optionWord)
      out += "\\-";
    else
      out += c;
  }
  std::string guarded;
  for (const std::string& line : splitKeepingEmpty(out, '\n')) {
    if (!line.empty() && (line.front() == '.' || line.front() == '\'')) guarded += "\\&";
    guarded += line + "\n";
  }
  if (!guarded.empty() && (out.empty() || out.back() != '\n')) guarded.pop_back();
  return guarded;
}

std::string upper(std::string text) {
  for (char& c : text)
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  return text;
}

std::string lowerIfShouting(std::string text) {
  if (text != upper(text)) return text;
  for (char& c : text)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return text;
}

// ".TP" paragraph of one option: its names and value, then what it does and takes.
void roffOption(std::string& out, const OptionInfo& o) {
  out += ".TP\n";
  std::vector<std::string> names;
  for (const std::string& n : o.names)
    names.push_back(o.positional ? "\\fI" + roffName(n) + "\\fR" : "\\fB" + roffName(n) + "\\fR");
  out += join(names, ", ");
  if (!o.positional && !o.flag) out += " \\fI" + roffName(o.type) + "\\fR";
  if (o.several) out += o.commaList ? "[,...]" : " ...";
  out += "\n" + roffText(o.description) + "\n";
  std::vector<std::string> notes;
  if (!o.values.empty()) {
    std::vector<std::string> values;
    for (const std::string& v : o.values) values.push_back("\\fB" + roffName(v) + "\\fR");
    notes.push_back("Values: " + join(values, ", ") + ".");
  }
  if (!o.check.empty()) notes.push_back("Valid: " + roffText(lowerIfShouting(o.check)) + ".");
  if (o.several)
    notes.push_back(o.commaList ? "One or several values, separated by commas."
                                : "One or several values.");
  if (!o.defaultValue.empty())
    notes.push_back("Default: \\fB" + roffName(o.defaultValue) + "\\fR.");
  if (o.required) notes.push_back("Required.");
  if (!o.excludes.empty()) {
    std::vector<std::string> ex;
    for (const std::string& e : o.excludes) ex.push_back("\\fB" + roffName(e) + "\\fR");
    notes.push_back("Not with " + join(ex, ", ") + ".");
  }
  for (const std::string& n : notes) out += ".br\n" + n + "\n";
}

std::string roffHeader(const std::string& page) {
  return fmt::format(
      ".\\\" Generated by `ibl manual` from the options of `ibl --help` (apps/manual.cpp).\n"
      ".TH {} 1 \"\" \"ibl {}\" \"ibl manual\"\n"
      ".nh\n.ad l\n",
      roffName(upper(page)), kVersion);
}

std::string topDescription(const CLI::App& top) {
  std::string d = top.get_description();
  if (d.rfind("ibl: ", 0) == 0) d = d.substr(5);
  return d;
}

std::string topPage(const CLI::App& top) {
  std::string out = roffHeader("ibl");
  out += ".SH NAME\nibl \\- " + roffText(topDescription(top)) + "\n";
  out += ".SH SYNOPSIS\n.B ibl\n[\\fIOPTIONS\\fR] \\fICOMMAND\\fR [\\fIARGUMENTS\\fR]\n";
  out += ".SH DESCRIPTION\n\\fBibl\\fR: " + roffText(topDescription(top)) + ".\n";
  out +=
      ".PP\nEach command has its own page, \\fBibl\\-\\fR\\fICOMMAND\\fR(1), and prints its "
      "options with \\fBibl\\fR \\fICOMMAND\\fR \\fB\\-\\-help\\fR.\n";
  out += ".SH COMMANDS\n";
  for (const CLI::App* c : commandsOf(top)) {
    out += ".TP\n\\fB" + roffName(c->get_name()) + "\\fR\n" + roffText(c->get_description()) +
           "\n.br\nSee \\fBibl\\-" + roffName(c->get_name()) + "\\fR(1).\n";
  }
  out += ".SH OPTIONS\nBefore or after the command.\n";
  for (const OptionInfo& o : optionsOf(top))
    if (!o.positional) roffOption(out, o);
  out +=
      ".SH EXIT STATUS\n"
      ".TP\n0\nSuccess.\n"
      ".TP\n1\nThe work failed (a file missing, unreadable or not what it says).\n"
      ".TP\n2\nA usage error: a wrong command line, found before any work.\n"
      ".TP\n128 + \\fIN\\fR\nInterrupted by signal \\fIN\\fR; no output was left "
      "half\\-written.\n"
      ".PP\nA command may have its own (\\fBibl compare \\-\\-max\\-rel\\-error\\fR: 3).\n";
  out += ".SH SEE ALSO\n";
  const std::vector<const CLI::App*> commands = commandsOf(top);
  for (std::size_t i = 0; i < commands.size(); ++i)
    out += ".BR ibl\\-" + roffName(commands[i]->get_name()) + " (1)" +
           (i + 1 < commands.size() ? "," : "") + "\n";
  return out;
}

std::string commandPage(const CLI::App& top, const CLI::App& command) {
  const std::string name = command.get_name();
  const std::vector<OptionInfo> options = optionsOf(command);
  std::string out = roffHeader("ibl-" + name);
  out += ".SH NAME\nibl\\-" + roffName(name) + " \\- " + roffText(command.get_description()) + "\n";
  out += ".SH SYNOPSIS\n.B ibl " + roffName(name) + "\n[\\fIOPTIONS\\fR]";
  for (const OptionInfo& p : positionals(options)) {
    std::string arg = "\\fI" + roffName(p.names.front()) + "\\fR" + (p.several ? "..." : "");
    out += " " + (p.required ? arg : "[" + arg + "]");
  }
  out += "\n.SH DESCRIPTION\n" + roffText(command.get_description()) + ".\n";
  std::vector<std::string> globals;
  for (const OptionInfo& g : globalOptions(top))
    globals.push_back("\\fB" + roffName(g.names.back()) + "\\fR");
  if (!globals.empty())
    out += ".PP\nThe global options of \\fBibl\\fR(1) (" + join(globals, ", ") +
           ") may come before or after the command.\n";
  if (!positionals(options).empty()) {
    out += ".SH ARGUMENTS\n";
    for (const OptionInfo& p : positionals(options)) roffOption(out, p);
  }
  out += ".SH OPTIONS\n";
  for (const OptionInfo& o : options)
    if (!o.positional) roffOption(out, o);
  std::string footer = command.get_footer();
  while (!footer.empty() && footer.front() == '\n') footer.erase(0, 1);
  if (!footer.empty()) {
    // The footer's first line is its title ("Window controls:"), the rest a preformatted table.
    const std::size_t end = footer.find('\n');
    std::string title = footer.substr(0, end);
    if (!title.empty() && title.back() == ':') title.pop_back();
    out += ".SH " + roffText(upper(title)) + "\n";
    if (end != std::string::npos) out += ".nf\n" + roffText(footer.substr(end + 1)) + "\n.fi\n";
  }
  out += ".SH SEE ALSO\n.BR ibl (1)\n";
  return out;
}

// --- completions ---

std::vector<std::string> allNames(const std::vector<OptionInfo>& options) {
  std::vector<std::string> names;
  for (const OptionInfo& o : options)
    if (!o.positional) names.insert(names.end(), o.names.begin(), o.names.end());
  return names;
}

// What completes an option's value: its allowed values, a file name, or nothing (a number).
enum class ValueKind { None, One, List, File, Other };

ValueKind valueKind(const OptionInfo& o) {
  if (o.flag) return ValueKind::None;
  if (!o.values.empty()) return o.several && o.commaList ? ValueKind::List : ValueKind::One;
  if (o.type == "TEXT") return ValueKind::File;
  return ValueKind::Other;
}

// A bash `case` pattern for `command option` (single-quoted words).
std::string bashPattern(const std::string& command, const OptionInfo& o) {
  std::vector<std::string> patterns;
  for (const std::string& n : o.names)
    patterns.push_back(command.empty() ? "*' " + n + "'" : "'" + command + " " + n + "'");
  return join(patterns, " | ");
}

void bashValueCase(std::string& out, const std::string& command, const OptionInfo& o) {
  switch (valueKind(o)) {
    case ValueKind::None:
      return;
    case ValueKind::One:
    case ValueKind::List:
      out += fmt::format("    {}) _ibl_kind={} _ibl_words='{}' ;;\n", bashPattern(command, o),
                         valueKind(o) == ValueKind::One ? "one" : "list", join(o.values, " "));
      return;
    case ValueKind::File:
      out += fmt::format("    {}) _ibl_kind=file ;;\n", bashPattern(command, o));
      return;
    case ValueKind::Other:
      out += fmt::format("    {}) _ibl_kind=other ;;\n", bashPattern(command, o));
      return;
  }
}

// zsh: a description in an _arguments spec's brackets, or an item of _describe, inside single
// quotes; cut to its first clause to fit a listing.
std::string zshDescription(const std::string& text, bool brackets) {
  // Up to the first "; ", ". " or ": " outside parentheses.
  std::string d = text;
  int depth = 0;
  for (std::size_t i = 0; i + 1 < d.size(); ++i) {
    depth += d[i] == '(' ? 1 : d[i] == ')' ? -1 : 0;
    if (depth == 0 && i >= 12 && (d[i] == ';' || d[i] == '.' || d[i] == ':') && d[i + 1] == ' ') {
      d = d.substr(0, i);
      break;
    }
  }
  if (d.size() > 80) {
    const std::size_t space = d.rfind(' ', 77);
    d = d.substr(0, space == std::string::npos ? 77 : space) + "...";
  }
  std::string out;
  for (char c : d) {
    if (c == '\'')
      out += "'\\''";
    else if (c == '\\')
      out += "\\\\";
    else if (brackets && (c == '[' || c == ']'))
      out += std::string("\\") + c;
    else
      out += c;
  }
  return out;
}

// The action that completes a value in an _arguments spec.
std::string zshAction(const OptionInfo& o) {
  switch (valueKind(o)) {
    case ValueKind::One:
      return "(" + join(o.values, " ") + ")";
    case ValueKind::List:
      return "_values -s , " + o.names.back().substr(o.names.back().find_first_not_of('-')) + " " +
             join(o.values, " ");
    case ValueKind::File:
      return "_files";
    default:
      return " ";
  }
}

std::string zshSpec(const OptionInfo& o) {
  if (o.positional) {
    const std::string message = o.names.front() + ":" + zshAction(o);
    if (o.several) return "'*:" + message + "'";
    return o.required ? "':" + message + "'" : "'::" + message + "'";
  }
  std::string exclusions;
  if (o.help) {
    exclusions = "(- *)";
  } else if (o.names.size() > 1 || !o.excludes.empty()) {
    std::vector<std::string> ex = o.names;
    ex.insert(ex.end(), o.excludes.begin(), o.excludes.end());
    exclusions = "(" + join(ex, " ") + ")";
  }
  // -o+ and --output= take the value in the same word or the next one.
  std::vector<std::string> names;
  for (const std::string& n : o.names)
    names.push_back(n + (o.flag ? "" : n.rfind("--", 0) == 0 ? "=" : "+"));
  // '(-o --output)'{-o+,--output=}'[...]...': the brace expansion gives one spec per name.
  std::string spec = "'" + std::string(o.several && !o.help ? "*" : "") + exclusions;
  spec += names.size() > 1 ? "'{" + join(names, ",") + "}'" : names.front();
  spec += "[" + zshDescription(o.description, true) + "]";
  if (!o.flag)
    spec += ":" + (o.values.empty() ? o.type : std::string("value")) + ":" + zshAction(o);
  return spec + "'";
}

std::string zshFunctionName(const std::string& command) {
  std::string name = "_ibl_" + command;
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

void writeFile(const std::filesystem::path& path, const std::string& text) {
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw Error(path.string() + ": cannot write");
}

}  // namespace

std::string manPage(const CLI::App& top, const CLI::App* command) {
  return command ? commandPage(top, *command) : topPage(top);
}

std::vector<std::pair<std::string, std::string>> manPages(const CLI::App& top) {
  std::vector<std::pair<std::string, std::string>> pages{{"ibl.1", topPage(top)}};
  for (const CLI::App* c : commandsOf(top))
    pages.emplace_back("ibl-" + c->get_name() + ".1", commandPage(top, *c));
  return pages;
}

std::string bashCompletion(const CLI::App& top) {
  const std::vector<OptionInfo> globals = globalOptions(top);
  std::vector<std::string> commandNames;
  for (const CLI::App* c : commandsOf(top)) commandNames.push_back(c->get_name());
  std::string out =
      "# bash completion for ibl; generated by `ibl completion bash` from the options of `ibl "
      "--help`.\n"
      "# Install as ~/.local/share/bash-completion/completions/ibl, or source it.\n\n";
  // What an option's value is: _ibl_kind one (a value of _ibl_words), list (comma-separated
  // values), file, other (nothing to complete), or empty (a flag, or no option).
  out += "_ibl_value() {\n  _ibl_kind='' _ibl_words=''\n  case \"$1 $2\" in\n";
  for (const CLI::App* c : commandsOf(top))
    for (const OptionInfo& o : optionsOf(*c))
      if (!o.positional) bashValueCase(out, c->get_name(), o);
  for (const OptionInfo& o : globals) bashValueCase(out, "", o);
  out += "  esac\n}\n\n";
  out += "_ibl_positional() {\n  _ibl_kind=other _ibl_words=''\n  case \"$1\" in\n";
  for (const CLI::App* c : commandsOf(top)) {
    const std::vector<OptionInfo> p = positionals(optionsOf(*c));
    if (p.empty()) continue;
    OptionInfo first = p.front();
    first.flag = false;
    const ValueKind kind = valueKind(first);
    out += fmt::format("    '{}') _ibl_kind={} _ibl_words='{}' ;;\n", c->get_name(),
                       kind == ValueKind::One    ? "one"
                       : kind == ValueKind::File ? "file"
                                                 : "other",
                       join(first.values, " "));
  }
  out += "  esac\n}\n\n";
  out += "_ibl_options() {\n  case \"$1\" in\n";
  for (const CLI::App* c : commandsOf(top)) {
    std::vector<std::string> names = allNames(optionsOf(*c));
    for (const std::string& g : allNames(globals))
      if (std::find(names.begin(), names.end(), g) == names.end()) names.push_back(g);
    out += fmt::format("    '{}') _ibl_words='{}' ;;\n", c->get_name(), join(names, " "));
  }
  out +=
      fmt::format("    *) _ibl_words='{}' ;;\n  esac\n}}\n\n", join(allNames(optionsOf(top)), " "));
  // The global options that take a value, skipped when looking for the command.
  std::vector<std::string> valued;
  for (const OptionInfo& o : globals)
    if (!o.flag) valued.insert(valued.end(), o.names.begin(), o.names.end());
  const std::string valuedPattern = valued.empty() ? "--" : join(valued, " | ");
  out += R"BASH(_ibl() {
  local cur="${COMP_WORDS[COMP_CWORD]}" prev="" option="" prefix="" cmd="" head="" i w
  local _ibl_kind="" _ibl_words=""
  ((COMP_CWORD > 0)) && prev="${COMP_WORDS[COMP_CWORD - 1]}"
  # The command: the first word after ibl that is neither an option nor a global option's value.
  for ((i = 1; i < COMP_CWORD; i++)); do
    w="${COMP_WORDS[i]}"
    case "$w" in
      )BASH" +
         valuedPattern +
         R"BASH()
        if [[ "${COMP_WORDS[i + 1]}" == "=" ]]; then ((i += 2)); else ((i += 1)); fi ;;
      -* | =) ;;
      *)
        cmd="$w"
        break
        ;;
    esac
  done
  # The option whose value is being completed: "--opt VALUE", "--opt=VALUE" (bash splits the
  # words at '=' unless COMP_WORDBREAKS lacks it).
  if [[ "$cur" == "=" && "$prev" == -* ]]; then
    option="$prev" cur=""
  elif [[ "$prev" == "=" ]] && ((COMP_CWORD > 1)) && [[ "${COMP_WORDS[COMP_CWORD - 2]}" == -* ]]; then
    option="${COMP_WORDS[COMP_CWORD - 2]}"
  elif [[ "$cur" == -*=* ]]; then
    option="${cur%%=*}" prefix="${cur%%=*}=" cur="${cur#*=}"
  elif [[ "$prev" == -* ]]; then
    # Only an option that takes a value: after a flag comes anything else.
    _ibl_value "$cmd" "$prev"
    [[ -n "$_ibl_kind" ]] && option="$prev"
  fi
  if [[ -n "$option" ]]; then
    _ibl_value "$cmd" "$option"
  elif [[ "$cur" == -* ]]; then
    _ibl_options "$cmd"
    _ibl_kind=one
  elif [[ -z "$cmd" ]]; then
    _ibl_kind=one _ibl_words=')BASH" +
         join(commandNames, " ") + R"BASH('
  else
    _ibl_positional "$cmd"
  fi
  case "$_ibl_kind" in
    one) mapfile -t COMPREPLY < <(compgen -P "$prefix" -W "$_ibl_words" -- "$cur") ;;
    list)
      [[ "$cur" == *,* ]] && head="${cur%,*},"
      mapfile -t COMPREPLY < <(compgen -P "$prefix$head" -W "$_ibl_words" -- "${cur##*,}")
      ;;
    file)
      compopt -o filenames 2>/dev/null
      mapfile -t COMPREPLY < <(compgen -f -- "$cur")
      ;;
    other) COMPREPLY=() ;;
    *)
      compopt -o filenames 2>/dev/null
      mapfile -t COMPREPLY < <(compgen -f -- "$cur")
      ;;
  esac
}

complete -F _ibl ibl
)BASH";
  return out;
}

std::string zshCompletion(const CLI::App& top) {
  std::string out =
      "#compdef ibl\n"
      "# zsh completion for ibl; generated by `ibl completion zsh` from the options of `ibl "
      "--help`.\n"
      "# Install as _ibl in a folder of $fpath, or source it after compinit.\n\n";
  const std::vector<OptionInfo> globals = globalOptions(top);
  for (const CLI::App* c : commandsOf(top)) {
    out += zshFunctionName(c->get_name()) + "() {\n  _arguments -s -S";
    std::vector<std::string> names;
    for (const OptionInfo& o : optionsOf(*c)) {
      if (!o.positional) {
        out += " \\\n    " + zshSpec(o);
        names.insert(names.end(), o.names.begin(), o.names.end());
      }
    }
    for (const OptionInfo& g : globals)
      if (std::none_of(g.names.begin(), g.names.end(), [&](const std::string& n) {
            return std::find(names.begin(), names.end(), n) != names.end();
          }))
        out += " \\\n    " + zshSpec(g);
    for (const OptionInfo& p : positionals(optionsOf(*c))) out += " \\\n    " + zshSpec(p);
    out += "\n}\n\n";
  }
  out +=
      "_ibl() {\n  local curcontext=\"$curcontext\" state line ret=1\n"
      "  typeset -A opt_args\n  _arguments -C";
  for (const OptionInfo& o : optionsOf(top))
    if (!o.positional) out += " \\\n    " + zshSpec(o);
  out += " \\\n    ':command:->command' \\\n    '*::argument:->argument' && ret=0\n";
  out += "  case $state in\n    command)\n      local -a commands=(\n";
  for (const CLI::App* c : commandsOf(top))
    out += "        '" + c->get_name() + ":" + zshDescription(c->get_description(), false) + "'\n";
  out +=
      "      )\n      _describe -t commands 'ibl command' commands && ret=0\n      ;;\n"
      "    argument)\n      curcontext=\"${curcontext%:*:*}:ibl-$words[1]:\"\n"
      "      case $words[1] in\n";
  for (const CLI::App* c : commandsOf(top))
    out += "        " + c->get_name() + ") " + zshFunctionName(c->get_name()) + " && ret=0 ;;\n";
  out +=
      "      esac\n      ;;\n  esac\n  return ret\n}\n\n"
      "# Autoloaded from $fpath, complete; sourced, register.\n"
      "if [[ $zsh_eval_context[-1] == loadautofunc ]]; then\n  _ibl \"$@\"\nelse\n"
      "  compdef _ibl ibl\nfi\n";
  return out;
}

void addManualCommands(CLI::App& app) {
  CLI::App* completion = app.add_subcommand(
      "completion",
      "Print a shell completion script (bash or zsh) for ibl's commands, options and values");
  auto shell = std::make_shared<std::string>();
  completion->add_option("shell", *shell, "bash or zsh")
      ->required()
      ->check(CLI::IsMember({"bash", "zsh"}));
  completion->callback([&app, shell] {
    fmt::print("{}", *shell == "zsh" ? zshCompletion(app) : bashCompletion(app));
  });

  // Hidden: what the build writes (cmake/manual_pages.cmake).
  struct Outputs {
    std::string manDir, bash, zsh;
  };
  auto outputs = std::make_shared<Outputs>();
  CLI::App* manual = app.add_subcommand("manual", "Write the manual pages and completion scripts");
  manual->group("");
  manual->add_option("--man-dir", outputs->manDir, "Folder for ibl.1 and ibl-COMMAND.1");
  manual->add_option("--bash", outputs->bash, "The bash completion script");
  manual->add_option("--zsh", outputs->zsh, "The zsh completion script");
  manual->callback([&app, outputs] {
    if (!outputs->manDir.empty())
      for (const auto& [name, text] : manPages(app))
        writeFile(std::filesystem::path(outputs->manDir) / name, text);
    if (!outputs->bash.empty()) writeFile(outputs->bash, bashCompletion(app));
    if (!outputs->zsh.empty()) writeFile(outputs->zsh, zshCompletion(app));
  });
}

}  // namespace ibl::cli
