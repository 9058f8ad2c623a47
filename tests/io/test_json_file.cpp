// Reading JSON (ibl/io/json_file.hpp): the text's positions counted here by hand, the one error
// message of every reader ("<name>: line L, column C: <problem>"), and order kept on request.
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "ibl/io/file_io.hpp"
#include "ibl/io/json_file.hpp"
#include "support/helpers.hpp"

using namespace ibl;
using namespace ibl::test;

TEST(JsonFile, PositionsCountLinesAndBytesFromOne) {
  const std::string text = "{\n  \"a\": 1,\n}";
  EXPECT_EQ(jsonTextPosition(text, 0), "line 1, column 1");
  EXPECT_EQ(jsonTextPosition(text, 1), "line 1, column 2");  // the first '\n'
  EXPECT_EQ(jsonTextPosition(text, 4), "line 2, column 3");  // the '"' of "a"
  EXPECT_EQ(jsonTextPosition(text, 12), "line 3, column 1");
  EXPECT_EQ(jsonTextPosition(text, 99), "line 3, column 2");  // past the end
}

TEST(JsonFile, MistakesNameTheFileLineAndColumn) {
  // The '}' after a trailing comma, at line 3, column 1.
  const std::string comma =
      errorOf([] { parseJsonText<nlohmann::json>("{\n  \"a\": 1,\n}", "m.json"); });
  EXPECT_EQ(comma.rfind("m.json: line 3, column 1: ", 0), 0u) << comma;
  // A number out of range is placed at its first digit.
  const std::string range = errorOf([] { parseJsonText<nlohmann::json>("[1, 1e999]", "n.json"); });
  EXPECT_EQ(
      range,
      "n.json: line 1, column 5: the number 1e999 is out of range (a double reaches 1.8e308)");
  // A byte that is not printable ASCII is shown escaped, and nothing may follow the value.
  EXPECT_EQ(errorOf([] { parseJsonText<nlohmann::json>("[\x80]", "b.json"); }),
            "b.json: line 1, column 2: invalid literal; last read: '[\\x80'");
  EXPECT_NE(
      errorOf([] { parseJsonText<nlohmann::json>("{} {}", "t.json"); }).find("t.json: line 1"),
      std::string::npos);
}

TEST(JsonFile, FilesAreReadWholeAndOrderIsKeptOnRequest) {
  TempDir dir;
  const std::string text = "{\"b\": 1, \"a\": [true, null]}";
  writeFileAtomic(dir / "f.json", std::vector<std::uint8_t>(text.begin(), text.end()));
  const nlohmann::json j = readJsonFile(dir / "f.json");
  EXPECT_EQ(j["b"], 1);
  EXPECT_EQ(j["a"][0], true);
  const auto ordered = parseJsonText<nlohmann::ordered_json>(text, "o.json");
  EXPECT_EQ(ordered.begin().key(), "b");
  EXPECT_NE(errorOf([&] { readJsonFile(dir / "missing.json"); }).find("missing.json"),
            std::string::npos);
}
