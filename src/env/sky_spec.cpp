// "sky:key=value,..." descriptions of a sky, and the date and time options.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <system_error>
#include <vector>

#include <fmt/format.h>

#include "ibl/core/error.hpp"
#include "ibl/env/sky.hpp"

namespace ibl {

namespace {

double parseNumber(std::string_view text, std::string_view what) {
  double v = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v))
    failUsage(what, fmt::format("\"{}\" is not a number", text));
  return v;
}

// Integers separated by `separator`, `count` of them (or `count - 1` when the last is optional).
std::vector<int> parseFields(std::string_view text, char separator, std::size_t count,
                             bool lastOptional, std::string_view what, std::string_view form) {
  std::vector<int> fields;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find(separator, start), text.size());
    int v = 0;
    const auto [p, ec] = std::from_chars(text.data() + start, text.data() + end, v);
    if (ec != std::errc() || p != text.data() + end || end == start)
      failUsage(what, fmt::format("\"{}\" is not {}", text, form));
    fields.push_back(v);
    start = end + 1;
  }
  if (fields.size() != count && !(lastOptional && fields.size() + 1 == count))
    failUsage(what, fmt::format("\"{}\" is not {}", text, form));
  return fields;
}

}  // namespace

void parseDate(std::string_view text, DateTime& when, std::string_view option) {
  const auto f = parseFields(text, '-', 3, false, option, "a date YYYY-MM-DD");
  constexpr int days[] = {31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  if (f[0] < 1900 || f[0] > 2100 || f[1] < 1 || f[1] > 12 || f[2] < 1 || f[2] > days[f[1] - 1])
    failUsage(option, fmt::format("\"{}\" is not a date from 1900 to 2100", text));
  when.year = f[0];
  when.month = f[1];
  when.day = f[2];
}

void parseClockTime(std::string_view text, DateTime& when, std::string_view option) {
  const auto f = parseFields(text, ':', 3, true, option, "a time HH:MM[:SS]");
  const int seconds = f.size() == 3 ? f[2] : 0;
  if (f[0] < 0 || f[0] > 23 || f[1] < 0 || f[1] > 59 || seconds < 0 || seconds > 59)
    failUsage(option, fmt::format("\"{}\" is not a time of day", text));
  when.hours = f[0] + f[1] / 60.0 + seconds / 3600.0;
}

bool isSkySpec(std::string_view text) {
  return text == "sky" || text.starts_with("sky:");
}

SkySpec parseSkySpec(std::string_view text) {
  const std::string what(text);
  if (!isSkySpec(text)) failUsage(what, "not a sky description (sky:key=value,...)");
  SkySpec spec;
  std::map<std::string, std::string, std::less<>> values;
  std::string_view rest = text.size() > 4 ? text.substr(4) : std::string_view();
  while (!rest.empty()) {
    const std::size_t comma = std::min(rest.find(','), rest.size());
    const std::string_view item = rest.substr(0, comma);
    const std::size_t eq = item.find('=');
    if (eq == std::string_view::npos || eq == 0)
      failUsage(what, fmt::format("\"{}\" is not key=value", item));
    const std::string key(item.substr(0, eq));
    static const std::set<std::string, std::less<>> known = {
        "elevation", "azimuth",  "date",      "time",  "utc",    "latitude",
        "longitude", "altitude", "turbidity", "ozone", "albedo", "size"};
    if (!known.contains(key))
      failUsage(what,
                fmt::format("unknown key \"{}\" (elevation, azimuth, date, time, utc, latitude, "
                            "longitude, altitude, turbidity, ozone, albedo, size)",
                            key));
    if (!values.emplace(key, std::string(item.substr(eq + 1))).second)
      failUsage(what, fmt::format("\"{}\" given twice", key));
    rest = comma < rest.size() ? rest.substr(comma + 1) : std::string_view();
  }
  const auto number = [&](const char* key) { return parseNumber(values.at(key), what); };
  SkyParameters& p = spec.parameters;
  const bool angles = values.contains("elevation") || values.contains("azimuth");
  const bool clock = values.contains("date") || values.contains("time");
  if (angles && clock)
    failUsage(what, "give the sun's elevation and azimuth, or a date and time, not both");
  if (angles) {
    if (values.contains("elevation")) p.sunElevation = static_cast<float>(number("elevation"));
    if (values.contains("azimuth")) p.sunAzimuth = static_cast<float>(number("azimuth"));
  }
  if (!clock &&
      (values.contains("latitude") || values.contains("longitude") || values.contains("utc")))
    failUsage(what, "latitude, longitude and utc place a date and time: give date= and time=");
  if (values.contains("altitude")) p.altitude = static_cast<float>(number("altitude"));
  if (clock) {
    for (const char* key : {"date", "time", "latitude", "longitude"})
      if (!values.contains(key))
        failUsage(what, fmt::format("a date and time need date, time, latitude and longitude; "
                                    "\"{}\" is missing",
                                    key));
    DateTime when;
    parseDate(values.at("date"), when, what);
    parseClockTime(values.at("time"), when, what);
    if (values.contains("utc")) when.utcOffset = number("utc");
    const double latitude = number("latitude"), longitude = number("longitude");
    if (std::abs(latitude) > 90.0 || std::abs(longitude) > 180.0 || std::abs(when.utcOffset) > 14.0)
      failUsage(what, "latitude must be in [-90, 90], longitude in [-180, 180], utc in [-14, 14]");
    const SolarPosition sun = solarPosition(when, latitude, longitude, p.altitude);
    p.sunElevation = static_cast<float>(sun.elevation);
    p.sunAzimuth = static_cast<float>(sun.azimuth);
  }
  if (values.contains("turbidity")) p.turbidity = static_cast<float>(number("turbidity"));
  if (values.contains("ozone")) p.ozone = static_cast<float>(number("ozone"));
  if (values.contains("albedo")) p.groundAlbedo = static_cast<float>(number("albedo"));
  if (values.contains("size")) {
    const auto f = parseFields(values.at("size"), 'x', 2, false, what, "a size WxH");
    if (f[0] < 8 || f[0] > 16384 || f[1] < 4 || f[1] > 8192)
      failUsage(what, fmt::format("size {}x{} out of range (8x4 to 16384x8192)", f[0], f[1]));
    spec.width = f[0];
    spec.height = f[1];
  }
  checkSkyParameters(p, what);
  return spec;
}

}  // namespace ibl
