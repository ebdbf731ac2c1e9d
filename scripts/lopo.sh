#!/usr/bin/env bash
# scripts/lopo.sh WORK: leave one performer out on the CMU corpus (issue 27,
# item 1; docs/lopo.md). For every performer P of the corpus's clips.csv
# (subject column): train the transfer model on the other performers' clips
# (all their takes, as take 1) simulated on the 16 retargeted bodies, and
# evaluate it on P's clips (as take 2) simulated on the 4 original bodies, so
# `ptnet evaluate` reports P's pairs as "unseen"; otherwise the Table 2
# protocol of docs/results.md (bodies and simulate --seed 1, --placement follow).
# Then scripts/lopo.py aggregate prints the table and writes WORK/lopo.json.
#
# Preset: fast by default (12 epochs, 1 LibTorch thread, ~5-10 min a fold
# on 2 cores); PRESET=full (30 epochs, mirrored windows) overrides it.
# Environment:
#   PRESET      fast | full | paper (default fast)
#   SEED        the training seed (default 1; bodies and sensor noise keep seed 1)
#   SAMPLING    the retargeted training bodies: paper (Gaussian draws, default) or
#               cover (a Latin hypercube over mean +- 2.5 sd: 132-208 cm); the
#               original test bodies are the same either way
#   SPEEDS      playback speeds of the training clips (e.g. 0.8,1,1.25: ptnet simulate
#               --speeds, each clip re-simulated at each speed); the test clips stay at 1
#   TRAIN_ARGS  more `ptnet train` flags (e.g. "--epochs 1 --samples-per-epoch 256" to try it out)
#   CORPUS      the corpus folder (default ../shared/mocap-corpus beside the source folder)
#   PTNET       the ptnet binary (default build/ptnet of the source folder)
# Every command runs on one thread. Resumable: a fold whose report/metrics.json
# exists is skipped, and a fold's finished steps are kept (train.h5, test.h5,
# model/); a work folder made with another PRESET, SEED, TRAIN_ARGS or corpus
# is refused. Each fold's folder WORK/performer_P holds the clips CSVs, the
# two datasets, check.txt (the performers each dataset holds, read back with
# h5dump), the model, the report, times.txt (wall seconds a step) and one log
# a step.
set -euo pipefail

usage() { sed -n '2,25s/^# \{0,1\}//p' "$0"; }
die() { echo "lopo: $*" >&2; exit 1; }

case "${1:-}" in
  -h | --help) usage; exit 0 ;;
esac
[ $# -eq 1 ] && [ -n "$1" ] || { echo "usage: $0 WORK (--help: what it does)" >&2; exit 2; }

src=$(cd "$(dirname "$0")/.." && pwd)
work=$1
preset=${PRESET:-fast}
seed=${SEED:-1}
sampling=${SAMPLING:-paper}
speeds=${SPEEDS:-}
train_args=${TRAIN_ARGS:-}
corpus=${CORPUS:-$src/../shared/mocap-corpus}
ptnet=${PTNET:-$src/build/ptnet}

case "$preset" in fast | full | paper) ;; *) die "PRESET: expected fast, full or paper, found '$preset'" ;; esac
[[ "$seed" =~ ^[0-9]+$ ]] || die "SEED: expected a whole number, found '$seed'"
case "$sampling" in paper | cover) ;; *) die "SAMPLING: expected paper or cover, found '$sampling'" ;; esac
[[ -z "$speeds" || "$speeds" =~ ^[0-9.]+(,[0-9.]+)*$ ]] || die "SPEEDS: expected speeds like 0.8,1,1.25, found '$speeds'"
if [ -z "${CORPUS:-}" ] && [ ! -d "$src/../shared" ]; then
  die "$src/../shared: no such folder (the shared data beside the source folder; or set CORPUS)"
fi
[ -f "$corpus/clips.csv" ] || die "$corpus/clips.csv: no such file (the CMU corpus; set CORPUS to its folder)"
corpus=$(cd "$corpus" && pwd)
[ -x "$ptnet" ] || die "$ptnet: not found (make build, or set PTNET)"
command -v h5dump >/dev/null || die "h5dump: not found (apt-get install hdf5-tools): the held-out check reads the datasets with it"
command -v python3 >/dev/null || die "python3: not found (the aggregator needs Python 3)"
read -r -a extra <<<"$train_args"

mkdir -p "$work"
work=$(cd "$work" && pwd)

# The settings that decide the figures; a resumed run must have the same.
settings="preset=$preset
seed=$seed
train_args=$train_args
corpus=$corpus"
# SAMPLING and SPEEDS enter the settings only when not the default, so work
# folders made before they existed still resume.
[ "$sampling" = paper ] || settings="$settings
sampling=$sampling"
[ -z "$speeds" ] || settings="$settings
speeds=$speeds"
if [ -f "$work/settings.txt" ]; then
  recorded=$(grep -E '^(preset|seed|train_args|corpus|sampling|speeds)=' "$work/settings.txt")
  [ "$recorded" = "$settings" ] || die "$work/settings.txt: made with other settings ($(echo $recorded)); use another work folder"
else
  cpu=$(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //')
  printf '%s\ncommit=%s\nptnet=%s\nstarted=%s\nmachine=%s vCPUs, %s\n' "$settings" \
    "$(git -C "$src" rev-parse --short HEAD 2>/dev/null || echo unknown)" "$("$ptnet" --version)" \
    "$(date -u +%Y-%m-%dT%H:%M:%SZ)" "$(nproc)" "$cpu" >"$work/settings.txt.tmp"
  mv "$work/settings.txt.tmp" "$work/settings.txt"
fi

# A step: the command's output goes to LOG; a failure prints the log's last line.
step() {
  local log=$1
  shift
  if ! "$@" </dev/null >"$log.tmp" 2>&1; then
    mv "$log.tmp" "$log"
    die "$(tail -n 1 "$log") (the step's log: $log)"
  fi
  mv "$log.tmp" "$log"
}

# timed NAME LOG COMMAND...: a step of the fold in $dir, its wall seconds added
# to $dir/times.txt as NAME=SECONDS (a resumed step adds a second line).
timed() {
  local name=$1 t0=$SECONDS
  shift
  step "$@"
  { [ ! -f "$dir/times.txt" ] || cat "$dir/times.txt"; echo "$name=$((SECONDS - t0))"; } >"$dir/times.txt.tmp"
  mv "$dir/times.txt.tmp" "$dir/times.txt"
  echo "$head: $name $((SECONDS - t0)) s"
}

# The performers a dataset's sequences hold (their performer attribute), sorted, one line.
performers_of() {
  h5dump -A -g /sequences "$1" | awk '
    /ATTRIBUTE "performer"/ { want = 1; next }
    want && /\(0\):/ { sub(/^[^"]*"/, ""); sub(/"[^"]*$/, ""); print; want = 0 }' | sort -n | uniq | paste -sd' '
}
sequences_of() { h5dump -A -g /sequences "$1" | grep -c 'ATTRIBUTE "performer"'; }

if [ ! -f "$work/bodies.csv" ]; then
  step "$work/bodies.log" "$ptnet" bodies --males 8 --females 8 --originals 2,2 --seed 1 --sampling "$sampling" --out "$work/bodies.csv"
fi
folds=$(python3 "$src/scripts/lopo.py" folds "$corpus/clips.csv" "$work/bodies.csv" "$work") || exit 1
n=$(wc -l <<<"$folds")
echo "lopo: $n folds, preset $preset, training seed $seed${train_args:+, train $train_args}, in $work"

i=0
while read -r p n_train n_test; do
  i=$((i + 1))
  dir=$work/performer_$p
  head="[fold $i/$n] performer $p (train $n_train clips, test $n_test)"
  if [ -f "$dir/report/metrics.json" ]; then
    echo "$head: report exists, skipped"
    continue
  fi
  common=(--placement follow --seed 1 --threads 1)
  at_speeds=()
  [ -z "$speeds" ] || at_speeds=(--speeds "$speeds")
  [ -f "$dir/train.h5" ] || timed simulate_train "$dir/simulate_train.log" \
    "$ptnet" simulate --clips "$dir/train_clips.csv" --bodies "$work/bodies_retargeted.csv" --out "$dir/train.h5" \
    "${common[@]}" "${at_speeds[@]}"
  [ -f "$dir/test.h5" ] || timed simulate_test "$dir/simulate_test.log" \
    "$ptnet" simulate --clips "$dir/test_clips.csv" --bodies "$work/bodies_original.csv" --out "$dir/test.h5" "${common[@]}"

  # The held-out check: what the datasets hold, read back from the files.
  in_train=$(performers_of "$dir/train.h5")
  in_test=$(performers_of "$dir/test.h5")
  [[ " $in_train " != *" $p "* ]] || die "$dir/train.h5: holds sequences of the held-out performer $p"
  [ "$in_test" = "$p" ] || die "$dir/test.h5: expected performer $p only, found $in_test"
  printf 'train.h5: %s sequences of performers %s\ntest.h5: %s sequences of performer %s\n' \
    "$(sequences_of "$dir/train.h5")" "$in_train" "$(sequences_of "$dir/test.h5")" "$in_test" >"$dir/check.txt"

  if [ ! -f "$dir/model/.done" ]; then
    resume=(--force)
    [ -f "$dir/model/checkpoint.pt" ] && resume=(--resume)
    timed train "$dir/train.log" "$ptnet" train --data "$dir/train.h5" --out "$dir/model" --preset "$preset" \
      --seed "$seed" --threads 1 "${resume[@]}" "${extra[@]}"
    touch "$dir/model/.done"
  fi
  timed evaluate "$dir/evaluate.log" "$ptnet" evaluate --model "$dir/model" --data "$dir/test.h5" \
    --out "$dir/report" --threads 1 --force
  # A model no better than the all-zero or copy baseline on validation: evaluate's warning.
  grep -h '^evaluate: warning: ' "$dir/evaluate.log" | sed "s|^evaluate: |$head: |" || true
done <<<"$folds"

python3 "$src/scripts/lopo.py" aggregate "$work"
