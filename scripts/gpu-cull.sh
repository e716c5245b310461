#!/usr/bin/env bash
# Issue #18's GPU figures: `stripkit-bench cull-gpu` (frame time along the helix, single
# strips drawn whole against the segment tree's ranges) on a machine with a GPU, from a
# bundle built elsewhere (see scripts/gpu-bench.sh for the layout):
#   .gpu/stripkit-bench, .gpu/stripkit   release binaries
#   .gpu/models/                         the meshes
#   .gl/                                 the glvnd loader, where the machine lacks it
# Also times `stripkit cull` (the CPU traversal) on horse Loop x2 on that machine's CPU.
# Writes tables, JSON and logs to the folder given as $1 (default: gpu-out).
set -u
out=${1:-gpu-out}
mkdir -p "$out"
here=$(pwd)
[ -d .gl ] && export LD_LIBRARY_PATH="$here/.gl${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
if ! ls /usr/share/glvnd/egl_vendor.d/*nvidia* /etc/glvnd/egl_vendor.d/*nvidia* >/dev/null 2>&1; then
    for f in /usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json /usr/lib/x86_64-linux-gnu/nvidia/10_nvidia.json; do
        [ -f "$f" ] && export __EGL_VENDOR_LIBRARY_FILENAMES="$f" && break
    done
fi
(nvidia-smi --query-gpu=name,driver_version,clocks.max.graphics --format=csv 2>&1 || true) | tee "$out/gpu.txt"
(lscpu | grep -E "Model name|^CPU\(s\)" || true) | tee -a "$out/gpu.txt"
b=.gpu/stripkit-bench
timeout ${SMALL_LIMIT:-200} "$b" cull-gpu --models .gpu/models ${ONLY:+--only "$ONLY"} --out "$out/cull-gpu.md" --json "$out/cull-gpu.json" \
    2> "$out/log-cull.txt" >/dev/null
echo "models: exit $?"
tail -n 2 "$out/log-cull.txt"
timeout ${BIG_LIMIT:-240} "$b" cull-gpu --models .gpu/models --only "" --subdivided horse.ply:2 --repeats 2 --check-views 3 \
    --out "$out/cull-gpu-horse2.md" --json "$out/cull-gpu-horse2.json" 2> "$out/log-horse2.txt" >/dev/null
echo "horse Loop x2: exit $?"
tail -n 2 "$out/log-horse2.txt"
if [ -x .gpu/stripkit ]; then
    .gpu/stripkit gen subdivide .gpu/models/horse.ply --scheme loop --levels 2 -o /tmp/horse2.ply >/dev/null &&
        timeout ${CPU_LIMIT:-90} .gpu/stripkit cull /tmp/horse2.ply --json > "$out/cull-cpu-horse2.json" 2>"$out/log-cpu.txt"
    echo "cpu cull horse Loop x2: exit $?"
fi
