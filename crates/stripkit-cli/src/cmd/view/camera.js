// Camera and drawing: glam's look_at_rh and perspective_rh_gl (column-major), the
// orbit about the first camera, and the one drawElements(TRIANGLE_STRIP) of a frame.

const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const norm = (a) => { const l = Math.hypot(...a); return a.map((x) => x / l); };

/** The projection times the view of `cam` for a canvas of `aspect` (width / height). */
function viewProj(cam, aspect) {
    const f = norm(sub(cam.target, cam.eye)), s = norm(cross(f, cam.up)), v = cross(s, f);
    const view = [s[0], v[0], -f[0], 0, s[1], v[1], -f[1], 0, s[2], v[2], -f[2], 0,
        -dot(s, cam.eye), -dot(v, cam.eye), dot(f, cam.eye), 1];
    const t = 1 / Math.tan(cam.fov * Math.PI / 360), inv = 1 / (cam.near - cam.far);
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

/**
 * The camera of the current orbit: the `first` eye turned about the first up (yaw) and
 * the first right (pitch) around the target, its distance divided by zoom.
 */
function orbitCamera(first, state) {
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

/** Draws one frame for the current state (the culling colours first, for the held eye). */
function draw(v) {
    const { gl, state, model } = v, first = model.camera;
    const cam = orbitCamera(first, state);
    // "Hold the culling eye": orbit away to see what that eye culls.
    if (!state.hold || !v.heldEye) v.heldEye = cam.eye.map(Math.fround);
    if (state.color === 'cull' && v.tree) paintCull(v, v.heldEye);
    gl.viewport(0, 0, v.canvas.width, v.canvas.height);
    gl.clearColor(1, 1, 1, 1);
    gl.clearDepth(1);
    gl.enable(gl.DEPTH_TEST);
    gl.depthFunc(gl.LESS);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.useProgram(v.program);
    gl.uniformMatrix4fv(v.u.u_mvp, false, viewProj(cam, model.size[0] / model.size[1]));
    if (state.shading === 'smooth' && !v.normals) {
        v.normals = gather(v, vertexNormals(v), 3, new Float32Array(3 * v.n), 0, v.n);
        gl.bindBuffer(gl.ARRAY_BUFFER, v.normalBuffer);
        gl.bufferSubData(gl.ARRAY_BUFFER, 0, v.normals);
    }
    gl.uniform1i(v.u.u_shading, { smooth: 0, flat: 1, unlit: 2 }[state.shading]);
    gl.uniform1i(v.u.u_checker, state.color === 'checker' ? 1 : 0);
    gl.uniform1i(v.u.u_wire, state.wireframe ? 1 : 0);
    const light = cam.first ? first.light : cam.light;
    gl.uniform3fv(v.u.u_light, norm(light));
    gl.bindVertexArray(v.vao);
    gl.drawElements(gl.TRIANGLE_STRIP, v.n, gl.UNSIGNED_INT, 0);
    gl.bindVertexArray(null);
}

/** A draw on the next animation frame (one however many asks come before it). */
function redraw(v) {
    if (v.pending) return;
    v.pending = true;
    requestAnimationFrame(() => { v.pending = false; draw(v); });
}
