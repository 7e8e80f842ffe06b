#!/usr/bin/env bash
# Installs the Debian 12 packages dicsynth builds and tests with, when any is missing.
# Runs apt-get through sudo unless already root. Quiet and quick when everything is there.
set -euo pipefail

packages=(
  g++ make cmake pkg-config          # toolchain
  libvulkan-dev glslc                # Vulkan headers/loader, GLSL → SPIR-V compiler
  mesa-vulkan-drivers                # lavapipe: Vulkan on the CPU when there is no GPU
  vulkan-validationlayers            # the test suite runs with validation on
  libopenimageio-dev libopenexr-dev  # image and ground-truth files
  libglm-dev libcli11-dev liblua5.4-dev doctest-dev
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "dicsynth: installing ${missing[*]}" >&2
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
