#!/usr/bin/env bash
# The total cost of a path-dependent style's sequence rendered in chunks,
# against one run: the chunks starting from checkpoints (each chunk writing
# the next one's start, so they run one after another), a first pass that
# writes every chunk's checkpoint followed by the chunks (which may then run
# in parallel), and the chunks replaying their earlier frames (no
# checkpoints). Times are wall-clock seconds of each `npr render`, summed per
# strategy, taken in one run of this script; the ratios to the single run
# are what docs/PERFORMANCE.md records.
#
#   farm/bench_chunks.sh [STYLE] [SCENE] [FRAMES] [CHUNKS] [SIZE]
#   (default: examples/halftone.npr examples/scenes/cows.toml 48 4 256x192)
set -euo pipefail
style=${1:-examples/halftone.npr}
scene=${2:-examples/scenes/cows.toml}
frames=${3:-48}
chunks=${4:-4}
size=${5:-256x192}
npr=${NPR:-target/debug/npr} # the dev profile is optimized (Cargo.toml)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
render() { "$npr" render "$style" --scene "$scene" --size "$size" "$@" 2>/dev/null; }
seconds() { local t0 t1; t0=$(date +%s.%N); "$@"; t1=$(date +%s.%N); echo "$t1 - $t0" | bc; }
last=$((frames - 1))
every=$((frames / chunks))

single=$(seconds render --frames "0-$last" -o "$work/single/f_{frame}.png")

chain=0
for ((i = 0; i < chunks; i++)); do
  t=$(seconds render --frames "0-$last" --chunk "$i/$chunks" --checkpoints "$work/chain_ck" -o "$work/chain/f_{frame}.png")
  chain=$(echo "$chain + $t" | bc)
done

prepass=$(seconds render --frames "0-$last" --checkpoints "$work/pre_ck" --checkpoint-every "$every")
parallel=$prepass
for ((i = 0; i < chunks; i++)); do
  t=$(seconds render --frames "0-$last" --chunk "$i/$chunks" --checkpoints "$work/pre_ck" -o "$work/par/f_{frame}.png")
  parallel=$(echo "$parallel + $t" | bc)
done

replay=0
for ((i = 0; i < chunks; i++)); do
  t=$(seconds render --frames "0-$last" --chunk "$i/$chunks" -o "$work/replay/f_{frame}.png")
  replay=$(echo "$replay + $t" | bc)
done

for d in chain par replay; do
  cmp -s <(cd "$work/single" && cat ./*.png) <(cd "$work/$d" && cat ./*.png) || { echo "$d: frames differ from the single run" >&2; exit 1; }
done
ratio() { echo "scale=2; $1 / $single" | bc; }
echo "$style on $scene, $frames frames at $size in $chunks chunks (total seconds; ratio to one run)"
printf '%-44s %8.2f s  %5sx\n' "one run" "$single" "1.00"
printf '%-44s %8.2f s  %5sx\n' "chunks from checkpoints, chained" "$chain" "$(ratio "$chain")"
printf '%-44s %8.2f s  %5sx\n' "first pass + chunks from its checkpoints" "$parallel" "$(ratio "$parallel")"
printf '%-44s %8.2f s  %5sx\n' "chunks replaying from frame 0" "$replay" "$(ratio "$replay")"
