// Binding numbers and specialization-constant ids of render.comp, shared by C++ and GLSL.
#ifndef DS_SHARED_BINDINGS_H
#define DS_SHARED_BINDINGS_H

// Binding numbers of render.comp's buffers (set 0). Cameras, objects and lights are bound twice: as
// storage buffers and as uniform blocks of DS_UNIFORM_BLOCK_BYTES; the shader reads the uniform
// blocks when the scene fits in them (DS_SPEC_UNIFORM_SCENE), and the texels through a uniform
// texel buffer when DS_SPEC_TEXEL_VIEW says so. Why: see shaders/render.comp.
#define DS_BINDING_CAMERAS 0
#define DS_BINDING_OBJECTS 1
#define DS_BINDING_LIGHTS 2
#define DS_BINDING_TEXTURES 3
#define DS_BINDING_TEXELS 4
#define DS_BINDING_PIXELS 5
#define DS_BINDING_NURBS_NODES 6
#define DS_BINDING_NURBS_SUBPATCHES 7
#define DS_BINDING_NURBS_PATCHES 8
#define DS_BINDING_NURBS_POINTS 9
#define DS_BINDING_CAMERAS_UNIFORM 10
#define DS_BINDING_OBJECTS_UNIFORM 11
#define DS_BINDING_LIGHTS_UNIFORM 12
#define DS_BINDING_TEXEL_VIEW 13
#define DS_BINDING_QUERIES 14  // visibility queries (render.comp's query mode; a dummy otherwise)
#define DS_BINDING_COUNT 15

// Size of each uniform block: Vulkan's guaranteed minimum of maxUniformBufferRange, so every
// device takes it. Holds 51 cameras, 28 objects, 128 lights in fp64; 51, 30, 204 in df64; 93, 46,
// 204 in fp32.
#define DS_UNIFORM_BLOCK_BYTES 16384

// Object and light counts up to which the pipeline is specialized to the exact count (loops over
// objects and lights unroll to constant indices); above, the count comes from the push constants.
// 8 objects, not 4: on lavapipe a loop over a dynamic count reading the objects' uniform block
// compiled for minutes on a cold shader cache (LLVM's coroutine pass over the lane-by-lane loads),
// while the unrolled loop compiles in seconds and renders faster on both Mesas. Measured
// 2026-11-29 on the 2-core VM (bench/RESULTS.md, "Unrolled object counts"): 8 objects, 2 lights,
// first render on Mesa 25 minus a warm one, fp32 / df64 / fp64: 87.7 / 96.3 / 32.4 s dynamic,
// 3.8 / 11.6 / 9.8 s unrolled (bench/bench_pipeline_cold.sh); 640 × 480 fp32 16 spp render
// 0.42 -> 0.32 s (Mesa 25), 2.55 -> 0.81 s (Mesa 22.3).
// Unrolled 16 objects took 16 / 49 / 43 s to create: the unrolled code grows faster than linearly.
#define DS_MAX_UNROLLED_OBJECTS 8
#define DS_MAX_UNROLLED_LIGHTS 4

// Deepest NURBS BVH the traversal stack holds (root = depth 0); the host refuses deeper ones.
#define DS_NURBS_STACK_SIZE 48

// Workgroup size of render.comp (pixels).
#define DS_LOCAL_SIZE_X 8
#define DS_LOCAL_SIZE_Y 8

// Specialization constant ids: features a scene lacks are compiled out.
#define DS_SPEC_HAS_LIGHTS 0
#define DS_SPEC_HAS_DISTORTION 1
#define DS_SPEC_HAS_FILE_TEXTURES 2
#define DS_SPEC_SHAPE_KINDS 3  // bit k set: some object has shape kind k
#define DS_SPEC_NURBS_DEGREE 4  // the degree (both directions) every Bézier patch is raised to
#define DS_SPEC_HAS_SPECKLE_TEXTURES 8  // some object has a Texture.Speckle (analytic disks)
#define DS_SPEC_HAS_QUINTIC_TEXTURES 9  // some Texture.File interpolates with the quintic B-spline
#define DS_SPEC_HAS_TARGET_TEXTURES 18  // some object has a calibration target (Checkerboard, CircleGrid)
#define DS_SPEC_CAMERA_KINDS 5  // bit k set: some camera has camera kind k (DS_CAMERA_*)
#define DS_SPEC_HAS_RATIONAL_DISTORTION 6  // bool: some camera has Distortion.Rational (k4..k6, s1..s4)
#define DS_SPEC_SHADER_KINDS 11  // bit k set: some object has shader kind k (DS_SHADER_*)
#define DS_SPEC_LIGHT_KINDS 12   // bit k set: the scene has a light of kind k (DS_LIGHT_*)

#define DS_SPEC_TEXEL_VIEW 7      // bool: texels are read through the uniform texel buffer
#define DS_SPEC_UNIFORM_SCENE 13  // bool: cameras, objects and lights are read from the uniform blocks
#define DS_SPEC_OBJECT_COUNT 14   // 1..DS_MAX_UNROLLED_OBJECTS: exactly that many objects; 0: any number
#define DS_SPEC_LIGHT_COUNT 15    // 0..DS_MAX_UNROLLED_LIGHTS: exactly that many lights; -1: any number
#define DS_SPEC_LOCAL_SCENE 17    // bool: the objects and lights of exact counts are copied per invocation

// Arithmetic switches of shaders/lib/df64.glsl (any shader that includes it).
#define DS_SPEC_DF64_FMA 16  // bool: TwoProd by fma(a, b, -p); only where the self-test proved fma exact

#endif
