// The panel: the model's figures, the level slider (a .sets or .lodseq: the level
// extracted by the cursor, only the changed strips uploaded), the frame slider and play
// (a .lodseq), the colour / shading / wireframe controls, and the orbit by pointer.

/** The figures table, and the colour options the model offers. */
function showFigures(v) {
    const model = v.model;
    document.getElementById('name').textContent = model.name;
    const rows = [['triangles', model.triangles], ['strips', model.strips], ['indices (restart)', model.indices],
        ['indices / triangle', (model.indices / Math.max(model.triangles, 1)).toFixed(3)], ['ACMR', model.acmr.toFixed(3)],
        ['vertices', model.vertices], ['algorithm', model.algo]];
    const table = document.getElementById('figures');
    for (const [k, x] of rows) {
        const tr = table.insertRow();
        tr.insertCell().textContent = k;
        tr.insertCell().textContent = typeof x === 'number' ? x.toLocaleString('en') : x;
    }
    const cullOption = document.querySelector('#color option[value=cull]');
    if (!v.tree) cullOption.remove();
    else document.getElementById('cullFigures').hidden = false;
    const checker = document.querySelector('#color option[value=checker]');
    if (!v.uv) { checker.disabled = true; checker.textContent += ' — no UVs'; }
}

/**
 * Moves the cursor to `level` (and a .lodseq's `frame`): the changed strips, and a
 * moved frame's positions, uploaded; the figures in v.lod. A .lodseq's level is
 * clamped to each frame's model, and kept as asked.
 */
function setLevel(v, level, frame = v.lod.frame) {
    const t = performance.now();
    const changed = v.seq ? v.cursor.set(frame, level) : v.cursor.setLevel(level);
    const t1 = performance.now();
    const frameMoved = v.seq !== null && v.cursor.frame !== v.lod.frame;
    if (frameMoved) v.positions = v.scaled(v.cursor.positions());
    uploadStrips(v, changed, frameMoved);
    Object.assign(v.lod, { level: v.cursor.level, asked: level, frame: v.seq ? v.cursor.frame : 0, changed: changed.length, extractMs: t1 - t, uploadMs: performance.now() - t1 });
    return changed;
}

/** The level's figures in the panel. */
function showLevel(v) {
    const t = document.getElementById('levelFigures'), lod = v.lod;
    t.textContent = '';
    const rows = [['level', `${lod.level.toLocaleString('en')} of ${v.levelCount.toLocaleString('en')}`],
        ['triangles', v.cursor.triangles().toLocaleString('en')], ['strips changed', lod.changed],
        ['extraction', lod.extractMs.toFixed(2) + ' ms'], ['upload', lod.uploadMs.toFixed(2) + ' ms']];
    if (v.seq) rows.unshift(['frame', `${lod.frame + 1} of ${v.seq.frames}: ${v.seq.names[lod.frame]}`]);
    for (const [k, x] of rows) { const tr = t.insertRow(); tr.insertCell().textContent = k; tr.insertCell().textContent = x; }
}

/** The level slider of a .sets or .lodseq page. */
function setupLevelSlider(v) {
    if (!v.sets && !v.seq) return;
    document.getElementById('lod').hidden = false;
    const slider = document.getElementById('level');
    slider.max = v.levelCount;
    slider.addEventListener('input', () => { setLevel(v, Number(slider.value)); showLevel(v); redraw(v); });
    showLevel(v);
}

/**
 * A .lodseq: the frame slider (at the page's first frame), and play: one frame further
 * every 1/30 s, drawn on the animation frame that follows.
 */
function setupPlay(v) {
    if (!v.seq) return;
    document.getElementById('anim').hidden = false;
    const frameSlider = document.getElementById('frame'), play = document.getElementById('play');
    frameSlider.max = v.seq.frames - 1;
    frameSlider.value = v.lod.frame;
    frameSlider.addEventListener('input', () => { setLevel(v, v.lod.asked, Number(frameSlider.value)); showLevel(v); redraw(v); });
    let last = 0;
    function tick(now) {
        if (!v.playing) return;
        if (now - last >= 1000 / 30) {
            last = now;
            setLevel(v, v.lod.asked, (v.lod.frame + 1) % v.seq.frames);
            v.lod.played++;
            frameSlider.value = v.lod.frame;
            showLevel(v);
            draw(v);
        }
        requestAnimationFrame(tick);
    }
    play.addEventListener('click', () => {
        v.playing = !v.playing;
        play.textContent = v.playing ? 'pause' : 'play';
        if (v.playing) requestAnimationFrame(tick);
    });
}

/** The colour, shading, wireframe, hold and reset controls, and orbit / zoom by pointer. */
function setupControls(v) {
    const state = v.state, canvas = v.canvas;
    const on = (id, ev, f) => document.getElementById(id).addEventListener(ev, f);
    on('color', 'change', (e) => { state.color = e.target.value; paint(v, state.color); redraw(v); });
    on('shading', 'change', (e) => { state.shading = e.target.value; redraw(v); });
    on('wireframe', 'change', (e) => { state.wireframe = e.target.checked; redraw(v); });
    on('hold', 'change', (e) => { state.hold = e.target.checked; redraw(v); });
    on('reset', 'click', () => { Object.assign(state, { yaw: 0, pitch: 0, zoom: 1 }); redraw(v); });
    let drag = null;
    canvas.addEventListener('pointerdown', (e) => { drag = [e.clientX, e.clientY]; canvas.setPointerCapture(e.pointerId); });
    canvas.addEventListener('pointerup', () => { drag = null; });
    canvas.addEventListener('pointermove', (e) => {
        if (!drag) return;
        state.yaw -= (e.clientX - drag[0]) * 0.01;
        state.pitch = Math.max(-1.5, Math.min(1.5, state.pitch + (e.clientY - drag[1]) * 0.01));
        drag = [e.clientX, e.clientY];
        redraw(v);
    });
    canvas.addEventListener('wheel', (e) => {
        e.preventDefault();
        state.zoom = Math.max(0.2, Math.min(50, state.zoom * Math.exp(-e.deltaY * 0.001)));
        redraw(v);
    }, { passive: false });
}

/** The first state from the address (#color=order&shading=smooth&wireframe=1), shown in the controls. */
function readAddress(v) {
    const state = v.state;
    for (const [k, x] of new URLSearchParams(location.hash.slice(1))) {
        if (k === 'wireframe') state.wireframe = x === '1';
        else if ((k === 'color' || k === 'shading') && document.querySelector(`#${k} option[value=${CSS.escape(x)}]`)) state[k] = x;
    }
    document.getElementById('color').value = state.color;
    document.getElementById('shading').value = state.shading;
    document.getElementById('wireframe').checked = state.wireframe;
}
