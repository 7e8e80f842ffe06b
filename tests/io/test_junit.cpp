// The JUnit XML writer (host/io/junit.h), read back by an independent parser (OIIO's bundled
// pugixml) for structure, counts and values, and checked character by character against XML 1.0's
// Char production after glibc's iconv decoded it (an independent UTF-8 decoder).
#include <doctest/doctest.h>
#include <iconv.h>

#include <OpenImageIO/detail/pugixml/pugixml.hpp>  // OIIO's bundled pugixml: a test-only XML parser
#include <cstdlib>
#include <string>
#include <vector>

#include "io/junit.h"
#include "temp_folder.h"

using namespace dicsynth;
using test::TempFolder;

namespace {

// The document's code points, or an empty vector when it is not valid UTF-8 (per glibc's iconv).
std::vector<char32_t> decodeUtf8(const std::string& text) {
  iconv_t cd = iconv_open("UTF-32LE", "UTF-8");
  REQUIRE(cd != iconv_t(-1));
  std::vector<char32_t> out(text.size() + 1);
  char* in = const_cast<char*>(text.data());
  std::size_t inLeft = text.size(), outLeft = out.size() * 4;
  char* o = reinterpret_cast<char*>(out.data());
  const std::size_t r = iconv(cd, &in, &inLeft, &o, &outLeft);
  iconv_close(cd);
  if (r == std::size_t(-1) || inLeft != 0) return {};
  out.resize(out.size() - outLeft / 4);
  return out;
}

// XML 1.0 §2.2: Char ::= #x9 | #xA | #xD | [#x20-#xD7FF] | [#xE000-#xFFFD] | [#x10000-#x10FFFF]
bool xmlChar(char32_t c) {
  return c == 0x9 || c == 0xA || c == 0xD || (c >= 0x20 && c <= 0xD7FF) || (c >= 0xE000 && c <= 0xFFFD) ||
         (c >= 0x10000 && c <= 0x10FFFF);
}

junit::Report sampleReport(const std::string& awkward) {
  junit::Report r{"dicsynth compare"};
  junit::TestSuite a{"scenes/a.lua", "2026-11-21T16:00:00", {{"precision", "fp64"}, {"note", awkward}}};
  a.cases.push_back({"a", "left", 1.5});
  a.cases.push_back({"a", "right", 0.25, junit::Outcome::Failed, "right: radiance 3 px > allowed 0 px",
                     "ToleranceExceeded", "details\nline 2"});
  a.systemOut = "text of a\n";
  junit::TestSuite b{awkward};
  b.cases.push_back({awkward, awkward, 2.0, junit::Outcome::Error, awkward, "InputError", awkward});
  r.suites = {a, b};
  return r;
}

}  // namespace

TEST_CASE("junit: structure, counts and times read back by an XML parser") {
  const std::string xml = junit::toXml(sampleReport("plain"));
  pugi::xml_document doc;
  REQUIRE(doc.load_string(xml.c_str()));
  const pugi::xml_node root = doc.child("testsuites");
  REQUIRE(root);
  CHECK(std::string(root.attribute("name").value()) == "dicsynth compare");
  CHECK(root.attribute("tests").as_int() == 3);
  CHECK(root.attribute("failures").as_int() == 1);
  CHECK(root.attribute("errors").as_int() == 1);
  CHECK(root.attribute("time").as_double() == doctest::Approx(3.75));
  std::vector<pugi::xml_node> suites;
  for (auto s : root.children("testsuite")) suites.push_back(s);
  REQUIRE(suites.size() == 2);
  const pugi::xml_node a = suites[0];
  CHECK(std::string(a.attribute("name").value()) == "scenes/a.lua");
  CHECK(a.attribute("tests").as_int() == 2);
  CHECK(a.attribute("failures").as_int() == 1);
  CHECK(a.attribute("errors").as_int() == 0);
  CHECK(a.attribute("time").as_double() == doctest::Approx(1.75));
  CHECK(std::string(a.attribute("timestamp").value()) == "2026-11-21T16:00:00");
  CHECK(std::string(a.child("properties").find_child_by_attribute("property", "name", "precision")
                        .attribute("value").value()) == "fp64");
  std::vector<pugi::xml_node> cases;
  for (auto c : a.children("testcase")) cases.push_back(c);
  REQUIRE(cases.size() == 2);
  CHECK(std::string(cases[0].attribute("classname").value()) == "a");
  CHECK(std::string(cases[0].attribute("name").value()) == "left");
  CHECK(cases[0].attribute("time").as_double() == doctest::Approx(1.5));
  CHECK_FALSE(cases[0].first_child());  // a passing case is empty
  const pugi::xml_node failure = cases[1].child("failure");
  REQUIRE(failure);
  CHECK(std::string(failure.attribute("message").value()) == "right: radiance 3 px > allowed 0 px");
  CHECK(std::string(failure.attribute("type").value()) == "ToleranceExceeded");
  CHECK(std::string(failure.text().get()) == "details\nline 2");
  CHECK(std::string(a.child("system-out").text().get()) == "text of a\n");
  const pugi::xml_node error = suites[1].child("testcase").child("error");
  REQUIRE(error);
  CHECK(std::string(error.attribute("type").value()) == "InputError");
  CHECK_FALSE(suites[1].child("properties"));  // none given: no element
  CHECK_FALSE(suites[1].attribute("timestamp"));
}

TEST_CASE("junit: names with markup, quotes, controls and invalid UTF-8 stay well-formed XML") {
  // Markup characters and quotes must come back unchanged; tab/newline survive in attributes (as
  // character references); a C0 control (forbidden even as a reference), DEL and invalid UTF-8 (a
  // lone continuation byte, an overlong encoding, a UTF-16 surrogate, a truncated sequence) become
  // U+FFFD; valid multi-byte characters pass.
  const std::string awkward = std::string("a&b <c> \"d\" 'e'\tf\ng") + '\x01' + '\x7F' + "\x80" + "\xC0\xAF" +
                              "\xED\xA0\x80" + "\xC3" + " \xC3\xA9 \xE2\x80\x93 \xF0\x9F\x98\x80";
  const std::string expected = std::string("a&b <c> \"d\" 'e'\tf\ng") + "\xEF\xBF\xBD\xEF\xBF\xBD\xEF\xBF\xBD" +
                               "\xEF\xBF\xBD\xEF\xBF\xBD" + "\xEF\xBF\xBD\xEF\xBF\xBD\xEF\xBF\xBD" + "\xEF\xBF\xBD" +
                               " \xC3\xA9 \xE2\x80\x93 \xF0\x9F\x98\x80";
  const std::string xml = junit::toXml(sampleReport(awkward));
  const std::vector<char32_t> chars = decodeUtf8(xml);
  REQUIRE_FALSE(chars.empty());  // valid UTF-8 throughout
  for (char32_t c : chars) CHECK(xmlChar(c));
  pugi::xml_document doc;
  REQUIRE(doc.load_string(xml.c_str()));
  const pugi::xml_node b = doc.child("testsuites").last_child();
  CHECK(std::string(b.attribute("name").value()) == expected);
  const pugi::xml_node c = b.child("testcase");
  CHECK(std::string(c.attribute("classname").value()) == expected);
  CHECK(std::string(c.attribute("name").value()) == expected);
  CHECK(std::string(c.child("error").attribute("message").value()) == expected);
  CHECK(std::string(c.child("error").text().get()) == expected);
  CHECK(std::string(doc.child("testsuites").first_child().child("properties").last_child()
                        .attribute("value").value()) == expected);
}

TEST_CASE("junit: the report is written atomically, and an unwritable path is an error") {
  TempFolder dir;
  const std::string path = dir.file("report.xml");
  junit::writeReport(path, sampleReport("x"));
  CHECK(test::readBytes(path) == junit::toXml(sampleReport("x")));
  CHECK(dir.entries() == std::vector<std::string>{"report.xml"});  // no temporary left behind
  CHECK_THROWS(junit::writeReport(dir.file("missing/report.xml"), sampleReport("x")));
  CHECK(dir.entries() == std::vector<std::string>{"report.xml"});
}
