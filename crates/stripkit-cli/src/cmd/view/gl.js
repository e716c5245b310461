// WebGL2: the program, and the buffers of the strips' places (one vertex per place, so
// that a strip can carry its own colour), written again for the strips a level changes.

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

/** The linked program and its uniforms' locations (`u`). */
function createProgram(gl) {
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
    return { program, u };
}

/** Each place's vertex values (k per vertex) gathered from `values` in [a, b). */
function gather(v, values, k, out, a, b) {
    const labels = v.labels;
    for (let i = a; i < b; i++) {
        const w = labels[i];
        for (let d = 0; d < k; d++) out[k * i + d] = w === RESTART ? 0 : values[k * w + d];
    }
    return out;
}

/** The vertex array and buffers of every place: v.vao, v.placed, v.index and the buffers. */
function createBuffers(v) {
    const { gl, n } = v;
    v.vao = gl.createVertexArray();
    gl.bindVertexArray(v.vao);
    function attribute(loc, data, size, type, normalized) {
        const buf = gl.createBuffer();
        gl.bindBuffer(gl.ARRAY_BUFFER, buf);
        gl.bufferData(gl.ARRAY_BUFFER, data, gl.DYNAMIC_DRAW);
        gl.enableVertexAttribArray(loc);
        gl.vertexAttribPointer(loc, size, type, normalized, 0, 0);
        return buf;
    }
    v.placed = gather(v, v.positions, 3, new Float32Array(3 * n), 0, n);
    v.positionBuffer = attribute(0, v.placed, 3, gl.FLOAT, false);
    v.normalBuffer = attribute(1, new Float32Array(n * 3), 3, gl.FLOAT, false);
    v.colorBuffer = attribute(2, new Uint8Array(n * 4), 4, gl.UNSIGNED_BYTE, true);
    attribute(3, v.uv ? gather(v, v.uv, 2, new Float32Array(2 * n), 0, n) : new Float32Array(n * 2), 2, gl.FLOAT, false);
    const bary = new Float32Array(n * 3), strips = v.strips;
    for (let s = 0; s < strips; s++) {
        const [a, b] = placeOf(v, s);
        for (let i = a; i < b; i++) bary[3 * i + ((i - a) % 3)] = 1;
    }
    attribute(4, bary, 3, gl.FLOAT, false);
    v.index = new Uint32Array(n);
    const labels = v.labels, index = v.index;
    for (let i = 0; i < n; i++) index[i] = labels[i] === RESTART ? RESTART : i;
    v.indexBuffer = gl.createBuffer();
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, v.indexBuffer);
    gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, v.index, gl.DYNAMIC_DRAW);
    gl.bindVertexArray(null);
    v.normals = null;
}

/**
 * A new level: the places of the changed strips written again, and uploaded as one
 * range from the first changed place to the last (one call per buffer: a call per
 * strip cost 78 ms for bunny's 400 strips under SwiftShader). `frameMoved`: every
 * place's position is gathered again and uploaded whole.
 */
function uploadStrips(v, changed, frameMoved = false) {
    const { gl, n, placed, index, labels } = v;
    if (frameMoved) {
        gather(v, v.positions, 3, placed, 0, n);
        gl.bindBuffer(gl.ARRAY_BUFFER, v.positionBuffer);
        gl.bufferSubData(gl.ARRAY_BUFFER, 0, placed);
        v.normals = null;
    }
    if (changed.length === 0) return;
    let lo = n, hi = 0;
    for (const s of changed) {
        const [a, b] = placeOf(v, s);
        gather(v, v.positions, 3, placed, a, b);
        for (let i = a; i < b; i++) index[i] = labels[i] === RESTART ? RESTART : i;
        lo = Math.min(lo, a);
        hi = Math.max(hi, b);
    }
    gl.bindBuffer(gl.ARRAY_BUFFER, v.positionBuffer);
    gl.bufferSubData(gl.ARRAY_BUFFER, 12 * lo, placed, 3 * lo, 3 * (hi - lo));
    gl.bindVertexArray(v.vao);
    gl.bufferSubData(gl.ELEMENT_ARRAY_BUFFER, 4 * lo, index, lo, hi - lo);
    gl.bindVertexArray(null);
    v.normals = null;
}

/** The colour buffer for `mode` (strips, order, or grey; culling colours per eye in draw). */
function paint(v, mode) {
    if (mode === 'cull') return;
    const n = v.n, strips = v.strips, col = new Uint8Array(n * 4);
    for (let k = 0; k < strips; k++) {
        const [a, b] = placeOf(v, k);
        const c = mode === 'strips' ? stripColor(k) : [205, 205, 205];
        for (let i = a; i < b; i++) {
            const g = mode === 'order' ? gradient(n > 1 ? i / (n - 1) : 0) : c;
            col[4 * i] = g[0]; col[4 * i + 1] = g[1]; col[4 * i + 2] = g[2]; col[4 * i + 3] = 255;
        }
    }
    v.gl.bindBuffer(v.gl.ARRAY_BUFFER, v.colorBuffer);
    v.gl.bufferSubData(v.gl.ARRAY_BUFFER, 0, col);
}
