#!/bin/sh
# Packs what the CPU-vs-GPU checks need for a machine with a real GPU and a Vulkan driver but none
# of this project's Debian packages (an x86-64 Linux with a glibc at least Debian 12's 2.36), into
# DIR (default .gpu-bundle, ~60 MB):
#   DIR/bin      dicsynth and dicsynth_gpu_checks (CMake target of the suite's CPU-vs-GPU tests)
#   DIR/lib      their shared libraries, except the C library's own (libc, libm, ld.so: the
#                machine's), the Vulkan loader included, and GLVND's dispatch libraries (libGLX,
#                libEGL, libGLdispatch, ...): NVIDIA's Vulkan driver is libGLX_nvidia, which on a
#                machine without them loads but answers no vkCreateInstance (seen on an H100 image;
#                installing Debian's libglvnd0, libglx0, libegl1, libgl1, libgles2, libopengl0
#                system-wide fixed it there)
#   DIR/lib-gcc  libstdc++ and libgcc_s, used only where the machine's are older than Debian 12's
#   DIR/layers   the Khronos validation layer, under which the checks run
# Then copy the repository (its scenes/, docs/, shaders/ are read) and DIR to the GPU machine and run
# scripts/gpu-checks.sh DIR LOGDIR there (bench/RESULTS.md, "GPU machines").
# Usage: scripts/gpu-bundle.sh [BUILD_DIR] [DIR]   (defaults: build .gpu-bundle)
set -eu
BUILD=${1:-build}
DIR=${2:-.gpu-bundle}
cmake --build "$BUILD" -j2 --target dicsynth dicsynth_gpu_checks
rm -rf "$DIR"
mkdir -p "$DIR/bin" "$DIR/lib" "$DIR/lib-gcc" "$DIR/layers"
cp "$BUILD/dicsynth" "$BUILD/dicsynth_gpu_checks" "$DIR/bin/"
LIBDIR=/usr/lib/x86_64-linux-gnu
LAYER=$LIBDIR/libVkLayer_khronos_validation.so
[ -f "$LAYER" ] || { echo "gpu-bundle: $LAYER missing (apt install vulkan-validationlayers)" >&2; exit 1; }
# Every library the two binaries and the layer load, by the path this machine resolves.
ldd "$BUILD/dicsynth" "$BUILD/dicsynth_gpu_checks" "$LAYER" | awk '$2 == "=>" && $3 ~ /^\// { print $1, $3 }' |
  sort -u | while read -r name path; do
    case $name in
      libc.so.*|libm.so.*|libdl.so.*|libpthread.so.*|librt.so.*|ld-linux*) ;;
      libstdc++.so.*|libgcc_s.so.*) cp -L "$path" "$DIR/lib-gcc/$name" ;;
      *) cp -L "$path" "$DIR/lib/$name" ;;
    esac
  done
for lib in libGLdispatch.so.0 libGLX.so.0 libEGL.so.1 libGL.so.1 libGLESv2.so.2 libOpenGL.so.0; do
  cp -L "$LIBDIR/$lib" "$DIR/lib/"
done
cp -L "$LAYER" "$DIR/layers/"
# The layer's manifest names its library by a path relative to the manifest itself.
sed 's|"library_path": *"[^"]*"|"library_path": "./libVkLayer_khronos_validation.so"|' \
  /usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json >"$DIR/layers/VkLayer_khronos_validation.json"
# The paths the binaries were built with (DS_SOURCE_DIR, DS_BINARY): gpu-checks.sh recreates them.
sed -n 's/^CMAKE_HOME_DIRECTORY:INTERNAL=//p' "$BUILD/CMakeCache.txt" >"$DIR/source-dir"
(cd "$BUILD" && pwd) >"$DIR/build-dir"
du -sh "$DIR"
