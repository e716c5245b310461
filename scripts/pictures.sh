#!/bin/sh
# Makes the README's pictures, docs/pictures/*.png, with the release CLI's
# `stripkit render` (offscreen EGL; Mesa's llvmpipe is enough). Reads the research
# meshes of ../shared/models (or $MODELS). Prints one line per picture: strips,
# triangles, the time to upload, draw and read back, and the picture's size.
#
#   scripts/pictures.sh            # from the repository root or anywhere
set -eu
cd "$(dirname "$0")/.."
MODELS=${MODELS:-../shared/models}
OUT=docs/pictures
[ -d "$MODELS" ] || { echo "pictures.sh: no $MODELS (set MODELS to the research meshes)" >&2; exit 2; }
cargo build --release -q -p stripkit-cli
S=target/release/stripkit
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
mkdir -p "$OUT"

# render NAME WxH MESH [FLAGS...]: docs/pictures/NAME.png.
render() {
    name=$1 size=$2 mesh=$3
    shift 3
    "$S" render "$mesh" -o "$OUT/$name.png" --size "$size" "$@" --json >"$TMP/$name.json"
    # One line: the name, strips, triangles, milliseconds to upload, draw and read back.
    sed -e 's/.*"strips":\([0-9]*\),"triangles":\([0-9]*\).*"draw_ms":\([0-9.]*\).*/\1 \2 \3/' "$TMP/$name.json" |
        { read -r strips tris ms; printf '%-27s %5s strips %6s triangles  draw %4.0f ms  %6s bytes\n' \
            "$name" "$strips" "$tris" "$ms" "$(wc -c <"$OUT/$name.png")"; }
}

# 1. The bunny, each stripifier, coloured by strip and by strip order.
BUNNY=$MODELS/bunny.obj
for algo in greedy cache balanced; do
    render "bunny-$algo-strips" 320x320 "$BUNNY" --algo "$algo"
    render "bunny-$algo-order" 320x320 "$BUNNY" --algo "$algo" --color order
    render "bunny-$algo-zoom" 320x320 "$BUNNY" --algo "$algo" --zoom 3
done
# What back-face culling skips for the eye of the pictures above, seen from the bunny's front.
render bunny-cull 240x240 "$BUNNY" --color cull --view -1,0.3,0.4 --cull-view 0.3,0.4,1

# 2. QSTRIP on quad meshes: rows of quads become long swap-free strips (greedy beside
# it on the same quads), and fandisk's few strips with their edges (each quad's diagonal)
# and their order.
SPOT=$MODELS/quads/spot_quadrangulated.obj
render spot-quads-qstrip 320x320 "$SPOT" --algo qstrip --view 0.8,0.4,-1
render spot-quads-greedy 320x320 "$SPOT" --algo greedy --view 0.8,0.4,-1
render fandisk-quads-qstrip 320x320 "$MODELS/quads/fandisk_quads.off" --algo qstrip --view 1,0.6,-0.9 --wireframe
render fandisk-quads-qstrip-order 320x320 "$MODELS/quads/fandisk_quads.off" --algo qstrip --view 1,0.6,-0.9 \
    --color order

# 3. Levels of detail: the bunny simplified (endpoint placement), each level stripped.
for ratio in 0.25 0.05 0.01; do
    "$S" simplify "$BUNNY" --ratio "$ratio" -o "$TMP/bunny-$ratio.ply" >/dev/null
    render "bunny-lod-$ratio" 240x240 "$TMP/bunny-$ratio.ply"
done
render bunny-lod-1 240x240 "$BUNNY"

# 4. A morph between two frames of the horse gallop, blended on the GPU; the strips are
# frame 1's (every frame shares its connectivity), and the camera frames both frames so
# that the pictures line up.
GALLOP=$MODELS/sequences/horse-gallop
for t in 0 0.33 0.67 1; do
    render "horse-morph-$t" 320x200 "$GALLOP/horse-gallop-01.obj.gz" --morph "$GALLOP/horse-gallop-07.obj.gz" \
        --t "$t" --view 1,0.15,0.05
done

# 5. Single strips (--algo single): one strip per model, coloured along its length
# (blue first, red last), for each weight kind. Cull keeps to flat regions, cache winds
# around compact balls of a breadth-first tree of edges, direction:0,0,1 runs along z
# (the horse's up).
for w in uniform cull cache direction:0,0,1; do
    tag=$(echo "$w" | cut -d: -f1)
    render "fandisk-single-$tag" 240x240 "$MODELS/fandisk.obj" --algo single --weights "$w" --color order --view 1,0.6,-0.9
    render "horse-single-$tag" 320x240 "$MODELS/horse.ply" --algo single --weights "$w" --color order \
        --view 1,-0.5,0.3 --up 0,0,1
done

# 6. SETS (stripkit lod): the level-0 strips kept through the collapses, drawn at the
# levels of section 3 with their own strips (compare: section 3 strips each level anew).
"$S" lod build "$BUNNY" -o "$TMP/bunny.sets" --check off >/dev/null
for ratio in 1 0.25 0.05 0.01; do
    render "bunny-sets-$ratio" 240x240 "$TMP/bunny.sets" --ratio "$ratio"
done

# 7. The horse gallop's level-of-detail strips (stripkit lod build-seq): frames 1, 7, 13
# and 19 at 10% of the triangles, each with the simplification sequence chosen for it,
# on one strip connectivity.
"$S" lod build-seq "$GALLOP" -o "$TMP/gallop.lodseq" --position-bits 12 --max-sequences 7 --check off >/dev/null
for f in 0 6 12 18; do
    render "gallop-lod-$f" 320x200 "$TMP/gallop.lodseq" --frame "$f" --ratio 0.1 --view 1,0.15,0.05
done
