#version 460
// The df64 probe with the library as shipped (see df64_probe.glsl).
#include "df64_probe.glsl"
