#!/usr/bin/env bash
# Installs every build and test dependency of luxel from Debian 12 packages.
# Idempotent: packages already present are skipped, so a second run is fast and offline.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libembree-dev libtbb-dev libassimp-dev libglm-dev libopenexr-dev libstb-dev
  nlohmann-json3-dev libcli11-dev libfmt-dev libgtest-dev libgmock-dev libbenchmark-dev
  libepoxy-dev libegl-dev libeigen3-dev unzip
  # quadric-error simplification for seed 002's room (the room-* built-in scenes)
  libmeshoptimizer-dev
  # content hashes: the keys of the face-cluster hierarchy's disk cache and the bench's references
  libxxhash-dev
  # `make fuzz`: clang with libFuzzer and the sanitizer runtimes (fuzz/, docs/fuzzing.md)
  clang libclang-rt-14-dev
  # Mesa: its EGL driver and llvmpipe give a headless OpenGL 4.5 context with no GPU (tests/gl)
  libegl-mesa0 libgl1-mesa-dri
  # `luxel view`: GLFW windows and input, Dear ImGui panels; Xvfb (xvfb-run, xauth) runs its window tests
  libglfw3-dev libimgui-dev xvfb xauth
  # `luxel animate -o movie.mp4` runs ffmpeg to encode the frames (its test skips without it)
  ffmpeg
)

# `luxel bake` writes glTF through tinygltf; its test runs the Khronos glTF validator under Node.js.
# Debian's nodejs and npm unless a Node.js with npm is there already (NodeSource's nodejs bundles
# npm and conflicts with Debian's npm package).
packages+=(libtinygltf-dev)
# The three.js checks (tools/three-check, CTest Web.ThreeLightmap and Web.HtmlViewer) drive Debian's headless
# Chromium (/usr/bin/chromium; WebGL through its bundled SwiftShader, no GPU) with playwright-core.
packages+=(chromium)
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  packages+=(nodejs npm)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
else
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null 2>&1 || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
    SUDO="sudo"
  fi
  echo "install-deps: installing ${missing[*]}"
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get update -qq
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# The Khronos glTF validator (npm package gltf-validator, the version pinned by
# tools/gltf-validator/package-lock.json) into tools/gltf-validator/node_modules, ignored by git.
validator="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/tools/gltf-validator"
if [ ! -f "$validator/node_modules/gltf-validator/package.json" ]; then
  echo "install-deps: installing the glTF validator (npm ci in tools/gltf-validator)"
  npm ci --prefix "$validator" --no-audit --no-fund
fi

# three.js and playwright-core (the versions pinned by tools/three-check/package-lock.json) into
# tools/three-check/node_modules, ignored by git; no browser is downloaded (the check uses Debian's).
# The build also embeds this three.js in luxel for `luxel bake --html` (docs/baking.md, "Viewing a
# bake in the browser"): without it that option says to run this script and rebuild.
three_check="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/tools/three-check"
if [ ! -f "$three_check/node_modules/three/package.json" ] || [ ! -f "$three_check/node_modules/playwright-core/package.json" ]; then
  echo "install-deps: installing three.js and playwright-core (npm ci in tools/three-check)"
  PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --prefix "$three_check" --no-audit --no-fund
fi
