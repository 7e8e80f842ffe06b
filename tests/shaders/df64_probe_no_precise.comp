#version 460
// A deliberately broken df64 library: no `precise` (SPIR-V NoContraction) on its temporaries. The
// compiler may then fuse a*b+c and simplify t − (t − a) to a, as lavapipe does: the self-test must
// catch it (docs/design.md §4).
#define DS_DF64_PRECISE
#include "df64_probe.glsl"
