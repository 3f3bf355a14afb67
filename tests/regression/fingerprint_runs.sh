#!/usr/bin/env bash
# Fingerprints of short runs of every repository input and the shared Uintah inputs, for checking
# that a change leaves results bit-identical: history.csv without its wall-time column, and every
# particle .vtu written (binary data, compared byte for byte), at 1 and 2 threads; and the
# distributed runs of tests/parallel on 1 to 4 ranks (RANKS="1 2 3 4", one thread each; an empty
# RANKS skips them).
# Usage: fingerprint_runs.sh SUS OUTDIR > fingerprints.txt; compare two such files with diff.
set -uo pipefail
sus=$1
out=$2
root=$(cd "$(dirname "$0")/../.." && pwd)
shared=$root/../shared/inputs
mkdir -p "$out"
ranks=${RANKS-1 2 3 4}
fingerprint() {  # label dir rc
  local dir=$2
  local hist=$(cut -d, -f1-$(($(head -1 "$dir/history.csv" 2>/dev/null | tr ',' '\n' | wc -l) - 1)) \
    "$dir/history.csv" 2>/dev/null | md5sum | cut -c1-12)
  local vtu=$(cat "$dir"/particles/*.vtu "$dir"/particles/*/*.vtu 2>/dev/null | md5sum | cut -c1-12)
  echo "$1 exit=$3 history=$hist vtu=$vtu"
}
run() {  # name steps input
  local name=$1 steps=$2 input=$3
  for threads in 1 2; do
    local dir=$out/${name}_t$threads
    rm -rf "$dir"
    OMP_WAIT_POLICY=passive "$sus" --threads $threads --max-timesteps "$steps" -o "$dir" "$input" \
      > "$dir.log" 2>&1
    fingerprint "$name threads=$threads" "$dir" $?
  done
}
run_ranks() {  # name steps input
  local name=$1 steps=$2 input=$3
  for np in $ranks; do
    local dir=$out/${name}_np$np
    rm -rf "$dir"
    OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1 \
      OMP_WAIT_POLICY=passive mpirun -np "$np" "$sus" --threads 1 --max-timesteps "$steps" \
      -o "$dir" "$input" > "$dir.log" 2>&1
    fingerprint "$name ranks=$np" "$dir" $?
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
for f in $(cd "$root/tests/parallel" && ls *.ups); do
  case $f in
    Implicit*) steps=4 ;;
    *) steps=40 ;;
  esac
  [ -n "$ranks" ] && run_ranks "parallel_${f%.ups}" $steps "$root/tests/parallel/$f"
done
