#pragma once
// Progress of long work on stderr (the frames of a render, the points of a sweep): on a terminal a
// bar redrawn in place, at most 5 times a second,
//   render: [#########...........] 7/15 frames, 0.84 frames/s, ETA 0:00:09
// and otherwise (a log file, a cluster job) one quiet line at each tenth of the work and at the
// end, once the work has taken kQuietSeconds (short runs print nothing), so that logs stay short:
//   render: 7/15 frames (46%), 0.84 frames/s, ETA 0:00:09
#include <chrono>
#include <cstdint>
#include <string>

namespace dicsynth {

class ProgressBar {
 public:
  static constexpr double kQuietSeconds = 10;
  // `unit`: what is counted, plural ("frames", "points"). `terminal`: stderr is a terminal.
  ProgressBar(std::string label, std::string unit, std::int64_t total, bool terminal);
  // `done` of the total are finished; `extra` is appended (e.g. "12.3 img/s"). `instant` of the
  // `done` took no work (a resumed sweep's points already complete): the rate and the ETA count
  // the others only (a resumed sweep's ETA was half the time left: sweep audit, 2026-11-28).
  void update(std::int64_t done, const std::string& extra = "", std::int64_t instant = 0);
  double elapsedSeconds() const;  // since construction

 private:
  std::string label_, unit_;
  std::int64_t total_;
  bool terminal_;
  int lastTenth_ = -1;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now(), lastDraw_{};
};

// "H:MM:SS".
std::string clockText(double seconds);

}  // namespace dicsynth
