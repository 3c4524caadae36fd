#!/usr/bin/env bash
# Configures and builds bsg. Usage: scripts/build.sh [release|asan] [extra cmake args...]
#   release: optimised build in build/release (the default)
#   asan:    Debug build with AddressSanitizer + UndefinedBehaviorSanitizer in build/asan
# BSG_BUILD_TARGET=bsg builds only the program (default: everything, tests included).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
flavour="${1:-release}"
shift || true
case "$flavour" in
  release) build_type=Release; sanitize=OFF ;;
  asan)    build_type=Debug;   sanitize=ON ;;
  *) echo "build.sh: unknown build flavour '$flavour' (expected release or asan)" >&2; exit 2 ;;
esac
build_dir="$root/build/$flavour"
cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE="$build_type" -DBSG_SANITIZE="$sanitize" "$@" >/dev/null
cmake --build "$build_dir" --parallel "$(nproc)" ${BSG_BUILD_TARGET:+--target "$BSG_BUILD_TARGET"}
echo "build.sh: built $build_dir/bsg"
