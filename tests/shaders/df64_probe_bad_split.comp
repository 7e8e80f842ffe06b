#version 460
// A deliberately broken df64 library: Dekker's split by 4096 instead of 2^12 + 1, the classic slip.
// It is subtle: the "high half" t − (t − a) still has at most 12 bits, except where 4095·a falls
// into the binade below 4096·a (a's significand within 2^-12 above a power of two); there the
// halves have 13 and 12 bits, a partial product is rounded, and a product keeps only float accuracy.
// Random inputs rarely hit it; the self-test's hard cases (1 + 2^-12)² do: it must fail.
#define DS_DF64_SPLIT 4096.0
#include "df64_probe.glsl"
