// stripkit view: draws the model in the JSON block #model with WebGL2, one
// drawElements(TRIANGLE_STRIP) over every strip, the strips separated by the fixed
// restart index 0xFFFFFFFF (always on in WebGL2). The strips lie in one buffer, each
// at a fixed place one longer than its level-0 length, the rest of it restart
// indices: the layout of the `.sets` runtime's cursor, so that a level change rewrites
// only the places of the strips that changed. Every place has its own vertex (so that
// a strip can carry its own colour). The pieces are files beside this one, inlined
// where the main function begins, after the runtime: decode.js (the model),
// colours.js, gl.js (program and buffers), camera.js (camera, draw), cull.js (segment
// tree), panel.js (figures, sliders, play, controls), hooks.js (window.stripkitView,
// for tests). They share one object, `v`, the page's state. A `.lodseq` page decodes
// its file asynchronously (deflated positions).
'use strict';
(async function () {
    /*MODULES*/
    const model = JSON.parse(document.getElementById('model').textContent);
    const t0 = performance.now();
    const v = await decodeModel(model);
    const canvas = document.getElementById('view');
    [canvas.width, canvas.height] = model.size;
    canvas.style.width = model.size[0] + 'px';
    canvas.style.height = model.size[1] + 'px';
    const gl = canvas.getContext('webgl2', { antialias: false, preserveDrawingBuffer: true });
    if (!gl) { document.body.textContent = 'This page needs WebGL2.'; return; }
    gl.getExtension('OES_standard_derivatives');
    Object.assign(v, { canvas, gl, ...createProgram(gl), tree: decodeTree(model.tree), heldEye: null, pending: false, playing: false });
    v.state = { color: 'strips', shading: 'flat', wireframe: false, hold: false, yaw: 0, pitch: 0, zoom: 1 };
    v.levelCount = v.sets ? v.sets.levels : v.seq ? Math.max(...v.seq.models.map((m) => m.levels)) : 0;
    v.lod = { level: 0, asked: 0, frame: v.seq ? v.cursor.frame : 0, changed: 0, extractMs: 0, uploadMs: 0, played: 0 };
    createBuffers(v);
    showFigures(v);
    setupLevelSlider(v);
    setupPlay(v);
    setupControls(v);
    readAddress(v);
    paint(v, v.state.color);
    draw(v);
    gl.finish();
    window.stripkitView = pageHooks(v, t0);
})();
