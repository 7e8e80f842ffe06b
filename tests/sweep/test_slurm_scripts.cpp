// scripts/slurm/*.sbatch without Slurm: run by bash with the variables a job array sets, as Slurm
// would run them, so the suite catches a change of `dicsynth sweep`'s options or of the merge
// summary the merge script reads ("manifest: C of T points complete"). The real Slurm run is
// scripts/test-slurm.sh (README "Running sweeps on a cluster").
#include <doctest/doctest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "temp_folder.h"

using dicsynth::test::TempFolder;

namespace {

const std::string kSource = DS_SOURCE_DIR;
const std::string kSweep = kSource + "/scenes/rectangle.lua OUT --downscale 8 --spp 1 --precision fp64 --sweep shift=0:0.001:3";

struct Run {
  int exitCode = -1;
  std::string out;
};

// bash SCRIPT ARGS with `env` (VAR=value ...) and DICSYNTH set; "OUT" in args is the output folder.
Run runScript(const TempFolder& dir, const std::string& env, const std::string& script) {
  std::string args = kSweep;
  args.replace(args.find("OUT"), 3, dir.file("sweep"));
  const std::string log = dir.file("log");
  const std::string command = "env -u SLURM_ARRAY_TASK_ID -u SLURM_ARRAY_TASK_COUNT -u SLURM_ARRAY_TASK_MIN "
                              "-u SLURM_ARRAY_TASK_MAX -u SLURM_ARRAY_TASK_STEP " + env +
                              " DICSYNTH=" + DS_BINARY + " bash " + kSource + "/scripts/slurm/" + script + " " + args +
                              " >" + log + " 2>&1";
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, dicsynth::test::readBytes(log)};
}

}  // namespace

TEST_CASE("slurm scripts: array tasks shard by the Slurm variables and the merge job checks completeness") {
  TempFolder dir;
  // An array 1-2 (SLURM_ARRAY_TASK_MIN=1): task 1 is shard 0 (points 0, 2), task 2 shard 1 (point 1).
  // Before any task the folder does not exist: --merge-only refuses it (exit 2, as a mistyped
  // folder) instead of creating it with an empty manifest, and the job fails.
  const Run merge0 = runScript(dir, "", "sweep-merge.sbatch");
  CHECK(merge0.exitCode == 2);
  CHECK(merge0.out.find(": no such folder: --merge-only merges the points of an existing sweep") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir.file("sweep")));
  const Run task1 = runScript(dir, "SLURM_ARRAY_TASK_ID=1 SLURM_ARRAY_TASK_COUNT=2 SLURM_ARRAY_TASK_MIN=1",
                              "sweep-array.sbatch");
  INFO(task1.out);
  REQUIRE(task1.exitCode == 0);
  CHECK(task1.out.find("dicsynth sweep: task 1 of 2") != std::string::npos);
  CHECK(std::filesystem::exists(dir.file("sweep/point_00000/point.json")));
  CHECK(std::filesystem::exists(dir.file("sweep/point_00002/point.json")));
  CHECK_FALSE(std::filesystem::exists(dir.file("sweep/point_00001")));
  const Run merge1 = runScript(dir, "", "sweep-merge.sbatch");
  CHECK(merge1.exitCode == 1);
  CHECK(merge1.out.find("sweep incomplete: 1 of 3 points missing") != std::string::npos);
  const Run task2 = runScript(dir, "SLURM_ARRAY_TASK_ID=2 SLURM_ARRAY_TASK_COUNT=2 SLURM_ARRAY_TASK_MIN=1",
                              "sweep-array.sbatch");
  INFO(task2.out);
  REQUIRE(task2.exitCode == 0);
  CHECK(std::filesystem::exists(dir.file("sweep/point_00001/point.json")));
  const Run merge2 = runScript(dir, "", "sweep-merge.sbatch");
  INFO(merge2.out);
  CHECK(merge2.exitCode == 0);
  CHECK(merge2.out.find("manifest: 3 of 3 points complete") != std::string::npos);
  // Usage errors: exit 2 before anything runs.
  TempFolder other;
  CHECK(std::system(("bash " + kSource + "/scripts/slurm/sweep-merge.sbatch >/dev/null 2>&1").c_str()) != 0);
  CHECK(std::system(("bash " + kSource + "/scripts/slurm/submit-sweep.sh 0 a.lua " + other.file("x") +
                     " >/dev/null 2>&1").c_str()) != 0);
  CHECK_FALSE(std::filesystem::exists(other.file("x")));
}
