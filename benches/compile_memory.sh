#!/bin/sh
# Wall time and peak memory of `lpm derive --format rust` (parse, derive,
# optimize, emit) for the 40- and 100-link chains and the three-link conical
# pendulum, with the release build: `sh benches/compile_memory.sh` from the
# repository root. Each model runs three times; the figures are /usr/bin/time's
# (on a busy machine the CPU time is the steadier figure).
set -e
cargo build -q --release -p lpm
lpm=target/release/lpm
dir=$(mktemp -d)
$lpm chain 40 > "$dir/chain40.lpm"
$lpm chain 100 > "$dir/chain100.lpm"
cp tests/specs/three_link_conical_pendulum.lpm "$dir/conical.lpm"
for model in chain40 chain100 conical; do
    for run in 1 2 3; do
        /usr/bin/time -v $lpm derive --format rust "$dir/$model.lpm" 2> "$dir/time.txt" > /dev/null
        wall=$(grep 'Elapsed (wall clock)' "$dir/time.txt" | sed 's/.*: //')
        rss=$(grep 'Maximum resident' "$dir/time.txt" | sed 's/.*: //')
        user=$(grep 'User time' "$dir/time.txt" | sed 's/.*: //')
        sys=$(grep 'System time' "$dir/time.txt" | sed 's/.*: //')
        echo "$model run $run: wall $wall, CPU ${user} s user + ${sys} s sys, peak RSS $rss kB"
    done
done
rm -r "$dir"
