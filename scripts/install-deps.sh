#!/usr/bin/env bash
# Installs the Debian 12 packages dicsynth builds and tests with, when any is missing.
# Runs apt-get through sudo unless already root. Quiet and quick when everything is there.
#
#   scripts/install-deps.sh               # Debian 12's packages, and dicsynth's own lavapipe
#                                         # (Mesa 25 of bookworm-backports, in .deps/lavapipe/,
#                                         # for dicsynth alone: scripts/install-lavapipe.sh)
#   scripts/install-deps.sh --system-mesa # Debian 12's packages only: dicsynth then renders on
#                                         # the CPU with the system's lavapipe (Mesa 22.3)
set -euo pipefail

packages=(
  g++ make cmake pkg-config          # toolchain
  libvulkan-dev glslc                # Vulkan headers/loader, GLSL → SPIR-V compiler
  mesa-vulkan-drivers                # lavapipe: Vulkan on the CPU when there is no GPU
  vulkan-validationlayers            # the test suite runs with validation on
  libopenimageio-dev libopenexr-dev libtiff-dev  # image and ground-truth files
  zlib1g-dev                         # zlib: behind libdeflate (host/io/zip_deflate.cpp)
  libdeflate-dev                     # deflate of zip EXRs, CRC-32 of sweep files, Adler-32 of cached textures
  libssl-dev                         # SHA-256 of texture files (host/geometry/texture_disk_cache.h)
  libjsoncpp-dev                     # JSON files read back: point records, caches (host/core/json.h)
  libglm-dev libcli11-dev liblua5.4-dev doctest-dev
  libvtk9-dev                        # finite-element meshes (Field.load), read in a module loaded on use
  fonts-dejavu-core                  # the labels of `dicsynth preview` pictures
  pybind11-dev python3-dev python3-numpy python3-pytest  # the Python module and its tests
  python3-openimageio                # tests: an independent reader of the CLI's files from Python
  locales                            # tests: a German locale made with localedef (scenes read numbers in "C")
  python3-opencv python3-matplotlib  # examples/: the worked DIC study (run by the tests too)
  libopencv-calib3d-dev libopencv-features2d-dev libopencv-video-dev  # tests only: OpenCV calibrates
                                                                      # our images, ECC registers them
)

own_lavapipe=true
for arg in "$@"; do
  case "$arg" in
    --system-mesa) own_lavapipe=false ;;
    --backports-mesa)
      echo "install-deps.sh: --backports-mesa is gone: Mesa 25's lavapipe is now installed for dicsynth" \
           "by default, in .deps/lavapipe/, without changing the system's drivers" >&2
      exit 2 ;;
    *) echo "install-deps.sh: unknown option $arg" >&2; exit 2 ;;
  esac
done

sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
export DEBIAN_FRONTEND=noninteractive

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "dicsynth: installing ${missing[*]}" >&2
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

if $own_lavapipe; then
  "$(dirname "$0")/install-lavapipe.sh"
fi
