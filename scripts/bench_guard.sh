#!/usr/bin/env bash
# The bench suite's rule for the guarded cases of issue 33 (benches/guarded.rs): each case's
# cost now against a saved baseline, and every case slower by more than 10% named.
#   bash scripts/bench_guard.sh [--save] [BINARY]
#     instruction counts (valgrind --tool=callgrind, one thread, so the counts repeat exactly
#     and a shared machine's load does not move them) of the guarded commands, run with BINARY
#     (default target/release/dqsym), against bench/guard_baseline.txt; --save writes that file.
#   bash scripts/bench_guard.sh --criterion [--save]
#     the criterion bench `guarded` against its saved baseline `guard` (wall time, noisier:
#     for a quiet machine), from criterion's own change estimates.
# Exit status 1 when a guarded case is slower by more than 10%, 0 otherwise.
set -u
cd "$(dirname "$0")/.."
limit=10
save=0
criterion=0
bin=target/release/dqsym
for a in "$@"; do
  case "$a" in
    --save) save=1 ;;
    --criterion) criterion=1 ;;
    *) bin=$a ;;
  esac
done
base=bench/guard_baseline.txt

if [ $criterion = 1 ]; then
  if [ $save = 1 ]; then
    exec cargo bench --bench guarded -- --save-baseline guard
  fi
  cargo bench --bench guarded -- --baseline guard >/dev/null || exit 2
  slow=0
  for f in target/criterion/guarded_*/*/change/estimates.json; do
    case=${f#target/criterion/}; case=${case%/change/estimates.json}
    pct=$(python3 -c "import json,sys; print(round(100*json.load(open(sys.argv[1]))['mean']['point_estimate'], 1))" "$f")
    if python3 -c "import sys; sys.exit(0 if float(sys.argv[1]) > $limit else 1)" "$pct"; then
      echo "SLOWER  $case  +$pct%"; slow=1
    else
      echo "ok      $case  $pct%"
    fi
  done
  exit $slow
fi

R=examples/robots
# name|command (the arguments of dqsym)
cases=(
  "puma560_fk_jacobian|fk --jacobian $R/puma560.toml"
  "symbolic_4r_fk_jacobian|fk --jacobian benches/support/symbolic_4r.toml"
  "symbolic_6r_fk_jacobian|fk --jacobian tests/data/generic_6r.toml"
  "jaco_style_fk_jacobian|fk --jacobian tests/data/jaco_style.toml"
  "sin1_sin2_sin3|-e sin(1)*sin(2)*sin(3)"
  "cos1_cos2_cos3_cos4|-e cos(1)*cos(2)*cos(3)*cos(4)"
  "x_plus_y_plus_z_pow_30|--term-limit 1000000 --work-budget 1000000000 -e (x+y+z)^30"
)
tmp=$(mktemp -d)
out=$tmp/counts
slow=0
for c in "${cases[@]}"; do
  name=${c%%|*}
  args=${c#*|}
  # shellcheck disable=SC2086
  DQSYM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file="$tmp/cg" "$bin" $args \
    >/dev/null 2>"$tmp/err"
  n=$(grep -o 'Collected : [0-9]*' "$tmp/err" | awk '{print $3}')
  echo "$name $n" >>"$out"
  old=$(awk -v k="$name" '$1 == k {print $2}' "$base" 2>/dev/null)
  if [ -z "$old" ] || [ $save = 1 ]; then
    printf 'new     %-28s %14s instructions\n' "$name" "$n"
  elif [ $((n * 100)) -gt $((old * (100 + limit))) ]; then
    printf 'SLOWER  %-28s %14s instructions (baseline %s, +%s%%)\n' "$name" "$n" "$old" $(((n - old) * 100 / old))
    slow=1
  else
    printf 'ok      %-28s %14s instructions (baseline %s)\n' "$name" "$n" "$old"
  fi
done
if [ $save = 1 ]; then
  { echo "# instruction counts of scripts/bench_guard.sh's cases (one thread), written by --save"
    cat "$out"; } >"$base"
  echo "saved $base"
fi
rm -rf "$tmp"
exit $slow
