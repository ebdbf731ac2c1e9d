#!/usr/bin/env bash
# scripts/check-numerics.sh [BUILD]: runs the tests that compare floating-point
# results (ctest label `numerics`) as they would run on other x86-64 CPUs:
# under every instruction-set level this CPU allows x LibTorch threads 1 and 2,
# one summary line per combination; exits 1 if any combination fails
# (make check-cpu; README, Development).
#
# A level stands for a CPU. It caps every library that picks its kernels from
# the CPU at run time, since a CPU-dependent result can come from any of them:
#   ATEN_CPU_CAPABILITY  ATen's vectorised kernels (default, avx2, avx512)
#   DNNL_MAX_CPU_ISA     oneDNN's convolutions (LibTorch's mkldnn path)
#   OPENBLAS_CORETYPE    OpenBLAS's sgemm kernels and blocking (conv via im2col, linear layers)
#   GLIBC_TUNABLES       libm's exp/log/pow variants (the FMA ones round differently)
# Levels: default (SSE4.1: a pre-2013 x86-64), avx2 (Haswell), zen (avx2 with
# OpenBLAS's Zen kernels and blocking: AMD EPYC), avx512 (Skylake-X), native
# (nothing capped: what this CPU picks). Threads: OMP_NUM_THREADS (LibTorch's
# intra-op pool where ptnet leaves it; the project's own loops give the same
# results for any thread count, core/parallel.hpp).
#
# Environment: LEVELS="default avx2" and THREADS="1" choose a subset; JOBS
# (default: the CPU count) tests run at once; CTEST_ARGS is passed on (e.g.
# "-R model_"). Run from the source folder; the build folder (default build/)
# must be built.
set -u
BUILD=${1:-build}
if [ ! -f "$BUILD/CTestTestfile.cmake" ]; then
  echo "check-numerics: $BUILD is not a build folder (make build first)" >&2
  exit 2
fi

flags=$(grep -m1 '^flags' /proc/cpuinfo)
has() { [[ " ${flags#*:} " == *" $1 "* ]]; }
levels=(default)
has avx2 && has fma && levels+=(avx2 zen)
has avx512f && has avx512bw && has avx512vl && has avx512dq && levels+=(avx512)
levels+=(native)
if [ -n "${LEVELS:-}" ]; then
  read -r -a wanted <<<"$LEVELS"
  for l in "${wanted[@]}"; do
    [[ " ${levels[*]} " == *" $l "* ]] || { echo "check-numerics: level $l: this CPU allows ${levels[*]}" >&2; exit 2; }
  done
  levels=("${wanted[@]}")
fi
read -r -a threads <<<"${THREADS:-1 2}"

# The environment of a level (one VAR=VALUE a line).
level_env() {
  local no_fma="glibc.cpu.hwcaps=-AVX512F,-AVX512VL,-AVX512BW,-AVX512DQ,-AVX2,-FMA,-AVX"
  local no_avx512="glibc.cpu.hwcaps=-AVX512F,-AVX512VL,-AVX512BW,-AVX512DQ"
  case $1 in
    default) printf '%s\n' ATEN_CPU_CAPABILITY=default DNNL_MAX_CPU_ISA=SSE41 OPENBLAS_CORETYPE=Nehalem \
                            "GLIBC_TUNABLES=$no_fma" ;;
    avx2)    printf '%s\n' ATEN_CPU_CAPABILITY=avx2 DNNL_MAX_CPU_ISA=AVX2 OPENBLAS_CORETYPE=Haswell \
                            "GLIBC_TUNABLES=$no_avx512" ;;
    zen)     printf '%s\n' ATEN_CPU_CAPABILITY=avx2 DNNL_MAX_CPU_ISA=AVX2 OPENBLAS_CORETYPE=Zen \
                            "GLIBC_TUNABLES=$no_avx512" ;;
    avx512)  printf '%s\n' ATEN_CPU_CAPABILITY=avx512 DNNL_MAX_CPU_ISA=AVX512_CORE OPENBLAS_CORETYPE=SkylakeX ;;
    native)  ;;
  esac
}

log_dir="$BUILD/check-numerics"
mkdir -p "$log_dir"
failed=0
echo "check-numerics: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'), $(nproc) CPUs; levels ${levels[*]}; threads ${threads[*]}"
for level in "${levels[@]}"; do
  mapfile -t vars < <(level_env "$level")
  for t in "${threads[@]}"; do
    log="$log_dir/$level-t$t.log"
    start=$SECONDS
    # shellcheck disable=SC2086  # CTEST_ARGS is a list of arguments
    (cd "$BUILD" && env "${vars[@]}" OMP_NUM_THREADS="$t" ctest -L numerics --output-on-failure \
      -j "${JOBS:-$(nproc)}" ${CTEST_ARGS:-}) \
      >"$log" 2>&1
    rc=$?
    summary=$(grep -E '^[0-9]+% tests passed' "$log" | tail -1)
    bad=$(grep -E '^[[:space:]]+[0-9]+ - .*\((Failed|Timeout|SEGFAULT|Subprocess aborted|Not Run|Exception)' "$log" |
          sed -E 's/^[[:space:]]+[0-9]+ - //; s/ \(.*//' | tr '\n' ' ')
    [ $rc -eq 0 ] || failed=1
    printf '%-8s threads %s: %s%s (%d s; %s)\n' "$level" "$t" "${summary:-ctest failed to run (rc $rc)}" \
      "${bad:+; failed: $bad}" $((SECONDS - start)) "$log"
  done
done
exit $failed
