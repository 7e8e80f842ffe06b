#pragma once
// Whole-number knobs read from the environment (DICSYNTH_EXR_BAND_ROWS, DICSYNTH_WRITERS,
// DICSYNTH_TEXTURE_CACHE_MB): unset or empty gives `fallback`; a value that is not a whole number in
// [lo, hi] is a warning (core/warning.h) once per call, naming the variable and its range, and
// `fallback` is used (a knob tunes speed, never results: a run does not stop for it).
namespace dicsynth {

long envCount(const char* name, long fallback, long lo, long hi);

}  // namespace dicsynth
