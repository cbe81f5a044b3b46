#!/usr/bin/env bash
# Build the scene fuzzer with clang (libFuzzer + ASan + UBSan) and run it for a bounded time.
#
#   tests/fuzz/run.sh SECONDS [BUILD_DIR]
#
# BUILD_DIR (default: build-fuzz next to this repository's top) holds the build, the working
# corpus (corpus/, grown across runs) and any findings (findings/crash-*, leak-*, timeout-*,
# oom-*). Seeds: configs/, tests/data/bad/, tests/data/warn/ and tests/fuzz/seeds/, with tests/fuzz/scene.dict.
# Environment: CXX (default clang++). Exits non-zero when the fuzzer found anything; the last
# lines of fuzz.log then name the input, which belongs in tests/data/bad/ once fixed.
set -euo pipefail

[[ $# -ge 1 && $# -le 2 && $1 =~ ^[0-9]+$ ]] || {
  sed -n '2,10s/^# \{0,1\}//p' "${BASH_SOURCE[0]}" >&2
  exit 2
}
readonly SECONDS_TO_RUN="$1"
readonly FUZZ_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
readonly SOURCE_DIR="$(cd "$FUZZ_DIR/../.." && pwd)"
readonly BUILD_DIR="${2:-$SOURCE_DIR/build-fuzz}"

# The fuzzer hunts input bugs; warnings are the ordinary (gcc, -Werror) build's job, so a
# clang-only warning must not stop it.
cmake -S "$SOURCE_DIR" -B "$BUILD_DIR" -DCMAKE_CXX_COMPILER="${CXX:-clang++}" \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDISCREEL_FUZZ=ON -DDISCREEL_WERROR=OFF \
  -DDISCREEL_BUILD_TESTS=OFF -DDISCREEL_BUILD_BENCH=OFF >/dev/null
cmake --build "$BUILD_DIR" --target scene_fuzzer

mkdir -p "$BUILD_DIR/corpus" "$BUILD_DIR/findings"
# -max_len: above every seed but the largest crafted ones, and enough for deep nesting; the
# 64 MiB limit and larger inputs are tested directly (tests/fuzz/huge_input_test.cpp).
# -rss_limit_mb / -timeout: a memory blow-up or a hang is a finding, not a stuck CI job. The
# slowest valid scene (100 000 random discs) takes about 3 s under the sanitizers; on a busy CI
# machine several times that, hence a timeout far above it.
set +e
"$BUILD_DIR/tests/fuzz/scene_fuzzer" \
  -max_total_time="$SECONDS_TO_RUN" -max_len=16384 -timeout=60 -rss_limit_mb=2048 \
  -dict="$FUZZ_DIR/scene.dict" -artifact_prefix="$BUILD_DIR/findings/" \
  -print_final_stats=1 \
  "$BUILD_DIR/corpus" "$SOURCE_DIR/configs" "$SOURCE_DIR/tests/data/bad" \
  "$SOURCE_DIR/tests/data/warn" "$FUZZ_DIR/seeds" \
  >"$BUILD_DIR/fuzz.log" 2>&1
status=$?
set -e
grep -E '^(#[0-9]+ +DONE|stat::|INFO: (Seed|Loaded))' "$BUILD_DIR/fuzz.log" >&2 || true
if [[ $status -ne 0 ]]; then
  tail -n 60 "$BUILD_DIR/fuzz.log" >&2
  echo "run.sh: the fuzzer found a problem (exit $status); see $BUILD_DIR/fuzz.log" >&2
fi
exit "$status"
