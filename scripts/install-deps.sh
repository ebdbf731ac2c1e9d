#!/usr/bin/env bash
# Installs the Debian packages ptnet needs, only those that are missing.
# Does nothing (and needs no network) when everything is present.
#   scripts/install-deps.sh          everything: building, every test, the benchmarks, the package
#   scripts/install-deps.sh build    what building and running `ptnet` needs (make demo): about
#                                    two thirds of the download (no chromium, no Python PyTorch)
set -euo pipefail
build_packages=(cmake ninja-build g++ make ccache pkg-config
          libtorch-dev libgloo-dev libhdf5-dev libeigen3-dev libcli11-dev
          nlohmann-json3-dev zlib1g-dev libdeflate-dev libpng-dev libgif-dev
          libopenblas0-openmp)  # OpenBLAS: LibTorch falls back to netlib BLAS (~25x slower) without it
packages=("${build_packages[@]}"
          hdf5-tools libgtest-dev libgmock-dev libbenchmark-dev
          chromium fonts-dejavu-core  # the report-page tests load index.html in headless chromium
          pybind11-dev python3-dev python3-numpy python3-h5py  # the Python module and its tests (/usr/bin/python3)
          python3-torch  # ptnet export's weights in PyTorch: python/ptnet_torch.py and its tests (~100 MB)
          dpkg-dev  # make package: dpkg-shlibdeps finds the .deb's Depends
          universal-ctags)  # scripts/check-sizes.sh (ctest check_sizes): the functions' lengths
case "${1:-all}" in
  all) ;;
  build) packages=("${build_packages[@]}") ;;
  *) echo "install-deps.sh: expected no argument or 'build', found '$1'" >&2; exit 2 ;;
esac
# make fuzz only: clang with libFuzzer and the sanitizer runtimes.
if [ "${PTNET_FUZZ_DEPS:-0}" = 1 ]; then packages=(clang libclang-rt-14-dev); fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "install-deps: installing ${missing[*]}" >&2
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
if ! $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"; then
  $sudo apt-get update -q
  $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
