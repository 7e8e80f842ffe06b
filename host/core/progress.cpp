#include "core/progress.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace dicsynth {

std::string clockText(double seconds) {
  const auto s = std::int64_t(std::max(0.0, std::round(seconds)));
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%lld:%02lld:%02lld", (long long)(s / 3600), (long long)(s / 60 % 60),
                (long long)(s % 60));
  return buffer;
}

ProgressBar::ProgressBar(std::string label, std::string unit, std::int64_t total, bool terminal)
    : label_(std::move(label)), unit_(std::move(unit)), total_(std::max<std::int64_t>(total, 1)), terminal_(terminal) {}

double ProgressBar::elapsedSeconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void ProgressBar::update(std::int64_t done, const std::string& extra, std::int64_t instant) {
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double rate = elapsed > 0 ? double(std::max<std::int64_t>(done - instant, 0)) / elapsed : 0;
  const bool finished = done >= total_;
  std::string tail = std::to_string(done) + "/" + std::to_string(total_) + " " + unit_;
  char numbers[96];
  std::snprintf(numbers, sizeof numbers, ", %.3g %s/s", rate, unit_.c_str());
  tail += numbers;
  if (!extra.empty()) tail += ", " + extra;
  tail += finished ? ", " + clockText(elapsed) + " in all" : ", ETA " + (rate > 0 ? clockText(double(total_ - done) / rate) : "?");
  if (terminal_) {
    if (!finished && now - lastDraw_ < std::chrono::milliseconds(200)) return;
    lastDraw_ = now;
    constexpr int kWidth = 24;
    const int filled = int(double(kWidth) * double(std::min(done, total_)) / double(total_));
    std::fprintf(stderr, "\r%s: [%s%s] %s   %s", label_.c_str(), std::string(std::size_t(filled), '#').c_str(),
                 std::string(std::size_t(kWidth - filled), '.').c_str(), tail.c_str(), finished ? "\n" : "");
  } else {
    // Quiet: nothing for work done within kQuietSeconds (a short run's log stays its own output).
    if (elapsed < kQuietSeconds) return;
    const int tenth = int(10 * std::min(done, total_) / total_);
    if (tenth == lastTenth_ && !finished) return;
    if (finished && lastTenth_ == 10) return;
    lastTenth_ = tenth;
    std::fprintf(stderr, "%s: %lld/%lld %s (%d%%)%s\n", label_.c_str(), (long long)done, (long long)total_, unit_.c_str(),
                 int(100 * std::min(done, total_) / total_), tail.substr(tail.find(unit_) + unit_.size()).c_str());
  }
  std::fflush(stderr);
}

}  // namespace dicsynth
