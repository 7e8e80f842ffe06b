// Binding numbers and specialization-constant ids of render.comp, shared by C++ and GLSL.
#ifndef DS_SHARED_BINDINGS_H
#define DS_SHARED_BINDINGS_H

// Binding numbers of render.comp's storage buffers (set 0).
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
#define DS_BINDING_COUNT 10

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
#define DS_SPEC_CAMERA_KINDS 5  // bit k set: some camera has camera kind k (DS_CAMERA_*)
#define DS_SPEC_HAS_RATIONAL_DISTORTION 6  // bool: some camera has Distortion.Rational (k4..k6, s1..s4)
#define DS_SPEC_SHADER_KINDS 11  // bit k set: some object has shader kind k (DS_SHADER_*)
#define DS_SPEC_LIGHT_KINDS 12   // bit k set: the scene has a light of kind k (DS_LIGHT_*)

// Arithmetic switches of shaders/lib/df64.glsl (any shader that includes it).
#define DS_SPEC_DF64_FMA 16  // bool: TwoProd by fma(a, b, -p); only where the self-test proved fma exact

#endif
