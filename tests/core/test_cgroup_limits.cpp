// core/cgroup_limits.h: the CPUs a control group's quota grants, read from fake /proc/self/cgroup texts
// and cgroup trees in a temporary folder (cgroup v2, v1, a joint cpu,cpuacct mount, quotas on
// ancestors, unlimited and unreadable files). Until 2026-11-29 only the affinity mask was counted,
// so `docker run --cpus 2` on a 64-CPU host ran 64 threads (the planning note).
#include <doctest/doctest.h>

#include <string>

#include "core/cgroup_limits.h"
#include "temp_folder.h"

using namespace dicsynth;

TEST_CASE("cgroup limits: cgroup v2's cpu.max, the tightest of the group and its ancestors, rounded up") {
  test::TempFolder dir;
  const std::filesystem::path mount = dir.path();
  // No quota anywhere, and "max": none.
  dir.write("a/b/cpu.max", "max 100000\n");
  CHECK_FALSE(cgroupCpuLimit("0::/a/b\n", mount).has_value());
  // 2.5 CPUs on the group: 3 threads; 1.5 on the parent wins: 2.
  dir.write("a/b/cpu.max", "250000 100000\n");
  CHECK(cgroupCpuLimit("0::/a/b\n", mount) == 3u);
  dir.write("a/cpu.max", "150000 100000\n");
  CHECK(cgroupCpuLimit("0::/a/b\n", mount) == 2u);
  // Less than one CPU: one thread.
  dir.write("a/cpu.max", "20000 100000\n");
  CHECK(cgroupCpuLimit("0::/a/b\n", mount) == 1u);
  // A namespace that hides the ancestors: its root's own file holds ("0::/" inside a container).
  test::TempFolder ns;
  ns.write("cpu.max", "400000 100000\n");
  CHECK(cgroupCpuLimit("0::/\n", ns.path()) == 4u);
  // A path the mount does not show: read down to the deepest existing folder.
  CHECK(cgroupCpuLimit("0::/system.slice/docker-1.scope\n", ns.path()) == 4u);
  // A quota beyond any machine counts as 2^20 CPUs, not as 0 threads (the review of 2026-11-29).
  ns.write("cpu.max", "4294967296000 1000\n");
  CHECK(cgroupCpuLimit("0::/\n", ns.path()) == 1u << 20);
  // Nonsense and unreadable files count as no quota.
  ns.write("cpu.max", "lots 100000\n");
  CHECK_FALSE(cgroupCpuLimit("0::/\n", ns.path()).has_value());
  ns.write("cpu.max", "100000 0\n");
  CHECK_FALSE(cgroupCpuLimit("0::/\n", ns.path()).has_value());
  CHECK_FALSE(cgroupCpuLimit("", ns.path()).has_value());
  CHECK_FALSE(cgroupCpuLimit("0::/\n", dir.file("no-such-mount")).has_value());
}

TEST_CASE("cgroup limits: cgroup v1's cfs quota and period, under cpu or cpu,cpuacct, -1 for none") {
  test::TempFolder dir;
  const std::string self = "12:memory:/job\n4:cpu,cpuacct:/slurm/job_7\n0::/\n";
  dir.write("cpu,cpuacct/cpu.cfs_quota_us", "-1\n");
  dir.write("cpu,cpuacct/cpu.cfs_period_us", "100000\n");
  dir.write("cpu,cpuacct/slurm/job_7/cpu.cfs_quota_us", "-1\n");
  dir.write("cpu,cpuacct/slurm/job_7/cpu.cfs_period_us", "100000\n");
  CHECK_FALSE(cgroupCpuLimit(self, dir.path()).has_value());
  dir.write("cpu,cpuacct/slurm/job_7/cpu.cfs_quota_us", "300000\n");
  CHECK(cgroupCpuLimit(self, dir.path()) == 3u);
  // The controller named alone ("N:cpu:PATH", mounted as cpu), the line's controllers in any order.
  test::TempFolder alone;
  alone.write("cpu/x/cpu.cfs_quota_us", "50000\n");
  alone.write("cpu/x/cpu.cfs_period_us", "50000\n");
  CHECK(cgroupCpuLimit("3:cpuacct,cpu:/x\n", alone.path()) == 1u);
  // Another controller's line is not read ("cpuset" is not "cpu").
  CHECK_FALSE(cgroupCpuLimit("3:cpuset:/x\n", alone.path()).has_value());
}

TEST_CASE("cgroup limits: the memory a group's limit leaves, v2 and v1, the tightest of the group and its ancestors") {
  test::TempFolder v2;
  v2.write("job/memory.max", "max\n");
  v2.write("job/memory.current", "1000\n");
  CHECK_FALSE(cgroupMemoryHeadroom("0::/job\n", v2.path()).has_value());
  v2.write("job/memory.max", "4096\n");
  CHECK(cgroupMemoryHeadroom("0::/job\n", v2.path()) == 3096u);
  v2.write("job/step/memory.max", "max\n");
  v2.write("job/step/memory.current", "10\n");
  CHECK(cgroupMemoryHeadroom("0::/job/step\n", v2.path()) == 3096u);  // the parent's limit holds
  v2.write("job/memory.current", "5000\n");  // over its limit: nothing left, not a wrapped number
  CHECK(cgroupMemoryHeadroom("0::/job\n", v2.path()) == 0u);
  // The file cache is not in use, but for shared memory: the kernel drops it at the limit (a job
  // that had written its limit in files was refused every frame: the review and the hostile-input
  // trial of 2026-11-29).
  v2.write("job/memory.stat", "anon 1000\nfile 3900\nshmem 300\nactive_file 100\ninactive_file 3500\n");
  CHECK(cgroupMemoryHeadroom("0::/job\n", v2.path()) == 4096u - (5000u - 3600u));  // shared memory stays used
  test::TempFolder v1;
  const std::string self = "9:memory:/slurm/uid_0/job_3\n4:cpu,cpuacct:/slurm\n";
  v1.write("memory/slurm/uid_0/job_3/memory.limit_in_bytes", "9223372036854771712\n");  // v1's "none"
  v1.write("memory/slurm/uid_0/job_3/memory.usage_in_bytes", "100\n");
  CHECK_FALSE(cgroupMemoryHeadroom(self, v1.path()).has_value());
  v1.write("memory/slurm/uid_0/job_3/memory.limit_in_bytes", "2147483648\n");
  CHECK(cgroupMemoryHeadroom(self, v1.path()) == 2147483548u);
  v1.write("memory/slurm/uid_0/job_3/memory.usage_in_bytes", "2000000000\n");
  v1.write("memory/slurm/uid_0/job_3/memory.stat", "cache 1900000000\ntotal_cache 1800000000\ntotal_shmem 100000000\n"
                                                     "total_inactive_file 1500000000\n");
  CHECK(cgroupMemoryHeadroom(self, v1.path()) == 2147483648u - 300000000u);
  // The cpu line is not the memory controller's.
  CHECK_FALSE(cgroupMemoryHeadroom("4:cpu,cpuacct:/slurm/uid_0/job_3\n", v1.path()).has_value());
}
