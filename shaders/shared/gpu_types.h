// Layouts of the GPU buffers (std430), shared by C++ (host/gpu/gpu_layout.h) and GLSL (render.comp).
// One source, two precision variants: `real4` is vec4/dvec4 in GLSL and a 16/32-byte aligned struct
// of float/double in C++. Members are real4/ivec4/uvec4 only (DESIGN.md §4: no vec3 alignment
// traps), and every struct's size is a multiple of its std430 alignment (16 bytes; 32 with dvec4
// members), so arrays have no hidden padding; host/gpu/gpu_layout.h static_asserts sizes and offsets.
//
// No include guard: C++ includes this file once per precision namespace.

struct GpuCamera {
  real4 worldFromCamera[3];  // rows of the 3x3 rotation [R_wc], w = camera centre coordinate (m)
  real4 intrinsics;          // fx, fy, cx, cy (px)
  real4 brown0;              // k1, k2, k3, p1
  real4 brown1;              // p2, side of the sensitive square (px), 0, 0
  ivec4 size;                // width, height, strataX, strataY
  ivec4 flags;               // distorted (0/1), 0, 0, 0
};

struct GpuObject {
  real4 objectFromWorld[4];  // rows of the 4x4 homography H⁻¹
  real4 shape0;              // Sphere: radius; Box: half sizes; Rect/Plane: w, h; Triangle: p0
  real4 shape1;              // Triangle: p1
  real4 shape2;              // Triangle: p2
  real4 shape3;              // Triangle: uv0.xy, uv1.xy
  real4 shape4;              // Triangle: uv2.xy
  real4 shading;             // albedo, constant texture value, 0, 0
  ivec4 kinds;               // shape kind, shader kind, texture index (-1: constant), objectId
  ivec4 pad;
};

struct GpuLight {
  real4 positionIntensity;  // xyz (m), intensity
};

struct GpuTexture {
  ivec4 info;  // width, height, offset of the first coefficient in the texel buffer, 0
};

// One pixel of output. Background: objectId 0 (the other ground-truth fields are then undefined).
struct GpuPixel {
  real4 radianceDepthUV;  // mean radiance over samples, depth Z (m), u, v
  real4 positionId;       // P (world, m), objectId (exact small integer)
  real4 normal;           // N (world, unit, facing the camera), 0
};

// Push constants of one dispatch (one tile of one camera).
struct GpuTileParams {
  ivec4 tile;       // x0, y0, width, height (px)
  ivec4 counts;     // camera index, samples per pixel, object count, light count
  uvec4 random;     // seed, frame, 0, 0
};
