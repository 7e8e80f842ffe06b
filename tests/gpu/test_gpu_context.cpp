// host/gpu: device listing and selection, buffers, compute pipelines, pipeline cache, validation.
// Runs on whatever Vulkan device is selected automatically (lavapipe on a machine without a GPU),
// always with VK_LAYER_KHRONOS_validation: any warning or error it reports fails the test.
#include <doctest/doctest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "core/json.h"
#include "core/error.h"
#include "run_cli.h"
#include "temp_folder.h"
#include "gpu/buffer.h"
#include "gpu/compute.h"
#include "gpu/context.h"
#include "gpu/renderer.h"
#include "gpu_test_context.h"
#include "geometry/prepared_scene.h"
#include "scene/scene.h"
#include "gpu/vk_check.h"
#include "spirv/buffer_ops_fp32.h"
#include "spirv/buffer_ops_fp64.h"

using namespace dicsynth;
using namespace dicsynth::gpu;
namespace fs = std::filesystem;

namespace {

ContextOptions testOptions(const test::TempFolder& cache) {
  ContextOptions options;
  options.validation = true;
  options.cacheDir = cache.path().string();
  return options;
}

void checkNoValidationMessages(const Context& ctx) {
  std::string all;
  for (const auto& m : ctx.validationMessages()) all += m + "\n";
  CHECK_MESSAGE(ctx.validationMessageCount() == 0, all);
}

// buffer_ops.comp's push-constant block.
struct Push {
  uint32_t count;
  float scale;
};
static_assert(sizeof(Push) == 8);

// Runs buffer_ops on `input`; the output buffer is pre-filled with `sentinel` so that elements the
// shader must not touch (index >= count) can be checked.
template <typename Real>
std::vector<Real> runBufferOps(Context& ctx, std::span<const uint32_t> spirv, const std::vector<Real>& input,
                               Push push, const std::vector<SpecConstant>& spec = {}, Real sentinel = -1) {
  Buffer in(ctx, input.size() * sizeof(Real), BufferUse::Input);
  Buffer out(ctx, input.size() * sizeof(Real), BufferUse::Readback);
  in.upload(input.data(), input.size() * sizeof(Real));
  std::vector<Real> result(input.size(), sentinel);
  out.upload(result.data(), result.size() * sizeof(Real));
  ComputePipeline pipeline(ctx, spirv, 2, sizeof(Push), spec);
  Buffer* buffers[] = {&in, &out};
  dispatchAndWait(ctx, pipeline, buffers, &push, (push.count + 63) / 64);
  out.download(result.data(), result.size() * sizeof(Real));
  return result;
}

std::vector<uint8_t> readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeFile(const fs::path& path, const std::vector<uint8_t>& data) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data.data()), static_cast<std::streamsize>(data.size()));
}

}  // namespace

TEST_CASE("gpu: listDevices finds llvmpipe with shaderFloat64") {
  std::vector<DeviceInfo> devices = listDevices();
  REQUIRE(!devices.empty());
  const DeviceInfo* lvp = nullptr;
  for (size_t i = 0; i < devices.size(); ++i) {
    CHECK(devices[i].index == i);
    if (devices[i].name.find("llvmpipe") != std::string::npos) lvp = &devices[i];
  }
  REQUIRE_MESSAGE(lvp != nullptr, "lavapipe (mesa-vulkan-drivers) is needed by the GPU tests");
  CHECK(lvp->type == "CPU");
  CHECK(lvp->driver.find("llvmpipe") == 0);
  CHECK(lvp->driver.find("Mesa") != std::string::npos);
  CHECK(lvp->apiVersion >= VK_API_VERSION_1_2);
  CHECK(lvp->shaderFloat64);
  CHECK(lvp->shaderInt64);
  CHECK(lvp->maxStorageBufferRange >= (64u << 20));
  CHECK(lvp->subgroupSize >= 1);
  CHECK(lvp->pipelineCacheUUID.size() == 32);
}

TEST_CASE("gpu: selectDevice prefers discrete GPUs and accepts index or name") {
  auto device = [](uint32_t index, std::string name, std::string type) {
    DeviceInfo d;
    d.index = index;
    d.name = std::move(name);
    d.type = std::move(type);
    d.apiVersion = VK_API_VERSION_1_3;
    return d;
  };
  std::vector<DeviceInfo> devices = {device(0, "llvmpipe (LLVM 15.0.6, 256 bits)", "CPU"),
                                     device(1, "Intel(R) UHD Graphics 630", "integrated GPU"),
                                     device(2, "NVIDIA GeForce RTX 3080", "discrete GPU")};
  CHECK(selectDevice(devices, "") == 2);
  CHECK(selectDevice({devices[0], devices[1]}, "") == 1);
  CHECK(selectDevice(devices, "0") == 0);
  CHECK(selectDevice(devices, "1") == 1);
  CHECK(selectDevice(devices, "LLVMPIPE") == 0);
  CHECK(selectDevice(devices, "uhd") == 1);
  CHECK(selectDevice(devices, "nvidia") == 2);
  CHECK_THROWS_AS(selectDevice(devices, "3"), InputError);
  CHECK_THROWS_AS(selectDevice(devices, "99999999999999999999"), InputError);
  CHECK_THROWS_AS(selectDevice(devices, "radeon"), InputError);
  try {
    selectDevice(devices, "amd");
    FAIL("no InputError");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()) ==
          "--device 'amd': no such Vulkan device; available: 0: llvmpipe (LLVM 15.0.6, 256 bits) [CPU], "
          "1: Intel(R) UHD Graphics 630 [integrated GPU], 2: NVIDIA GeForce RTX 3080 [discrete GPU]");
  }
  // A device too old for our SPIR-V loses to any usable one.
  devices[2].apiVersion = VK_API_VERSION_1_1;
  CHECK(selectDevice(devices, "") == 1);
  // No device at all is not the user's fault: Error, with the hint.
  CHECK_THROWS_AS(selectDevice({}, ""), Error);
  CHECK_THROWS_WITH(selectDevice({}, "0"), doctest::Contains("mesa-vulkan-drivers"));
}

TEST_CASE("gpu: Context selects a device by index or name, unknown names are input errors") {
  test::TempFolder cache;
  ContextOptions options = testOptions(cache);
  std::vector<DeviceInfo> devices = listDevices();
  uint32_t lvp = selectDevice(devices, "llvmpipe");
  {
    options.device = std::to_string(lvp);
    Context ctx(options);
    CHECK(ctx.validationEnabled());
    CHECK(ctx.info().index == lvp);
    CHECK(ctx.info().name == devices[lvp].name);
    CHECK(ctx.device() != VK_NULL_HANDLE);
    CHECK(ctx.queue() != VK_NULL_HANDLE);
    CHECK(ctx.commandPool() != VK_NULL_HANDLE);
    CHECK(ctx.pipelineCache() != VK_NULL_HANDLE);
    checkNoValidationMessages(ctx);
  }
  {
    options.device = "LLVMpipe";
    Context ctx(options);
    CHECK(ctx.info().name.find("llvmpipe") != std::string::npos);
    checkNoValidationMessages(ctx);
  }
  options.device = "no-such-gpu";
  CHECK_THROWS_AS(Context{options}, InputError);
  CHECK_THROWS_WITH(Context{options}, doctest::Contains("available: "));
}

TEST_CASE("gpu: DS_VK names the call, the result and the place") {
  CHECK(vkResultName(VK_ERROR_DEVICE_LOST) == "VK_ERROR_DEVICE_LOST");
  CHECK(vkResultName(static_cast<VkResult>(-12345)) == "VkResult(-12345)");
  CHECK(DS_VK(VK_TIMEOUT) == VK_TIMEOUT);  // success codes are returned, not thrown
  try {
    DS_VK(VK_ERROR_OUT_OF_DEVICE_MEMORY);
    FAIL("no Error");
  } catch (const Error& e) {
    std::string what = e.what();
    CHECK(what.find("DS_VK") == std::string::npos);
    CHECK(what.find("VK_ERROR_OUT_OF_DEVICE_MEMORY failed: VK_ERROR_OUT_OF_DEVICE_MEMORY") == 0);
    CHECK(what.find("test_gpu_context.cpp:") != std::string::npos);
  }
}

TEST_CASE("gpu: an fp32 shader doubles an array exactly") {
  test::TempFolder cache;
  Context ctx(testOptions(cache));
  std::vector<float> input(1000);  // not a multiple of the work group size
  for (size_t i = 0; i < input.size(); ++i) input[i] = 0.1f * float(i) - 17.25f;
  std::vector<float> out = runBufferOps<float>(ctx, spirv::buffer_ops_fp32, input, {1000, 2.0f});
  for (size_t i = 0; i < input.size(); ++i) REQUIRE(out[i] == 2.0f * input[i]);
  checkNoValidationMessages(ctx);
}

TEST_CASE("gpu: the fp64 variant keeps 1 + 2^-40, which float cannot hold") {
  test::TempFolder cache;
  Context ctx(testOptions(cache));
  REQUIRE(ctx.info().shaderFloat64);
  const double tiny = std::ldexp(1.0, -40);
  std::vector<SpecConstant> onePlus = {{0, 1}};
  std::vector<double> out64 = runBufferOps<double>(ctx, spirv::buffer_ops_fp64, {tiny, -tiny, 0.5}, {3, 1}, onePlus);
  CHECK(out64[0] == 1.0 + tiny);
  CHECK(out64[1] == 1.0 - tiny);
  CHECK(out64[2] == 1.5);
  CHECK(out64[0] != 1.0);
  // The same computation in the fp32 variant rounds the 2^-40 away.
  std::vector<float> out32 =
      runBufferOps<float>(ctx, spirv::buffer_ops_fp32, {float(tiny)}, {1, 1}, onePlus);
  CHECK(out32[0] == 1.0f);
  checkNoValidationMessages(ctx);
}

TEST_CASE("gpu: specialization constants change the result") {
  test::TempFolder cache;
  Context ctx(testOptions(cache));
  std::vector<float> input = {1, 2, 3, 4};
  CHECK(runBufferOps<float>(ctx, spirv::buffer_ops_fp32, input, {4, 3.0f}) == std::vector<float>{3, 6, 9, 12});
  CHECK(runBufferOps<float>(ctx, spirv::buffer_ops_fp32, input, {4, 3.0f}, {{0, 2}, {1, 100}}) ==
        std::vector<float>{103, 106, 109, 112});
  CHECK(runBufferOps<float>(ctx, spirv::buffer_ops_fp32, input, {4, 3.0f}, {{1, uint32_t(-5)}, {0, 2}}) ==
        std::vector<float>{-2, 1, 4, 7});
  CHECK_THROWS_AS(ComputePipeline(ctx, spirv::buffer_ops_fp32, 2, 8, {{0, 1}, {0, 2}}), Error);
  checkNoValidationMessages(ctx);
}

TEST_CASE("gpu: push constants reach the shader") {
  test::TempFolder cache;
  Context ctx(testOptions(cache));
  std::vector<float> input = {1, 2, 3, 4, 5};
  // count = 3: the last two outputs keep the sentinel; scale = 0.5.
  CHECK(runBufferOps<float>(ctx, spirv::buffer_ops_fp32, input, {3, 0.5f}, {}, -7.0f) ==
        std::vector<float>{0.5f, 1.0f, 1.5f, -7.0f, -7.0f});
  CHECK(runBufferOps<float>(ctx, spirv::buffer_ops_fp32, input, {5, -4.0f}) ==
        std::vector<float>{-4, -8, -12, -16, -20});
  checkNoValidationMessages(ctx);
}

TEST_CASE("gpu: dispatchAndWait reuses its resources over many dispatches") {
  test::TempFolder cache;
  Context ctx(testOptions(cache));
  constexpr uint32_t n = 256;
  std::vector<float> values(n);
  for (uint32_t i = 0; i < n; ++i) values[i] = float(i);
  Buffer a(ctx, n * sizeof(float), BufferUse::Input);
  Buffer b(ctx, n * sizeof(float), BufferUse::Readback);
  a.upload(values.data(), n * sizeof(float));
  ComputePipeline twice(ctx, spirv::buffer_ops_fp32, 2, sizeof(Push));
  // Ping-pong a → b → a …: each dispatch reads what the previous one wrote (tests the barriers).
  constexpr int kDispatches = 40;
  auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < kDispatches; ++k) {
    Buffer* buffers[] = {k % 2 ? &b : &a, k % 2 ? &a : &b};
    Push push{n, 2.0f};
    dispatchAndWait(ctx, twice, buffers, &push, n / 64);
  }
  double perDispatch_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / kDispatches;
  MESSAGE("dispatchAndWait (256 floats, validation on): ", perDispatch_ms, " ms per call");
  std::vector<float> result(n);
  a.download(result.data(), n * sizeof(float));  // an even number of dispatches ends in a
  for (uint32_t i = 0; i < n; ++i) REQUIRE(result[i] == std::ldexp(float(i), kDispatches));

  // Wrong buffer count and missing push constants are reported before anything is recorded.
  Buffer* one[] = {&a};
  Push push{n, 1.0f};
  CHECK_THROWS_AS(dispatchAndWait(ctx, twice, one, &push, 1), Error);
  Buffer* two[] = {&a, &b};
  CHECK_THROWS_AS(dispatchAndWait(ctx, twice, two, nullptr, 1), Error);
  checkNoValidationMessages(ctx);
}

TEST_CASE("gpu: buffer sizes and ranges are checked") {
  test::TempFolder cache;
  Context ctx(testOptions(cache));
  const uint64_t limit = ctx.info().maxStorageBufferRange;
  CHECK_THROWS_WITH_AS(Buffer(ctx, limit + 1, BufferUse::Input),
                       doctest::Contains((std::to_string(limit + 1) + " bytes").c_str()), Error);
  CHECK_THROWS_AS(Buffer(ctx, limit + 1, BufferUse::Readback), Error);

  Buffer buffer(ctx, 10, BufferUse::Readback);
  CHECK(buffer.size() == 10);
  char bytes[16] = {};
  CHECK_THROWS_AS(buffer.upload(bytes, 11), Error);
  CHECK_THROWS_AS(buffer.upload(bytes, 4, 7), Error);
  CHECK_THROWS_AS(buffer.download(bytes, 1, SIZE_MAX), Error);
  const char hello[] = "hello";
  buffer.upload(hello, 5, 5);
  buffer.download(bytes, 5, 5);
  CHECK(std::string(bytes, 5) == "hello");
  // write(): the bytes filled in place, at the offset, within the same range checks.
  CHECK_THROWS_AS(buffer.write(6, 5, [](void*) {}), Error);
  buffer.write(3, 1, [](void* to) { std::memcpy(to, "abc", 3); });
  buffer.download(bytes, 3, 1);
  CHECK(std::string(bytes, 3) == "abc");
  buffer.download(bytes, 5, 5);
  CHECK(std::string(bytes, 5) == "hello");  // the bytes after it untouched

  // Moving keeps the handle; an empty buffer still exists and can be bound.
  VkBuffer handle = buffer.handle();
  Buffer moved = std::move(buffer);
  CHECK(moved.handle() == handle);
  CHECK(buffer.handle() == VK_NULL_HANDLE);  // NOLINT(bugprone-use-after-move): the moved-from state
  Buffer empty(ctx, 0, BufferUse::Input);
  CHECK(empty.size() == 0);
  CHECK(empty.handle() != VK_NULL_HANDLE);
  Buffer out(ctx, 4, BufferUse::Readback);
  ComputePipeline pipeline(ctx, spirv::buffer_ops_fp32, 2, sizeof(Push));
  Buffer* buffers[] = {&empty, &out};
  Push push{0, 1.0f};
  dispatchAndWait(ctx, pipeline, buffers, &push, 1);
  checkNoValidationMessages(ctx);
}

TEST_CASE("gpu: Input buffers work through staging copies when they are not mapped") {
  test::TempFolder cache;
  ContextOptions options = testOptions(cache);
  options.mapInputBuffers = false;  // as on a discrete GPU without host-visible device memory
  Context ctx(options);
  // Partial uploads and downloads at offsets.
  std::vector<int32_t> values(100);
  for (int i = 0; i < 100; ++i) values[i] = i * i - 50;
  Buffer buffer(ctx, 100 * sizeof(int32_t), BufferUse::Input);
  buffer.upload(values.data(), 60 * sizeof(int32_t));
  buffer.upload(values.data() + 60, 40 * sizeof(int32_t), 60 * sizeof(int32_t));
  std::vector<int32_t> back(30, 0);
  buffer.download(back.data(), 30 * sizeof(int32_t), 55 * sizeof(int32_t));
  CHECK(back == std::vector<int32_t>(values.begin() + 55, values.begin() + 85));
  // write() through the staging buffer: 10 values filled in place at value 20.
  buffer.write(10 * sizeof(int32_t), 20 * sizeof(int32_t), [](void* to) {
    for (int i = 0; i < 10; ++i) static_cast<int32_t*>(to)[i] = 1000 + i;
  });
  std::vector<int32_t> all(100, 0);
  buffer.download(all.data(), 100 * sizeof(int32_t));
  for (int i = 0; i < 100; ++i) CHECK(all[std::size_t(i)] == (i >= 20 && i < 30 ? 1000 + i - 20 : values[std::size_t(i)]));
  // A shader reads what the staging copy wrote.
  std::vector<float> input = {1.5f, -2.0f, 1e30f};
  CHECK(runBufferOps<float>(ctx, spirv::buffer_ops_fp32, input, {3, 2.0f}) ==
        std::vector<float>{3.0f, -4.0f, 2e30f});
  checkNoValidationMessages(ctx);
}

TEST_CASE("gpu: the pipeline cache file is written and reloaded, bad files are ignored") {
  test::TempFolder cache;
  ContextOptions options = testOptions(cache);
  fs::path file;
  {
    Context ctx(options);
    file = ctx.pipelineCachePath();
    CHECK(file == cache.path() / ("pipelines-" + ctx.info().pipelineCacheUUID + ".bin"));
    CHECK(ctx.pipelineCacheLoadedBytes() == 0);
    ComputePipeline pipeline(ctx, spirv::buffer_ops_fp32, 2, sizeof(Push));
    ctx.savePipelineCache();
    REQUIRE(fs::exists(file));
    checkNoValidationMessages(ctx);
  }
  std::vector<uint8_t> saved = readFile(file);
  REQUIRE(saved.size() >= 32);
  MESSAGE("pipeline cache file: ", saved.size(), " bytes");
  for (const auto& entry : fs::directory_iterator(cache.path()))  // no temporary file left behind
    CHECK(entry.path() == file);
  {
    Context ctx(options);
    CHECK(ctx.pipelineCacheLoadedBytes() == saved.size());
    ComputePipeline pipeline(ctx, spirv::buffer_ops_fp32, 2, sizeof(Push));
    checkNoValidationMessages(ctx);
  }
  // Another device's cache (UUID differs) and a truncated file are not handed to the driver.
  std::vector<uint8_t> foreign = saved;
  foreign[16] ^= 0xff;
  writeFile(file, foreign);
  {
    Context ctx(options);
    CHECK(ctx.pipelineCacheLoadedBytes() == 0);
    checkNoValidationMessages(ctx);
  }
  // The destructor rewrote the file with a valid cache.
  CHECK(readFile(file).size() >= 32);
  CHECK(readFile(file)[16] == saved[16]);
  writeFile(file, std::vector<uint8_t>(saved.begin(), saved.begin() + 20));
  {
    Context ctx(options);
    CHECK(ctx.pipelineCacheLoadedBytes() == 0);
    checkNoValidationMessages(ctx);
  }
  // An unusable folder disables the cache with a warning, never an exception.
  options.cacheDir = (cache.path() / "file-not-folder").string();
  writeFile(options.cacheDir, {1, 2, 3});
  {
    Context ctx(options);
    CHECK(ctx.pipelineCacheLoadedBytes() == 0);
    ComputePipeline pipeline(ctx, spirv::buffer_ops_fp32, 2, sizeof(Push));
    CHECK_NOTHROW(ctx.savePipelineCache());
    checkNoValidationMessages(ctx);
  }
}

TEST_CASE("gpu: validation messages are counted (a layout missing a binding the shader uses)") {
  test::TempFolder cache;
  Context ctx(testOptions(cache));
  REQUIRE(ctx.validationEnabled());
  // buffer_ops uses bindings 0 and 1; a layout with only binding 0 is invalid API use.
  {
    ComputePipeline wrong(ctx, spirv::buffer_ops_fp32, 1, sizeof(Push));
  }
  CHECK(ctx.validationMessageCount() >= 1);
  std::string all;
  for (const auto& m : ctx.validationMessages()) all += m + "\n";
  MESSAGE("expected validation message(s):\n", all);
  CHECK(all.find("[error]") != std::string::npos);
}

TEST_CASE("gpu: dicsynth devices lists the devices as text and JSON") {
  std::vector<DeviceInfo> devices = listDevices();
  uint32_t automatic = selectDevice(devices, "");
  const test::CliResult listed = test::runCli("devices");
  const int code = listed.exitCode;
  const std::string& text = listed.out;
  CHECK(code == 0);
  CHECK(text.find("* " + std::to_string(automatic) + ": " + devices[automatic].name) != std::string::npos);
  CHECK(text.find("fp64 (shaderFloat64): yes") != std::string::npos);

  const test::CliResult asJson = test::runCli("devices --json --device llvmpipe");
  const int jsonCode = asJson.exitCode;
  const std::string& json = asJson.out;
  CHECK(jsonCode == 0);
  const auto parsed = json::parse(json);
  REQUIRE(parsed);
  REQUIRE(parsed->isArray());
  bool selectedLlvmpipe = false;
  for (const Json::Value& device : *parsed)
    if (json::boolMember(device, "selected") == true) {
      selectedLlvmpipe = json::stringMember(device, "name").value_or("").rfind("llvmpipe", 0) == 0;
      CHECK(json::boolMember(device, "shaderFloat64") == true);
    }
  CHECK(selectedLlvmpipe);

  CHECK(test::runCli("devices --device no-such-gpu").exitCode == 2);
}

TEST_CASE("gpu: a render that runs into lavapipe's loop limit is refused, not returned") {
  // llvmpipe ends all loops of a batch of 8 lanes after 65 535 passes in total (render.comp's
  // sentinel). 65 536 samples per pixel (256 × 256 strata) take more passes than that in the sample
  // loop alone, on any scene: the render must throw, naming the limit. On other drivers (no such
  // limit) the same render is an ordinary one.
  const PreparedScene scene =
      prepareScene(loadScene(std::string(DS_SOURCE_DIR) + "/scenes/rectangle.lua", {}), {100});  // 8 × 6 px
  gpu::Renderer renderer(test::gpuContext());
  RenderOptions options;
  options.samplesPerPixel = 65536;
  options.precision = Precision::Fp32;
  if (test::gpuContext().info().name.find("llvmpipe") == std::string::npos) {
    CHECK_NOTHROW(renderer.render(scene, options));
    return;
  }
  // Measured: Mesa 22.3 (Debian 12) limits the loops; Mesa 25.0 (bookworm-backports) does not, and
  // renders the same scene in full. Versions between: either outcome, never a silent cut.
  const std::string& driver = test::gpuContext().info().driver;
  const std::size_t at = driver.find("Mesa ");
  const int mesaMajor = at == std::string::npos ? 0 : std::atoi(driver.c_str() + at + 5);
  INFO("driver: " << driver);
  if (mesaMajor <= 22) {
    CHECK_THROWS_WITH(renderer.render(scene, options), doctest::Contains("cut the shader's loops short"));
  } else if (mesaMajor >= 25) {
    CHECK_NOTHROW(renderer.render(scene, options));
  } else {
    try {
      renderer.render(scene, options);
    } catch (const std::exception& e) {
      CHECK(std::string(e.what()).find("cut the shader's loops short") != std::string::npos);
    }
  }
  // Below the limit the same scene renders.
  options.samplesPerPixel = 16;
  CHECK_NOTHROW(renderer.render(scene, options));
}
