#!/usr/bin/env bash
# One entry point for people and CI:
#   ./tuneray.sh demo            install dependencies, build, render the default scene into out/
#   ./tuneray.sh test [--sanitize]   install, build, run the whole test suite (ctest)
#   ./tuneray.sh build           install and build only
#   ./tuneray.sh run ARGS...     build, then run `tuneray ARGS...`
set -euo pipefail
cd "$(dirname "$0")"
ROOT=$(pwd)
JOBS=$(nproc 2>/dev/null || echo 2)

build() {  # build <dir> [cmake args...]
  local dir=$1; shift
  "$ROOT/scripts/install-deps"
  cmake -S "$ROOT" -B "$dir" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
  cmake --build "$dir" -j "$JOBS"
}

cmd=${1:-help}
shift || true
case "$cmd" in
  demo)
    build "$ROOT/build"
    mkdir -p out
    "$ROOT/build/src/app/tuneray" render cornell --spp 64 --size 640x480 \
      --out out/cornell.png --out out/cornell.exr --report out/cornell-report.json "$@"
    echo
    echo "Demo output:"
    echo "  image   $ROOT/out/cornell.png (tonemapped) and $ROOT/out/cornell.exr (linear)"
    echo "  report  $ROOT/out/cornell-report.json (timings per phase)"
    ;;
  test)
    if [ "${1:-}" = "--sanitize" ]; then
      # -O1: sanitizer builds compile much faster than at -O3 and still run the suite quickly.
      build "$ROOT/build-sanitize" -DTUNERAY_SANITIZE=ON -DTUNERAY_BUILD_BENCH=OFF \
        -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -DNDEBUG"
      ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
        ctest --test-dir "$ROOT/build-sanitize" --output-on-failure -j "$JOBS" -LE slow
    else
      build "$ROOT/build"
      ctest --test-dir "$ROOT/build" --output-on-failure -j "$JOBS"
    fi
    ;;
  build)
    build "$ROOT/build"
    ;;
  run)
    build "$ROOT/build" >/dev/null
    exec "$ROOT/build/src/app/tuneray" "$@"
    ;;
  *)
    sed -n '2,6p' "$0"
    [ "$cmd" = help ] || exit 2
    ;;
esac
