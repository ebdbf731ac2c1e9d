#!/usr/bin/env bash
# The installed package as another project and a Python user see it (ctest
# label `install`): installs the build into a fresh prefix, runs the installed
# ptnet from outside the source tree (its model commands go through
# PREFIX/libexec/ptnet/ptnet-torch), builds examples/ against the prefix with
# find_package(ptnet), runs it, and imports ptnet and ptnet_torch from the
# prefix's site folder alone.
#
#   tests/install_test.sh SOURCE_DIR BUILD_DIR WORK_DIR [PYTHON]
set -euo pipefail
src=$1 build=$2 work=$3 python=${4:-}
fail() { echo "install_test: $*" >&2; exit 1; }

rm -rf "$work"
mkdir -p "$work/run"
prefix=$work/prefix
cmake --install "$build" --prefix "$prefix" > "$work/install.log"
for f in bin/ptnet libexec/ptnet/ptnet-torch include/ptnet/transfer.hpp share/man/man1/ptnet.1.gz \
         share/man/man1/ptnet-train.1.gz share/doc/ptnet/README.md share/doc/ptnet/docs/formats.md; do
  [ -e "$prefix/$f" ] || fail "$prefix/$f: not installed"
done
lib=$(find "$prefix" -name 'libptnet.so.*.*.*')
[ -n "$lib" ] || fail "$prefix: no libptnet.so.X.Y.Z"
soname=$(objdump -p "$lib" | awk '$1 == "SONAME" { print $2 }')
[ "$soname" = "libptnet.so.$(basename "$lib" | cut -d. -f3-4)" ] || fail "$lib: SONAME $soname"

# The installed command, from a folder of its own: a tiny dataset and model.
cd "$work/run"
ptnet=$prefix/bin/ptnet
"$ptnet" --version
"$ptnet" -q bodies --males 1 --females 1 --originals 1,1 --seed 1 --out bodies.csv
"$ptnet" -q simulate --embedded --performers 1 --takes 1 --seconds 2 --bodies bodies.csv --out data.h5 \
  --threads 1 --no-floor
# (trained long enough that its contact head predicts contact: the transfers are not all zero)
"$ptnet" -q train --data data.h5 --out model --preset fast --epochs 2 --samples-per-epoch 2048 --lr 0.01 \
  --val-samples 16 --channels 4,8,8 --hidden 16 --latent 16 --batch 16 --micro-batch 16 --threads 1
"$ptnet" -q transfer --model model --in data.h5 --sequence p1_walking_t1__f01 --target female,165,60 --out walk.npy

# examples/ against the prefix, and nothing else: no package registry, and
# the package found must be the prefix's.
launcher=()
if command -v ccache > /dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S "$src/examples" -B "$work/examples" -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix" \
  -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF "${launcher[@]}" > "$work/examples_configure.log"
found=$(sed -n 's/^ptnet_DIR:PATH=//p' "$work/examples/CMakeCache.txt")
case $found in "$prefix"/*) ;; *) fail "find_package(ptnet) found $found, not $prefix" ;; esac
cmake --build "$work/examples" -j 2 > "$work/examples_build.log"
"$work/examples/transfer_example" model walk.npy out.npy | tee example.txt
awk '/^second/ { n++; if ($4 > 0 && $7 > 0) ok++ } END { exit !(n >= 1 && ok == n) }' example.txt ||
  fail "transfer_example: expected a positive force per second, recorded and transferred"
[ -s out.npy ] || fail "transfer_example wrote no out.npy"

# Python: only the prefix's site folder on the path (no build/python, no
# python/); the modules must come from the prefix.
if [ -n "$python" ]; then
  site=$(dirname "$(find "$prefix" -name 'ptnet_torch.py')")
  [ -n "$site" ] || fail "$prefix: no ptnet_torch.py"
  env -u PYTHONHOME PYTHONPATH="$site" "$python" -s - "$prefix" <<'EOF'
import sys
import numpy as np
import ptnet, ptnet_torch
prefix = sys.argv[1]
for m in (ptnet, ptnet_torch):
    assert m.__file__.startswith(prefix + "/"), (m.__name__, m.__file__)
# The module and the C++ example run the same library: the same transfer.
walk = np.load("walk.npy")
out = ptnet.Transfer("model").run(walk, source=ptnet.Body("female", 165, 60), target=ptnet.Body("male", 185, 95))
assert np.array_equal(out, np.load("out.npy")), abs(out - np.load("out.npy")).max()
print("python:", ptnet.__file__, ptnet_torch.__file__)
EOF
fi
echo "install_test: ok ($prefix)"
