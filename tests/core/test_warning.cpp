// core/warning.h and core/env_count.h: a capture receives every warning raised while it lives, from
// any thread, in order per thread, and nothing after it ends; two live captures both receive them;
// notes come with the warnings, in order, and take() drops them;
// a knob's bad value is a warning naming the variable and its range, and the fallback is used.
#include <doctest/doctest.h>

#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "core/env_count.h"
#include "core/warning.h"

using namespace dicsynth;

TEST_CASE("warnings: a capture collects them from every thread, two captures both, none after the end") {
  std::vector<std::string> outer;
  {
    WarningCapture first;
    {
      WarningCapture second;
      std::vector<std::thread> threads;
      for (int t = 0; t < 4; ++t)
        threads.emplace_back([t] {
          for (int i = 0; i < 100; ++i) warn("thread " + std::to_string(t) + " warning " + std::to_string(i));
        });
      for (std::thread& t : threads) t.join();
      const std::vector<std::string> inner = second.take();
      REQUIRE(inner.size() == 400);
      CHECK(second.take().empty());  // taken: gone
      // In order within each thread.
      for (int t = 0; t < 4; ++t) {
        int next = 0;
        for (const std::string& text : inner)
          if (text.rfind("thread " + std::to_string(t) + " ", 0) == 0)
            CHECK(text == "thread " + std::to_string(t) + " warning " + std::to_string(next++));
        CHECK(next == 100);
      }
    }
    warn("after the second capture");
    outer = first.take();
  }
  REQUIRE(outer.size() == 401);
  CHECK(outer.back() == "after the second capture");
}

TEST_CASE("notes: captured with the warnings in the order said, take() keeps the warnings only") {
  WarningCapture capture;
  note("scene.lua:3: hello");
  warn("a warning");
  note(std::string("a byte \0 inside", 15));  // a scene's print may hold any byte
  const std::vector<WarningCapture::Message> said = capture.takeMessages();
  REQUIRE(said.size() == 3);
  CHECK((!said[0].warning && said[0].text == "scene.lua:3: hello"));
  CHECK((said[1].warning && said[1].text == "a warning"));
  CHECK((!said[2].warning && said[2].text == std::string("a byte \0 inside", 15)));
  CHECK(capture.takeMessages().empty());
  note("dropped");
  warn("kept");
  CHECK(capture.take() == std::vector<std::string>{"kept"});
  CHECK(capture.takeMessages().empty());
}

TEST_CASE("warnAtMost: n of a kind per capture, each capture its own count, the last with its note") {
  // Python's calls each make a capture: a warning said "once" in the process was said in the first
  // call only, and a later call with the same mistake was silent.
  for (int call = 0; call < 2; ++call) {
    WarningCapture capture;
    for (int i = 0; i < 5; ++i) warnAtMost("kind a", 3, "a" + std::to_string(i), " (no more)");
    warnAtMost("kind b", 1, "b");
    warnAtMost("kind b", 1, "b again");
    CHECK(capture.take() == std::vector<std::string>{"a0", "a1", "a2 (no more)", "b"});
  }
  WarningCapture outer;
  warnAtMost("kind c", 1, "c");
  {
    WarningCapture inner;  // alive with outer: each counts for itself
    warnAtMost("kind c", 1, "c in both");
    CHECK(inner.take() == std::vector<std::string>{"c in both"});
  }
  CHECK(outer.take() == std::vector<std::string>{"c"});
}

TEST_CASE("warnings: a knob's value that is not a whole number in its range is said, and the fallback used") {
  struct Case {
    const char* value;
    long expected;
    bool warned;
  };
  // Values strtol would misread without the checks: a sign, trailing text, an overflow.
  const Case cases[] = {{"", 7, false},  {"12", 12, false}, {"0", 0, false},   {"100", 100, false},
                        {"-1", 7, true}, {"101", 7, true},  {"12x", 7, true}, {"1e2", 7, true},
                        {"99999999999999999999", 7, true}};
  for (const Case& c : cases) {
    CAPTURE(c.value);
    setenv("DICSYNTH_TEST_KNOB", c.value, 1);
    WarningCapture capture;
    CHECK(envCount("DICSYNTH_TEST_KNOB", 7, 0, 100) == c.expected);
    const std::vector<std::string> said = capture.take();
    if (c.warned) {
      REQUIRE(said.size() == 1);
      CHECK(said[0] == "DICSYNTH_TEST_KNOB=" + std::string(c.value) + " is not a whole number from 0 to 100: using 7");
    } else {
      CHECK(said.empty());
    }
  }
  unsetenv("DICSYNTH_TEST_KNOB");
  CHECK(envCount("DICSYNTH_TEST_KNOB", 7, 0, 100) == 7);
}
