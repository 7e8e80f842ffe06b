#version 460
// Test shader of tests/gpu/test_gpu_context.cpp: out[i] = op(in[i]) for i < count.
// DS_FP32 (and DS_DF64): the arrays hold float. DS_FP64: they hold double and the arithmetic is done in double,
// which proves shaderFloat64 works (1 + 2^-40 survives only there).
#if defined(DS_FP64)
#define Real double
#elif defined(DS_FP32) || defined(DS_DF64)
#define Real float
#else
#error "compile with -DDS_FP32, -DDS_FP64 or -DDS_DF64"
#endif

layout(local_size_x = 64) in;

// kOp: 0 → in·scale; 1 → 1 + in; 2 → in·scale + kBias.
layout(constant_id = 0) const uint kOp = 0;
layout(constant_id = 1) const int kBias = 0;

layout(push_constant) uniform Push {
  uint count;   // number of elements to process
  float scale;  // multiplier of ops 0 and 2
} pc;

layout(std430, set = 0, binding = 0) readonly buffer Input { Real inValues[]; };
layout(std430, set = 0, binding = 1) writeonly buffer Output { Real outValues[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  Real x = inValues[i];
  Real y;
  if (kOp == 0u) {
    y = x * Real(pc.scale);
  } else if (kOp == 1u) {
    y = Real(1) + x;
  } else {
    y = x * Real(pc.scale) + Real(kBias);
  }
  outValues[i] = y;
}
