#include "core/json.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>

#include <json/reader.h>
#include <json/writer.h>

#include "core/exact_number.h"

namespace dicsynth::json {

std::string quote(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (c < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += char(c);
        }
    }
  }
  return out + "\"";
}

std::string number(double v) { return std::isfinite(v) ? exactNumber(v) : "null"; }

Json::Value value(double v) { return std::isfinite(v) ? Json::Value(v) : Json::Value(Json::nullValue); }

std::string write(const Json::Value& document, bool pretty) {
  Json::StreamWriterBuilder builder;
  builder["indentation"] = pretty ? "  " : "";
  builder["precision"] = 17;  // every double reads back exactly
  builder["precisionType"] = "significant";
  builder["emitUTF8"] = true;  // names and paths as written, not as \u escapes
  builder["enableYAMLCompatibility"] = true;  // "name": value, as people write JSON (not "name" : value)
  builder["commentStyle"] = "None";  // no comments to keep; with "All" every short array spans lines
  return Json::writeString(builder, document) + "\n";
}

std::optional<Json::Value> parse(std::string_view text) {
  Json::CharReaderBuilder builder;
  builder["collectComments"] = false;
  builder["failIfExtra"] = true;  // one document and nothing after it: trailing bytes mean damage
  const std::unique_ptr<Json::CharReader> reader(builder.newCharReader());
  Json::Value document;
  std::string errors;
  // jsoncpp throws, rather than failing, where a document nests deeper than its stackLimit (1000): a
  // point.json or cache file of 100000 '[' ended every sweep or render that read it with a bare
  // "Exceeded stackLimit in readValue()" (the hostile-input trial of 2026-11-29). Not JSON we wrote:
  // no document, as for any other damage.
  try {
    if (!reader->parse(text.data(), text.data() + text.size(), &document, &errors)) return std::nullopt;
  } catch (const std::exception&) {
    return std::nullopt;
  }
  return document;
}

std::optional<Json::Value> readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return std::nullopt;
  return parse(text.str());
}

namespace {
const Json::Value* find(const Json::Value& object, const char* name) {
  return object.isObject() ? object.find(name, name + std::char_traits<char>::length(name)) : nullptr;
}
}  // namespace

std::optional<double> numberMember(const Json::Value& object, const char* name) {
  const Json::Value* v = find(object, name);
  if (v == nullptr || !v->isNumeric() || !std::isfinite(v->asDouble())) return std::nullopt;
  return v->asDouble();
}

std::optional<std::string> stringMember(const Json::Value& object, const char* name) {
  const Json::Value* v = find(object, name);
  if (v == nullptr || !v->isString()) return std::nullopt;
  return v->asString();
}

std::optional<bool> boolMember(const Json::Value& object, const char* name) {
  const Json::Value* v = find(object, name);
  if (v == nullptr || !v->isBool()) return std::nullopt;
  return v->asBool();
}

std::optional<std::uint64_t> countMember(const Json::Value& object, const char* name) {
  const Json::Value* v = find(object, name);
  if (v == nullptr || !v->isIntegral() || (v->isInt64() && v->asInt64() < 0)) return std::nullopt;
  return v->asUInt64();
}

}  // namespace dicsynth::json
