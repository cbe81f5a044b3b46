#!/usr/bin/env bash
# Set up a Debian bookworm machine for discreel, build it, and render the demo or run the tests.
#
#   bash setup.sh demo          install packages, build, render the demo to out/demo.mp4
#   bash setup.sh test [ARGS]   install packages (with the container tools, clang, the
#                               aarch64 cross compiler and qemu, chromium, Slurm), build, run
#                               ctest (the fuzzer for 60 s and the `arch` builds included) and
#                               clang-tidy over src/; then build again with ASan + UBSan and
#                               run the suite once more under them.
#                               ARGS go to both ctest runs, e.g. `bash setup.sh test -LE container`
#   bash setup.sh build         install packages, build (what the Dockerfile runs)
#   bash setup.sh deps          install packages only
#
# Environment: BUILD_DIR (default: build, relative to this file), SANITIZE_BUILD_DIR (default:
# build-asan), JOBS (default: all cores).
# Only missing packages are installed; a machine that has them all is never touched by apt.
set -euo pipefail

readonly SOURCE_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
readonly BUILD_DIR="${BUILD_DIR:-$SOURCE_DIR/build}"
readonly SANITIZE_BUILD_DIR="${SANITIZE_BUILD_DIR:-$SOURCE_DIR/build-asan}"
readonly JOBS="${JOBS:-$(nproc)}"

# What the top-level CMakeLists.txt finds, plus ffprobe/ffmpeg, which the tests call.
readonly BUILD_PACKAGES=(
  g++ cmake make pkg-config
  libosmesa6-dev libeigen3-dev libyaml-cpp-dev libcli11-dev libfreetype-dev fonts-dejavu-core
  libavcodec-dev libavformat-dev libswscale-dev libavutil-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libboost-dev libcpp-httplib-dev nlohmann-json3-dev libsqlite3-dev
  ffmpeg
)
# Only the container test (ctest label `container`) needs these; see docs/container.md.
readonly CONTAINER_TEST_PACKAGES=(buildah podman debootstrap debian-archive-keyring)
# The scene fuzzer (ctest label `fuzz`) needs clang and its libFuzzer runtime; see
# docs/reliability.md.
readonly CHECK_PACKAGES=(clang libclang-rt-14-dev clang-tidy)
# The service's browser test (ctest label `browser`) drives chromium over the DevTools protocol
# from Python; see docs/serve.md. The container test talks to the service with curl.
readonly BROWSER_TEST_PACKAGES=(chromium python3 python3-websocket curl)
# The Slurm test (ctest label `slurm`) runs munged, slurmctld and two slurmd nodes on this
# machine; see docs/scale.md.
readonly SLURM_TEST_PACKAGES=(slurm-wlm munge)
# The aarch64 test (ctest label `arch`) cross-builds physics and runs it under qemu; see
# docs/physics.md.
readonly ARCH_TEST_PACKAGES=(g++-aarch64-linux-gnu qemu-user)

usage() {
  sed -n '2,13s/^# \{0,1\}//p' "${BASH_SOURCE[0]}" >&2
  exit 2
}

log() { printf '\n==> %s\n' "$*" >&2; }

as_root() {
  if [[ $EUID -eq 0 ]]; then
    "$@"
  elif command -v sudo >/dev/null; then
    sudo "$@"
  else
    echo "setup.sh: installing packages needs root (or sudo): $*" >&2
    exit 1
  fi
}

missing_packages() {
  local package
  for package in "$@"; do
    if [[ "$(dpkg-query -W -f='${db:Status-Status}' "$package" 2>/dev/null)" != installed ]]; then
      echo "$package"
    fi
  done
}

install_packages() {
  local missing
  mapfile -t missing < <(missing_packages "$@")
  if [[ ${#missing[@]} -eq 0 ]]; then
    log "All ${#@} required packages are installed"
    return
  fi
  log "Installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  as_root apt-get update
  as_root apt-get install -y --no-install-recommends "${missing[@]}" </dev/null
}

build() {
  log "Configuring (Release) in $BUILD_DIR"
  cmake -S "$SOURCE_DIR" -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release
  log "Building with $JOBS jobs"
  cmake --build "$BUILD_DIR" --parallel "$JOBS"
}

[[ $# -ge 1 ]] || usage
command="$1"
shift
case "$command" in
  deps)
    install_packages "${BUILD_PACKAGES[@]}"
    ;;
  build)
    install_packages "${BUILD_PACKAGES[@]}"
    build
    ;;
  demo)
    install_packages "${BUILD_PACKAGES[@]}"
    build
    mkdir -p "$SOURCE_DIR/out"
    log "Rendering the built-in demo"
    "$BUILD_DIR/bin/discreel" render -o "$SOURCE_DIR/out/demo.mp4"
    log "Done: $SOURCE_DIR/out/demo.mp4"
    ;;
  test)
    install_packages "${BUILD_PACKAGES[@]}" "${CONTAINER_TEST_PACKAGES[@]}" "${CHECK_PACKAGES[@]}" \
      "${ARCH_TEST_PACKAGES[@]}" "${BROWSER_TEST_PACKAGES[@]}" "${SLURM_TEST_PACKAGES[@]}"
    build
    log "Running the tests"
    ctest --test-dir "$BUILD_DIR" --output-on-failure --parallel "$JOBS" "$@"
    # The agreed checks of .clang-tidy, every finding an error; the Release build's
    # compile_commands.json says how each file is compiled.
    log "Running clang-tidy over src/"
    run-clang-tidy -p "$BUILD_DIR" -j "$JOBS" -quiet "$SOURCE_DIR/src/" >"$BUILD_DIR/clang-tidy.log" 2>&1 \
      || { grep -E "(error|warning):" "$BUILD_DIR/clang-tidy.log" >&2; log "clang-tidy found problems (whole output: $BUILD_DIR/clang-tidy.log)"; exit 1; }
    # The same suite again, where a memory error or undefined behaviour stops the test that
    # hit it; without the container test (it builds the Release image) and the benchmarks.
    # A sanitizer build registers no fuzzer test: the fuzzer runs under them already. Peak
    # memory is not measured there: ASan's shadow memory and quarantine are most of it.
    log "Configuring (ASan + UBSan) in $SANITIZE_BUILD_DIR"
    cmake -S "$SOURCE_DIR" -B "$SANITIZE_BUILD_DIR" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DDISCREEL_SANITIZE=ON -DDISCREEL_BUILD_BENCH=OFF
    cmake --build "$SANITIZE_BUILD_DIR" --parallel "$JOBS"
    log "Running the tests under the sanitizers"
    ctest --test-dir "$SANITIZE_BUILD_DIR" --output-on-failure --parallel "$JOBS" \
      -LE container -E PeakMemory "$@"
    ;;
  *)
    usage
    ;;
esac
