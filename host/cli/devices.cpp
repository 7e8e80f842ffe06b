// `dicsynth devices`: the Vulkan devices this machine offers, and which one a render would use.
//
//   dicsynth devices                    one block per device; '*' marks the automatic choice
//   dicsynth devices --device NVIDIA    marks the device that selector picks (errors as render does)
//   dicsynth devices --json             the same as a JSON array of objects
//
// Per device: index, name, type, driver, Vulkan version, fp64 (shaderFloat64), int64 (shaderInt64),
// largest storage buffer, subgroup size. fp64 decides whether the native double-precision shader
// variant can run on the device. Also the df64 self-test (host/gpu/df64.h): whether double-float
// arithmetic is right on the device, its worst operation, and whether fma() is exact there (then
// df64 products use it). That needs a Vulkan context per device; the result is cached per device
// and driver version next to the pipeline cache, so only the first listing pays for it. And the
// precision calibration behind `--precision auto` (render/precision_calibration.h): each
// precision's speed and geometric error on a small fixed scene, also cached.
// Devices below Vulkan 1.2 are listed with a note instead.
#include <cmath>
#include <cstdio>
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "core/json.h"
#include "core/error.h"
#include "gpu/bundled_driver.h"
#include "gpu/context.h"
#include "gpu/df64.h"
#include "gpu/renderer.h"
#include "render/precision_calibration.h"
#include "gpu/device_query.h"

namespace dicsynth::cli {

namespace {

struct DevicesOptions {
  std::string device;
  bool json = false;
};

double mebibytes(uint64_t bytes) { return static_cast<double>(bytes) / (1024.0 * 1024.0); }

const char* yesNo(bool b) { return b ? "yes" : "no"; }

// The df64 self-test and the precision calibration of one device (both cached per device), or
// why there are none.
struct Df64Status {
  std::optional<gpu::Df64SelfTest> selfTest;
  std::optional<PrecisionCalibration> calibration;
  std::string note;  // when there is no self-test
};

Df64Status df64Status(const gpu::DeviceInfo& d) {
  if (d.apiVersion < VK_API_VERSION_1_2) return {std::nullopt, std::nullopt, "skipped (Vulkan below 1.2)"};
  try {
    gpu::ContextOptions options;
    options.device = std::to_string(d.index);
    gpu::Context context(options);
    gpu::Renderer renderer(context);
    return {gpu::runDf64SelfTest(context), calibratePrecisions(context, renderer), ""};
  } catch (const std::exception& e) {
    return {std::nullopt, std::nullopt, std::string("not run: ") + e.what()};
  }
}

void printText(const std::vector<gpu::DeviceInfo>& devices, const std::vector<Df64Status>& df64,
               uint32_t selected, const std::string& selector) {
  for (const auto& d : devices) {
    std::string version = gpu::apiVersionString(d.apiVersion);
    if (d.apiVersion < VK_API_VERSION_1_2) version += " (dicsynth needs 1.2)";
    std::printf("%s %u: %s\n", d.index == selected ? "*" : " ", d.index, d.name.c_str());
    std::printf("    type:                 %s\n", d.type.c_str());
    std::printf("    driver:               %s\n", d.driver.c_str());
    std::printf("    Vulkan:               %s\n", version.c_str());
    std::printf("    fp64 (shaderFloat64): %s\n", yesNo(d.shaderFloat64));
    std::printf("    int64 (shaderInt64):  %s\n", yesNo(d.shaderInt64));
    std::printf("    max storage buffer:   %.6g MiB\n", mebibytes(d.maxStorageBufferRange));
    std::printf("    subgroup size:        %u\n", d.subgroupSize);
    const Df64Status& status = df64[d.index];
    if (status.selfTest) {
      std::printf("    df64 self-test:       %s\n", gpu::describeDf64(*status.selfTest).c_str());
      const gpu::Df64SelfTest& t = *status.selfTest;
      std::printf("    fma exact:            %s\n",
                  !t.fmaExact ? "no (df64 products use Dekker's split)"
                  : t.useFma  ? "yes (df64 products use fma)"
                  : !t.fmaPassed()
                      ? "yes, but the fma variant failed (Dekker's split)"
                      : "yes (the fma variant passes the probe; renders use Dekker's split, docs/design.md §4)");
    } else {
      std::printf("    df64 self-test:       %s\n", status.note.c_str());
    }
    if (status.calibration)
      std::printf("    calibration:          %s%s\n", status.calibration->fromCache ? "(cached) " : "",
                  describeCalibration(*status.calibration).c_str());
  }
  if (selector.empty())
    std::printf("* = automatic choice (discrete GPU > integrated > virtual > CPU; of two drivers of one device, "
                "the newer); --device overrides\n");
  else
    std::printf("* = selected by --device '%s'\n", selector.c_str());
  if (const auto& bundled = gpu::addBundledDriver())
    std::printf("dicsynth's own lavapipe is among them: %s (scripts/install-lavapipe.sh; DICSYNTH_LAVAPIPE=system "
                "leaves it out)\n", bundled->c_str());
}

void printJson(const std::vector<gpu::DeviceInfo>& devices, const std::vector<Df64Status>& df64,
               uint32_t selected) {
  Json::Value list(Json::arrayValue);
  for (const gpu::DeviceInfo& d : devices) {
    Json::Value o(Json::objectValue);
    o["index"] = d.index;
    o["name"] = d.name;
    o["type"] = d.type;
    o["driver"] = d.driver;
    o["vulkan"] = gpu::apiVersionString(d.apiVersion);
    o["vendorID"] = d.vendorID;
    o["deviceID"] = d.deviceID;
    o["shaderFloat64"] = d.shaderFloat64;
    o["shaderInt64"] = d.shaderInt64;
    o["maxStorageBufferRange"] = Json::UInt64(d.maxStorageBufferRange);
    o["maxStorageBuffer_MiB"] = json::value(mebibytes(d.maxStorageBufferRange));
    o["subgroupSize"] = d.subgroupSize;
    o["pipelineCacheUUID"] = d.pipelineCacheUUID;
    const Df64Status& status = df64[d.index];
    if (status.selfTest) {
      const gpu::Df64OpError& worst = status.selfTest->worst();
      o["df64_pass"] = status.selfTest->passed;
      o["df64_worst_log2"] = json::value(worst.log2);  // null when every result was exact
      o["df64_worst_op"] = worst.name;
      o["fma_exact"] = status.selfTest->fmaExact;
    } else {
      for (const char* name : {"df64_pass", "df64_worst_log2", "df64_worst_op", "fma_exact"}) o[name] = Json::nullValue;
      o["df64_note"] = status.note;
    }
    Json::Value& precisions = o["precisions"] = Json::Value(Json::arrayValue);
    if (status.calibration)
      for (const PrecisionMeasurement& m : status.calibration->modes) {
        Json::Value p(Json::objectValue);
        p["precision"] = toString(m.precision);
        p["available"] = m.available;
        p["unavailable"] = m.unavailable;  // why not ("" when available)
        // null for a precision not measured: 0.0 read as "exact" (the preview audit of 2026-11-28).
        p["mrays_per_s"] = m.available ? json::value(m.mraysPerSecond) : Json::Value(Json::nullValue);
        p["max_error_px"] = m.available ? json::value(m.maxErrorPx) : Json::Value(Json::nullValue);
        precisions.append(p);
      }
    o["selected"] = d.index == selected;
    list.append(o);
  }
  std::fputs(json::write(list).c_str(), stdout);
}

int runDevices(const DevicesOptions& options) {
  std::vector<gpu::DeviceInfo> devices = gpu::listDevices();
  uint32_t selected = gpu::selectDevice(devices, options.device);  // throws as render would
  std::vector<Df64Status> df64;
  for (const auto& d : devices) df64.push_back(df64Status(d));
  if (options.json)
    printJson(devices, df64, selected);
  else
    printText(devices, df64, selected, options.device);
  return kExitOk;
}

}  // namespace

void addDevicesCommand(CLI::App& root, RunFn& run) {
  auto options = std::make_shared<DevicesOptions>();
  auto* sub = root.add_subcommand("devices", "List Vulkan devices and mark the one a render would use");
  sub->add_option("--device", options->device,
                  "Show which device this selector picks: an index or a case-insensitive name part");
  sub->add_flag("--json", options->json, "Print a JSON array instead of text");
  sub->callback([&run, options] { run = [options] { return runDevices(*options); }; });
}

}  // namespace dicsynth::cli
