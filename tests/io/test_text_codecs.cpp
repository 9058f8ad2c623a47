// The text codecs (src/io/text_codecs.cpp) against the RFCs' own examples: base64 (RFC 4648
// section 10), data URIs (RFC 2397 section 4) and percent-encoding (RFC 3986 sections 2.1 and
// 2.5).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "../../src/io/text_codecs.hpp"
#include "support/text_file.hpp"

using namespace ibl;
using ibl::test::bytesOf;

// RFC 4648 section 10: BASE64("") = "", BASE64("f") = "Zg==", ... BASE64("foobar") = "Zm9vYmFy";
// decoded with or without the padding, and sized without decoding.
TEST(TextCodecs, Base64DecodesTheRfc4648TestVectors) {
  const std::pair<const char*, const char*> vectors[] = {{"", ""},
                                                         {"f", "Zg=="},
                                                         {"fo", "Zm8="},
                                                         {"foo", "Zm9v"},
                                                         {"foob", "Zm9vYg=="},
                                                         {"fooba", "Zm9vYmE="},
                                                         {"foobar", "Zm9vYmFy"}};
  for (const auto& [plain, encoded] : vectors) {
    std::string unpadded(encoded);
    while (!unpadded.empty() && unpadded.back() == '=') unpadded.pop_back();
    for (const std::string& text : {std::string(encoded), unpadded}) {
      EXPECT_EQ(decodeBase64(text), std::optional(bytesOf(plain))) << text;
      EXPECT_EQ(base64Size(text), std::string_view(plain).size()) << text;
    }
  }
}

// RFC 4648 section 5: the URL alphabet writes 62 and 63 as '-' and '_' where the standard one
// writes '+' and '/'. 0xFB 0xFF is 111110 111111 1111(00): 62, 63, 60.
TEST(TextCodecs, Base64ReadsBothAlphabets) {
  const std::vector<std::uint8_t> bytes = {0xFB, 0xFF};
  EXPECT_EQ(decodeBase64("+/8="), bytes);
  EXPECT_EQ(decodeBase64("-_8"), bytes);
}

// Not base64: a character outside both alphabets (padding included, inside the text), or a last
// group of one character (6 bits: not a byte).
TEST(TextCodecs, Base64RefusesWhatIsNotBase64) {
  for (const char* text : {"!!!!", "Zm9v!", "Zg=g", "Z=g=", "Zm9vY", "Z", "Zm 9v"})
    EXPECT_EQ(decodeBase64(text), std::nullopt) << text;
}

// RFC 2397: "data:[<mediatype>][;base64],<data>"; the media type's parameters are not kept, a
// missing one is left empty.
TEST(TextCodecs, DataUrisWithAndWithoutBase64) {
  const std::optional<DataUri> binary = parseDataUri("data:application/octet-stream;base64,AAAA");
  ASSERT_TRUE(binary.has_value());
  EXPECT_EQ(binary->mimeType, "application/octet-stream");
  EXPECT_TRUE(binary->base64);
  EXPECT_EQ(binary->payload, "AAAA");
  // RFC 2397 section 4's first example: no media type, URL-encoded text.
  const std::optional<DataUri> note = parseDataUri("data:,A%20brief%20note");
  ASSERT_TRUE(note.has_value());
  EXPECT_EQ(note->mimeType, "");
  EXPECT_FALSE(note->base64);
  EXPECT_EQ(note->payload, "A%20brief%20note");
  EXPECT_EQ(percentDecode(note->payload), "A brief note");
  const std::optional<DataUri> text = parseDataUri("data:text/plain;charset=utf-8;base64,aGk=");
  ASSERT_TRUE(text.has_value());
  EXPECT_EQ(text->mimeType, "text/plain");
  EXPECT_TRUE(text->base64);
  EXPECT_EQ(decodeBase64(text->payload), bytesOf("hi"));
}

// Not a data URI: nullopt; one without its comma: no type, not base64, no payload.
TEST(TextCodecs, MalformedDataUris) {
  EXPECT_EQ(parseDataUri("textures/wood.png"), std::nullopt);
  EXPECT_EQ(parseDataUri("DATA:,x"), std::nullopt);  // the scheme as glTF writes it
  const std::optional<DataUri> noComma = parseDataUri("data:image/png;base64");
  ASSERT_TRUE(noComma.has_value());
  EXPECT_EQ(noComma->mimeType, "");
  EXPECT_FALSE(noComma->base64);
  EXPECT_EQ(noComma->payload, "");
}

// RFC 3986 section 2.1: "%20" is a space, hex digits in either case; section 2.5: "À" (U+00C0)
// is "%C3%80" in UTF-8. A '%' without two hexadecimal digits after it is kept as written.
TEST(TextCodecs, PercentDecodingFollowsRfc3986) {
  EXPECT_EQ(percentDecode("wood%20grain.png"), "wood grain.png");
  EXPECT_EQ(percentDecode("%7Euser"), "~user");
  EXPECT_EQ(percentDecode("%C3%80"), "\xC3\x80");
  EXPECT_EQ(percentDecode("%c3%80"), "\xC3\x80");
  EXPECT_EQ(percentDecode("plain.bin"), "plain.bin");
  for (const char* kept : {"100%", "%4", "%G1", "%%", "a%2"}) EXPECT_EQ(percentDecode(kept), kept);
}
