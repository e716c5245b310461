#!/usr/bin/env bash
# Writes the outputs a refactoring must not change, for a before/after comparison:
#   bash scripts/same-outputs.sh OUT        # in the old checkout, then in the new one
#   python3 scripts/same-outputs.py OLD/out NEW/out
# OUT/out: strips of the shared models by every algorithm (PLY, glTF, OBJ, JSON reports),
# fandisk's single strip, culling figures and SETS model, the bundled spot as .glb;
# OUT/hashes.txt: the strip hashes of every mode (the ignored strip_hashes test);
# OUT/bench-strips.md: the stripifier table next to meshoptimizer (one run).
# Needs the research meshes: STRIPKIT_MODELS, else ../shared/models.
set -euo pipefail
out=$(realpath -m "${1:?usage: same-outputs.sh OUT}")
cd "$(dirname "$0")/.."
models=$(realpath "${STRIPKIT_MODELS:-../shared/models}")
export STRIPKIT_MODELS=$models
mkdir -p "$out/out"
cargo build -q --release -p stripkit-cli -p stripkit-bench
bin=target/release/stripkit
for f in bunny.obj cow.obj fandisk.obj horse.ply spot_triangulated.obj \
         quads/spot_quadrangulated.obj quads/fandisk_quads.off quads/horse_quad.obj; do
    b=${f//\//_}
    for a in auto greedy cache balanced qstrip; do
        "$bin" strip "$models/$f" -o "$out/out/$b.$a.ply" --algo "$a" --json >"$out/out/$b.$a.json" 2>"$out/out/$b.$a.err" || true
    done
    "$bin" strip "$models/$f" -o "$out/out/$b.glb" >"$out/out/$b.glb.txt" 2>&1 || true
    "$bin" strip "$models/$f" -o "$out/out/$b.obj" >"$out/out/$b.objout.txt" 2>&1 || true
done
"$bin" strip "$models/fandisk.obj" -o "$out/out/fandisk.single.ply" --algo single --json >"$out/out/fandisk.single.json" 2>&1 || true
"$bin" strip assets/spot.obj -o "$out/out/spot.glb" >"$out/out/spot.glb.txt" 2>&1 || true
"$bin" cull "$models/fandisk.obj" --json >"$out/out/fandisk.cull.json" 2>&1 || true
"$bin" lod build "$models/fandisk.obj" -o "$out/out/fandisk.sets" >"$out/out/fandisk.lod.txt" 2>&1 || true
STRIPKIT_HASH_DIRS="$models:$models/quads" cargo test -q --release -p stripkit --lib strip_hashes -- --ignored --nocapture >"$out/hashes.txt" 2>&1
target/release/stripkit-bench strips --runs 1 --out "$out/bench-strips.md" "$models" >"$out/bench-strips.log" 2>&1
echo "written to $out"
