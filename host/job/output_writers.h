#pragma once
// How many frames of a render, or points of a sweep, are derived and written at once while the
// next renders (each on a WorkerPool thread).
#include <cstdint>

namespace dicsynth {

// Writing a frame (its ground truth derived on the host, the sensor model, the EXR compressed by
// OpenEXR, whose calls keep at most 4 cores busy with the default 64-row bands) takes longer than
// rendering it on a GPU: on an NVIDIA H200 machine (16 cores) a sweep point of Figure 1 at 800x600
// took 0.127 s with one writer, of which 0.015 s rendering (bench/RESULTS.md, "GPU machines"): the
// writer set the pace. Writers in parallel put the other cores to work. One writer per 4 hardware
// threads (1 below 8 threads: on 2 cores rendering and writing already fill the machine), at most
// 8, and no more than the available memory holds beside the unit rendering: each writer holds one
// unit (a frame, or a sweep point's frames) until written; `unitBytes` is its size at render_job.h's
// kBytesPerPixelInFlight. DICSYNTH_WRITERS=N overrides it (for measuring).
unsigned outputWriters(std::uint64_t unitBytes);

}  // namespace dicsynth
