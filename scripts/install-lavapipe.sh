#!/usr/bin/env bash
# Installs dicsynth's own copy of lavapipe (Mesa's Vulkan driver for the CPU) from Debian 12's
# bookworm-backports into .deps/lavapipe/, for dicsynth alone: the machine's apt sources and Vulkan
# drivers are left as they are. Called by scripts/install-deps.sh unless --system-mesa is given;
# quiet when the copy is there (remove .deps/lavapipe/ to get backports' current one).
#
# Why: Debian 12's lavapipe (Mesa 22.3) renders ~1.5x slower than bookworm-backports' (Mesa 25),
# and ends every loop of a batch of pixels after 65535 iterations (dicsynth then refuses the
# render). docs/performance.md "Which lavapipe" has the figures.
#
# How: apt downloads mesa-vulkan-drivers of bookworm-backports with a sources list and package
# lists of its own in a temporary folder (no root needed, nothing of /etc/apt or /var/lib/apt
# written); libvulkan_lvp.so and a Vulkan driver manifest naming it are put in .deps/lavapipe/,
# which the dicsynth binary adds to the loader's drivers at start (host/gpu/bundled_driver.h).
# The library is kept only if all it needs resolves against this machine's libraries (ldd -r); it
# is moved into place whole, so an interrupted install leaves nothing half-written.
# Any failure (no network, another architecture, a backport needing newer libraries) is a
# warning: dicsynth then uses the system's lavapipe, slower but correct.
set -euo pipefail
cd "$(dirname "$0")/.."

dest=.deps/lavapipe
manifest="$dest/dicsynth_lvp_icd.json"
[ -f "$manifest" ] && [ -f "$dest/libvulkan_lvp.so" ] && exit 0

warn() {
  echo "dicsynth: lavapipe of bookworm-backports not installed ($1); the system's lavapipe will be" \
       "used (slower on a CPU; docs/performance.md)" >&2
  exit 0
}

command -v apt-get >/dev/null && command -v dpkg-deb >/dev/null || warn "no apt-get/dpkg-deb"
arch=$(dpkg --print-architecture)
multiarch=$(gcc -print-multiarch 2>/dev/null || true)
[ -n "$multiarch" ] || warn "gcc -print-multiarch gave nothing"

work=$(mktemp -d)
partial=""
trap 'rm -rf "$work" ${partial:+"$partial"}' EXIT
mkdir -p "$work/lists/partial" "$work/cache/archives/partial" "$work/deb"
echo "deb http://deb.debian.org/debian bookworm-backports main" > "$work/sources.list"
apt_options=(
  -o Dir::Etc::SourceList="$work/sources.list" -o Dir::Etc::SourceParts=/nonexistent
  -o Dir::State::Lists="$work/lists" -o Dir::Cache="$work/cache" -o APT::Architecture="$arch"
)
# apt hands downloads to the unprivileged _apt user when run as root; the temporary folder is not
# theirs, so root downloads itself.
[ "$(id -u)" -ne 0 ] || apt_options+=(-o APT::Sandbox::User=root)

echo "dicsynth: downloading lavapipe of bookworm-backports (mesa-vulkan-drivers, ~11 MB)" >&2
apt-get "${apt_options[@]}" -qq update >"$work/log" 2>&1 || warn "apt-get update failed: $(tail -n 1 "$work/log")"
(cd "$work/deb" && apt-get "${apt_options[@]}" -qq download mesa-vulkan-drivers/bookworm-backports) \
  >"$work/log" 2>&1 || warn "apt-get download failed: $(tail -n 1 "$work/log")"
deb=$(ls "$work"/deb/mesa-vulkan-drivers_*.deb 2>/dev/null | head -n 1 || true)
[ -n "$deb" ] || warn "apt-get download gave no .deb"
dpkg-deb -x "$deb" "$work/root" || warn "dpkg-deb could not unpack $(basename "$deb")"

library="$work/root/usr/lib/$multiarch/libvulkan_lvp.so"
icd=$(ls "$work"/root/usr/share/vulkan/icd.d/lvp_icd*.json 2>/dev/null | head -n 1 || true)
[ -f "$library" ] && [ -n "$icd" ] || warn "$(basename "$deb") holds no libvulkan_lvp.so or manifest"
unresolved=$(ldd -r "$library" 2>&1 | grep -E "not found|undefined symbol" || true)
[ -z "$unresolved" ] || warn "it needs libraries this machine lacks: $(echo "$unresolved" | head -n 2)"

# Assembled in a folder of its own beside the destination, then renamed into place: a concurrent
# setup (CI jobs sharing a checkout) assembles its own, and whichever comes second keeps the
# first one's.
mkdir -p "$(dirname "$dest")"
partial=$(mktemp -d "$dest.partial.XXXXXX")
cp "$library" "$work/root/usr/share/doc/mesa-vulkan-drivers/copyright" "$partial/"
# The manifest's library_path made relative: the loader reads a path with a slash relative to the
# manifest's folder, so .deps/ can move with the checkout.
sed -E 's#"library_path": *"[^"]*"#"library_path": "./libvulkan_lvp.so"#' "$icd" > "$partial/$(basename "$manifest")"
grep -q '"./libvulkan_lvp.so"' "$partial/$(basename "$manifest")" || warn "unexpected manifest $(basename "$icd")"
dpkg-deb -f "$deb" Version > "$partial/VERSION"
chmod 755 "$partial"
# A concurrent setup may have installed one meanwhile: keep it (the trap removes ours).
[ -f "$manifest" ] && [ -f "$dest/libvulkan_lvp.so" ] && exit 0
rm -rf "$dest"  # an incomplete copy (manifest or library missing), or nothing
mv -T "$partial" "$dest" 2>/dev/null || [ -f "$manifest" ] || warn "could not move it into $dest"
echo "dicsynth: lavapipe $(cat "$dest/VERSION") installed in $dest" >&2
