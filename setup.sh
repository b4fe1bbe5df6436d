#!/usr/bin/env bash
# filmback's two commands (README.md):
#   ./setup.sh         install what is missing, build (Release), render the default scene to out/
#   ./setup.sh test    the same set-up, plus the peers the tests use, then the whole test suite
# Debian 12 packages only; sudo only when not root. Re-running rebuilds only what changed.
set -euo pipefail
cd "$(dirname "$0")"

mode=${1:-render}
case "$mode" in render|test) ;; *) echo "usage: $0 [test]" >&2; exit 2 ;; esac

packages=(g++ cmake ninja-build pkg-config
          libembree-dev libtbb-dev libopenimageio-dev openimageio-tools libopenexr-dev
          libtinygltf-dev libcli11-dev nlohmann-json3-dev libgtest-dev libbenchmark-dev libosd-dev)
# Peers the tests render with (Blender's Cycles and glTF exporter; POV-Ray with its include files
# and sample scenes), the test drivers' Python, matplotlib for `filmback bench`'s plots, and a second
# compiler that builds an out-of-tree plugin against the installed SDK.
[ "$mode" = test ] && packages+=(blender povray povray-includes povray-examples
                                 python3 python3-numpy python3-matplotlib clang)
# npm only when the machine has none: a Node.js from another Debian source (nodesource's `nodejs`,
# which ships its own npm) conflicts with Debian's `npm` package.
[ "$mode" = test ] && ! command -v npm >/dev/null && packages+=(npm)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

[ -f build/CMakeCache.txt ] || cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build

if [ "$mode" = test ]; then
  # The Khronos glTF validator, from the npm registry, for the add-on's tests (tests/blender).
  validator=gltf-validator@2.0.0-dev.3.10
  [ -d build/npm/node_modules/gltf-validator ] ||
    npm install --silent --no-audit --no-fund --prefix build/npm "$validator"
  ctest --test-dir build --output-on-failure -j 2
else
  mkdir -p out
  build/bin/filmback render scenes/default/default.gltf -o out/default.exr -o out/default.png
fi
