#!/usr/bin/env bash
# The graph cut's energy parameters swept on the Middlebury pairs
# (docs/graphcut.md, "Limits": the joint sweep of the energy's parameters). Each line
# of the sweep runs the Explore test of sim_eval_tests once
# and prints its score line, prefixed with the setting. Two runs at a time (one
# per core); about 10 minutes on 2 cores for the Baby1 grid.
#   tests/bench/graphcut_param_sweep.sh [baby1|others] [BUILD_DIR]
# baby1: 54 settings of K, lambda1, lambda2, edge threshold and clip on Baby1
#   (automatic K 107, lambda1 63, lambda2 21);
# others: the two settings best for Baby1, scaled to each other pair's
#   automatic K (edge threshold 32; K x 2 with lambda1 = lambda2 = 0.39 K).
set -euo pipefail
cd "$(dirname "$0")/../.."
which=${1:-baby1}
case "$which" in baby1 | others) ;; *) echo "usage: $0 [baby1|others] [BUILD_DIR]"; exit 2 ;; esac
build=${2:-build/release}
test_bin=$build/tests/sim_eval_tests
[ -x "$test_bin" ] || { echo "missing $test_bin (cmake --build $build --target sim_eval_tests)"; exit 1; }

# One setting: scene K lambda1 lambda2 edge clip ("-" keeps the automatic value).
run_one() {
  local scene=$1 k=$2 l1=$3 l2=$4 edge=$5 clip=$6
  local envs=(PETRA_GC_SCENES="$scene" PETRA_GC_EDGE="$edge" PETRA_GC_CLIP="$clip")
  [ "$k" != - ] && envs+=(PETRA_GC_K="$k")
  [ "$l1" != - ] && envs+=(PETRA_GC_LAMBDA1="$l1")
  [ "$l2" != - ] && envs+=(PETRA_GC_LAMBDA2="$l2")
  env "${envs[@]}" "$test_bin" --gtest_filter='*Explore*' 2>&1 | grep ' strict ' |
    sed "s/^/K=$k l1=$l1 l2=$l2 edge=$edge clip=$clip | /"
}
export -f run_one
export test_bin

settings() {
  case "$which" in
    baby1)
      # K from half to twice the automatic value, lambda = K/20 .. 2K/5 (lambda1 = 3 lambda2).
      for k in 54 75 107 150 214; do
        for div in 20 10 5 2.5; do
          l=$(awk -v k="$k" -v d="$div" 'BEGIN { l = int(k / d + 0.5); print (l < 1 ? 1 : l) }')
          echo "Baby1 $k $((3 * l)) $l 8 30"
        done
      done
      # Edge threshold and clip at the automatic K and lambda.
      for e in 4 8 16 32; do for c in 15 30 60 90; do
        [ "$e" = 8 ] && [ "$c" = 30 ] && continue
        echo "Baby1 107 63 21 $e $c"
      done; done
      # The ratio lambda1 / lambda2, then one lambda at larger K.
      echo "Baby1 107 21 21 8 30"; echo "Baby1 107 63 7 8 30"; echo "Baby1 107 63 63 8 30"
      echo "Baby1 107 42 21 8 30"
      for k in 214 321 428; do for l in 42 63 100 150; do echo "Baby1 $k $l $l 8 30"; done; done
      # Threshold 32 at larger K.
      echo "Baby1 214 63 21 32 30"; echo "Baby1 214 126 42 32 30"; echo "Baby1 321 63 21 32 30"
      ;;
    others)
      for s in tsukuba venus sawtooth map teddy cones Aloe; do echo "$s - - - 32 30"; done
      # K x 2 and lambda1 = lambda2 = 0.39 K of each pair's automatic K
      # (45, 29, 43, 256, 157, 206, 250).
      echo "tsukuba 90 18 18 8 30"; echo "venus 58 11 11 8 30"; echo "sawtooth 86 17 17 8 30"
      echo "map 512 100 100 8 30"; echo "teddy 314 61 61 8 30"; echo "cones 412 80 80 8 30"
      echo "Aloe 500 98 98 8 30"
      ;;
  esac
}
settings | xargs -P 2 -L 1 bash -c 'run_one "$@"' _
