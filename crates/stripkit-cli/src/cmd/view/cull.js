// Culling (--cull): the segment tree's traversal for an eye, as stripkit's cull module
// does it from the roots, in single precision (Math.fround after every operation, as
// the f32 arithmetic of the library), so that the ranges are its ranges.

/** The tree's arrays from the model's base64 (or null without --cull). */
function decodeTree(t) {
    return t ? {
        bounds: new Float32Array(bytes(t.bounds)),
        ranges: new Uint32Array(bytes(t.ranges)),
        roots: new Uint32Array(bytes(t.roots)),
    } : null;
}
const BACK = 0, FRONT = 1, SPLIT = 2, NONE = 0xffffffff;
/** Whether node k faces away from `eye` (BACK), towards it (FRONT) or both (SPLIT). */
function classify(tree, k, eye) {
    const f = Math.fround, b = tree.bounds, o = 9 * k;
    const cos = b[o + 7], sin = b[o + 8], r = b[o + 3];
    if (cos > 1.5) return BACK;
    const d0 = f(b[o] - eye[0]), d1 = f(b[o + 1] - eye[1]), d2 = f(b[o + 2] - eye[2]);
    const dsq = f(f(f(d0 * d0) + f(d1 * d1)) + f(d2 * d2));
    const dn = f(f(f(b[o + 4] * d0) + f(b[o + 5] * d1)) + f(b[o + 6] * d2));
    const dd = f(Math.sqrt(dsq));
    const s = f(f(Math.sqrt(Math.max(f(dsq - f(dn * dn)), 0))) * sin);
    const far = f(-dd - r);
    const back = f(cos * dd) >= -dn ? f(f(f(dn * cos) - s) - r) : far;
    const front = f(cos * dd) >= dn ? f(f(f(-dn * cos) - s) - r) : far;
    return back >= 0 ? BACK : front > 0 ? FRONT : SPLIT;
}
/** The drawn ranges (of the strips' indices) for `eye` and the traversal's counts. */
function cullTree(tree, eye, minTriangles = 0, maxGap = 0) {
    const R = tree.ranges, out = { ranges: [], drawn: 0, culled: 0, visited: 0 };
    let gap = 0, lastStrip = NONE;
    const stack = [];
    for (const root of tree.roots) {
        stack.push(root);
        while (stack.length) {
            const id = stack.pop(), facing = classify(tree, id, eye);
            const [start, end, triangles, strip, right] = R.subarray(5 * id, 5 * id + 5);
            out.visited++;
            if (facing === SPLIT && right !== NONE && triangles > minTriangles) { stack.push(right, id + 1); continue; }
            if (facing === BACK) { out.culled += triangles; gap += triangles; continue; }
            out.drawn += triangles;
            const last = out.ranges[out.ranges.length - 1];
            if (last && lastStrip === strip && gap <= maxGap) { last[1] = end; out.drawn += gap; out.culled -= gap; }
            else out.ranges.push([start, end]);
            gap = 0;
            lastStrip = strip;
        }
    }
    return out;
}
const CULL_DRAWN = [58, 110, 190], CULL_SKIPPED = [246, 214, 200];
/**
 * Colours the places by the ranges culled for `eye` (index i of strip s lies at place
 * i + s); the figures go to the panel.
 */
function paintCull(v, eye) {
    const t = performance.now(), out = cullTree(v.tree, eye), ms = performance.now() - t;
    const n = v.n, places = v.places, col = new Uint8Array(n * 4);
    for (let i = 0; i < n; i++) col.set(CULL_SKIPPED, 4 * i);
    let s = 0;
    for (const [a, b] of out.ranges) {
        while (places[s + 1] <= a) s++;
        for (let i = a; i < b; i++) col.set(CULL_DRAWN, 4 * (i + s));
    }
    for (let i = 3; i < col.length; i += 4) col[i] = 255;
    v.gl.bindBuffer(v.gl.ARRAY_BUFFER, v.colorBuffer);
    v.gl.bufferSubData(v.gl.ARRAY_BUFFER, 0, col);
    document.getElementById('cullText').textContent =
        `${out.ranges.length} segments drawn, ${out.drawn.toLocaleString('en')} triangles drawn, ${out.culled.toLocaleString('en')} culled, ${out.visited} nodes visited, ${ms.toFixed(2)} ms`;
}
