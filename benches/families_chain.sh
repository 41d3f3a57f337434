#!/usr/bin/env bash
# Derive time and peak memory of a chain of N masses written with families
# (BENCHMARKS.md, "Models at scale"): writes the 5-line spec and times
# `lpm derive` on it. Usage: sh benches/families_chain.sh N [LPM]
set -eu
n=$1
lpm=${2:-target/release/lpm}
spec=$(mktemp --suffix=.lpm)
cat > "$spec" <<SPEC
model Chain$n;
coordinates { x[$n] [m] }
parameters { m[$n] [kg] = 1000.0, k[$((n - 1))] [N/m] = 1.0e6 }
kinetic = sum(i in 1..=$n, 0.5 * m[i] * pow(dot(x[i]), 2));
potential = sum(i in 1..=$((n - 1)), 0.5 * k[i] * pow(x[i + 1] - x[i], 2));
SPEC
/usr/bin/time -f "$n masses: %e s, %M kB peak" "$lpm" derive "$spec" > /dev/null
rm -f "$spec"
