#!/usr/bin/env bash
# Builds the libFuzzer targets of tests/fuzz/libfuzzer with Debian's clang
# (the readers' sources instrumented, -fsanitize=fuzzer,address,undefined;
# the rest linked from the project's static libraries in BUILD_DIR) and runs
# each for SECONDS seconds from its seed corpus. Exit 77 (ctest: skipped) if
# clang++ or its libFuzzer runtime is missing.
# Usage: run_libfuzzer.sh SOURCE_DIR BUILD_DIR SECONDS [TARGET...]
set -euo pipefail
source_dir="$1"
build_dir="$2"
seconds="$3"
shift 3
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(progress_log run_file checkpoint)

clang="$(command -v clang++ || command -v clang++-14 || true)"
if [ -z "$clang" ] || ! "$clang" -print-file-name=libclang_rt.fuzzer-x86_64.a | grep -q /; then
  echo "SKIPPED: clang++ with libFuzzer (clang, libclang-rt-14-dev) is not installed"
  exit 77
fi
runtime="$("$clang" -print-file-name=libclang_rt.fuzzer-x86_64.a)"
if [ ! -f "$runtime" ] && [ ! -f "$(dirname "$("$clang" -print-libgcc-file-name)")/libclang_rt.fuzzer-x86_64.a" ]; then
  echo "SKIPPED: libFuzzer's runtime is missing (libclang-rt-14-dev)"
  exit 77
fi

work="$build_dir/libfuzzer"
mkdir -p "$work"
launcher=()
command -v ccache >/dev/null && launcher=(ccache)
# The instruction set of the project's build (CMakeLists.txt: BSG_NATIVE, and any -m option of
# CMAKE_CXX_FLAGS): Eigen's inline allocation must align the same in the clang objects and the
# libraries, or the fuzzer crashes on its first input.
if [ ! -f "$build_dir/CMakeCache.txt" ]; then
  echo "run_libfuzzer.sh: $build_dir is not a configured build directory (no CMakeCache.txt)" >&2
  exit 2
fi
instruction_set=()
if grep -q '^BSG_NATIVE:BOOL=ON$' "$build_dir/CMakeCache.txt"; then
  instruction_set=(-march=native -mno-avx512f)
fi
for flag in $(sed -n 's/^CMAKE_CXX_FLAGS:STRING=//p' "$build_dir/CMakeCache.txt"); do
  case "$flag" in -m*) instruction_set+=("$flag") ;; esac
done
flags=(-std=c++20 -g -O1 "${instruction_set[@]}" -DBT_USE_DOUBLE_PRECISION -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined
       -I"$source_dir" -isystem /usr/include/eigen3 $(mpicxx --showme:compile) $(pkg-config --cflags bullet)
       -DBSG_CONFIGS_DIR="\"$source_dir/configs\"")
# The readers, instrumented for coverage; the rest comes from the libraries.
readers=(algos/training/progress_csv_reader algos/training/progress_csv algos/training/training_checkpoint common/message_text
         common/checkpoint_file common/binary_io common/file_reading common/config_entries
         common/run_config_schema common/run_config_resolve common/run_config_checks common/config_scalar
         common/run_config_yaml)
objects=()
for reader in "${readers[@]}"; do
  object="$work/$(echo "$reader" | tr / _).o"
  "${launcher[@]}" "$clang" "${flags[@]}" -c "$source_dir/$reader.cpp" -o "$object"
  objects+=("$object")
done
# Every room's library, highest first as a static link needs them (CMakeLists.txt).
libraries=()
for room in algos_training algos_trust_region algos_first_order algos_lagrange algos_core envs envs_assembly \
            envs_tasks envs_sensors envs_agents envs_physics envs_description common; do
  libraries+=("$build_dir/libbsg_$room.a")
done
system_libraries=(-lyaml-cpp $(pkg-config --libs bullet) $(mpicxx --showme:link))

status=0
for target in "${targets[@]}"; do
  program="$work/${target}_fuzzer"
  "${launcher[@]}" "$clang" "${flags[@]}" -c "$source_dir/tests/fuzz/libfuzzer/${target}_fuzzer.cpp" -o "$program.o"
  "$clang" -fsanitize=fuzzer,address,undefined "$program.o" "${objects[@]}" "${libraries[@]}" \
    "${system_libraries[@]}" -o "$program"
  corpus="$work/corpus_$target"
  mkdir -p "$corpus"
  cp -n "$source_dir/tests/fuzz/libfuzzer/corpus/$target/"* "$corpus/" 2>/dev/null || true
  if [ "$target" = checkpoint ] && [ -x "$build_dir/tests/bsg_fuzz_tests" ]; then
    # A valid training checkpoint payload, written by the GoogleTest fuzz test.
    BSG_FUZZ_CHECKPOINT_SEED="$corpus/seed.bin" "$build_dir/tests/bsg_fuzz_tests" \
      --gtest_filter='ReadersFuzz.AMutatedCheckpoint*' >/dev/null
  fi
  echo "== $target: $seconds s"
  # A fixed seed (BSG_FUZZ_SEED to change it), so that a short CI run explores the same way each time.
  if ! ASAN_OPTIONS=detect_leaks=1 "$program" -seed="${BSG_FUZZ_SEED:-1}" -artifact_prefix="$work/$target-" -max_total_time="$seconds" -max_len=65536 -timeout=10 \
       -rss_limit_mb=2048 -print_final_stats=1 "$corpus" 2>&1 | tail -n 25; then
    status=1
  fi
done
exit $status
