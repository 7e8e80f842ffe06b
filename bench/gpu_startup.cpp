// gpu_startup: how long a process needs before its first dispatch — Context creation (instance,
// device selection, logical device, pipeline cache file) and one compute pipeline.
//
//   gpu_startup [--device SEL] [--validation] [SPIRV_FILE]
//
// Without SPIRV_FILE the pipeline is tests/shaders/buffer_ops.comp (fp32); give a larger shader
// (glslc --target-env=vulkan1.2 -O x.comp -o x.spv) to see compile times that matter. The pipeline
// cache folder follows the usual rule ($DICSYNTH_CACHE_DIR, …); run twice to compare cold and warm.
// Mesa drivers keep their own on-disk shader cache ($MESA_SHADER_CACHE_DIR, default
// ~/.cache/mesa_shader_cache; MESA_SHADER_CACHE_DISABLE=true turns it off).
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "bench_args.h"
#include "gpu/buffer.h"
#include "gpu/compute.h"
#include "gpu/context.h"
#include "spirv/buffer_ops_fp32.h"

namespace {

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

std::vector<uint32_t> readSpirv(const char* path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<uint32_t> words(bytes.size() / 4);
  std::memcpy(words.data(), bytes.data(), words.size() * 4);
  return words;
}

}  // namespace

static int run(int argc, char** argv) {
  using namespace dicsynth::gpu;
  ContextOptions options;
  const char* spirvFile = nullptr;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--device") == 0 && i + 1 < argc) options.device = argv[++i];
    else if (std::strcmp(argv[i], "--validation") == 0) options.validation = true;
    else spirvFile = argv[i];
  }
  try {
    std::vector<uint32_t> fileWords = spirvFile ? readSpirv(spirvFile) : std::vector<uint32_t>{};
    std::span<const uint32_t> spirv = spirvFile ? std::span<const uint32_t>(fileWords)
                                                : std::span<const uint32_t>(dicsynth::spirv::buffer_ops_fp32);
    auto t0 = std::chrono::steady_clock::now();
    Context context(options);
    double context_ms = msSince(t0);

    // A file shader must fit buffer_ops' layout: storage buffers at bindings 0 and 1 (64 elements of
    // up to 8 bytes), push constants {uint count; float scale;}, local size ≤ 64.
    auto t1 = std::chrono::steady_clock::now();
    ComputePipeline pipeline(context, spirv, 2, 8);
    double pipeline_ms = msSince(t1);

    // Drivers may compile lazily, at the first dispatch (lavapipe does): time that too.
    Buffer in(context, 64 * 8, BufferUse::Input), out(context, 64 * 8, BufferUse::Readback);
    std::vector<char> zeros(64 * 8);
    in.upload(zeros.data(), zeros.size());
    Buffer* buffers[] = {&in, &out};
    struct { uint32_t count; float scale; } push{64, 2.0f};
    auto t2 = std::chrono::steady_clock::now();
    dispatchAndWait(context, pipeline, buffers, &push, 1);
    double dispatch_ms = msSince(t2);
    auto t2b = std::chrono::steady_clock::now();
    dispatchAndWait(context, pipeline, buffers, &push, 1);
    double secondDispatch_ms = msSince(t2b);
    auto t3 = std::chrono::steady_clock::now();
    context.savePipelineCache();
    double save_ms = msSince(t3);

    std::printf("device: %s\ncontext: %.1f ms\npipeline: %.1f ms (%zu SPIR-V words)\n",
                context.info().name.c_str(), context_ms, pipeline_ms, spirv.size());
    std::printf("first dispatch: %.2f ms, second: %.2f ms\n", dispatch_ms, secondDispatch_ms);
    std::printf("pipeline cache: %zu bytes loaded from %s; save %.1f ms\n",
                context.pipelineCacheLoadedBytes(), context.pipelineCachePath().c_str(), save_ms);
    std::printf("total: %.1f ms\n", msSince(t0));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gpu_startup: %s\n", e.what());
    return 1;
  }
  return 0;
}

int main(int argc, char** argv) {
  return dicsynth::bench::guarded([&] { return run(argc, argv); });
}
