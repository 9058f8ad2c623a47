#include "ibl/io/json_file.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "ibl/core/error.hpp"
#include "ibl/io/file_io.hpp"

namespace ibl {

namespace {

// nlohmann's DOM builder that keeps, instead of throwing, what parse_error hears of the first
// error.
template <typename Json>
class PositionedDomParser : public nlohmann::detail::json_sax_dom_parser<Json> {
 public:
  explicit PositionedDomParser(Json& result)
      : nlohmann::detail::json_sax_dom_parser<Json>(result, false) {}
  template <typename Exception>
  bool parse_error(std::size_t charactersRead, const std::string& token, const Exception& e) {
    charactersRead_ = charactersRead;
    token_ = token;
    message_ = e.what();
    id_ = e.id;
    return false;
  }
  std::string describe(std::string_view text) const {
    return describeJsonError(text, charactersRead_, token_, id_, message_);
  }

 private:
  std::size_t charactersRead_ = 0;
  std::string token_;  // the last token read
  std::string message_;
  int id_ = 0;
};

// The parser's message in words: without its "[json.exception.parse_error.101] parse error at
// line 1, column 2: syntax error while parsing value - " preamble, bytes that are not printable
// ASCII escaped (a binary file must not reach the terminal as it is).
std::string problemOf(const std::string& message) {
  std::string text = message;
  if (const auto bracket = text.find("] ");
      text.rfind("[json.exception.", 0) == 0 && bracket != std::string::npos)
    text = text.substr(bracket + 2);
  if (text.rfind("parse error", 0) == 0)
    if (const auto colon = text.find(": "); colon != std::string::npos)
      text = text.substr(colon + 2);
  if (const auto dash = text.find(" - ");
      text.rfind("syntax error", 0) == 0 && dash != std::string::npos)
    text = text.substr(dash + 3);
  std::string printable;
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x20 && byte < 0x7f)
      printable += c;
    else
      printable += fmt::format("\\x{:02x}", byte);
  }
  return printable;
}

}  // namespace

std::string jsonTextPosition(std::string_view text, std::size_t offset) {
  offset = std::min(offset, text.size());
  const std::string_view before = text.substr(0, offset);
  const std::size_t line =
      1 + static_cast<std::size_t>(std::count(before.begin(), before.end(), '\n'));
  const std::size_t lineStart = before.rfind('\n');
  const std::size_t column = lineStart == std::string_view::npos ? offset + 1 : offset - lineStart;
  return fmt::format("line {}, column {}", line, column);
}

std::string describeJsonError(std::string_view text, std::size_t charactersRead,
                              const std::string& lastToken, int exceptionId,
                              const std::string& message) {
  // The parser has read the offending character last.
  const std::size_t offset = charactersRead > 0 ? charactersRead - 1 : 0;
  if (exceptionId == 406) {  // a number beyond a double's range, read whole: where it starts
    const std::size_t end = offset + 1;
    return fmt::format("{}: the number {} is out of range (a double reaches 1.8e308)",
                       jsonTextPosition(text, end - std::min(end, lastToken.size())),
                       problemOf(lastToken));
  }
  return fmt::format("{}: {}", jsonTextPosition(text, offset), problemOf(message));
}

template <typename Json>
Json parseJsonText(std::string_view text, const std::string& name) {
  Json root;
  PositionedDomParser<Json> parser(root);
  if (!Json::sax_parse(text.begin(), text.end(), &parser)) fail(name, parser.describe(text));
  return root;
}

template nlohmann::json parseJsonText<nlohmann::json>(std::string_view, const std::string&);
template nlohmann::ordered_json parseJsonText<nlohmann::ordered_json>(std::string_view,
                                                                      const std::string&);

nlohmann::json readJsonFile(const std::filesystem::path& path) {
  const auto bytes = readFileBytes(path);
  return parseJsonText<nlohmann::json>(
      std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), path.string());
}

}  // namespace ibl
