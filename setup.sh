#!/usr/bin/env bash
# filmback's two commands (README.md):
#   ./setup.sh         install what is missing, build (Release), render the default scene to out/
#   ./setup.sh test    the same set-up, plus the peers the tests use, then the whole test suite,
#                      with a fixed half of the shots of the longest suites against peers (below)
#   ./setup.sh test-all  the same with every shot
# Debian 12 packages only; sudo only when not root. Re-running rebuilds only what changed.
set -euo pipefail
cd "$(dirname "$0")"

mode=${1:-render}
case "$mode" in
  render | test) all_shots=no ;;
  test-all) mode=test all_shots=yes ;;
  *) echo "usage: $0 [test | test-all]" >&2; exit 2 ;;
esac

packages=(g++ cmake ninja-build pkg-config
          libembree-dev libtbb-dev libopenimageio-dev openimageio-tools libopenexr-dev
          libtinygltf-dev libcli11-dev nlohmann-json3-dev libgtest-dev libbenchmark-dev libosd-dev
          libopencolorio-dev libfreetype-dev libpng-dev libmurmurhash-dev)
# Peers the tests render with (Blender's Cycles and glTF exporter; POV-Ray with its include files
# and sample scenes), the test drivers' Python, matplotlib for `filmback bench`'s plots, and clang:
# a second compiler for an out-of-tree plugin against the installed SDK, and with its sanitizer and
# libFuzzer runtimes (libclang-rt-14-dev) the compiler of the sanitized build and the fuzz harnesses;
# strace, which shows that a render makes no network system call; Slurm's controller, node daemon
# and client for `filmback submit`'s one-node-cluster test (tests/slurm/, docs/distributed.md), and
# OpenImageIO's Python module, with which that test compares EXR files bit for bit; a virtual X
# display (xvfb, and xauth for xvfb-run) for the render engine's test in Blender's window, and
# xdotool, which presses Esc there as a keyboard does (through the X server's XTEST extension).
[ "$mode" = test ] && packages+=(blender povray povray-includes povray-examples
                                 python3 python3-numpy python3-matplotlib clang libclang-rt-14-dev strace
                                 slurmctld slurmd slurm-client python3-openimageio xvfb xauth
                                 xdotool)
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

# `./setup.sh test` leaves the fast unit tests out of the Release build: its sanitized build runs
# them (below). A build/ made by `./setup.sh` keeps them; they are then built and not run here.
release_options=()
[ "$mode" = test ] && release_options+=(-DFILMBACK_UNIT_TESTS=OFF)
# Unity builds (CMake compiles a batch of 8 source files as one): each batch parses the heavy
# headers (CLI11, nlohmann/json, OpenImageIO, GoogleTest) once instead of 8 times, which cuts the
# compile time of a fresh build (docs/testing.md, "Unity builds"). A developer's own build can leave
# them off for faster rebuilds of one file.
unity=(-DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=8)
[ -f build/CMakeCache.txt ] ||
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "${unity[@]}" "${release_options[@]}"
cmake --build build

if [ "$mode" = test ]; then
  # The Khronos glTF validator, from the npm registry, for the add-on's and convert's tests.
  validator=gltf-validator@2.0.0-dev.3.10
  [ -d build/npm/node_modules/gltf-validator ] ||
    npm install --silent --no-audit --no-fund --prefix build/npm "$validator"
  # docs/testing.md, "Sanitizers": build-sanitize/ is a second build (clang, AddressSanitizer with
  # LeakSanitizer, UndefinedBehaviorSanitizer, -O1) that also holds the fuzz harnesses. Every test
  # runs once (the hostile files in both builds). The Release build runs the suites against peers
  # (Blender, POV-Ray), the render-heavy ones (label `render`) and the SDK's, starting at once, so
  # that they fill the processor time the sanitized build's compiler leaves idle and the other
  # way round; the sanitized build runs all others and, at the lowest priority, the fuzz harnesses
  # (half a minute each; longer runs: docs/reliability.md); then, alone and one at a time, the
  # tests that measure processor time (two at once on this machine's two hardware threads inflate
  # each other's) and the SDL's sample-scene sweeps (`release_only`).
  release_only='^(Sdl\.RunawayScenesFailCleanlyAndQuickly|cli\.never_lose\..*|Sdl\.(Truncated'
  release_only+='SampleScenesFailCleanly|ShapesIncHeightFieldMacros|SampleScenesEvaluate))$'
  # The hostile files' refusals are held to a CPU-time bound: in the Release build they too run
  # alone at the end (the sanitized build runs them with its own bound, among the others).
  release_last="$release_only|^hostile\..*$"
  # CI's time (docs/testing.md, "CI's sample"): the suites that render each shot with a peer and
  # with filmback, several times, run a fixed half of their shots; `./setup.sh test-all` runs all.
  # Left out: shots whose model another shot or a unit test also covers.
  # One group of full names: CMake's regular expressions take at most ten groups in all (with
  # release_last's), and more make ctest's -E silently exclude nothing.
  sampled_names=()
  sample_out() {
    local suite=$1 shot
    shift
    for shot in "$@"; do sampled_names+=("$suite$shot"); done
  }
  if [ "$all_shots" = no ]; then
    sample_out 'Shots/BlenderRadiometry\.MatchesCycles/' '"hdr_world"' '"spread"' '"spot_radius"' \
      '"point_glossy"' '"point_spot"' '"sun_glossy"' '"disk_ellipse"'
    sample_out 'Against/BlenderShot\.MarkersMatchCycles/' bokeh_anamorphic bokeh_hexagon \
      landscape_auto portrait_auto tele_600mm vertical_fit wide_12mm far_from_origin \
      portrait_vertical_shift
    sample_out 'Shots/BlenderPrincipled\.MatchesCycles/' roughness_0_2 roughness_0_5 roughness_0_9 \
      anisotropic nodes sphere_light layers disk_light
    sample_out 'Against/BlenderPanorama\.MarkersAndCircleMatchCycles/' fisheye_equidistant \
      mirrorball fisheye_polynomial
    sample_out 'BlenderMaterials\.' AlphaCutoutMatchesCycles EmissiveTextureMatchesCycles \
      TexturedGroundAndGlossySpheresMatchCycles
    sample_out 'BlenderSubdiv\.' SubdividedObjectMatchesCycles
    sample_out 'Steps/BlenderDeformBlur\.StreaksOfEvaluatedShapesMatchCycles/' blur3 blur7
    sample_out 'Steps/BlenderDeformSwing\.ArcsCutIntoCyclesChordsMatchCycles/' swing3
    sample_out '' 'BlenderAlbedo\..*' 'BlenderMotion\..*' 'PovGeometryRender\..*'
    sample_out 'Against/BlenderDistortion\.MarkersLandWhereTheMovieDistortionNodePutsThem/' \
      division nuke
    sample_out 'Shots/PovConvert\.ValidatesAndRendersAsThePovWithinNoise/' mirrored_camera lights \
      sample_debug sample_filtfun sample_laser sample_macro1 patterns
  fi
  sampled_out='^$'
  [ ${#sampled_names[@]} -eq 0 ] || sampled_out="^($(IFS='|'; echo "${sampled_names[*]}"))( |\$)"
  # A pattern ctest cannot compile excludes nothing, silently: refuse to run such a sample.
  all_tests=$(ctest --test-dir build -N | grep -c '^  Test')
  kept_tests=$(ctest --test-dir build -N -E "$release_last|$sampled_out" | grep -c '^  Test')
  if [ "$kept_tests" -ge "$all_tests" ]; then
    echo "setup.sh: the exclusion pattern for ctest excludes nothing (too many groups?)" >&2
    exit 1
  fi
  status=0
  mkdir -p build/logs
  ctest --test-dir build --output-on-failure -j 2 -E "$release_last|$sampled_out" \
    -L 'blender|pov|bench|filters|hard|sdk|hostile|render|slurm' >build/logs/ctest.log 2>&1 &
  release=$!
  [ -f build-sanitize/CMakeCache.txt ] ||
    CC=clang CXX=clang++ cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DFILMBACK_FUZZ=ON -DFILMBACK_UNIT_TEST_SHARDS=4 "${unity[@]}"
  cmake --build build-sanitize -j 2 || status=1
  # OpenImageIO 2.4's TextureSystem::destroy deletes its implementation through the base class
  # with a sized delete, which AddressSanitizer reports inside that library, not filmback.
  # intercept_tls_get_addr=0: clang 14's runtime takes a dynamic TLS block that happens to start
  # 16 bytes into a page for a pre-2.25 glibc header and reads an address from before it, and
  # LeakSanitizer's tracer dies at exit ("Tracer caught signal 11"), here in one process of a
  # few hundred (google/sanitizers#1322; fixed after LLVM 16). Such blocks are then not scanned for
  # pointers, which could only report a leak that is not one, never hide one.
  export ASAN_OPTIONS=new_delete_type_mismatch=0:intercept_tls_get_addr=0
  mkdir -p build-sanitize/logs
  if [ $status -eq 0 ]; then
    nice -n 19 tests/fuzz/run_fuzzers.sh build-sanitize 30 >build-sanitize/logs/fuzz.log 2>&1 &
    fuzz=$!
    ctest --test-dir build-sanitize --output-on-failure -j 2 -LE 'sdk|render' -E "$release_only" \
      >build-sanitize/logs/ctest.log 2>&1 || status=1
    wait $fuzz || status=1
    cat build-sanitize/logs/fuzz.log build-sanitize/logs/ctest.log
  fi
  wait $release || status=1
  cat build/logs/ctest.log
  ctest --test-dir build --output-on-failure -j 1 -R "$release_last" || status=1
  exit $status
else
  mkdir -p out
  build/bin/filmback render scenes/default/default.gltf -o out/default.exr -o out/default.png
fi
