#!/usr/bin/env bash
# The `arch` tests: physics and its determinism check without GoogleTest
# (physics_determinism_check) built in a build tree of their own, in another configuration,
# and run; it must give the hash pinned in tests/physics/busy_scene.hpp, as x86-64 does.
#
#   tests/arch/cross_check.sh aarch64 BUILD_DIR     cross-built with g++-aarch64-linux-gnu
#                                                   (cmake/aarch64-linux-gnu.cmake) and run
#                                                   under qemu-aarch64 (package qemu-user)
#   tests/arch/cross_check.sh no-clones BUILD_DIR   built for this machine without the AVX2
#                                                   clones (DISCREEL_AVX2_CLONES=OFF) and with
#                                                   simd.hpp's lane-by-lane shuffles
#
# Only src/common and src/physics are built (DISCREEL_PHYSICS_ONLY): Eigen is all they need.
# Environment: JOBS (default 2), CXX_LAUNCHER (a compiler launcher such as ccache; default
# none), CXX (the no-clones build's compiler; default CMake's choice).
set -euo pipefail

[[ $# -eq 2 && ( $1 == aarch64 || $1 == no-clones ) ]] || {
  sed -n '2,15s/^# \{0,1\}//p' "${BASH_SOURCE[0]}" >&2
  exit 2
}
readonly MODE="$1" BUILD_DIR="$2"
readonly SOURCE_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
readonly JOBS="${JOBS:-2}"

options=(-DCMAKE_BUILD_TYPE=Release -DDISCREEL_PHYSICS_ONLY=ON)
if [[ -n "${CXX_LAUNCHER:-}" ]]; then
  options+=("-DCMAKE_CXX_COMPILER_LAUNCHER=$CXX_LAUNCHER")
fi
run=()
case "$MODE" in
  aarch64)
    for tool in aarch64-linux-gnu-g++ qemu-aarch64; do
      command -v "$tool" >/dev/null || {
        echo "cross_check.sh: $tool not found (apt-get install g++-aarch64-linux-gnu qemu-user)" >&2
        exit 1
      }
    done
    options+=("-DCMAKE_TOOLCHAIN_FILE=$SOURCE_DIR/cmake/aarch64-linux-gnu.cmake")
    run=(qemu-aarch64 -L /usr/aarch64-linux-gnu)
    ;;
  no-clones)
    options+=(-DDISCREEL_AVX2_CLONES=OFF -DCMAKE_CXX_FLAGS=-DDISCREEL_SIMD_GENERIC)
    ;;
esac

mkdir -p "$BUILD_DIR"
echo "== configuring $MODE in $BUILD_DIR"
cmake -S "$SOURCE_DIR" -B "$BUILD_DIR" "${options[@]}" >"$BUILD_DIR/configure.log" 2>&1 || {
  cat "$BUILD_DIR/configure.log" >&2
  exit 1
}
echo "== building physics_determinism_check with $JOBS jobs"
cmake --build "$BUILD_DIR" --target physics_determinism_check --parallel "$JOBS"
echo "== running it${run:+ under ${run[*]}}"
"${run[@]}" "$BUILD_DIR/tests/physics/physics_determinism_check"
