// df64 (shaders/lib/df64.glsl) on the device against long double references, the host split/join,
// the cached self-test, and proof that the self-test fails a broken library.
#include <doctest/doctest.h>

#include <algorithm>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/json.h"
#include "core/warning.h"
#include "gpu/context.h"
#include "gpu/device_cache.h"
#include "gpu/df64.h"
#include "gpu/df64_cases.h"
#include "gpu_test_context.h"
#include "run_cli.h"
#include "shared/rng.h"
#include "spirv/df64_probe_bad_split_fp32.h"
#include "spirv/df64_probe_fp32.h"
#include "spirv/df64_probe_no_precise_fp32.h"
#include "temp_folder.h"

using namespace dicsynth;

namespace {

void report(const char* variant, const std::vector<gpu::Df64OpError>& ops) {
  for (const auto& e : ops) {
    char line[200];
    std::snprintf(line, sizeof line, "%s %-17s max rel. error 2^%6.1f  bound 2^%6.1f  (%zu inputs)", variant,
                  e.name.c_str(), e.log2, e.bound > 0 ? std::log2(e.bound) : -INFINITY, e.inputs);
    MESSAGE(line);
  }
}

// ≥ 10^5 inputs per operation; each within 2^-44 and within the bound documented in df64.glsl.
void checkAll(const char* variant, const std::vector<gpu::Df64OpError>& ops) {
  report(variant, ops);
  REQUIRE(ops.size() == 19);
  for (const auto& e : ops) {
    INFO(variant << " " << e.name);
    CHECK(e.passed());
    CHECK(e.unnormalized == 0);
    CHECK(e.maxRelError <= e.bound);
    if (e.name != "constants") CHECK(e.inputs >= 100000);
  }
}

const gpu::Df64OpError& op(const std::vector<gpu::Df64OpError>& ops, const std::string& name) {
  auto it = std::find_if(ops.begin(), ops.end(), [&](const auto& e) { return e.name == name; });
  REQUIRE(it != ops.end());
  return *it;
}

gpu::ContextOptions optionsWithCache(const test::TempFolder& folder) {
  gpu::ContextOptions o;
  o.validation = true;
  o.cacheDir = folder.path().string();
  return o;
}

void checkNoValidationMessages(const gpu::Context& ctx) {
  for (const auto& m : ctx.validationMessages()) MESSAGE("validation: " << m);
  CHECK(ctx.validationMessageCount() == 0);
}

}  // namespace

TEST_CASE("df64: every operation within 2^-44 and its documented bound (Dekker TwoProd)") {
  auto& ctx = test::gpuContext();
  checkAll("dekker", gpu::measureDf64(ctx, spirv::df64_probe_fp32, {false, 100000}));
  test::expectNoValidationMessages();
}

TEST_CASE("df64: the fma TwoProd variant where fma is exact, else Dekker only") {
  auto& ctx = test::gpuContext();
  const bool fmaExact = gpu::probeFmaExact(ctx, spirv::df64_probe_fp32);
  const auto fmaOps = gpu::measureDf64(ctx, spirv::df64_probe_fp32, {true, 100000});
  if (fmaExact) {
    checkAll("fma", fmaOps);
  } else {
    MESSAGE("fma(a, b, c) is not computed exactly on '" << ctx.info().name
                                                        << "': the fma TwoProd variant is not checked "
                                                           "against the bounds (DS_SPEC_DF64_FMA stays false)");
    // The probe's verdict is consistent: with an unfused fma, fma(a, b, −p) is 0 and a product
    // keeps float accuracy, so the fma variant fails where the Dekker one passes.
    report("fma (not exact, for information)", fmaOps);
    CHECK_FALSE(op(fmaOps, "mul").passed());
    const auto dekker = gpu::measureDf64(ctx, spirv::df64_probe_fp32, {false, 20000});
    for (const auto& e : dekker) {
      INFO(e.name);
      CHECK(e.passed());
    }
  }
  test::expectNoValidationMessages();
}

TEST_CASE("df64: the fma probe tells a fused fma from an unfused one") {
  // Host-side check of the verdict itself: correctly rounded results pass, unfused ones do not.
  const auto items = gpu::df64::makeFmaItems();
  std::vector<gpu::Df64ProbeResult> fused(items.size()), unfused(items.size());
  for (std::size_t i = 0; i < items.size(); ++i) {
    const float a = items[i].aHi[0], b = items[i].bHi[0], c = items[i].aLo[0];
    fused[i].hi[0] = std::fmaf(a, b, c);
    const float p = a * b;  // rounded: what an unfused fma computes first
    unfused[i].hi[0] = p + c;
  }
  CHECK(gpu::df64::fmaResultsExact(items, fused));
  CHECK_FALSE(gpu::df64::fmaResultsExact(items, unfused));
  CHECK(unfused[0].hi[0] == 0.0f);  // (1 + 2^-12)² − (1 + 2^-11): 2^-24 fused, 0 unfused
  CHECK(fused[0].hi[0] == 0x1p-24f);
}

TEST_CASE("df64: the div and sqrt bounds follow the device's float division and sqrt") {
  // Host-side: float items whose results are off by a known amount, and the bounds evaluate()
  // then documents (shaders/lib/df64.glsl: div ((2 + δ)² + 3)u², sqrt (ε²/2 + (1 + δ)ε + 1)u²,
  // ε = σ + 1/2).
  auto bound = [](const std::vector<gpu::Df64OpError>& ops, const char* name) {
    for (const auto& e : ops)
      if (e.name == name) return e.bound / 0x1p-48;
    FAIL("no operation " << name);
    return 0.0;
  };
  // No float items: correct rounding (δ = σ = 1), the table's 12u² and 5.125u².
  const auto none = gpu::df64::evaluate({}, {});
  CHECK(bound(none, "div") == 12.0);
  CHECK(bound(none, "div_scalar") == 12.0);
  CHECK(bound(none, "sqrt") == 5.125);
  CHECK(bound(none, "mul") == 8.0);  // the others keep their constants

  auto item = [](int op, float a, float b) {
    gpu::Df64ProbeItem it{};
    it.op = std::uint32_t(op);
    it.width = 1;
    it.aHi[0] = a;
    it.bHi[0] = b;
    return it;
  };
  // 1/3 two ulps above its float (fl(1/3) is 1/3 ulp high, an ulp there 2^-25: 7/3 · 2^-25 over
  // 1/3 = 3.5u) and sqrt(2) correctly rounded (≤ 1u, counted as 1).
  std::vector<gpu::Df64ProbeItem> items = {item(DS_DF64_OP_FLOAT_DIV, 1.0f, 3.0f), item(DS_DF64_OP_FLOAT_SQRT, 2.0f, 0.0f)};
  std::vector<gpu::Df64ProbeResult> results(2);
  results[0].hi[0] = std::nextafter(std::nextafter(1.0f / 3.0f, 1.0f), 1.0f);
  results[1].hi[0] = std::sqrt(2.0f);
  const gpu::df64::FloatAccuracy f = gpu::df64::floatAccuracy(items, results);
  const long double third = 1.0L / 3;
  const double expectedDiv = double(((long double)(results[0].hi[0]) - third) / third / 0x1p-24L);
  CHECK(f.divU == doctest::Approx(expectedDiv).epsilon(1e-12));
  CHECK(f.divU > 3.4);
  CHECK(f.divU < 3.6);
  CHECK(f.sqrtU == 1.0);
  const auto measured = gpu::df64::evaluate(items, results);
  CHECK(bound(measured, "div") == doctest::Approx((2 + f.divU) * (2 + f.divU) + 3));
  CHECK(bound(measured, "sqrt") == doctest::Approx(1.5 * 1.5 / 2 + (1 + f.divU) * 1.5 + 1));
  // Beyond what Vulkan allows (a NaN division, a sqrt 100 ulps off): the bounds stop growing at the
  // specification's 5u and 9u, so such a device fails them instead of loosening them.
  results[0].hi[0] = NAN;
  results[1].hi[0] = std::sqrt(2.0f) * (1.0f + 100 * 0x1p-23f);
  const gpu::df64::FloatAccuracy g = gpu::df64::floatAccuracy(items, results);
  CHECK(g.divU == 5.0);
  CHECK(g.sqrtU == 9.0);
}

TEST_CASE("df64: host split and join") {
  // Doubles of every exponent float can hold with lo normal: |x − (hi + lo)| ≤ 2^-48 |x|.
  double worst = 0;
  std::size_t inexactJoins = 0, unnormalized = 0;
  for (std::uint32_t i = 0; i < 200000; ++i) {
    const double m = 1.0 + double(ds_hash(2 * i) >> 6) * 0x1p-26 + double(ds_hash(2 * i + 1) >> 6) * 0x1p-52;
    const int e = -100 + int(ds_hash(~i) % 228);  // 2^-100 … 2^127
    const double x = (i & 1 ? -1 : 1) * std::ldexp(m, e);
    const gpu::Df64 d = gpu::splitDf64(x);
    const long double sum = (long double)d.hi + (long double)d.lo;
    inexactJoins += gpu::joinDf64(d) != sum;
    unnormalized += float(d.hi + d.lo) != d.hi;
    worst = std::max(worst, double(std::fabs(x - sum) / std::fabs(x)));
  }
  MESSAGE("split/join worst relative error 2^" << std::log2(worst));
  CHECK(worst <= 0x1p-48);
  CHECK(inexactJoins == 0);
  CHECK(unnormalized == 0);
  // A float splits into itself and 0.
  for (float f : {0.0f, -0.0f, 1.0f, 0x1p-149f, FLT_MIN, FLT_MAX, -3.1415927f, 0x1.fffffep-1f}) {
    const gpu::Df64 d = gpu::splitDf64(f);
    CHECK(d.hi == f);
    CHECK(d.lo == 0.0f);
    CHECK(std::signbit(d.hi) == std::signbit(f));
    CHECK(gpu::joinDf64(d) == double(f));
  }
  // Just inside float's range, and beyond it (where float rounding overflows).
  CHECK(gpu::splitDf64(double(FLT_MAX) * (1 + 0x1p-30)).hi == FLT_MAX);
  CHECK(std::isinf(gpu::splitDf64(0x1p128).hi));
  CHECK(gpu::splitDf64(-0x1p200).hi == -INFINITY);
}

TEST_CASE("df64: a self-test that cannot be cached is measured once a process, and said once") {
  // A cache folder that cannot be written (here: a file stands where it goes): the calibration and
  // each df64 render asked again, measured again and warned again (3 times a run, the cache audit
  // of 2026-11-28).
  test::TempFolder folder;
  gpu::Context ctx(test::unwritableCacheOptions(folder));
  WarningCapture warnings;
  const gpu::Df64SelfTest first = gpu::runDf64SelfTest(ctx);
  const gpu::Df64SelfTest second = gpu::runDf64SelfTest(ctx);
  CHECK(first.passed);
  CHECK_FALSE(second.fromCache);
  CHECK(second.seconds == first.seconds);  // the same measurement, not a second one
  const std::vector<std::string> said = warnings.take();
  REQUIRE(said.size() == 1);
  CHECK(said[0].rfind("df64 self-test result not cached: ", 0) == 0);
}

TEST_CASE("df64: the self-test is cached per device and ignores a damaged cache file") {
  test::TempFolder folder;
  gpu::Context ctx(optionsWithCache(folder));

  const auto start = std::chrono::steady_clock::now();
  const gpu::Df64SelfTest first = gpu::runDf64SelfTest(ctx);
  const double firstSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  CHECK_FALSE(first.fromCache);
  CHECK(first.passed);
  MESSAGE("self-test on " << ctx.info().name << ": " << gpu::describeDf64(first) << ", fma exact: "
                          << std::string(first.fmaExact ? "yes" : "no") << ", " << firstSeconds * 1e3
                          << " ms, cache " << first.cachePath);
  // Renders use Dekker's split on every device, fma exact or not (gpu::kRendersUseFma, df64.h).
  CHECK_FALSE(first.useFma);
  REQUIRE(!first.cachePath.empty());
  CHECK(std::filesystem::path(first.cachePath).parent_path() == folder.path());
  CHECK(first.cachePath.find(ctx.info().pipelineCacheUUID) != std::string::npos);
  REQUIRE(std::filesystem::exists(first.cachePath));

  // Second call (and a second Context on the same device): read from the file, same numbers.
  const auto again = std::chrono::steady_clock::now();
  const gpu::Df64SelfTest second = gpu::runDf64SelfTest(ctx);
  const double secondSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - again).count();
  MESSAGE("cached read: " << secondSeconds * 1e3 << " ms");
  CHECK(second.fromCache);
  CHECK(second.passed == first.passed);
  CHECK(second.fmaExact == first.fmaExact);
  CHECK(second.useFma == first.useFma);
  REQUIRE(second.dekker.size() == first.dekker.size());
  for (std::size_t i = 0; i < first.dekker.size(); ++i) {
    CHECK(second.dekker[i].name == first.dekker[i].name);
    CHECK(second.dekker[i].maxRelError == first.dekker[i].maxRelError);  // bit-exact (%a)
    CHECK(second.dekker[i].bound == first.dekker[i].bound);
  }
  {
    gpu::Context other(optionsWithCache(folder));
    CHECK(gpu::runDf64SelfTest(other).fromCache);
    checkNoValidationMessages(other);
  }

  const std::string valid = test::readBytes(first.cachePath);
  const auto document = json::parse(valid);
  REQUIRE(document);
  // The entry of the Dekker variant's operation `name`, edited by `edit`, as cache text: with its
  // checksum made again (the record dicsynth would write with those values) or the old one kept
  // (a file changed on disk).
  auto edited = [&document](const std::string& name, const std::function<void(Json::Value&)>& edit,
                            bool checksumAgain = true) {
    Json::Value d = *document;
    bool found = false;
    for (Json::Value& op : d["dekker"])
      if (op["name"].asString() == name) {
        edit(op);
        found = true;
      }
    REQUIRE(found);
    return checksumAgain ? gpu::checkedRecordText(d) : json::write(d);
  };
  // Damaged: garbage, truncated, a number that is no number, a missing member, a changed digit
  // under the old checksum (the cache audit: one byte, e-15 to e-13, made --precision df64 blame
  // the device), no checksum. Each is ignored and rewritten.
  const std::string badNumber = edited("mul", [](Json::Value& op) { op["max_rel_error"] = "0x1pZZ"; });
  const std::string missing = edited("mul", [](Json::Value& op) { op.removeMember("inputs"); });
  const std::string noBound = edited("div", [](Json::Value& op) { op.removeMember("bound"); });
  const std::string changedDigit =
      edited("div", [](Json::Value& op) { op["max_rel_error"] = op["max_rel_error"].asDouble() * 100; }, false);
  Json::Value unchecked = *document;
  unchecked.removeMember("checksum");
  for (const std::string& damaged : {std::string("not a cache\n"), valid.substr(0, valid.size() / 2), badNumber,
                                     missing, noBound, changedDigit, json::write(unchecked)}) {
    test::writeBytes(first.cachePath, damaged);
    const gpu::Df64SelfTest remeasured = gpu::runDf64SelfTest(ctx);
    CHECK_FALSE(remeasured.fromCache);
    CHECK(remeasured.passed);
    CHECK(gpu::runDf64SelfTest(ctx).fromCache);  // rewritten
  }

  // div's and sqrt's bounds follow the device's float division and sqrt, measured with the errors:
  // the cache keeps them. Before it did, a cached read gave the bounds of correctly rounded ones (on
  // an NVIDIA H200: div 4.3e-14 read back where 7.1e-14 was measured). A bound other than this
  // device's is read back as written.
  {
    double divBound = 0;
    for (const gpu::Df64OpError& e : first.dekker)
      if (e.name == "div") divBound = e.bound;
    REQUIRE(divBound > 0);
    test::writeBytes(first.cachePath, edited("div", [divBound](Json::Value& op) { op["bound"] = 1.5 * divBound; }));
    const gpu::Df64SelfTest looser = gpu::runDf64SelfTest(ctx);
    CHECK(looser.fromCache);
    for (const gpu::Df64OpError& e : looser.dekker)
      if (e.name == "div") CHECK(e.bound == 1.5 * divBound);
  }

  // A valid entry claiming a failure: requireDf64 refuses df64, naming the operation, error, bound.
  const std::string failing = edited("div", [](Json::Value& op) {
    op["max_rel_error"] = std::ldexp(1.0, -40);
    op["inputs"] = 100;
    op["unnormalized"] = 0;
  });
  test::writeBytes(first.cachePath, failing);
  const gpu::Df64SelfTest failed = gpu::runDf64SelfTest(ctx);
  CHECK(failed.fromCache);
  CHECK_FALSE(failed.useFma);  // the Dekker variant is the one in use
  CHECK_FALSE(failed.passed);
  CHECK(gpu::describeDf64(failed) == "FAIL (div 2^-40.0 > 2^-44.0)");
  CHECK_THROWS_WITH_AS(gpu::requireDf64(ctx),
                       doctest::Contains("div: max relative error 2^-40.0 (9.09e-13) > bound 2^-44.0"),
                       InputError);
  test::writeBytes(first.cachePath, valid);
  CHECK_NOTHROW(gpu::requireDf64(ctx));
  checkNoValidationMessages(ctx);
}

TEST_CASE("device cache: the key tells driver releases apart that report one UUID and version") {
  // Mesa 22.3.6's lavapipe reports the pipeline-cache UUID "val-%s" (76616c2d2573...) and driver
  // version 1 in every release; only its driverInfo ("Mesa 22.3.6 (LLVM 15.0.6)") names the
  // release. A 22.3.7 must not read 22.3.6's self-test and calibration.
  const std::string uuid = "76616c2d257300000000000000000000";
  const std::string a = gpu::deviceKey(uuid, 1, "llvmpipe Mesa 22.3.6 (LLVM 15.0.6)");
  const std::string b = gpu::deviceKey(uuid, 1, "llvmpipe Mesa 22.3.7 (LLVM 15.0.6)");
  CHECK(a != b);
  CHECK(a.rfind(uuid + "-00000001-", 0) == 0);
  CHECK(a.size() == uuid.size() + 18);  // "-" 8 hex digits "-" 8 hex digits
  CHECK(gpu::deviceKey(uuid, 2, "llvmpipe Mesa 22.3.6 (LLVM 15.0.6)") != a);
  CHECK(gpu::deviceKey(uuid, 1, "llvmpipe Mesa 22.3.6 (LLVM 15.0.6)") == a);  // stable: the cache is found again
  // The Context's key is this function of its own device's values.
  gpu::Context ctx(gpu::ContextOptions{});
  CHECK(gpu::deviceKey(ctx) == gpu::deviceKey(ctx.info().pipelineCacheUUID, ctx.properties().driverVersion, ctx.info().driver));
}

TEST_CASE("df64: the self-test fails a library with a broken split constant") {
  // df64_probe_bad_split.comp: Dekker's split by 4096 instead of 4097, wrong only for operands
  // within 2^-12 above a power of two. The hard cases ((1 + 2^-12)², …) catch it in every
  // product-based operation that meets such an operand (a test that cannot fail is not a test).
  auto& ctx = test::gpuContext();
  const auto ops = gpu::measureDf64(ctx, spirv::df64_probe_bad_split_fp32, {false, gpu::kDf64SelfTestInputs});
  report("bad split", ops);
  for (const std::string name : {"mul", "mul_float", "mul_scalar", "mul_scalar_float", "sqrt"}) {
    INFO(name);
    CHECK_FALSE(op(ops, name).passed());
    CHECK(op(ops, name).maxRelError > 0x1p-30);
  }
  // Sums do not use TwoProd and stay right: the failure is attributed to the broken operations.
  CHECK(op(ops, "add").passed());
  gpu::Df64SelfTest t;
  t.dekker = ops;
  CHECK(gpu::describeDf64(t) == "FAIL (mul 2^-24.0 > 2^-44.0)");
  test::expectNoValidationMessages();
}

TEST_CASE("df64: the self-test fails a library compiled without precise (on lavapipe)") {
  // df64_probe_no_precise.comp: no NoContraction. Whether a compiler then breaks the error-free
  // transformations is its choice; lavapipe's does (docs/design.md §4), so there the self-test must fail.
  auto& ctx = test::gpuContext();
  const auto ops = gpu::measureDf64(ctx, spirv::df64_probe_no_precise_fp32, {false, gpu::kDf64SelfTestInputs});
  report("no precise", ops);
  const bool allPassed = std::all_of(ops.begin(), ops.end(), [](const auto& e) { return e.passed(); });
  if (ctx.info().name.find("llvmpipe") != std::string::npos) {
    CHECK_FALSE(allPassed);
    CHECK_FALSE(op(ops, "add").passed());
    CHECK_FALSE(op(ops, "mul").passed());
  } else {
    MESSAGE("'" << ctx.info().name << "' without precise: "
                << std::string(allPassed ? "every operation passes" : "fails"));
  }
  test::expectNoValidationMessages();
}

TEST_CASE("df64: dicsynth devices reports the self-test per device") {
  const test::CliResult text = test::runCli("devices");
  CHECK(text.exitCode == 0);
  CHECK(text.out.find("df64 self-test:       pass (worst 2^-") != std::string::npos);
  CHECK(text.out.find("fma exact:            ") != std::string::npos);
  const test::CliResult json = test::runCli("devices --json");
  CHECK(json.exitCode == 0);
  const auto devices = json::parse(json.out);
  REQUIRE(devices);
  REQUIRE(devices->isArray());
  REQUIRE(devices->size() >= 1);
  for (const Json::Value& device : *devices) {
    CHECK(json::boolMember(device, "df64_pass") == true);
    const auto worst = json::numberMember(device, "df64_worst_log2");
    REQUIRE(worst);
    CHECK(*worst < -40);  // the df64 bound is 2^-44 (shaders/lib/df64.glsl)
    CHECK(json::stringMember(device, "df64_worst_op"));
    CHECK(json::boolMember(device, "fma_exact"));
  }
  CHECK(json.err.empty());
}
