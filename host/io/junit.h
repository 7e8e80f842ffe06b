#pragma once
// JUnit XML reports (`compare --junit`), in the dialect that Jenkins, GitLab and GitHub's test
// reporters read: <testsuites> → <testsuite> → <testcase classname= name= time=>, a test case
// failing with <failure message= type=>details</failure> or broken with <error …>, counts in
// attributes, times in seconds.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace dicsynth::junit {

enum class Outcome { Passed, Failed, Error };

struct TestCase {
  std::string classname;  // Jenkins groups by it (dots separate "packages")
  std::string name;
  double time_s = 0;
  Outcome outcome = Outcome::Passed;
  std::string message;    // one line: the failure's or error's message attribute
  std::string type;       // the failure's or error's type attribute
  std::string details;    // the element's text (several lines allowed)
};

struct TestSuite {
  std::string name;
  std::string timestamp;  // ISO 8601 (UTC) of the suite's start; omitted when empty
  std::vector<std::pair<std::string, std::string>> properties;
  std::vector<TestCase> cases;
  std::string systemOut;  // omitted when empty
};

struct Report {
  std::string name;
  std::vector<TestSuite> suites;
};

// The document, UTF-8. Every name, message and text is escaped (xmlEscape); suite and report times
// are the sums of their cases' times.
std::string toXml(const Report& report);

// Writes toXml(report) to `path` atomically (core/atomic_file.h). Throws Error.
void writeReport(const std::string& path, const Report& report);

// Text usable both as attribute value and element content: & < > " ' as entities; tab, newline and
// carriage return as character references (so attribute values keep them); the other C0 controls,
// which XML 1.0 forbids even as references, and invalid UTF-8 sequences (a file name may contain
// any bytes) become U+FFFD.
std::string xmlEscape(std::string_view text);

// Current time as "YYYY-MM-DDThh:mm:ss" (UTC), JUnit's timestamp format.
std::string timestampNow();

}  // namespace dicsynth::junit
