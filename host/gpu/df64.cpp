// df64 on the host: split/join, running the probe shader, the cached self-test.
#include "gpu/df64.h"
#include "gpu/device_cache.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <system_error>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/json.h"
#include "core/warning.h"
#include "gpu/buffer.h"
#include "gpu/compute.h"
#include "gpu/context.h"
#include "gpu/df64_cases.h"
#include "gpu/pipeline_cache.h"
#include "shared/bindings.h"
#include "spirv/df64_probe_fp32.h"

namespace dicsynth::gpu {

namespace fs = std::filesystem;

Df64 splitDf64(double x) {
  // From 2^128·(1 − 2^-25) on, float(x) rounds to infinity (and C++ leaves the conversion undefined).
  constexpr float kInf = std::numeric_limits<float>::infinity();
  if (std::fabs(x) >= 0x1.ffffffp127) return {x > 0 ? kInf : -kInf, 0.0f};
  const float hi = static_cast<float>(x);
  return {hi, static_cast<float>(x - static_cast<double>(hi))};
}

double joinDf64(Df64 d) { return static_cast<double>(d.hi) + static_cast<double>(d.lo); }

const Df64OpError& Df64SelfTest::worst() const {
  const auto& list = ops();
  DS_CHECK(!list.empty(), "df64 self-test without operations");
  auto unnormalized =
      std::find_if(list.begin(), list.end(), [](const Df64OpError& e) { return e.unnormalized > 0; });
  if (unnormalized != list.end()) return *unnormalized;
  return *std::max_element(list.begin(), list.end(), [](const Df64OpError& a, const Df64OpError& b) {
    return a.maxRelError < b.maxRelError;
  });
}

namespace {

// The probe's results for `items`, in chunks of at most 2^16 items per dispatch.
std::vector<Df64ProbeResult> runProbe(Context& context, std::span<const std::uint32_t> spirv, bool fma,
                                      std::span<const Df64ProbeItem> items) {
  std::vector<Df64ProbeResult> results(items.size());
  if (items.empty()) return results;
  const ComputePipeline pipeline(context, spirv, 2, sizeof(std::uint32_t),
                                 {{DS_SPEC_DF64_FMA, fma ? 1u : 0u}});
  const std::size_t chunk = std::min<std::size_t>(items.size(), 1u << 16);
  Buffer in(context, chunk * sizeof(Df64ProbeItem), BufferUse::Input);
  Buffer out(context, chunk * sizeof(Df64ProbeResult), BufferUse::Readback);
  Buffer* buffers[] = {&in, &out};
  for (std::size_t first = 0; first < items.size(); first += chunk) {
    const std::size_t n = std::min(chunk, items.size() - first);
    in.upload(items.data() + first, n * sizeof(Df64ProbeItem));
    const auto count = static_cast<std::uint32_t>(n);
    dispatchAndWait(context, pipeline, buffers, &count, static_cast<std::uint32_t>((n + 63) / 64));
    out.download(results.data() + first, n * sizeof(Df64ProbeResult));
  }
  return results;
}

bool allPassed(const std::vector<Df64OpError>& ops) {
  return !ops.empty() && std::all_of(ops.begin(), ops.end(), [](const Df64OpError& e) { return e.passed(); });
}

std::string log2Text(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "2^%.1f", std::log2(x));
  return x > 0 ? buf : "0";
}

std::string describeOp(const Df64OpError& e) {
  if (e.unnormalized > 0)
    return e.name + ": " + std::to_string(e.unnormalized) + " results not normalized (|lo| > ulp(hi)/2)";
  char buf[160];
  std::snprintf(buf, sizeof buf, "%s: max relative error %s (%.3g) > bound %s", e.name.c_str(),
                log2Text(e.maxRelError).c_str(), e.maxRelError, log2Text(kDf64MaxRelError).c_str());
  return buf;
}

}  // namespace

bool Df64SelfTest::fmaPassed() const { return fmaExact && allPassed(fma); }

namespace {

Df64SelfTest measureSelfTest(Context& context) {
  const auto start = std::chrono::steady_clock::now();
  Df64SelfTest t;
  // The Dekker pipeline also runs the fma items (fma() itself does not depend on the constant).
  const std::vector<Df64ProbeItem> items = df64::makeItems(kDf64SelfTestInputs);
  const std::vector<Df64ProbeItem> fmaItems = df64::makeFmaItems();
  std::vector<Df64ProbeItem> all = items;
  all.insert(all.end(), fmaItems.begin(), fmaItems.end());
  const std::vector<Df64ProbeResult> results = runProbe(context, spirv::df64_probe_fp32, false, all);
  const std::span<const Df64ProbeResult> resultSpan(results);
  t.dekker = df64::evaluate(items, resultSpan.first(items.size()));
  t.fmaExact = df64::fmaResultsExact(fmaItems, resultSpan.subspan(items.size()));
  if (t.fmaExact) t.fma = df64::evaluate(items, runProbe(context, spirv::df64_probe_fp32, true, items));
  t.useFma = kRendersUseFma && t.fmaPassed();
  t.passed = allPassed(t.ops());
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return t;
}

// ---- Cache file: one per device and driver version, in the pipeline cache's folder ----
// JSON (core/json.h; doubles with 17 digits read back bit-exact). The key names the device and
// driver, the probe's SPIR-V (its FNV-1a hash: any change of df64.glsl or the probe), the dicsynth
// version (the input set is host code) and the input count; a file whose key, format or operation
// list differs is ignored and rewritten.
constexpr int kCacheVersion = 3;  // 1: a line-based text format; 2: without the bounds

std::string cacheKey(const Context& context) {
  std::uint64_t hash = 0xcbf29ce484222325ull;
  for (std::uint32_t word : spirv::df64_probe_fp32)
    for (int byte = 0; byte < 4; ++byte) hash = (hash ^ ((word >> (8 * byte)) & 0xffu)) * 0x100000001b3ull;
  char buf[200];
  std::snprintf(buf, sizeof buf, "%s %08x %016llx %s %zu", context.info().pipelineCacheUUID.c_str(),
                context.properties().driverVersion, static_cast<unsigned long long>(hash), DS_VERSION,
                kDf64SelfTestInputs);
  return buf;
}

std::string serialize(const Df64SelfTest& t, const std::string& key) {
  Json::Value d(Json::objectValue);
  d["dicsynth_df64_selftest"] = kCacheVersion;
  d["key"] = key;
  d["fma_exact"] = t.fmaExact;
  d["seconds"] = json::value(t.seconds);
  auto ops = [](const std::vector<Df64OpError>& list) {
    Json::Value a(Json::arrayValue);
    for (const Df64OpError& e : list) {
      Json::Value op(Json::objectValue);
      op["name"] = e.name;
      op["max_rel_error"] = e.maxRelError;
      op["bound"] = e.bound;  // div's and sqrt's follow the device's float accuracy, measured with it
      op["inputs"] = Json::UInt64(e.inputs);
      op["unnormalized"] = Json::UInt64(e.unnormalized);
      a.append(op);
    }
    return a;
  };
  d["dekker"] = ops(t.dekker);
  d["fma"] = ops(t.fma);
  return checkedRecordText(d);
}

// The cached self-test, or false when the file is absent, damaged or for another key.
bool readCache(const std::string& path, const std::string& key, Df64SelfTest& t) {
  const auto d = readCheckedRecord(path);
  if (!d || json::countMember(*d, "dicsynth_df64_selftest") != std::uint64_t(kCacheVersion) ||
      json::stringMember(*d, "key") != key)
    return false;
  const auto fmaExact = json::boolMember(*d, "fma_exact");
  const auto seconds = json::numberMember(*d, "seconds");
  if (!fmaExact || !seconds) return false;
  t.fmaExact = *fmaExact;
  t.seconds = *seconds;
  const std::vector<Df64OpError> expected = df64::evaluate({}, {});  // the names, in order
  auto readOps = [&expected](const Json::Value& list, std::vector<Df64OpError>& out) {
    if (!list.isArray()) return false;
    for (const Json::Value& op : list) {
      if (out.size() >= expected.size() || json::stringMember(op, "name") != expected[out.size()].name) return false;
      Df64OpError e = expected[out.size()];
      const auto error = json::numberMember(op, "max_rel_error"), bound = json::numberMember(op, "bound");
      const auto inputs = json::countMember(op, "inputs"), unnormalized = json::countMember(op, "unnormalized");
      if (!error || *error < 0 || !bound || !(*bound >= 0) || !inputs || !unnormalized) return false;
      e.maxRelError = *error;
      e.bound = *bound;
      e.inputs = std::size_t(*inputs);
      e.unnormalized = std::size_t(*unnormalized);
      e.log2 = e.maxRelError > 0 ? std::log2(e.maxRelError) : -std::numeric_limits<double>::infinity();
      out.push_back(e);
    }
    return true;
  };
  if (!readOps((*d)["dekker"], t.dekker) || !readOps((*d)["fma"], t.fma) || t.dekker.size() != expected.size() ||
      t.fma.size() != (t.fmaExact ? expected.size() : 0))
    return false;
  t.useFma = kRendersUseFma && t.fmaPassed();
  t.passed = allPassed(t.ops());
  return true;
}

bool writeCache(const std::string& path, const std::string& text) {
  try {
    writeCacheFile(path, text);
    return true;
  } catch (const std::exception& e) {
    warn(std::string("df64 self-test result not cached: ") + e.what());
    return false;
  }
}

UncachedRecords<Df64SelfTest> gUncached;  // measured once a process where no file keeps them

}  // namespace

std::vector<Df64OpError> measureDf64(Context& context, std::span<const std::uint32_t> probeSpirv,
                                     const Df64ProbeOptions& options) {
  const std::vector<Df64ProbeItem> items = df64::makeItems(options.randomInputsPerOp);
  return df64::evaluate(items, runProbe(context, probeSpirv, options.fma, items));
}

bool probeFmaExact(Context& context, std::span<const std::uint32_t> probeSpirv) {
  const std::vector<Df64ProbeItem> items = df64::makeFmaItems();
  return df64::fmaResultsExact(items, runProbe(context, probeSpirv, false, items));
}

Df64SelfTest runDf64SelfTest(Context& context) {
  const std::string path = deviceCachePath(context, "df64-selftest"), key = cacheKey(context);
  Df64SelfTest cached;
  if (!path.empty() && readCache(path, key, cached)) {
    cached.fromCache = true;
    cached.cachePath = path;
    return cached;
  }
  if (std::optional<Df64SelfTest> measured = gUncached.find(context, path, key)) return *measured;
  Df64SelfTest t = measureSelfTest(context);
  t.cachePath = path;
  if (path.empty() || !writeCache(path, serialize(t, key))) gUncached.keep(context, path, key, t);
  return t;
}

Df64SelfTest requireDf64(Context& context) {
  Df64SelfTest t = runDf64SelfTest(context);
  if (!t.passed)
    throw InputError("df64: device '" + context.info().name + "' (" + context.info().driver +
                     ") fails the df64 self-test: " + describeOp(t.worst()) +
                     "; its df64 arithmetic cannot be trusted: use fp32 or fp64 on it, or another device");
  return t;
}

std::string describeDf64(const Df64SelfTest& t) {
  const Df64OpError& w = t.worst();
  if (t.passed) return "pass (worst " + log2Text(w.maxRelError) + ", " + w.name + ")";
  if (w.unnormalized > 0)
    return "FAIL (" + w.name + ": " + std::to_string(w.unnormalized) + " unnormalized results)";
  return "FAIL (" + w.name + " " + log2Text(w.maxRelError) + " > " + log2Text(kDf64MaxRelError) + ")";
}

}  // namespace dicsynth::gpu
