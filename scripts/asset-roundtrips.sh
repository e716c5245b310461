#!/usr/bin/env bash
# Issue #15's round trips: every source in DIR (.gltf .glb .obj .ply) stripped to .glb
# (EXT_mesh_primitive_restart + stitched fallback) and to .gltf --join degenerate, each
# output through the Khronos validator (.ci/validate-gltf.js, installed by .ci/run) and
# an independent check (scripts/gltf-check.py for glTF sources, scripts/mesh-check.py
# for OBJ/PLY; pip install pygltflib trimesh numpy), with the index counts beside
# gltfpack's output of the same file (GLTFPACK, e.g. node_modules/.bin/gltfpack), the
# file sizes beside each other, and at the end three.js's pictures of every output
# against its source (.ci/threejs-pixels.mjs: one headless Chromium for the whole
# folder; needs chromium and the npm packages three and playwright-core, which .ci/run
# installs; NO_PIXELS=1 skips it). The public assets to feed it: docs/assets-corpus.md.
#   scripts/asset-roundtrips.sh DIR [OUT]
set -u
dir=$1; out=${2:-roundtrips}; mkdir -p "$out"
here=$(cd "$(dirname "$0")/.." && pwd)
sk=${STRIPKIT:-$here/target/release/stripkit}
gp=${GLTFPACK:-}
pairs=()
declare -A seen
for src in "$dir"/*.gltf "$dir"/*.glb "$dir"/*.obj "$dir"/*.ply; do
    [ -f "$src" ] || continue
    b=$(basename "${src%.*}")
    # Two sources with one name (a.glb, a.obj): the second one's outputs add its extension.
    [ -n "${seen[$b]:-}" ] && b=${b}_${src##*.}
    seen[$b]=1
    echo "=== $src"
    if ! "$sk" strip "$src" -o "$out/$b.glb" --json > "$out/$b.json" 2> "$out/$b.err"; then
        echo "strip: $(head -c 300 "$out/$b.err")"; continue
    fi
    "$sk" strip "$src" -o "$out/${b}_plain.gltf" --join degenerate > /dev/null 2>&1 || echo "plain: failed"
    # Images a .gltf names by URI stay where they are: link them beside the outputs.
    for f in "$dir"/*.png "$dir"/*.jpg "$dir"/*.jpeg "$dir"/*.ktx2 "$dir"/*.webp; do
        [ -f "$f" ] && [ ! -e "$out/$(basename "$f")" ] && ln -s "$(cd "$(dirname "$f")" && pwd)/$(basename "$f")" "$out/"
    done
    node "$here/.ci/validate-gltf.js" "$out/$b.glb" "$out/${b}_plain.gltf" |
        python3 -c "import sys,json; [print('validator', (d:=json.loads(l))['file'], 'errors', d['errors'], 'warnings', d['warnings']) for l in sys.stdin]"
    case $src in
        *.obj|*.ply) check=$here/scripts/mesh-check.py ;;
        *) check=$here/scripts/gltf-check.py ;;
    esac
    for o in "$out/$b.glb" "$out/${b}_plain.gltf"; do printf '%s: ' "$(basename "$o")"; python3 "$check" "$src" "$o" 2>&1 | tail -1; done
    pairs+=("$src=$out/$b.glb" "$src=$out/${b}_plain.gltf")
    [ -n "$gp" ] && "$gp" -i "$src" -o "$out/${b}_gltfpack.glb" -noq -kv -km -kn > /dev/null 2>&1
    python3 - "$src" "$out/$b.glb" "$out/${b}_gltfpack.glb" <<'PY'
import os, sys, pygltflib
def count(path):
    if not os.path.exists(path) or not path.endswith(('.glb', '.gltf')):
        return '-', '-'
    g = pygltflib.GLTF2().load(path); n = r = 0
    for m in g.meshes:
        for p in m.primitives:
            n += g.accessors[p.indices].count if p.indices is not None else g.accessors[p.attributes.POSITION].count
        for grp in ((m.extensions or {}).get('EXT_mesh_primitive_restart') or {}).get('primitiveGroups', []):
            r += g.accessors[grp['indices']].count
    return n, r
src, ours, gp = count(sys.argv[1]), count(sys.argv[2]), count(sys.argv[3])
print(f"indices: input {src[0]}, stripkit stitched {ours[0]}, with restart {ours[1]}, gltfpack {gp[0]}")
def size(p):
    # A glTF with its .bin and images: every file it names by URI counts.
    if not os.path.exists(p):
        return '-'
    n = os.path.getsize(p)
    if p.endswith(('.gltf', '.glb')):
        g = pygltflib.GLTF2().load(p)
        for item in list(g.buffers) + list(g.images):
            if item.uri and not item.uri.startswith('data:'):
                n += os.path.getsize(os.path.join(os.path.dirname(p), item.uri))
    return n
print(f"bytes: input {size(sys.argv[1])}, stripkit {size(sys.argv[2])}, gltfpack {size(sys.argv[3])}")
PY
done
# three.js pictures: one line per output, 0 differing pixels in every pass expected
# (OBJ quads: OBJLoader splits them as fans, stripkit may take the other diagonal).
if [ -z "${NO_PIXELS:-}" ] && [ ${#pairs[@]} -gt 0 ]; then
    echo "=== three.js pixels (reference = source)"
    node "$here/.ci/threejs-pixels.mjs" "${pairs[@]}" |
        python3 -c "import sys,json; [print('pixels', os.path.basename((d:=json.loads(l))['candidate']), 'lit', d['drawn'], 'differing', d['differing']) for l in sys.stdin if (os:=__import__('os'))]"
fi
