#!/usr/bin/env bash
# A stand-in for `gearimpact sweep` and `gearimpact merge` with their command line and their file
# contract, so that the Slurm and GNU parallel recipes can be tested before the real sweep exists.
# It computes nothing about gears: each row's value is a fixed function of its key and of the
# case file's checksum (so the case file given must be the one read).
#
#   stand-in-gearimpact.sh sweep CASE [--lines L] [--points P] [--shard K/N] --out DIR
#   stand-in-gearimpact.sh merge DIR... --out DIR
#
# sweep: lines 0..L-1 (default 5), each swept up and down over P points (default 4); shard K of N
# (0-based) takes the lines l with l mod N = K. Without --shard, K and N come from
# SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT, else 0/1. Writes DIR/sweep.csv and
# DIR/poincare.csv, rows keyed (line, direction, index), and DIR/summary.json naming the shard.
# merge: checks that the folders hold shards 0..N-1 of one sweep, each once, and every key once,
# and writes the rows sorted by key with a summary that does not depend on N, so that the merged
# files are byte-identical for any shard count.
set -euo pipefail
export LC_ALL=C

fail() {
  echo "stand-in-gearimpact: $*" >&2
  exit 2
}

positive_integer() {
  if ! [[ "$2" =~ ^[0-9]+$ ]] || (("$2" < 1)); then
    fail "$1 must be an integer >= 1, got '$2'"
  fi
}

sweep() {
  local case_file="" lines=5 points=4 shard="" out=""
  while (($#)); do
    case "$1" in
      --lines) lines="${2-}"; shift 2 || fail "--lines needs a value" ;;
      --points) points="${2-}"; shift 2 || fail "--points needs a value" ;;
      --shard) shard="${2-}"; shift 2 || fail "--shard needs a value K/N" ;;
      --out) out="${2-}"; shift 2 || fail "--out needs a folder" ;;
      -*) fail "sweep: unknown option '$1'" ;;
      *) [[ -z "$case_file" ]] || fail "sweep: one case file only, got '$case_file' and '$1'"
        case_file="$1"; shift ;;
    esac
  done
  [[ -n "$case_file" ]] || fail "sweep: no case file given"
  [[ -r "$case_file" ]] || fail "sweep: cannot read case file '$case_file'"
  [[ -n "$out" ]] || fail "sweep: --out DIR is required"
  positive_integer --lines "$lines"
  positive_integer --points "$points"
  if [[ -z "$shard" ]]; then
    shard="${SLURM_ARRAY_TASK_ID:-0}/${SLURM_ARRAY_TASK_COUNT:-1}"
  fi
  [[ "$shard" =~ ^([0-9]+)/([0-9]+)$ ]] || fail "--shard must be K/N, got '$shard'"
  local k="${BASH_REMATCH[1]}" n="${BASH_REMATCH[2]}"
  ((n >= 1 && k < n)) || fail "--shard K/N needs N >= 1 and 0 <= K < N, got '$shard'"
  local seed
  seed="$(cksum <"$case_file" | cut -d' ' -f1)"
  mkdir -p "$out"
  awk -v k="$k" -v n="$n" -v lines="$lines" -v points="$points" -v seed="$seed" \
    -v sweep_csv="$out/sweep.csv" -v poincare_csv="$out/poincare.csv" \
    -v summary_json="$out/summary.json" '
    BEGIN {
      print "line,direction,index,parameter,value" > sweep_csv
      print "line,direction,index,sample,x" > poincare_csv
      own = ""
      split("up down", dirs, " ")
      for (l = k; l < lines; l += n) {
        own = own (own == "" ? "" : ",") l
        for (d = 1; d <= 2; d++) {
          for (i = 0; i < points; i++) {
            p = (d == 1 ? i : points - 1 - i) / (points > 1 ? points - 1 : 1)
            printf "%d,%s,%d,%.6f,%.9e\n", l, dirs[d], i, p,
              sin(seed % 1000 + 1.7 * l + p) > sweep_csv
            for (s = 0; s < 2; s++)
              printf "%d,%s,%d,%d,%.9e\n", l, dirs[d], i, s,
                cos(seed % 1000 + l + 0.3 * p + s) > poincare_csv
          }
        }
      }
      printf "{\"shard\": \"%d/%d\", \"lines\": %d, \"points\": %d, \"own_lines\": [%s]}\n",
        k, n, lines, points, own > summary_json
    }'
}

merge() {
  local out="" dirs=()
  while (($#)); do
    case "$1" in
      --out) out="${2-}"; shift 2 || fail "--out needs a folder" ;;
      -*) fail "merge: unknown option '$1'" ;;
      *) dirs+=("$1"); shift ;;
    esac
  done
  [[ -n "$out" ]] || fail "merge: --out DIR is required"
  ((${#dirs[@]})) || fail "merge: no shard folder given"
  local d f shards="" sweep_of="" seen=" "
  for d in "${dirs[@]}"; do
    for f in sweep.csv poincare.csv summary.json; do
      [[ -r "$d/$f" ]] || fail "merge: missing $d/$f"
    done
    local summary
    summary="$(<"$d/summary.json")"
    [[ "$summary" =~ \"shard\":\ \"([0-9]+)/([0-9]+)\",\ (\"lines\":\ [0-9]+,\ \"points\":\ [0-9]+) ]] ||
      fail "merge: $d/summary.json names no shard"
    local k="${BASH_REMATCH[1]}" n="${BASH_REMATCH[2]}" this_sweep="${BASH_REMATCH[3]}"
    [[ -z "$shards" || "$shards" == "$n" ]] || fail "merge: $d is shard $k/$n, others are of $shards"
    [[ -z "$sweep_of" || "$sweep_of" == "$this_sweep" ]] ||
      fail "merge: $d is of another sweep ($this_sweep, not $sweep_of)"
    [[ "$seen" != *" $k "* ]] || fail "merge: shard $k/$n given twice"
    shards="$n"
    sweep_of="$this_sweep"
    seen+="$k "
  done
  for ((k = 0; k < shards; k++)); do
    [[ "$seen" == *" $k "* ]] || fail "merge: missing shard $k/$shards"
  done
  [[ "$sweep_of" =~ \"lines\":\ ([0-9]+),\ \"points\":\ ([0-9]+) ]]
  local lines="${BASH_REMATCH[1]}" points="${BASH_REMATCH[2]}"
  mkdir -p "$out"
  merge_file sweep.csv "$lines" "$points" 1 "$out" "${dirs[@]}"
  merge_file poincare.csv "$lines" "$points" 2 "$out" "${dirs[@]}"
  printf '{"lines": %d, "points": %d, "rows": %d}\n' "$lines" "$points" \
    "$(($(wc -l <"$out/sweep.csv") - 1))" >"$out/summary.json"
}

# Sorts one file's rows by key (line, direction, index[, sample]) and checks that each expected
# key is there exactly once, naming the first one missing or repeated.
merge_file() {
  local name="$1" lines="$2" points="$3" per_point="$4" out="$5"
  shift 5
  local sorted="$out/$name.tmp"
  head -n 1 "$1/$name" >"$sorted"
  local d
  for d in "$@"; do tail -n +2 "$d/$name"; done | sort -t, -k1,1n -k2,2 -k3,3n -k4,4n >>"$sorted"
  awk -F, -v lines="$lines" -v points="$points" -v per_point="$per_point" -v name="$name" '
    NR > 1 {
      key = $1 "," $2 "," $3 (per_point > 1 ? "," $4 : "")
      if (key in seen) { print "merge: " name ": key (" key ") twice" > "/dev/stderr"; bad = 1 }
      seen[key] = 1
    }
    END {
      split("up down", dirs, " ")
      for (l = 0; l < lines; l++) for (d = 1; d <= 2; d++) for (i = 0; i < points; i++)
        for (s = 0; s < per_point; s++) {
          key = l "," dirs[d] "," i (per_point > 1 ? "," s : "")
          if (!(key in seen)) {
            print "merge: " name ": missing key (line, direction, index" \
              (per_point > 1 ? ", sample" : "") ") = (" key ")" > "/dev/stderr"
            exit 1
          }
        }
      exit bad
    }' "$sorted" || { rm -f "$sorted"; exit 2; }
  mv "$sorted" "$out/$name"
}

(($#)) || fail "usage: $0 sweep|merge ..."
command="$1"
shift
case "$command" in
  sweep) sweep "$@" ;;
  merge) merge "$@" ;;
  *) fail "unknown command '$command' (sweep, merge)" ;;
esac
