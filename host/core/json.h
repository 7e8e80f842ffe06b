#pragma once
// JSON, the one format of the files dicsynth writes for programs and reads back (sweep point
// records, caches, --json reports). Documents are jsoncpp's Json::Value; this file is the one
// writer and the one reader:
//  - write: doubles with 17 significant digits (they read back exactly), non-finite as null (JSON
//    has no NaN or infinity), members sorted by name (jsoncpp keeps objects as maps);
//  - parse / readFile: tolerant of layout, member order, unknown members and comments; nullopt for
//    text that is not one JSON document (anything after it included), never an exception: a
//    damaged cache or record counts as missing.
// quote / number / boolean serve writers that stream (the sweep manifest writes its points one by
// one, never holding the list) and keys whose text is part of an identity (sweep points' keys).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include <json/value.h>

namespace dicsynth::json {

std::string quote(const std::string& s);
// Exact (core/exact_number.h); JSON has no NaN/Infinity, so those become null.
std::string number(double v);
inline std::string boolean(bool b) { return b ? "true" : "false"; }

// A double as a JSON value: null when not finite.
Json::Value value(double v);

// The document as text: indented by 2 (pretty) or on one line, ending with a newline.
std::string write(const Json::Value& document, bool pretty = true);

// The document, or nullopt when `text` is not JSON.
std::optional<Json::Value> parse(std::string_view text);

// parse() of a file's text; nullopt when it cannot be read or is not JSON.
std::optional<Json::Value> readFile(const std::string& path);

// Typed members of an object, nullopt when absent or of another type (numbers: finite doubles;
// counts: non-negative integers).
std::optional<double> numberMember(const Json::Value& object, const char* name);
std::optional<std::string> stringMember(const Json::Value& object, const char* name);
std::optional<bool> boolMember(const Json::Value& object, const char* name);
std::optional<std::uint64_t> countMember(const Json::Value& object, const char* name);

}  // namespace dicsynth::json
