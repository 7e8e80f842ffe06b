// JUnit XML writer. Written by hand rather than through an XML library: the only one at hand is
// the pugixml copy bundled inside OpenImageIO (a detail header, used by the tests as an independent
// parser), and it passes C0 control characters and invalid UTF-8 through unchanged, which produces
// a document CI parsers reject; the format itself is a handful of elements.
#include "io/junit.h"

#include <cstdio>
#include <ctime>

#include "core/atomic_file.h"

namespace dicsynth::junit {
namespace {

constexpr const char* kReplacement = "\xEF\xBF\xBD";  // U+FFFD in UTF-8

// Length of the valid UTF-8 sequence starting at text[i] whose code point XML 1.0 allows
// (#x9 | #xA | #xD | [#x20-#xD7FF] | [#xE000-#xFFFD] | [#x10000-#x10FFFF]), or 0.
std::size_t validSequence(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return (unsigned char)text[k]; };
  const unsigned char b0 = byte(i);
  if (b0 < 0x80) return 1;
  std::size_t n;
  unsigned cp;
  if (b0 >= 0xC2 && b0 <= 0xDF) n = 2, cp = b0 & 0x1Fu;
  else if (b0 >= 0xE0 && b0 <= 0xEF) n = 3, cp = b0 & 0x0Fu;
  else if (b0 >= 0xF0 && b0 <= 0xF4) n = 4, cp = b0 & 0x07u;
  else return 0;  // continuation byte, overlong 2-byte lead (C0, C1) or beyond U+10FFFF (F5..FF)
  if (i + n > text.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    if ((byte(i + k) & 0xC0u) != 0x80u) return 0;
    cp = (cp << 6) | (byte(i + k) & 0x3Fu);
  }
  const bool overlong = (n == 3 && cp < 0x800) || (n == 4 && cp < 0x10000);
  const bool surrogate = cp >= 0xD800 && cp <= 0xDFFF;
  const bool nonCharacter = cp == 0xFFFE || cp == 0xFFFF;
  if (overlong || surrogate || nonCharacter || cp > 0x10FFFF) return 0;
  return n;
}

// Element content: as xmlEscape, but tab and newline stay literal (readable details); a carriage
// return stays a reference, since parsers turn a literal one into a newline.
std::string xmlContent(std::string_view text) {
  std::string out = xmlEscape(text);
  for (const auto& [ref, literal] : {std::pair<std::string_view, char>{"&#9;", '\t'}, {"&#10;", '\n'}})
    for (std::size_t at = out.find(ref); at != std::string::npos; at = out.find(ref, at + 1))
      out.replace(at, ref.size(), 1, literal);
  return out;
}

std::string seconds(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", s < 0 ? 0.0 : s);
  return buf;
}

std::string attribute(const char* name, std::string_view value) {
  return std::string(" ") + name + "=\"" + xmlEscape(value) + "\"";
}

double suiteTime(const TestSuite& s) {
  double t = 0;
  for (const auto& c : s.cases) t += c.time_s;
  return t;
}

struct Counts {
  std::size_t tests = 0, failures = 0, errors = 0;
  void add(const TestCase& c) {
    ++tests;
    failures += c.outcome == Outcome::Failed;
    errors += c.outcome == Outcome::Error;
  }
  std::string attributes() const {
    return " tests=\"" + std::to_string(tests) + "\" failures=\"" + std::to_string(failures) + "\" errors=\"" +
           std::to_string(errors) + "\" skipped=\"0\"";
  }
};

void writeCase(std::string& o, const TestCase& c) {
  o += "    <testcase" + attribute("classname", c.classname) + attribute("name", c.name) + " time=\"" +
       seconds(c.time_s) + "\"";
  if (c.outcome == Outcome::Passed) {
    o += "/>\n";
    return;
  }
  const char* element = c.outcome == Outcome::Failed ? "failure" : "error";
  o += ">\n      <" + std::string(element) + attribute("message", c.message) + attribute("type", c.type) + ">" +
       xmlContent(c.details) + "</" + element + ">\n    </testcase>\n";
}

}  // namespace

std::string xmlEscape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    switch (c) {
      case '&': out += "&amp;"; ++i; continue;
      case '<': out += "&lt;"; ++i; continue;
      case '>': out += "&gt;"; ++i; continue;
      case '"': out += "&quot;"; ++i; continue;
      case '\'': out += "&apos;"; ++i; continue;
      case '\t': out += "&#9;"; ++i; continue;
      case '\n': out += "&#10;"; ++i; continue;
      case '\r': out += "&#13;"; ++i; continue;
      default: break;
    }
    if ((unsigned char)c < 0x20 || c == 0x7F) {  // DEL is legal XML but invisible: replaced too
      out += kReplacement;
      ++i;
      continue;
    }
    const std::size_t n = validSequence(text, i);
    if (n == 0) {
      out += kReplacement;
      ++i;
    } else {
      out.append(text.substr(i, n));
      i += n;
    }
  }
  return out;
}

std::string timestampNow() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S", &utc);
  return buf;
}

std::string toXml(const Report& report) {
  Counts all;
  double total = 0;
  for (const auto& s : report.suites) {
    for (const auto& c : s.cases) all.add(c);
    total += suiteTime(s);
  }
  std::string o = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  o += "<testsuites" + attribute("name", report.name) + all.attributes() + " time=\"" + seconds(total) + "\">\n";
  for (std::size_t i = 0; i < report.suites.size(); ++i) {
    const TestSuite& s = report.suites[i];
    Counts counts;
    for (const auto& c : s.cases) counts.add(c);
    o += "  <testsuite" + attribute("name", s.name) + " id=\"" + std::to_string(i) + "\"" + counts.attributes() +
         " time=\"" + seconds(suiteTime(s)) + "\"";
    if (!s.timestamp.empty()) o += attribute("timestamp", s.timestamp);
    o += ">\n";
    if (!s.properties.empty()) {
      o += "    <properties>\n";
      for (const auto& [name, value] : s.properties)
        o += "      <property" + attribute("name", name) + attribute("value", value) + "/>\n";
      o += "    </properties>\n";
    }
    for (const auto& c : s.cases) writeCase(o, c);
    if (!s.systemOut.empty()) o += "    <system-out>" + xmlContent(s.systemOut) + "</system-out>\n";
    o += "  </testsuite>\n";
  }
  o += "</testsuites>\n";
  return o;
}

void writeReport(const std::string& path, const Report& report) { writeTextAtomically(path, toXml(report)); }

}  // namespace dicsynth::junit
