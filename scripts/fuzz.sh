#!/usr/bin/env bash
# Fuzzes the scene parser with libFuzzer (clang-14, ASan + UBSan) for a bounded time.
# Builds only the fuzz target and the libraries it needs (scene, solvers, core) in build/fuzz
# (CMake preset "fuzz"), seeds the corpus with scenes/*.json and runs with -max_total_time.
# A crash leaves its input in build/fuzz/artifacts/ and exits non-zero: add the input to
# tests/scene_fuzz_regress_test.cpp as a regression test.
# Usage: scripts/fuzz.sh [seconds (default 60)] [extra libFuzzer flags...]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
shift || true

# clang-14 and its runtimes: libFuzzer and the sanitizers are in libclang-rt-14-dev (Debian 12),
# OpenMP for clang in libomp-14-dev.
pkgs=(clang-14 libclang-rt-14-dev libomp-14-dev)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "fuzz: installing ${missing[*]}" >&2
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# ccache hits across clones, as in scripts/setup.sh: paths relative to the clone (without this
# every fresh clone, as CI's, compiled the fuzz build from scratch: about 5 minutes on 2 cores).
export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=true
build=build/fuzz
cmake --preset fuzz >/dev/null
cmake --build "$build" --target scene_fuzz -j "${RTSPH_FUZZ_JOBS:-2}"

corpus=$build/corpus/scene
artifacts=$build/artifacts
mkdir -p "$corpus" "$artifacts"
cp scenes/*.json "$corpus"/  # seeds (file names are stable, so this is idempotent)

echo "fuzz: scene_fuzz for ${seconds} s, corpus $corpus ($(ls "$corpus" | wc -l) inputs)" >&2
set +e
ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}" UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1}" \
  "$build/scene_fuzz" "$corpus" -dict=fuzz/scene.dict -max_total_time="$seconds" \
  -max_len=65536 -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
  -artifact_prefix="$artifacts/" "$@"
rc=$?
set -e
if [ "$rc" -ne 0 ]; then
  echo "fuzz: FAILED (exit $rc); reproducer(s) in $artifacts/:" >&2
  ls -t "$artifacts" | head -5 >&2
  echo "fuzz: add each as a test in tests/scene_fuzz_regress_test.cpp" >&2
  exit "$rc"
fi
echo "fuzz: no crash in ${seconds} s" >&2
