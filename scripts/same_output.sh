#!/usr/bin/env bash
# Output-unchanged check for refactors: runs the same commands with two dqsym binaries and
# diffs every byte of stdout, stderr and the exit status (and written files: --html, convert).
#   bash scripts/same_output.sh BEFORE_BINARY [AFTER_BINARY]
# AFTER_BINARY defaults to target/debug/dqsym. Exit status 0 when every output is identical.
set -u
cd "$(dirname "$0")/.."
before=${1:?usage: same_output.sh BEFORE_BINARY [AFTER_BINARY]}
after=${2:-target/debug/dqsym}
out=$(mktemp -d)
R=examples/robots
cmds=(
  "paper"
  "--format latex paper"
  "-e cos(a)*cos(b)-sin(a)*sin(b)"
  "--format latex -e sin(x/2)^2"
  "--explicit -e cos(a+b)*sin(c)"
  "-e cos(t+1)*sin(u-1/2)+cos(t-u+2)"
  "--format latex -e cos(t/2+1/3)^2*sin(x+1)"
  "--explicit -e cos(x+1)*cos(y+1)-sin(x+1)*sin(y+1)"
  "--format python -e cos(t+1/2+pi/5)*sin(t-3)"
)
for s in examples/*.dq; do
  cmds+=("run $s" "--format latex run $s" "walk $s" "walk --markdown $s" "walk --html OUT.html $s")
done
for fmt in plain latex rust sympy c python; do
  cmds+=("fk --format $fmt $R/puma560.toml" "fk --format $fmt $R/scara.toml" "ik --format $fmt $R/ur5.toml")
done
cmds+=(
  "fk $R/planar2r.toml" "fk --jacobian $R/rrr.toml" "fk --jacobian=rotation $R/planar2r.toml"
  "fk --explicit $R/stanford.toml" "fk $R/kuka_iiwa7.toml" "fk $R/irb140.toml" "fk --point 1,2,3 $R/rrr.toml"
  "fk --format c --jacobian $R/puma_like.toml" "fk benches/support/ur5.urdf"
  "ops" "ops $R/puma560.toml" "ops --jacobian $R/rrr.toml"
  "ik $R/puma560.toml" "ik $R/panda.toml --free theta3" "ik $R/kuka_iiwa7.toml --free theta3" "ik $R/scara.toml"
  "walk $R/rrr.toml" "walk --markdown $R/planar2r.toml" "walk --html OUT.html $R/puma_like.toml"
  "walk --ik $R/ur5.toml" "walk --ik --markdown $R/puma560.toml"
  "convert benches/support/ur5.urdf"
  "fk tests/data/urdf_bad/floating.urdf" "run tests/data/does_not_exist.dq"
  "repl:help" "repl:lines"
)
fail=0
n=0
for c in "${cmds[@]}"; do
  n=$((n + 1))
  for side in before after; do
    bin=${!side}
    d=$out/$n.$side
    mkdir -p "$d"
    args=${c//OUT.html/$d/page.html}
    case "$c" in
      repl:help) printf ':help\n' | "$bin" >"$d/stdout" 2>"$d/stderr"; echo $? >"$d/rc" ;;
      repl:lines) printf 'syms a b\nhalfangle c1, s1 = theta1\nq = (c1, s1, 0, 0)\nq * q\n:format latex\nq*q*(a, b, 0, 0)\n:quit\n' | "$bin" >"$d/stdout" 2>"$d/stderr"; echo $? >"$d/rc" ;;
      *) # shellcheck disable=SC2086
         timeout 600 "$bin" $args >"$d/stdout" 2>"$d/stderr"; echo $? >"$d/rc" ;;
    esac
    # the page path differs between the two runs: name it alike in the text
    sed -i "s#$d/#OUT/#g" "$d/stdout" "$d/stderr"
    sed -i "s#$bin#dqsym#g" "$d/stdout" "$d/stderr"
  done
  if diff -r "$out/$n.before" "$out/$n.after" >"$out/$n.diff"; then
    printf 'same  %s\n' "$c"
  else
    printf 'DIFF  %s  (%s)\n' "$c" "$out/$n.diff"
    fail=1
  fi
done
echo "$n commands, outputs in $out"
if [ $fail = 0 ]; then echo "ALL SAME"; else echo "SOME DIFFER"; fi
exit $fail
