#!/usr/bin/env bash
# Fills fuzz/corpus/<target>/ with small seed inputs. The corpus is git-ignored.
#   fuzz/seed.sh            # from the repository root or from fuzz/
# Sources: assets/*.obj (public domain Spot meshes), small meshes written by
# `stripkit gen` in every format, hand-written DIMACS graphs and door lists, and,
# when present, small files from ../shared/models (read at run time only: they are
# research data and never enter the repository).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/.." && pwd)"
corpus="$here/corpus"
cd "$root"
for t in read_obj read_ply read_off read_stl read_gltf read_glb dimacs door door_quads read_sequence scene options; do
    mkdir -p "$corpus/$t"
done

# 1. The Spot meshes in the repository.
for f in assets/*.obj; do
    cp "$f" "$corpus/read_obj/asset_$(basename "$f")"
done

# 2. Small generated meshes in every format.
cargo build --quiet -p stripkit-cli
cli="$root/target/debug/stripkit"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
for ext in obj ply off stl gltf glb; do
    out="$corpus/read_$ext"
    "$cli" gen grid 2 2 -o "$tmp/grid.$ext"
    "$cli" gen grid 3 2 --quads -o "$tmp/grid_quads.$ext" 2>/dev/null || true
    "$cli" gen icosphere 0 -o "$tmp/ico0.$ext"
    "$cli" gen icosphere 1 -o "$tmp/ico1.$ext"
    "$cli" gen torus --major 6 --minor 4 -o "$tmp/torus.$ext"
    "$cli" gen torus --major 5 --minor 3 --quads -o "$tmp/torus_quads.$ext" 2>/dev/null || true
    "$cli" gen cube -o "$tmp/cube.$ext" 2>/dev/null || true
    for f in "$tmp"/*."$ext"; do
        [ -f "$f" ] && cp "$f" "$out/gen_$(basename "$f")"
    done
done

# 3. Small research models, when the shared folder is there (not copied into git).
models="$root/../shared/models"
if [ -d "$models" ]; then
    while IFS= read -r -d '' f; do
        ext="${f##*.}"
        ext="${ext,,}"
        case "$ext" in
            obj|ply|off|stl|gltf|glb) cp "$f" "$corpus/read_$ext/shared_$(basename "$f")" ;;
        esac
    done < <(find "$models" -type f -size -64k -print0)
fi

# 4. DIMACS graphs.
d="$corpus/dimacs"
printf 'c a triangle plus a pendant\np edge 4 4\ne 1 2 3\ne 2 3 4\ne 3 1 5\ne 3 4 1\n' > "$d/pendant.txt"
printf 'p edge 2 1\ne 1 2 7\n' > "$d/edge.txt"
printf 'c odd cycle, no perfect matching\np edge 5 5\ne 1 2 1\ne 2 3 2\ne 3 4 3\ne 4 5 4\ne 5 1 5\n' > "$d/c5.txt"
printf 'p edge 6 9\ne 1 2 4\ne 2 3 1\ne 3 1 6\ne 4 5 2\ne 5 6 8\ne 6 4 3\ne 1 4 -2\ne 2 5 5\ne 3 6 0\n' > "$d/prism.txt"
printf 'p edge 4 5\ne 1 2 1\ne 1 2 9\ne 2 2 3\ne 3 4 1\ne 1 3 1\n' > "$d/parallel_loop.txt"
printf 'p edge 3 0\n' > "$d/empty.txt"

# 5. Door: first byte = algorithm and join, then two indices per byte (nibbles).
p="$corpus/door"
for a in 0 1 2 3 4 5 6 7 8 9 10 11; do
    # a 2x1 quad strip and a fan: (0,1,2) (2,1,3) (2,3,4) (4,3,5)
    printf "\\x$(printf %02x "$a")\\x10\\x12\\x31\\x32\\x44\\x53" > "$p/strip_$a"
done
printf '\x01\x10\x02\x32\x03\x43\x00\x54\x06\x71\x08\x98' > "$p/fan"
printf '\x04\x11\x11\x10\x21\x21\x10' > "$p/degenerate_dupes"
# 6. Door on quads: first byte = algorithm, then one face per two bytes (four
# nibbles; a last nibble of 15 makes a triangle). A 3x3 quad grid on the 4x4 points,
# a quad fan, and a mixed quad-triangle patch.
q="$corpus/door_quads"
for a in 0 1 2 3 4 5 6 7; do
    printf "\\x$(printf %02x "$a")\\x40\\x15\\x51\\x26\\x62\\x37\\x84\\x59\\x95\\x6a\\xa6\\x7b\\xc8\\x9d\\xd9\\xae\\xea\\xbf" > "$q/grid_$a"
done
printf '\x02\x10\x32\x30\x54\x50\x76\x21\xf3' > "$q/fan_mixed"
# 7. Collapse sequences, binary (first byte 0) and JSON (first byte 1), of small
# generated meshes.
r="$corpus/read_sequence"
"$cli" gen icosphere 1 -o "$tmp/ico.obj"
"$cli" gen grid 3 3 -o "$tmp/grid.obj"
for m in ico grid; do
    "$cli" simplify "$tmp/$m.obj" --ratio 0.3 -o "$tmp/${m}_s.obj" --sequence "$tmp/$m.bin" >/dev/null
    "$cli" simplify "$tmp/$m.obj" --ratio 0.3 -o "$tmp/${m}_s.obj" --sequence "$tmp/$m.json" >/dev/null
    { printf '\x00'; cat "$tmp/$m.bin"; } > "$r/$m.bin"
    { printf '\x01'; cat "$tmp/$m.json"; } > "$r/$m.json"
done
# 8. SETS models of small generated meshes, without their trailing CRC-32 (the
# target appends it, so that mutations reach the structure behind the checksum).
z="$corpus/read_sets"
mkdir -p "$z"
for m in ico grid; do
    "$cli" lod build "$tmp/$m.obj" -o "$tmp/$m.sets" >/dev/null
    "$cli" lod build "$tmp/$m.obj" -o "$tmp/${m}_opt.sets" --placement optimal >/dev/null
    for f in "$m" "${m}_opt"; do
        head -c -4 "$tmp/$f.sets" > "$z/$f"
    done
done
# 9. An animation model (three frames of one mesh), without its trailing CRC-32.
z="$corpus/read_lodseq"
mkdir -p "$z" "$tmp/anim"
for f in 0 1 2; do
    "$cli" gen icosphere 1 -o "$tmp/anim/frame-$f.obj" >/dev/null
done
"$cli" lod build-seq "$tmp/anim" -o "$tmp/anim.lodseq" --samples 200 >/dev/null
"$cli" lod build-seq "$tmp/anim" -o "$tmp/anim_q.lodseq" --samples 200 --position-bits 12 >/dev/null
head -c -4 "$tmp/anim.lodseq" > "$z/anim"
head -c -4 "$tmp/anim_q.lodseq" > "$z/anim_q"
# 10. Scenes with skins, morph targets, strips, fans and unindexed primitives, as
# GLB and glTF, and the committed regression inputs of every target.
cargo run --quiet -p stripkit-fuzzcheck --example fuzz_seeds -- "$corpus/scene" >/dev/null
cp "$corpus"/read_gltf/gen_*.gltf "$corpus"/read_glb/gen_*.glb "$corpus/scene/"
# 11. Option values: byte 0 picks the option (see crates/stripkit-fuzzcheck/src/options.rs).
mkdir -p "$corpus/options"
for t in scene options; do
    cp "$root/fuzz/regressions/$t"/* "$corpus/$t/"
done
echo "seeded: $(find "$corpus" -type f | wc -l) files in $corpus"
