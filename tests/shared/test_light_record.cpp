// The GPU's light record (ibl/shared/light_record.h): packLight then unpackLight gives back
// every field of every light type, the five vec4 hold the fields where the record's table puts
// them (what the shaders' buffers are read as), and the record is five vec4, 80 bytes.
#include <vector>

#include <gtest/gtest.h>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "ibl/shared/light_record.h"

namespace s = ibl::shared;

namespace {

// A light of `type` whose fields all differ (every component of every vector too), so that a
// field written to or read from another's place changes the light.
s::ShadingLight distinctLight(int type) {
  s::ShadingLight l{};
  l.type = type;
  l.position = glm::vec3(1.5f, -2.25f, 3.125f);
  l.direction = glm::vec3(0.48f, -0.6f, 0.64f);
  l.up = glm::vec3(0.8f, 0.36f, -0.48f);
  l.color = glm::vec3(11.0f, 12.5f, 13.75f);
  l.radius = 0.0375f;
  l.width = 4.5f;
  l.height = 5.25f;
  l.cosInner = 0.96875f;
  l.cosOuter = 0.875f;
  l.invSquaredRange = 0.015625f;
  return l;
}

void expectSameLight(const s::ShadingLight& got, const s::ShadingLight& expected) {
  EXPECT_EQ(got.type, expected.type);
  EXPECT_EQ(got.position, expected.position);
  EXPECT_EQ(got.direction, expected.direction);
  EXPECT_EQ(got.up, expected.up);
  EXPECT_EQ(got.color, expected.color);
  EXPECT_EQ(got.radius, expected.radius);
  EXPECT_EQ(got.width, expected.width);
  EXPECT_EQ(got.height, expected.height);
  EXPECT_EQ(got.cosInner, expected.cosInner);
  EXPECT_EQ(got.cosOuter, expected.cosOuter);
  EXPECT_EQ(got.invSquaredRange, expected.invSquaredRange);
}

}  // namespace

// Every light type, with and without an IES profile, comes back field for field.
TEST(LightRecord, PackThenUnpackGivesBackEveryField) {
  for (int type : {s::kLightPoint, s::kLightSpot, s::kLightSun, s::kLightSphere, s::kLightDisk,
                   s::kLightTube, s::kLightRect})
    for (float profile : {-1.0f, 0.0f, 7.0f}) {
      const s::ShadingLight light = distinctLight(type);
      const s::LightRecord record = s::packLight(light, profile);
      expectSameLight(s::unpackLight(record), light);
      EXPECT_EQ(s::lightRecordProfile(record), profile) << type;
    }
}

// The five vec4 as the record's table lays them out, in the order storeLightRecord writes them
// (the order of the buffers the shaders read).
TEST(LightRecord, LayoutIsTheTables) {
  const s::ShadingLight l = distinctLight(s::kLightRect);
  std::vector<glm::vec4> data(2 * s::kLightRecordVec4s, glm::vec4(-9.0f));
  s::storeLightRecord(s::packLight(l, 3.0f), &data[s::kLightRecordVec4s]);
  EXPECT_EQ(data[0], glm::vec4(-9.0f));  // nothing written before the record
  EXPECT_EQ(data[5], glm::vec4(l.position, static_cast<float>(s::kLightRect)));
  EXPECT_EQ(data[6], glm::vec4(l.direction, l.radius));
  EXPECT_EQ(data[7], glm::vec4(l.up, l.width));
  EXPECT_EQ(data[8], glm::vec4(l.color, l.height));
  EXPECT_EQ(data[9], glm::vec4(l.cosInner, l.cosOuter, l.invSquaredRange, 3.0f));
}

TEST(LightRecord, IsFiveVec4) {
  EXPECT_EQ(s::kLightRecordVec4s, 5);
  EXPECT_EQ(sizeof(s::LightRecord), 5u * 16u);
  EXPECT_EQ(sizeof(s::LightRecord), s::kLightRecordVec4s * sizeof(glm::vec4));
}
