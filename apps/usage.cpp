#include "usage.hpp"

#include <algorithm>
#include <cctype>
// GCC 12 under -fsanitize=address,undefined reports libstdc++'s own std::function inside
// std::regex's compiler as maybe uninitialized (a false positive of its own header, not of this
// file's code): silenced here alone, where the regexes are.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <regex>

#include <fmt/core.h>
#include <fmt/ranges.h>

namespace ibl::cli {

std::size_t editDistance(std::string_view a, std::string_view b) {
  // Wagner and Fischer's dynamic programme, one row at a time: row[j] is the distance between
  // the prefix of `a` read so far and b's first j characters.
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];  // the distance of a[0, i-1) and b[0, j-1)
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string nearestName(std::string_view word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t bestDistance = SIZE_MAX;
  for (const std::string& c : candidates) {
    const std::size_t d = editDistance(word, c);
    if (d < bestDistance) {
      bestDistance = d;
      best = c;
    }
  }
  // Dashes are not letters of the name: "--sz" is two letters, not four.
  const std::size_t letters = word.size() - std::min(word.find_first_not_of('-'), word.size());
  return bestDistance <= 2 && 2 * bestDistance < letters ? best : std::string();
}

namespace {

// The command the arguments named (the one CLI11 was parsing), or the top one.
const CLI::App& commandParsed(const CLI::App& app) {
  const std::vector<CLI::App*> parsed = app.get_subcommands();
  return parsed.empty() ? app : *parsed.back();
}

// The visible commands, in the order `ibl --help` lists them.
std::vector<std::string> commandNames(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* sub :
       app.get_subcommands([](const CLI::App* s) { return !s->get_group().empty(); }))
    names.push_back(sub->get_name());
  return names;
}

// The names an option can be given by on `command`'s line: its own and, as the global options
// may follow a command, the top command's.
std::vector<std::string> optionNames(const CLI::App& command, const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* a : {&command, &app}) {
    for (const CLI::Option* o : a->get_options()) {
      for (const std::string& l : o->get_lnames()) names.push_back("--" + l);
      for (const std::string& s : o->get_snames()) names.push_back("-" + s);
    }
    if (a == &app) break;
  }
  return names;
}

std::string commandLine(const CLI::App& command, const CLI::App& app) {
  return &command == &app ? "ibl --help" : fmt::format("ibl {} --help", command.get_name());
}

// The option of that name on the command or the top one (null when neither has it).
const CLI::Option* findOption(const CLI::App& command, const CLI::App& app,
                              const std::string& name) {
  const CLI::Option* o = command.get_option_no_throw(name);
  return o ? o : app.get_option_no_throw(name);
}

// "a, b or c".
std::string oneOf(const std::vector<std::string>& items) {
  std::string text;
  for (std::size_t i = 0; i < items.size(); ++i)
    text += (i == 0 ? "" : i + 1 == items.size() ? " or " : ", ") + items[i];
  return text;
}

std::vector<std::string> splitNonEmpty(const std::string& text, char separator) {
  std::vector<std::string> items;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t end = std::min(text.find(separator, begin), text.size());
    if (end > begin) items.push_back(text.substr(begin, end - begin));
    begin = end + 1;
  }
  return items;
}

// What an option's value must be, from its type and checks: "a whole number from 1 to 13",
// "a power of two from 1 to 4096", "a positive number".
std::string expectedValue(const CLI::Option* option) {
  if (!option) return "a value";
  const std::string type = option->get_type_name();
  const std::size_t colon = type.find(':');
  const std::string base = type.substr(0, colon);
  const std::string check = colon == std::string::npos ? "" : type.substr(colon + 1);
  const std::string kind = base == "INT" || base == "UINT" ? "a whole number"
                           : base == "FLOAT"               ? "a number"
                                                           : "a value";
  if (check.empty()) return kind;
  if (check.rfind("a ", 0) == 0) return check;
  if (check.size() > 2 && check.front() == '{' && check.back() == '}')  // a choice
    return oneOf(splitNonEmpty(check.substr(1, check.size() - 2), ','));
  if (std::isdigit(static_cast<unsigned char>(check[0])) || check[0] == '-')
    return fmt::format("{} from {}", kind, check);
  if (check == "POSITIVE") return "a positive number";
  if (check == "NON-NEGATIVE") return "a number, 0 or more";
  if (check == "FINITE") return "a finite number";
  return fmt::format("{} ({})", kind, check);
}

// An option's description up to its first sentence's end or ';', for what a missing one is.
std::string shortDescription(const CLI::Option* option) {
  if (!option) return {};
  std::string d = option->get_description();
  d = d.substr(0, std::min({d.find("; "), d.find(". "), d.size()}));
  // Whole parentheses only: cut before one the cut left open.
  std::vector<std::size_t> open;
  for (std::size_t i = 0; i < d.size(); ++i)
    if (d[i] == '(')
      open.push_back(i);
    else if (d[i] == ')' && !open.empty())
      open.pop_back();
  if (!open.empty())
    d = open.front() == 0 ? std::string()
                          : d.substr(0, d.find_last_not_of(' ', open.front() - 1) + 1);
  if (!d.empty()) d[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(d[0])));
  return d;
}

// An unknown option: its name, and the nearest one the command takes.
std::string unknownOption(const std::string& arg, const CLI::App& command, const CLI::App& app) {
  const std::string name = arg.substr(0, arg.find('='));
  const std::string near = nearestName(name, optionNames(command, app));
  if (!near.empty()) return fmt::format("unknown option {}; did you mean {}?", name, near);
  return fmt::format("unknown option {}; `{}` lists the options", name, commandLine(command, app));
}

// Whether `arg` is an option of the top command that takes a value (--threads N).
bool takesValue(const CLI::App& app, const std::string& arg) {
  if (arg.find('=') != std::string::npos) return false;
  const CLI::Option* o = app.get_option_no_throw(arg);
  return o && o->get_type_size_max() > 0 && o->get_expected_min() > 0;
}

// No command was parsed: a word that is none of them, an unknown option, or nothing.
std::string missingCommand(const CLI::App& app, const std::vector<std::string>& args) {
  const std::vector<std::string> commands = commandNames(app);
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (arg.size() > 1 && arg[0] == '-') {
      if (!app.get_option_no_throw(arg.substr(0, arg.find('='))))
        return unknownOption(arg, app, app);
      if (takesValue(app, arg)) ++i;
      continue;
    }
    const std::string near = nearestName(arg, commands);
    if (!near.empty()) return fmt::format("unknown command '{}'; did you mean {}?", arg, near);
    return fmt::format("unknown command '{}'; the commands are {}", arg, fmt::join(commands, ", "));
  }
  return fmt::format("a command is required: {}", fmt::join(commands, ", "));
}

}  // namespace

std::string usageErrorMessage(const CLI::App& app, const CLI::ParseError& e,
                              const std::vector<std::string>& args) {
  const CLI::App& command = commandParsed(app);
  std::string what = e.what();
  std::replace(what.begin(), what.end(), '\n', ' ');
  std::smatch m;
  if (dynamic_cast<const CLI::RequiredError*>(&e)) {
    if (what == "A subcommand is required") return missingCommand(app, args);
    if (std::regex_match(what, m, std::regex("(\\S+) is required"))) {
      const std::string description = shortDescription(findOption(command, app, m[1].str()));
      return description.empty() ? fmt::format("{}: required", m[1].str())
                                 : fmt::format("{}: required ({})", m[1].str(), description);
    }
  }
  if (dynamic_cast<const CLI::ExtrasError*>(&e)) {
    // "The following argument(s) was/were not expected: A B".
    const std::vector<std::string> extras = splitNonEmpty(what.substr(what.find(": ") + 2), ' ');
    for (const std::string& arg : extras)
      if (arg.size() > 1 && arg[0] == '-') return unknownOption(arg, command, app);
    if (&command == &app && !extras.empty()) return missingCommand(app, {extras.front()});
    return fmt::format("unexpected argument '{}'; `{}` lists what the command takes",
                       extras.empty() ? what : extras.front(), commandLine(command, app));
  }
  if (dynamic_cast<const CLI::ConversionError*>(&e)) {
    if (std::regex_match(what, m, std::regex("Could not convert: (\\S+) = (.*)"))) {
      const CLI::Option* option = findOption(command, app, m[1].str());
      if (option && option->get_expected_max() == 0)
        return fmt::format("{}: is a switch: give it without a value, not '{}'", m[1].str(),
                           m[2].str());
      return fmt::format("{}: '{}' is not {}", m[1].str(), m[2].str(), expectedValue(option));
    }
    if (std::regex_match(what, m, std::regex("(\\S+): (too many inputs for a flag|Should be .*)")))
      return fmt::format("{}: is a switch: give it without a value", m[1].str());
  }
  if (dynamic_cast<const CLI::ValidationError*>(&e) &&
      std::regex_match(what, m, std::regex("(\\S+): (.*) not in \\{(.*)\\}")))
    return fmt::format("{}: '{}' is not {}", m[1].str(), m[2].str(),
                       oneOf(splitNonEmpty(m[3].str(), ',')));
  if (dynamic_cast<const CLI::ArgumentMismatch*>(&e)) {
    std::string name;
    if (std::regex_search(what, m, std::regex("^(-\\S+?):")) ||
        std::regex_search(what, m, std::regex("arguments to (\\S+?),")))
      name = m[1].str();
    if (!name.empty()) {
      const std::string expected = expectedValue(findOption(command, app, name));
      return expected == "a value" ? fmt::format("{}: expects a value", name)
                                   : fmt::format("{}: expects a value: {}", name, expected);
    }
  }
  if (std::regex_match(what, m, std::regex("(\\S+) excludes (\\S+)")))
    return fmt::format("{}: contradicts {}; pass one of them", m[1].str(), m[2].str());
  if (std::regex_match(what, m, std::regex("(\\S+) requires (\\S+)")))
    return fmt::format("{}: needs {} too", m[1].str(), m[2].str());
  return what;
}

}  // namespace ibl::cli
