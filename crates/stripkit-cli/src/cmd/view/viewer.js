// stripkit view: draws the model in the JSON block #model with WebGL2, one
// drawElements(TRIANGLE_STRIP) over every strip, the strips separated by the fixed
// restart index 0xFFFFFFFF (always on in WebGL2). The strips lie in one buffer, each
// at a fixed place one longer than its level-0 length, the rest of it restart
// indices: the layout of the `.sets` runtime's cursor (inlined below), so that a
// level change rewrites only the places of the strips that changed. Every place has
// its own vertex (so that a strip can carry its own colour). window.stripkitView
// holds the state and figures for tests: ready, firstFrameMs, pixels(), level(L),
// frame(F, L). A `.lodseq` page decodes its file asynchronously (deflated positions).
'use strict';
(async function () {
    /*RUNTIME*/
    const RESTART = 0xffffffff;
    const model = JSON.parse(document.getElementById('model').textContent);
    const t0 = performance.now();

    function bytes(b64) {
        const s = atob(b64), out = new Uint8Array(s.length);
        for (let i = 0; i < s.length; i++) out[i] = s.charCodeAt(i);
        return out.buffer;
    }
    // The strips' places: a mesh's strips laid out as a cursor lays out a level.
    let sets = null, seq = null, cursor = null, positions, uv = null, places, labels;
    // A .lodseq's frames share one strip layout; positions change with the frame.
    const scaled = (p) => p.map((x) => x * model.scale);
    if (model.lodseq) {
        seq = await decodeLodSeq(bytes(model.lodseq));
        cursor = new LodSeqCursor(seq, 0, 0);
        positions = scaled(cursor.positions());
        places = seq.models[0].stripSlots;
        labels = cursor.buffer;
    } else if (model.sets) {
        sets = decodeSets(bytes(model.sets));
        cursor = new SetsCursor(sets, 0);
        positions = sets.positions.map((x) => x * model.scale);
        places = sets.stripSlots;
        labels = cursor.buffer;
    } else {
        positions = new Float32Array(bytes(model.positions));
        uv = model.uv ? new Float32Array(bytes(model.uv)) : null;
        const lengths = new Uint32Array(bytes(model.lengths));
        places = new Uint32Array(lengths.length + 1);
        for (let s = 0; s < lengths.length; s++) places[s + 1] = places[s] + lengths[s];
        labels = new Uint32Array(places[lengths.length] + lengths.length).fill(RESTART);
        const indices = new Uint32Array(bytes(model.strip_indices));
        for (let s = 0; s < lengths.length; s++) labels.set(indices.subarray(places[s], places[s + 1]), places[s] + s);
    }
    const strips = places.length - 1;
    const n = labels.length;
    const placeOf = (s) => [places[s] + s, places[s + 1] + s + 1];

    // Colours as stripkit-render's paint module makes them.
    function hsv(h, s, v) {
        const h6 = h * 6, i = Math.floor(h6) % 6, f = h6 - Math.floor(h6);
        const p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
        const rgb = [[v, t, p], [q, v, p], [p, v, t], [p, q, v], [t, p, v], [v, p, q]][i];
        return rgb.map((x) => Math.round(x * 255));
    }
    function stripColor(k) {
        const GOLDEN = 0.6180339887498949;
        const hue = (0.08 + k * GOLDEN) % 1;
        const [s, v] = [[0.70, 0.95], [0.95, 0.78], [0.45, 0.88]][k % 3];
        return hsv(hue, s, v);
    }
    const STOPS = [[40, 60, 200], [30, 150, 240], [40, 200, 160], [140, 220, 60], [250, 200, 40], [240, 110, 30], [200, 30, 30]];
    function gradient(t) {
        const x = Math.min(Math.max(t, 0), 1) * (STOPS.length - 1);
        const i = Math.min(Math.floor(x), STOPS.length - 2), f = x - i;
        return [0, 1, 2].map((j) => Math.round(STOPS[i][j] + (STOPS[i + 1][j] - STOPS[i][j]) * f));
    }

    // Smooth normals: each vertex the sum of its triangles' unnormalized normals.
    function vertexNormals() {
        const acc = new Float64Array(positions.length);
        for (let s = 0; s < strips; s++) {
            const [at, end] = placeOf(s);
            for (let i = at; i + 2 < end && labels[i + 2] !== RESTART; i++) {
                const odd = (i - at) & 1;
                const a = labels[i + odd], b = labels[i + 1 - odd], c = labels[i + 2];
                if (a === b || b === c || a === c) continue;
                const e = [0, 1, 2].map((d) => positions[3 * b + d] - positions[3 * a + d]);
                const g = [0, 1, 2].map((d) => positions[3 * c + d] - positions[3 * a + d]);
                const nx = e[1] * g[2] - e[2] * g[1], ny = e[2] * g[0] - e[0] * g[2], nz = e[0] * g[1] - e[1] * g[0];
                for (const v of [a, b, c]) { acc[3 * v] += nx; acc[3 * v + 1] += ny; acc[3 * v + 2] += nz; }
            }
        }
        const out = new Float32Array(positions.length);
        for (let v = 0; v < out.length; v += 3) {
            const l = Math.hypot(acc[v], acc[v + 1], acc[v + 2]);
            if (l > 0 && isFinite(l)) { out[v] = acc[v] / l; out[v + 1] = acc[v + 1] / l; out[v + 2] = acc[v + 2] / l; }
            else out[v + 2] = 1;
        }
        return out;
    }

    const canvas = document.getElementById('view');
    [canvas.width, canvas.height] = model.size;
    canvas.style.width = model.size[0] + 'px';
    canvas.style.height = model.size[1] + 'px';
    const gl = canvas.getContext('webgl2', { antialias: false, preserveDrawingBuffer: true });
    if (!gl) { document.body.textContent = 'This page needs WebGL2.'; return; }
    gl.getExtension('OES_standard_derivatives');

    const VS = `#version 300 es
precision highp float;
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_nrm;
layout(location = 2) in vec4 a_col;
layout(location = 3) in vec2 a_uv;
layout(location = 4) in vec3 a_bary;
uniform mat4 u_mvp;
out vec3 v_nrm; out vec3 v_pos; out vec4 v_col; out vec2 v_uv; out vec3 v_bary;
void main() {
    v_nrm = a_nrm; v_pos = a_pos; v_col = a_col; v_uv = a_uv; v_bary = a_bary;
    gl_Position = u_mvp * vec4(a_pos, 1.0);
}`;
    const FS = `#version 300 es
precision highp float;
in vec3 v_nrm; in vec3 v_pos; in vec4 v_col; in vec2 v_uv; in vec3 v_bary;
uniform int u_shading; uniform int u_checker; uniform int u_wire; uniform vec3 u_light;
out vec4 o_col;
void main() {
    vec3 n = u_shading == 1 ? normalize(cross(dFdx(v_pos), dFdy(v_pos))) : normalize(v_nrm);
    float l = u_shading == 2 ? 1.0 : 0.3 + 0.7 * abs(dot(n, u_light));
    vec3 c = v_col.rgb;
    if (u_checker == 1) {
        vec2 q = floor(v_uv * 16.0);
        c = mod(q.x + q.y, 2.0) < 1.0 ? vec3(0.93) : vec3(0.25, 0.45, 0.75);
    }
    c *= l;
    if (u_wire == 1) {
        vec3 w = v_bary / fwidth(v_bary);
        if (min(w.x, min(w.y, w.z)) < 0.8) c = vec3(30.0 / 255.0);
    }
    o_col = vec4(c, 1.0);
}`;
    function shader(type, text) {
        const s = gl.createShader(type);
        gl.shaderSource(s, text);
        gl.compileShader(s);
        if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
        return s;
    }
    const program = gl.createProgram();
    gl.attachShader(program, shader(gl.VERTEX_SHADER, VS));
    gl.attachShader(program, shader(gl.FRAGMENT_SHADER, FS));
    gl.linkProgram(program);
    if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(program));
    const u = {};
    for (const name of ['u_mvp', 'u_shading', 'u_checker', 'u_wire', 'u_light']) u[name] = gl.getUniformLocation(program, name);

    let normals = null;
    const vao = gl.createVertexArray();
    gl.bindVertexArray(vao);
    function attribute(loc, data, size, type, normalized) {
        const buf = gl.createBuffer();
        gl.bindBuffer(gl.ARRAY_BUFFER, buf);
        gl.bufferData(gl.ARRAY_BUFFER, data, gl.DYNAMIC_DRAW);
        gl.enableVertexAttribArray(loc);
        gl.vertexAttribPointer(loc, size, type, normalized, 0, 0);
        return buf;
    }
    // Each place's vertex values (k per vertex) gathered from `values` in [a, b).
    function gather(values, k, out, a, b) {
        for (let i = a; i < b; i++) {
            const v = labels[i];
            for (let d = 0; d < k; d++) out[k * i + d] = v === RESTART ? 0 : values[k * v + d];
        }
        return out;
    }
    const placed = gather(positions, 3, new Float32Array(3 * n), 0, n);
    const positionBuffer = attribute(0, placed, 3, gl.FLOAT, false);
    const normalBuffer = attribute(1, new Float32Array(n * 3), 3, gl.FLOAT, false);
    const colorBuffer = attribute(2, new Uint8Array(n * 4), 4, gl.UNSIGNED_BYTE, true);
    attribute(3, uv ? gather(uv, 2, new Float32Array(2 * n), 0, n) : new Float32Array(n * 2), 2, gl.FLOAT, false);
    const bary = new Float32Array(n * 3);
    for (let s = 0; s < strips; s++) {
        const [a, b] = placeOf(s);
        for (let i = a; i < b; i++) bary[3 * i + ((i - a) % 3)] = 1;
    }
    attribute(4, bary, 3, gl.FLOAT, false);
    const index = new Uint32Array(n);
    for (let i = 0; i < n; i++) index[i] = labels[i] === RESTART ? RESTART : i;
    const indexBuffer = gl.createBuffer();
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, indexBuffer);
    gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, index, gl.DYNAMIC_DRAW);
    gl.bindVertexArray(null);

    // A new level: the places of the changed strips written again, and uploaded as one
    // range from the first changed place to the last (one call per buffer: a call
    // per strip cost 78 ms for bunny's 400 strips under SwiftShader).
    // `frameMoved`: every place's position is gathered again and uploaded whole.
    function uploadStrips(changed, frameMoved = false) {
        if (frameMoved) {
            gather(positions, 3, placed, 0, n);
            gl.bindBuffer(gl.ARRAY_BUFFER, positionBuffer);
            gl.bufferSubData(gl.ARRAY_BUFFER, 0, placed);
            normals = null;
        }
        if (changed.length === 0) return;
        let lo = n, hi = 0;
        for (const s of changed) {
            const [a, b] = placeOf(s);
            gather(positions, 3, placed, a, b);
            for (let i = a; i < b; i++) index[i] = labels[i] === RESTART ? RESTART : i;
            lo = Math.min(lo, a);
            hi = Math.max(hi, b);
        }
        gl.bindBuffer(gl.ARRAY_BUFFER, positionBuffer);
        gl.bufferSubData(gl.ARRAY_BUFFER, 12 * lo, placed, 3 * lo, 3 * (hi - lo));
        gl.bindVertexArray(vao);
        gl.bufferSubData(gl.ELEMENT_ARRAY_BUFFER, 4 * lo, index, lo, hi - lo);
        gl.bindVertexArray(null);
        normals = null;
    }

    function paint(mode) {
        if (mode === 'cull') return; // coloured per eye in draw()
        const col = new Uint8Array(n * 4);
        for (let k = 0; k < strips; k++) {
            const [a, b] = placeOf(k);
            const c = mode === 'strips' ? stripColor(k) : [205, 205, 205];
            for (let i = a; i < b; i++) {
                const g = mode === 'order' ? gradient(n > 1 ? i / (n - 1) : 0) : c;
                col[4 * i] = g[0]; col[4 * i + 1] = g[1]; col[4 * i + 2] = g[2]; col[4 * i + 3] = 255;
            }
        }
        gl.bindBuffer(gl.ARRAY_BUFFER, colorBuffer);
        gl.bufferSubData(gl.ARRAY_BUFFER, 0, col);
    }

    // Camera: glam's look_at_rh and perspective_rh_gl, column-major.
    const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
    const norm = (a) => { const l = Math.hypot(...a); return a.map((x) => x / l); };
    function viewProj(cam) {
        const f = norm(sub(cam.target, cam.eye)), s = norm(cross(f, cam.up)), v = cross(s, f);
        const view = [s[0], v[0], -f[0], 0, s[1], v[1], -f[1], 0, s[2], v[2], -f[2], 0,
            -dot(s, cam.eye), -dot(v, cam.eye), dot(f, cam.eye), 1];
        const t = 1 / Math.tan(cam.fov * Math.PI / 360), inv = 1 / (cam.near - cam.far);
        const aspect = model.size[0] / model.size[1];
        const p = [t / aspect, t, (cam.near + cam.far) * inv, 2 * cam.near * cam.far * inv];
        const out = new Float32Array(16);
        for (let c = 0; c < 4; c++) {
            const col = view.slice(4 * c, 4 * c + 4);
            out[4 * c] = p[0] * col[0];
            out[4 * c + 1] = p[1] * col[1];
            out[4 * c + 2] = p[2] * col[2] + p[3] * col[3];
            out[4 * c + 3] = -col[2];
        }
        return out;
    }
    const first = model.camera;
    const state = { color: 'strips', shading: 'flat', wireframe: false, hold: false, yaw: 0, pitch: 0, zoom: 1 };
    let heldEye = null;
    // The camera of the current orbit: the first eye turned about the first up
    // (yaw) and the first right (pitch) around the target, its distance divided by zoom.
    function camera() {
        const back0 = sub(first.eye, first.target), dist = Math.hypot(...back0);
        const up0 = norm(first.up), back = norm(back0), right0 = cross(up0, back);
        const cy = Math.cos(state.yaw), sy = Math.sin(state.yaw), cp = Math.cos(state.pitch), sp = Math.sin(state.pitch);
        const b1 = [0, 1, 2].map((d) => cy * back[d] + sy * right0[d]);
        const r1 = [0, 1, 2].map((d) => cy * right0[d] - sy * back[d]);
        const b2 = [0, 1, 2].map((d) => cp * b1[d] + sp * up0[d]);
        const u2 = [0, 1, 2].map((d) => cp * up0[d] - sp * b1[d]);
        const d2 = dist / state.zoom, shift = dist - d2;
        return {
            eye: [0, 1, 2].map((d) => first.target[d] + b2[d] * d2), target: first.target, up: u2, fov: first.fov,
            near: Math.max(first.near - shift, first.near * 0.01), far: Math.max(first.far - shift, first.near),
            light: [0, 1, 2].map((d) => b2[d] + 0.5 * u2[d] - 0.35 * r1[d]), first: state.yaw === 0 && state.pitch === 0 && state.zoom === 1,
        };
    }
    function draw() {
        const cam = camera();
        // "Hold the culling eye": orbit away to see what that eye culls.
        if (!state.hold || !heldEye) heldEye = cam.eye.map(Math.fround);
        if (state.color === 'cull' && tree) paintCull(heldEye);
        gl.viewport(0, 0, canvas.width, canvas.height);
        gl.clearColor(1, 1, 1, 1);
        gl.clearDepth(1);
        gl.enable(gl.DEPTH_TEST);
        gl.depthFunc(gl.LESS);
        gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
        gl.useProgram(program);
        gl.uniformMatrix4fv(u.u_mvp, false, viewProj(cam));
        if (state.shading === 'smooth' && !normals) {
            normals = gather(vertexNormals(), 3, new Float32Array(3 * n), 0, n);
            gl.bindBuffer(gl.ARRAY_BUFFER, normalBuffer);
            gl.bufferSubData(gl.ARRAY_BUFFER, 0, normals);
        }
        gl.uniform1i(u.u_shading, { smooth: 0, flat: 1, unlit: 2 }[state.shading]);
        gl.uniform1i(u.u_checker, state.color === 'checker' ? 1 : 0);
        gl.uniform1i(u.u_wire, state.wireframe ? 1 : 0);
        const light = cam.first ? first.light : cam.light;
        gl.uniform3fv(u.u_light, norm(light));
        gl.bindVertexArray(vao);
        gl.drawElements(gl.TRIANGLE_STRIP, n, gl.UNSIGNED_INT, 0);
        gl.bindVertexArray(null);
    }
    let pending = false;
    function redraw() { if (!pending) { pending = true; requestAnimationFrame(() => { pending = false; draw(); }); } }

    // Culling (--cull): the segment tree's traversal for an eye, as stripkit's cull
    // module does it from the roots, in single precision (Math.fround after every
    // operation, as the f32 arithmetic of the library), so that the ranges are its ranges.
    const tree = model.tree && {
        bounds: new Float32Array(bytes(model.tree.bounds)),
        ranges: new Uint32Array(bytes(model.tree.ranges)),
        roots: new Uint32Array(bytes(model.tree.roots)),
    };
    const BACK = 0, FRONT = 1, SPLIT = 2, NONE = 0xffffffff;
    function classify(k, eye) {
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
    function cullTree(eye, minTriangles = 0, maxGap = 0) {
        const R = tree.ranges, out = { ranges: [], drawn: 0, culled: 0, visited: 0 };
        let gap = 0, lastStrip = NONE;
        const stack = [];
        for (const root of tree.roots) {
            stack.push(root);
            while (stack.length) {
                const id = stack.pop(), facing = classify(id, eye);
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
    // Colours the places by the ranges culled for the current eye (index i of strip s
    // lies at place i + s); the figures go to the panel.
    function paintCull(eye) {
        const t = performance.now(), out = cullTree(eye), ms = performance.now() - t;
        const col = new Uint8Array(n * 4);
        for (let i = 0; i < n; i++) col.set(CULL_SKIPPED, 4 * i);
        let s = 0;
        for (const [a, b] of out.ranges) {
            while (places[s + 1] <= a) s++;
            for (let i = a; i < b; i++) col.set(CULL_DRAWN, 4 * (i + s));
        }
        for (let i = 3; i < col.length; i += 4) col[i] = 255;
        gl.bindBuffer(gl.ARRAY_BUFFER, colorBuffer);
        gl.bufferSubData(gl.ARRAY_BUFFER, 0, col);
        document.getElementById('cullText').textContent =
            `${out.ranges.length} segments drawn, ${out.drawn.toLocaleString('en')} triangles drawn, ${out.culled.toLocaleString('en')} culled, ${out.visited} nodes visited, ${ms.toFixed(2)} ms`;
    }

    // Panel.
    document.getElementById('name').textContent = model.name;
    const rows = [['triangles', model.triangles], ['strips', model.strips], ['indices (restart)', model.indices],
        ['indices / triangle', (model.indices / Math.max(model.triangles, 1)).toFixed(3)], ['ACMR', model.acmr.toFixed(3)],
        ['vertices', model.vertices], ['algorithm', model.algo]];
    const table = document.getElementById('figures');
    for (const [k, v] of rows) {
        const tr = table.insertRow();
        tr.insertCell().textContent = k;
        tr.insertCell().textContent = typeof v === 'number' ? v.toLocaleString('en') : v;
    }
    const cullOption = document.querySelector('#color option[value=cull]');
    if (!tree) cullOption.remove();
    else document.getElementById('cullFigures').hidden = false;
    const checker = document.querySelector('#color option[value=checker]');
    if (!uv) { checker.disabled = true; checker.textContent += ' — no UVs'; }
    // The level slider (a .sets model): the level extracted by the cursor, only the
    // changed strips uploaded.
    // A .lodseq: the slider's level is clamped to each frame's model, and kept as asked.
    const levelCount = sets ? sets.levels : seq ? Math.max(...seq.models.map((m) => m.levels)) : 0;
    const lodFigures = { level: 0, asked: 0, frame: 0, changed: 0, extractMs: 0, uploadMs: 0, played: 0 };
    function setLevel(level, frame = lodFigures.frame) {
        const t = performance.now();
        const changed = seq ? cursor.set(frame, level) : cursor.setLevel(level);
        const t1 = performance.now();
        const frameMoved = seq !== null && cursor.frame !== lodFigures.frame;
        if (frameMoved) positions = scaled(cursor.positions());
        uploadStrips(changed, frameMoved);
        Object.assign(lodFigures, { level: cursor.level, asked: level, frame: seq ? cursor.frame : 0, changed: changed.length, extractMs: t1 - t, uploadMs: performance.now() - t1 });
        return changed;
    }
    function showLevel() {
        const t = document.getElementById('levelFigures');
        t.textContent = '';
        const rows = [['level', `${lodFigures.level.toLocaleString('en')} of ${levelCount.toLocaleString('en')}`],
            ['triangles', cursor.triangles().toLocaleString('en')], ['strips changed', lodFigures.changed],
            ['extraction', lodFigures.extractMs.toFixed(2) + ' ms'], ['upload', lodFigures.uploadMs.toFixed(2) + ' ms']];
        if (seq) rows.unshift(['frame', `${lodFigures.frame + 1} of ${seq.frames}: ${seq.names[lodFigures.frame]}`]);
        for (const [k, v] of rows) { const tr = t.insertRow(); tr.insertCell().textContent = k; tr.insertCell().textContent = v; }
    }
    if (sets || seq) {
        document.getElementById('lod').hidden = false;
        const slider = document.getElementById('level');
        slider.max = levelCount;
        slider.addEventListener('input', () => { setLevel(Number(slider.value)); showLevel(); redraw(); });
        showLevel();
    }
    // A .lodseq: the frame slider, and play: one frame further every 1/30 s, drawn on
    // the animation frame that follows.
    let playing = false;
    if (seq) {
        document.getElementById('anim').hidden = false;
        const frameSlider = document.getElementById('frame'), play = document.getElementById('play');
        frameSlider.max = seq.frames - 1;
        frameSlider.addEventListener('input', () => { setLevel(lodFigures.asked, Number(frameSlider.value)); showLevel(); redraw(); });
        let last = 0;
        function tick(now) {
            if (!playing) return;
            if (now - last >= 1000 / 30) {
                last = now;
                setLevel(lodFigures.asked, (lodFigures.frame + 1) % seq.frames);
                lodFigures.played++;
                frameSlider.value = lodFigures.frame;
                showLevel();
                draw();
            }
            requestAnimationFrame(tick);
        }
        play.addEventListener('click', () => {
            playing = !playing;
            play.textContent = playing ? 'pause' : 'play';
            if (playing) requestAnimationFrame(tick);
        });
    }
    const on = (id, ev, f) => document.getElementById(id).addEventListener(ev, f);
    on('color', 'change', (e) => { state.color = e.target.value; paint(state.color); redraw(); });
    on('shading', 'change', (e) => { state.shading = e.target.value; redraw(); });
    on('wireframe', 'change', (e) => { state.wireframe = e.target.checked; redraw(); });
    on('hold', 'change', (e) => { state.hold = e.target.checked; redraw(); });
    on('reset', 'click', () => { Object.assign(state, { yaw: 0, pitch: 0, zoom: 1 }); redraw(); });
    let drag = null;
    canvas.addEventListener('pointerdown', (e) => { drag = [e.clientX, e.clientY]; canvas.setPointerCapture(e.pointerId); });
    canvas.addEventListener('pointerup', () => { drag = null; });
    canvas.addEventListener('pointermove', (e) => {
        if (!drag) return;
        state.yaw -= (e.clientX - drag[0]) * 0.01;
        state.pitch = Math.max(-1.5, Math.min(1.5, state.pitch + (e.clientY - drag[1]) * 0.01));
        drag = [e.clientX, e.clientY];
        redraw();
    });
    canvas.addEventListener('wheel', (e) => {
        e.preventDefault();
        state.zoom = Math.max(0.2, Math.min(50, state.zoom * Math.exp(-e.deltaY * 0.001)));
        redraw();
    }, { passive: false });

    // The first state may come from the address: #color=order&shading=smooth&wireframe=1.
    for (const [k, v] of new URLSearchParams(location.hash.slice(1))) {
        if (k === 'wireframe') state.wireframe = v === '1';
        else if ((k === 'color' || k === 'shading') && document.querySelector(`#${k} option[value=${CSS.escape(v)}]`)) state[k] = v;
    }
    document.getElementById('color').value = state.color;
    document.getElementById('shading').value = state.shading;
    document.getElementById('wireframe').checked = state.wireframe;
    paint(state.color);
    draw();
    gl.finish();
    window.stripkitView = {
        ready: true,
        levels: levelCount,
        frames: seq ? seq.frames : 0,
        renderer: (() => { const e = gl.getExtension('WEBGL_debug_renderer_info'); return e ? gl.getParameter(e.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER); })(),
        /** A .lodseq page: frames moved by play so far, and the current frame. */
        played() { return { played: lodFigures.played, frame: lodFigures.frame, playing }; },
        /** A .lodseq page: moves to frame `f` at `level`; its non-empty strips and the frame's positions as decoded (unscaled). */
        frame(f, level) { setLevel(level, f); return { frame: cursor.frame, level: cursor.level, strips: cursor.strips(), positions: Array.from(cursor.positions()) }; },
        firstFrameMs: performance.now(),
        setupMs: performance.now() - t0,
        state, draw,
        set(changes) { Object.assign(state, changes); if (changes.color) paint(state.color); draw(); gl.finish(); },
        /** A --cull page: the traversal for an eye given in the input's units. */
        cull(eye) {
            const out = cullTree(eye.map((x) => Math.fround(x) * model.scale));
            return { segments: out.ranges.length, drawn: out.drawn, culled: out.culled, visited: out.visited, ranges: out.ranges };
        },
        /** A .sets (or .lodseq, at the current frame) page: moves to `level` and returns its non-empty strips. */
        level(level) { setLevel(level); return cursor.strips(); },
        /** A .sets page: one level per animation frame, as a slider dragged; resolves to the frames' intervals (ms). */
        sweepFrames(levels) {
            return new Promise((done) => {
                const times = [];
                let i = 0, last = null;
                function step(now) {
                    if (last !== null) times.push(now - last);
                    last = now;
                    if (i === levels.length) { done(times); return; }
                    setLevel(levels[i++]);
                    draw();
                    requestAnimationFrame(step);
                }
                requestAnimationFrame(step);
            });
        },
        /**
         * A .sets page: per move, the milliseconds to extract, upload, and draw a frame.
         * The draw is waited for by reading one pixel back: Chromium's gl.finish() returns
         * at once (0.0 to 0.2 ms for bunny, whose draw takes 60 ms and more in software).
         */
        sweep(levels) {
            const px = new Uint8Array(4);
            return levels.map((l) => {
                setLevel(l);
                const t = performance.now();
                draw();
                gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
                return [lodFigures.extractMs, lodFigures.uploadMs, performance.now() - t, lodFigures.changed];
            });
        },
        pixels() {
            const px = new Uint8Array(canvas.width * canvas.height * 4);
            gl.readPixels(0, 0, canvas.width, canvas.height, gl.RGBA, gl.UNSIGNED_BYTE, px);
            return Array.from(px);
        },
    };
})();
