#!/usr/bin/env bash
# scripts/check-sizes.sh [DIR...]: the size limits of the project's C++
# sources (issue 41): no function longer than 80 lines and no file longer
# than 450 lines under each DIR (default: src/, app/ and python/ beside this
# script: the library, the command-line tool and the Python module), SIMD
# kernels included. One line per breach (`src/sim/x.cpp:120: function f is
# 93 lines (limit 80)`), then exit 1; exit 0 when every function and file is
# within. The ctest test `check_sizes` (label unit) runs it on the three,
# so CI holds the limits.
#
# Functions: every C++ function definition Universal Ctags finds (free,
# member, inline in a class or header), from its first line (the one with
# its name) to its closing brace; a lambda counts within its function.
# Files: *.cpp, *.hpp, *.h, *.cc, lines as `wc -l` counts them.
# MAX_FUNCTION_LINES and MAX_FILE_LINES override the limits.
set -euo pipefail
if [ $# -ge 1 ]; then
  dirs=("$@")
else
  cd "$(dirname "$0")/.."
  dirs=(src app python)
fi
max_function=${MAX_FUNCTION_LINES:-80}
max_file=${MAX_FILE_LINES:-450}
if ! ctags --version 2>/dev/null | grep -q "Universal Ctags"; then
  echo "check-sizes: needs Universal Ctags as ctags (Debian: universal-ctags)" >&2
  exit 2
fi
files=()
for dir in "${dirs[@]}"; do
  [ -d "$dir" ] || { echo "check-sizes: $dir is not a folder" >&2; exit 2; }
  mapfile -t found < <(find "$dir" -type f \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' -o -name '*.cc' \) | sort)
  [ ${#found[@]} -gt 0 ] || { echo "check-sizes: no C++ sources under $dir" >&2; exit 2; }
  files+=("${found[@]}")
done

# Functions: name, file, line: and end: fields of ctags' tag lines (-o -).
functions=$(ctags --languages=C++ --c++-kinds=f --fields=+ne -o - "${files[@]}" |
  awk -F'\t' -v max="$max_function" '
    $1 ~ /^__anon/ { next }  # lambdas: counted within their function
    {
      start = ""; end = ""
      for (i = 4; i <= NF; i++) {
        if ($i ~ /^line:/) start = substr($i, 6)
        if ($i ~ /^end:/) end = substr($i, 5)
      }
      if (end == "") { printf "%s:%s: function %s: ctags found no end\n", $2, start, $1; next }
      n = end - start + 1
      if (n > max) printf "%s:%s: function %s is %d lines (limit %d)\n", $2, start, $1, n, max
    }' | sort -t: -k1,1 -k2,2n)
sizes=$(wc -l "${files[@]}" | awk -v max="$max_file" '$2 != "total" && $1 > max {
  printf "%s: file is %d lines (limit %d)\n", $2, $1, max }')

if [ -n "$functions$sizes" ]; then
  [ -z "$functions" ] || echo "$functions"
  [ -z "$sizes" ] || echo "$sizes"
  exit 1
fi
echo "check-sizes: ${#files[@]} files under ${dirs[*]}: every function <= $max_function lines, every file <= $max_file lines"
