#!/usr/bin/env bash
# Runs `stripkit-bench gpu` on a machine with a GPU, from a bundle built elsewhere:
#   .gpu/stripkit-bench   the release binary (cargo build --release -p stripkit-bench)
#   .gpu/models/          the meshes (../shared/models without sequences/)
#   .gl/                  libEGL.so.1, libGLdispatch.so.0, libGLESv2.so.2 (the glvnd loader),
#                         for machines that have NVIDIA's EGL driver but no loader
# Writes the tables and JSON to the folder given as $1 (default: gpu-out).
set -u
out=${1:-gpu-out}
mkdir -p "$out"
here=$(pwd)
[ -d .gl ] && export LD_LIBRARY_PATH="$here/.gl${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
# glvnd finds NVIDIA's vendor file in the usual folders; some images keep it elsewhere.
if ! ls /usr/share/glvnd/egl_vendor.d/*nvidia* /etc/glvnd/egl_vendor.d/*nvidia* >/dev/null 2>&1; then
    for f in /usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json /usr/lib/x86_64-linux-gnu/nvidia/10_nvidia.json; do
        [ -f "$f" ] && export __EGL_VENDOR_LIBRARY_FILENAMES="$f" && break
    done
fi
(nvidia-smi --query-gpu=name,driver_version,clocks.max.graphics --format=csv 2>&1 || true) | tee "$out/gpu.txt"
bench=.gpu/stripkit-bench
"$bench" gpu --models .gpu/models --only bunny_res4 --quick --draws 3 --repeats 1 --no-probes >/dev/null || exit 1
timeout ${SHARED_LIMIT:-240} "$bench" gpu --models .gpu/models --out "$out/gpu-shared.md" --json "$out/gpu-shared.json" \
    2> "$out/log-shared.txt" >/dev/null
echo "shared models: exit $?"
timeout ${BIG_LIMIT:-150} "$bench" gpu --models .gpu/models --only NONE --subdivided bunny.obj:2 --no-probes \
    --out "$out/gpu-bunny-loop2.md" --json "$out/gpu-bunny-loop2.json" 2> "$out/log-loop2.txt" >/dev/null
echo "bunny Loop x2: exit $?"
for f in "$out"/log-*.txt; do tail -n 3 "$f"; done
