// Colours as stripkit-render's paint module makes them, and smooth normals.

function hsv(h, s, v) {
    const h6 = h * 6, i = Math.floor(h6) % 6, f = h6 - Math.floor(h6);
    const p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
    const rgb = [[v, t, p], [q, v, p], [p, v, t], [p, q, v], [t, p, v], [v, p, q]][i];
    return rgb.map((x) => Math.round(x * 255));
}
/** Strip k's colour (golden-ratio hues, three saturation / value pairs). */
function stripColor(k) {
    const GOLDEN = 0.6180339887498949;
    const hue = (0.08 + k * GOLDEN) % 1;
    const [s, v] = [[0.70, 0.95], [0.95, 0.78], [0.45, 0.88]][k % 3];
    return hsv(hue, s, v);
}
const STOPS = [[40, 60, 200], [30, 150, 240], [40, 200, 160], [140, 220, 60], [250, 200, 40], [240, 110, 30], [200, 30, 30]];
/** The strip-order gradient's colour at t in [0, 1]. */
function gradient(t) {
    const x = Math.min(Math.max(t, 0), 1) * (STOPS.length - 1);
    const i = Math.min(Math.floor(x), STOPS.length - 2), f = x - i;
    return [0, 1, 2].map((j) => Math.round(STOPS[i][j] + (STOPS[i + 1][j] - STOPS[i][j]) * f));
}

/** Smooth normals: each vertex the sum of its triangles' unnormalized normals. */
function vertexNormals(v) {
    const { positions, labels, strips } = v;
    const acc = new Float64Array(positions.length);
    for (let s = 0; s < strips; s++) {
        const [at, end] = placeOf(v, s);
        for (let i = at; i + 2 < end && labels[i + 2] !== RESTART; i++) {
            const odd = (i - at) & 1;
            const a = labels[i + odd], b = labels[i + 1 - odd], c = labels[i + 2];
            if (a === b || b === c || a === c) continue;
            const e = [0, 1, 2].map((d) => positions[3 * b + d] - positions[3 * a + d]);
            const g = [0, 1, 2].map((d) => positions[3 * c + d] - positions[3 * a + d]);
            const nx = e[1] * g[2] - e[2] * g[1], ny = e[2] * g[0] - e[0] * g[2], nz = e[0] * g[1] - e[1] * g[0];
            for (const w of [a, b, c]) { acc[3 * w] += nx; acc[3 * w + 1] += ny; acc[3 * w + 2] += nz; }
        }
    }
    const out = new Float32Array(positions.length);
    for (let w = 0; w < out.length; w += 3) {
        const l = Math.hypot(acc[w], acc[w + 1], acc[w + 2]);
        if (l > 0 && isFinite(l)) { out[w] = acc[w] / l; out[w + 1] = acc[w + 1] / l; out[w + 2] = acc[w + 2] / l; }
        else out[w + 2] = 1;
    }
    return out;
}
