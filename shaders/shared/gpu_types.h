// Layouts of the GPU buffers (std430), shared by C++ (host/gpu/gpu_layout.h) and GLSL (render.comp).
// One source, three precision variants. `real4` is the variant's bulk type (vec4 in fp32 and df64,
// dvec4 in fp64); `hreal4` its geometric type (vec4, dvec4, or a df64 pair {vec4 hi; vec4 lo;}).
// In C++ they are 16/32-byte aligned structs of float/double. Members are real4/hreal4/ivec4/uvec4
// only (docs/design.md §4: no vec3 alignment traps), and every struct's size is a multiple of its
// std430 alignment (16 bytes; 32 with dvec4 members), so arrays have no hidden padding;
// host/gpu/gpu_layout.h static_asserts sizes and offsets.
//
// No include guard: C++ includes this file once per precision namespace.

// Bytes of the structs that also live in uniform blocks, given the bytes of hreal4 (H4) and real4
// (R4). std140 lays them out exactly as std430 does: every member is a 16- or 32-byte vector (or an
// array of 16-byte vectors), so no std140 rounding applies. gpu_layout.h checks both formulas.
#define DS_SHAPE_SLOTS 5  // hreal4 members of the largest shape GPU struct (Shape.Triangle)
#define DS_GPU_CAMERA_BYTES(H4, R4) (9 * (H4) + 32)
#define DS_GPU_OBJECT_BYTES(H4, R4) (12 * (H4) + 2 * (R4) + 128)
#define DS_GPU_LIGHT_BYTES(H4, R4) (3 * (R4) + 32)

struct GpuCamera {
  hreal4 worldFromCamera[3];  // rows of the 3x3 rotation [R_wc], w = camera centre coordinate (m)
  hreal4 intrinsics;          // fx, fy, cx, cy (px)
  hreal4 brown0;              // k1, k2, k3, p1
  hreal4 brown1;              // p2, side of the sensitive square (px), 0, 0
  ivec4 size;                // width, height, strataX, strataY
  ivec4 flags;               // distorted (0/1), camera kind (DS_CAMERA_*), 0, 0
  // Camera models (host/cameras/<kind>.h, camera/distortion.h). Orthographic: intrinsics.xy = px per metre.
  hreal4 rational0;          // k4, k5, k6, s1 (Distortion.Rational; 0 for Brown)
  hreal4 rational1;          // s2, s3, s4, 0
  hreal4 lens;               // ThinLens: lens radius R (m), R / focus distance, 0, 0
};

struct GpuObject {
  hreal4 objectFromWorld[4];  // rows of the 4x4 homography H⁻¹
  // The kind's GPU struct (host/shapes/<kind>.h and shaders/shapes/<kind>.glsl): member k in
  // shape[k], unused slots 0. Nurbs: shape[0].x = the surface size (m), the root node in extra.x.
  hreal4 shape[DS_SHAPE_SLOTS];
  real4 shading;             // albedo, constant texture value, 0, 0
  real4 material;            // the reflectance model's data: its home's gpu() (host/reflectance),
                             // read by its twin's Gpu<Kind> (shaders/reflectance/<kind>.glsl)
  ivec4 kinds;               // shape kind, shader kind, texture index (-1: constant), objectId
  ivec4 extra;               // Nurbs: root node in the NURBS node buffer; texture kind, 0, 0
  // Checkerboard and CircleGrid textures (host/texture/target_texture.h):
  hreal4 target0;            // origin_uv.xy, cell_uv.xy
  hreal4 target1;            // radiusSquared_cells, dark, light, 0
  ivec4 targetInfo;          // cols, rows, asymmetric (0/1), 0
  // Texture.Speckle (host/texture/analytic_speckle.h); speckleInfo pairs targetInfo (32 bytes):
  ivec4 speckleInfo;         // seed (bits), cells per period of u, of v (0: not periodic), 0
  hreal4 speckle0;           // cells per u, cells per v, dark, light
  uvec4 speckleCdf[4];       // Poisson inversion thresholds cdf[0..15]
};
// Every member of GpuObject, for render.comp's per-invocation copy (LOCAL_SCENE). A member added
// above goes here too: host/gpu/gpu_layout.h checks that the members listed fill the struct.
#define DS_GPU_OBJECT_MEMBERS(X) \
  X(objectFromWorld) X(shape) X(shading) X(material) X(kinds) X(extra) X(target0) X(target1) X(targetInfo) \
  X(speckleInfo) X(speckle0) X(speckleCdf)

struct GpuLight {
  real4 positionIntensity;  // xyz (m), intensity (Point, Spot: W/sr-like; Ambient: radiance)
  real4 direction;          // Spot: unit axis xyz (world), 0
  real4 cone;               // Spot: cos(outer angle), cos(inner angle), 0, 0
  ivec4 info;               // kind (DS_LIGHT_*), 0, 0, 0
  ivec4 pad;                // size a multiple of 32 bytes in fp64 (ivec4 members come in pairs)
};
// Every member of GpuLight read by the shaders (all but pad), for render.comp's per-invocation copy
// (LOCAL_SCENE); host/gpu/gpu_layout.h checks that with pad they fill the struct.
#define DS_GPU_LIGHT_MEMBERS(X) X(positionIntensity) X(direction) X(cone) X(info)

struct GpuTexture {
  ivec4 info;  // width, height, offset of the first coefficient in the texel buffer,
               // splineCode (host/texture/bspline.h): bit 0 the interpolation (0: cubic, 1:
               // quintic B-spline), bit 1 u repeats, bit 2 v repeats
};

// NURBS (host/geometry/nurbs_bvh.h): every NURBS object's BVH nodes, sub-patches, Bézier patches
// and homogeneous control points, concatenated; indices below are global (into these buffers).
// Bounds are float, rounded outwards: a box only decides where to look, never a result.
struct GpuNurbsNode {
  vec4 boundsMin;  // object frame, xyz
  vec4 boundsMax;
  ivec4 links;     // right child (-1: leaf; the left child is the next node), first sub-patch, count, 0
};

struct GpuNurbsSubPatch {
  vec4 local;  // aMin, bMin, aMax, bMax: range of the patch's local parameters (dyadic: exact in float)
  // patch, degenerate (0/1: informative, the search treats every sub-patch alike), first of its own
  // control points (range enlarged by 1/8; df64: an anchor, then the points relative to it), 0
  ivec4 info;
};

struct GpuNurbsPatch {
  hreal4 uvRange;  // uMin, vMin, uMax, vMax: the normalized surface parameters the patch covers
  ivec4 info;      // degreeU, degreeV, first control point, seam bits (gpu/pack.cpp)
  ivec4 pad;
};

// One pixel of output. Background: objectId 0 (the other ground-truth fields are then undefined).
struct GpuPixel {
  hreal4 positionDepth;   // P (world, m), depth Z (m)
  hreal4 uvRadianceId;    // u, v, mean radiance over the samples, objectId (exact small integer)
  real4 normal;           // N (world, unit, facing the camera), 1 where the loop-limit sentinel fired (render.comp)
};

// One visibility query (render.comp's query mode): the ray origin + t · direction, camera-relative
// like everything the GPU sees (PackedFrame), direction = point − origin so that the point is at
// t = 1. The answer: the GpuPixel at the same index, with the nearest hit's t in positionDepth.w
// and its objectId in uvRadianceId.w (0: none).
struct GpuRayQuery {
  hreal4 origin;     // xyz, 0
  hreal4 direction;  // xyz, 0
};

// Push constants of one dispatch (one tile of one camera).
struct GpuTileParams {
  ivec4 tile;       // x0, y0, width, height (px); query mode: 0, 0, width, height of the query block
  ivec4 counts;     // camera index, samples per pixel (query mode: first query), object count, light count
  uvec4 random;     // seed, frame, 0 (render.comp's loop-limit sentinel reads it), query mode (0/1)
};
