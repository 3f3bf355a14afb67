#!/usr/bin/env bash
# Fingerprints of short runs of every repository input and the shared Uintah inputs, for checking
# that a change leaves results bit-identical: history.csv without its wall-time column, and every
# particle .vtu written (binary data, compared byte for byte), at 1 and 2 threads.
# Usage: fingerprint_runs.sh SUS OUTDIR > fingerprints.txt; compare two such files with diff.
set -uo pipefail
sus=$1
out=$2
root=$(cd "$(dirname "$0")/../.." && pwd)
shared=$root/../shared/inputs
mkdir -p "$out"
run() {  # name steps input
  local name=$1 steps=$2 input=$3
  for threads in 1 2; do
    local dir=$out/${name}_t$threads
    rm -rf "$dir"
    OMP_WAIT_POLICY=passive "$sus" --threads $threads --max-timesteps "$steps" -o "$dir" "$input" \
      > "$dir.log" 2>&1
    local rc=$?
    local hist=$(cut -d, -f1-$(($(head -1 "$dir/history.csv" 2>/dev/null | tr ',' '\n' | wc -l) - 1)) \
      "$dir/history.csv" 2>/dev/null | md5sum | cut -c1-12)
    local vtu=$(cat "$dir"/particles/*.vtu 2>/dev/null | md5sum | cut -c1-12)
    echo "$name threads=$threads exit=$rc history=$hist vtu=$vtu"
  done
}
for f in $(cd "$root/inputs" && find . -name '*.ups' | sort); do
  name=$(echo "${f#./}" | tr / _ | sed 's/\.ups$//')
  case $name in
    Paper_QuasiStatic_Cycle_LargePillar) continue ;;  # its first step alone takes 6 minutes
    Benchmarks_*|Paper_Cycle_LargePillar|Paper_Substrate_*|Paper_QuasiStatic_*) steps=5 ;;
    *) steps=40 ;;
  esac
  run "$name" $steps "$root/inputs/$f"
done
run uintah_1D_Dirichlet 100000 "$shared/uintah/1D_Dirichlet.ups"
run uintah_NanoPillar2D 300 "$shared/uintah/NanoPillar2D_FBC_Sym.ups"
run uintah_SmoothNanoPillar2D 40 "$shared/uintah/SmoothNanoPillar2D_FBC.ups"
run benchmark_Pillar3D_CPDI_diffusion 30 "$shared/benchmarks/Pillar3D_CPDI_diffusion.ups"
run checkpoint_AutoCycleSlab 400 "$root/tests/checkpoint/AutoCycleSlab.ups"
