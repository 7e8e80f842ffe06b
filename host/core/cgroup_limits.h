#pragma once
// What control groups (and setrlimit) allow this process, where the machine's own figures overstate
// it. CPU: the CPU time a control group grants, as a count of CPUs: a container started with
// `docker run --cpus 2`, a Kubernetes CPU limit or a systemd CPUQuota cap the time, not the CPUs an
// affinity mask lists, so a process that starts one thread per visible CPU runs many threads on a
// slice of them, each preempted at every period's end (the planning note of 2026-11-29: "a cgroup CPU
// quota (not an affinity mask) is still not counted"). core/parallel.cpp takes the smaller of the
// two counts. Memory: the bytes a control group's limit (Slurm's --mem, `docker run --memory`) and
// the address-space limit (`ulimit -v`) leave, where /proc/meminfo's MemAvailable is the machine's:
// a render that fits the machine but not its job was killed, or ended in std::bad_alloc after its
// check had passed (the hostile-input trial of 2026-11-29; files/image_limits.h takes the least).
// No dependency but the standard library: the OpenImageIO module links this file alone.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace dicsynth {

// From the text of /proc/self/cgroup and the folder the hierarchies are mounted on (/sys/fs/cgroup):
// ceil(quota / period) of the tightest quota on the process's group and its ancestors, at least 1,
// or none without a quota. cgroup v2: "0::PATH" and PATH/cpu.max ("QUOTA PERIOD" or "max PERIOD");
// cgroup v1: the line whose controllers include "cpu" and cpu[,cpuacct]/PATH/cpu.cfs_quota_us and
// cpu.cfs_period_us (quota -1: none). A group path the mount does not show (a container whose
// namespace hides its ancestors) is read from the mount's root down to the deepest existing folder.
// Files that cannot be read or parsed count as no quota: the affinity mask still holds.
std::optional<unsigned> cgroupCpuLimit(const std::string& selfCgroup, const std::filesystem::path& mount);

// cgroupCpuLimit of this process, read once (/proc/self/cgroup, /sys/fs/cgroup).
std::optional<unsigned> processCpuLimit();

// The CPUs this process may use: its affinity mask (taskset, a Slurm or container CPU set; the
// machine's count where it cannot be read), at most processCpuLimit(). What core/parallel.h's
// hardwareThreads() is, and what processMemoryHeadroom() counts threads by.
unsigned processCpuCount();

// The bytes the tightest memory limit on the process's group and its ancestors leaves (limit minus
// usage, the file cache other than shared memory not counted as used; 0 when usage exceeds it), or
// none without a limit. v2: memory.max ("max": none), memory.current, memory.stat's file - shmem;
// v1: memory.limit_in_bytes (2^62 and more: none), memory.usage_in_bytes, memory.stat's
// total_cache - total_shmem. Read as cgroupCpuLimit reads its files.
std::optional<std::uint64_t> cgroupMemoryHeadroom(const std::string& selfCgroup, const std::filesystem::path& mount);

// The least of this process's cgroup headroom (read now: usage changes) and what `ulimit -v` leaves
// (RLIMIT_AS minus /proc/self/status's VmSize and the address space the run's threads will reserve),
// or none where neither limits it.
std::optional<std::uint64_t> processMemoryHeadroom();

}  // namespace dicsynth
