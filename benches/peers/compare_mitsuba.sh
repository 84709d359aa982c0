#!/usr/bin/env bash
# Runs Mitsuba 3's hair BSDF (mitsuba_hair_bench.py) and hairmath's batch (benches/bcsdf.rs in
# its peer mode) back to back on the same sample count and thread count, and prints Mitsuba's
# time over hairmath's for each of hairmath's instruction sets, from an array of structures and
# (`-soa`) from a structure of arrays, Mitsuba's layout (above 1: hairmath is faster).
# Figures are printed to 0.01 ns, so that rounding moves a ratio of 2 by at most 0.2%; with
# `rounds` above 1 the two run alternately that many times, a ratio per round (the machine's
# state drifts between runs, and alternating exposes it).
# usage: benches/peers/compare_mitsuba.sh [N] [threads] [rounds]   (README in this folder for the set-up)
set -euo pipefail
cd "$(dirname "$0")/../.."
n="${1:-1000000}"
threads="${2:-1}"
rounds="${3:-1}"
python="${MITSUBA_PYTHON:-/tmp/mi/bin/python}"
export DRJIT_LIBLLVM_PATH="${DRJIT_LIBLLVM_PATH:-/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1}"
for round in $(seq "$rounds"); do
    [ "$rounds" -gt 1 ] && echo "round $round of $rounds"
    mitsuba_line=$("$python" benches/peers/mitsuba_hair_bench.py "$n" "$threads" | tail -1)
    hairmath_line=$(BCSDF_PEER_N="$n" BCSDF_PEER_THREADS="$threads" cargo bench --quiet --bench bcsdf 2>/dev/null | tail -1)
    echo "$mitsuba_line"
    echo "$hairmath_line"
    mitsuba_ns=$(sed -E 's/.*: ([0-9.]+) ns per evaluation.*/\1/' <<<"$mitsuba_line")
    grep -oE '(Avx512|Avx2|Baseline)(-soa)? [0-9.]+ ns' <<<"$hairmath_line" | while read -r set ns _; do
        awk -v set="$set" -v m="$mitsuba_ns" -v h="$ns" \
            'BEGIN { printf "Mitsuba / hairmath on %s: %.2f\n", set, m / h }'
    done
done
