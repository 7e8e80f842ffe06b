// The arithmetic type of a shader variant: `real` is float (DS_FP32) or double (DS_FP64).
// Constants that are not exact binary fractions need care: an unsuffixed literal is a float rounded
// to 24 bits. They are either spelled per variant (the LF suffix for fp64) or computed as a quotient
// of exact numbers, `real(1.0) / real(23.0)`, which the compiler folds in the variant's precision.
#ifndef DS_REAL_GLSL
#define DS_REAL_GLSL

#if defined(DS_FP64)
#define real double
#define real2 dvec2
#define real3 dvec3
#define real4 dvec4
#define real3x3 dmat3
#define DS_FAR_AWAY 1.0e30LF
#elif defined(DS_FP32)
#define real float
#define real2 vec2
#define real3 vec3
#define real4 vec4
#define real3x3 mat3
#define DS_FAR_AWAY 1.0e30
#else
#error "compile with -DDS_FP32 or -DDS_FP64"
#endif

#if defined(DS_FP64)
const real DS_PI = 3.14159265358979323846LF;
const real DS_HALF_PI = 1.57079632679489661923LF;
#else
const real DS_PI = 3.14159265358979323846;
const real DS_HALF_PI = 1.57079632679489661923;
#endif

#endif
