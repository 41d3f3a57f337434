#!/usr/bin/env bash
# Instructions per q̈ of each implementation in benches/evaluation.rs (the
# compiled model, CasADi's C, the hand-written reference, the interpreter,
# the interpreter running native code (jit), and M, f alone), counted by
# callgrind: stable where wall-clock times on a shared machine are not.
#
# Each variant runs twice under callgrind, for N1 and N2 calls; the
# difference of the two totals over N2 − N1 is the count per call, free of
# the set-up both runs share.
#
#   benches/reference/callgrind_qdd.sh            (from the repository root)
set -euo pipefail
command -v valgrind >/dev/null || { echo "valgrind is not installed" >&2; exit 1; }
N1=${N1:-1000}
N2=${N2:-11000}
bench=$(cargo bench -p lagrangian --bench evaluation --no-run --message-format=json 2>/dev/null |
    sed -n 's/.*"executable":"\([^"]*\)".*/\1/p' | tail -n 1)
[ -x "$bench" ] || { echo "could not build the evaluation bench" >&2; exit 1; }

total() { # variant calls -> instructions of the whole run
    valgrind --tool=callgrind --callgrind-out-file=/dev/null "$bench" count "$1" "$2" 2>&1 |
        sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
}

echo "| variant | instructions per call |"
echo "|---|---|"
for variant in compiled casadi hand-written interpreted jit compiled-mf casadi-mf; do
    a=$(total "$variant" "$N1")
    b=$(total "$variant" "$N2")
    echo "| $variant | $(( (b - a) / (N2 - N1) )) |"
done
