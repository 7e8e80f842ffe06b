#include "core/cgroup_limits.h"

#include <sched.h>
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace dicsynth {
namespace {

std::optional<std::string> readText(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) return std::nullopt;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// CPUs from quota and period (µs); none for a quota that is absent, unlimited or nonsense.
std::optional<unsigned> cpus(long long quota, long long period) {
  if (quota <= 0 || period <= 0) return std::nullopt;
  // Rounded up: a quota of 1.5 CPUs keeps two threads busy half the time each rather than one
  // thread of the two the group may use (the rounding Go and .NET runtimes make).
  // At most 2^20: a nonsense quota (2^44 µs per ms) is no limit worth counting, and the conversion
  // of a double beyond unsigned's range gave 0 threads (the review of 2026-11-29).
  return unsigned(std::clamp(std::ceil(double(quota) / double(period)), 1.0, double(1u << 20)));
}

std::optional<unsigned> v2Limit(const std::filesystem::path& group) {
  const auto text = readText(group / "cpu.max");
  if (!text) return std::nullopt;
  std::istringstream in(*text);
  std::string quota;
  long long period = 0;
  if (!(in >> quota >> period) || quota == "max") return std::nullopt;
  try {
    return cpus(std::stoll(quota), period);
  } catch (...) {
    return std::nullopt;
  }
}

std::optional<unsigned> v1Limit(const std::filesystem::path& group) {
  const auto quota = readText(group / "cpu.cfs_quota_us"), period = readText(group / "cpu.cfs_period_us");
  if (!quota || !period) return std::nullopt;
  try {
    return cpus(std::stoll(*quota), std::stoll(*period));
  } catch (...) {
    return std::nullopt;
  }
}

// The tightest limit from `root` down along `path` ("/a/b": root, root/a, root/a/b), stopping at
// the first folder that does not exist.
template <typename Read>
auto tightest(const std::filesystem::path& root, const std::string& path, Read read) -> decltype(read(root)) {
  std::error_code ec;
  if (!std::filesystem::is_directory(root, ec)) return std::nullopt;
  decltype(read(root)) limit = read(root);
  std::filesystem::path at = root;
  std::istringstream parts(path);
  for (std::string part; std::getline(parts, part, '/');) {
    if (part.empty() || part == "." || part == "..") continue;
    at /= part;
    if (!std::filesystem::is_directory(at, ec)) break;
    if (const auto here = read(at)) limit = limit ? std::min(*limit, *here) : *here;
  }
  return limit;
}

// The tightest of `v2` over the unified hierarchy's groups and `v1` over the groups of the v1
// hierarchy whose controllers include `controller`, along the paths /proc/self/cgroup names.
template <typename T, typename ReadV2, typename ReadV1>
std::optional<T> tightestLimit(const std::string& selfCgroup, const std::filesystem::path& mount, const char* controller,
                               ReadV2 v2, ReadV1 v1) {
  std::optional<T> limit;
  const auto take = [&](std::optional<T> l) {
    if (l) limit = limit ? std::min(*limit, *l) : *l;
  };
  std::istringstream lines(selfCgroup);
  for (std::string line; std::getline(lines, line);) {
    // "ID:CONTROLLERS:PATH"; the path may hold ':' itself.
    const std::size_t a = line.find(':'), b = a == std::string::npos ? a : line.find(':', a + 1);
    if (b == std::string::npos) continue;
    const std::string controllers = line.substr(a + 1, b - a - 1), path = line.substr(b + 1);
    if (line.compare(0, a, "0") == 0 && controllers.empty()) {
      // The unified hierarchy: mounted on `mount` itself (v2), or on mount/unified beside v1
      // controllers (hybrid; there the controllers are v1's and v2's files are absent).
      take(tightest(mount, path, v2));
      continue;
    }
    std::vector<std::string> names;
    std::istringstream list(controllers);
    for (std::string c; std::getline(list, c, ',');) names.push_back(c);
    if (std::find(names.begin(), names.end(), controller) == names.end()) continue;
    // Mounted under the controller's name, or with the controllers it is joined with
    // ("cpu,cpuacct"; a symbolic link "cpu" to it on most systems).
    for (const std::string& folder : {std::string(controller), controllers}) {
      std::error_code ec;
      if (std::filesystem::is_directory(mount / folder, ec)) {
        take(tightest(mount / folder, path, v1));
        break;
      }
    }
  }
  return limit;
}

std::optional<long long> integerIn(const std::filesystem::path& file) {
  const auto text = readText(file);
  if (!text) return std::nullopt;
  try {
    std::size_t used = 0;
    const long long v = std::stoll(*text, &used);
    return v;
  } catch (...) {
    return std::nullopt;
  }
}

// The value of `key` in a memory.stat file ("key value" lines), 0 where absent.
long long statValue(const std::filesystem::path& file, const std::string& key) {
  const auto text = readText(file);
  if (!text) return 0;
  std::istringstream lines(*text);
  std::string name;
  long long value = 0;
  while (lines >> name >> value)
    if (name == key) return value;
  return 0;
}

// The limit less the usage, the file cache taken out of the usage: the kernel drops that cache
// when the group reaches its limit, and a job that had written its --mem in files (a sweep's EXRs)
// had no headroom left and was refused every frame (the review of 2026-11-29); the active part too,
// which files written and read back become (a 400 MiB group refused a 234 MiB render that then ran
// there: the hostile-input trial). Shared memory (tmpfs) is in the cache but not dropped: it stays.
std::optional<std::uint64_t> headroom(std::optional<long long> limit, std::optional<long long> usage, long long cache) {
  if (!limit || *limit < 0) return std::nullopt;
  const long long used = std::max(0LL, (usage && *usage > 0 ? *usage : 0) - std::max(0LL, cache));
  return std::uint64_t(std::max(0LL, *limit - used));
}

std::optional<std::uint64_t> v2Memory(const std::filesystem::path& group) {
  const auto max = readText(group / "memory.max");
  if (!max || max->rfind("max", 0) == 0) return std::nullopt;
  const std::filesystem::path stat = group / "memory.stat";
  return headroom(integerIn(group / "memory.max"), integerIn(group / "memory.current"),
                  statValue(stat, "file") - statValue(stat, "shmem"));
}

std::optional<std::uint64_t> v1Memory(const std::filesystem::path& group) {
  const auto limit = integerIn(group / "memory.limit_in_bytes");
  if (!limit || *limit >= (1LL << 62)) return std::nullopt;  // v1's "no limit": 2^63 rounded to pages
  const std::filesystem::path stat = group / "memory.stat";
  return headroom(limit, integerIn(group / "memory.usage_in_bytes"),
                  statValue(stat, "total_cache") - statValue(stat, "total_shmem"));
}

}  // namespace

std::optional<unsigned> cgroupCpuLimit(const std::string& selfCgroup, const std::filesystem::path& mount) {
  return tightestLimit<unsigned>(selfCgroup, mount, "cpu", v2Limit, v1Limit);
}

std::optional<std::uint64_t> cgroupMemoryHeadroom(const std::string& selfCgroup, const std::filesystem::path& mount) {
  return tightestLimit<std::uint64_t>(selfCgroup, mount, "memory", v2Memory, v1Memory);
}

std::optional<std::uint64_t> processMemoryHeadroom() {
  std::optional<std::uint64_t> least;
  if (const auto self = readText("/proc/self/cgroup")) least = cgroupMemoryHeadroom(*self, "/sys/fs/cgroup");
  rlimit limit{};
  if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    // VmSize: the address space already mapped (kB), which the limit counts.
    std::ifstream status("/proc/self/status");
    std::uint64_t mapped = 0;
    for (std::string line; std::getline(status, line);)
      if (line.rfind("VmSize:", 0) == 0) mapped = std::strtoull(line.c_str() + 7, nullptr, 10) * 1024;
    // Less what the threads a run starts will reserve: glibc's malloc arena (64 MiB of address space
    // each) and an 8 MiB stack, for the worker threads, the writers and lavapipe's own, about two
    // per CPU (the check passed under `ulimit -v 300000`, and the run ended in std::bad_alloc or
    // "Resource temporarily unavailable": the hostile-input trial of 2026-11-29).
    const std::uint64_t threads = 2 * std::uint64_t(processCpuCount()) + 2;
    const std::uint64_t reserved = mapped + threads * (std::uint64_t(72) << 20);
    const std::uint64_t left = std::uint64_t(limit.rlim_cur) > reserved ? std::uint64_t(limit.rlim_cur) - reserved : 0;
    least = least ? std::min(*least, left) : left;
  }
  return least;
}

unsigned processCpuCount() {
  cpu_set_t set;
  CPU_ZERO(&set);
  unsigned cpus = std::max(1u, std::thread::hardware_concurrency());
  if (::sched_getaffinity(0, sizeof set, &set) == 0) cpus = unsigned(std::max(1, CPU_COUNT(&set)));
  if (const auto quota = processCpuLimit()) cpus = std::min(cpus, *quota);
  return cpus;
}

std::optional<unsigned> processCpuLimit() {
  static const std::optional<unsigned> limit = [] {
    const auto self = readText("/proc/self/cgroup");
    return self ? cgroupCpuLimit(*self, "/sys/fs/cgroup") : std::nullopt;
  }();
  return limit;
}

}  // namespace dicsynth
