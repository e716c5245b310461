// window.stripkitView: the page's state and figures for tests and measurements
// (.ci/viewer-page.mjs): ready, firstFrameMs, setupMs, pixels(), cull(eye), level(L),
// frame(F, L), played(), sweep(levels), sweepFrames(levels).

/** The test hooks of the page `v`, whose script started at `t0`. */
function pageHooks(v, t0) {
    const { gl, canvas, state, model } = v;
    return {
        ready: true,
        levels: v.levelCount,
        frames: v.seq ? v.seq.frames : 0,
        renderer: (() => { const e = gl.getExtension('WEBGL_debug_renderer_info'); return e ? gl.getParameter(e.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER); })(),
        /** A .lodseq page: frames moved by play so far, the current frame, and whether it plays. */
        played() { return { played: v.lod.played, frame: v.lod.frame, playing: v.playing }; },
        /** A .lodseq page: moves to frame `f` at `level`; its non-empty strips and the frame's positions as decoded (unscaled). */
        frame(f, level) { setLevel(v, level, f); return { frame: v.cursor.frame, level: v.cursor.level, strips: v.cursor.strips(), positions: Array.from(v.cursor.positions()) }; },
        firstFrameMs: performance.now(),
        setupMs: performance.now() - t0,
        state,
        draw: () => draw(v),
        set(changes) { Object.assign(state, changes); if (changes.color) paint(v, state.color); draw(v); gl.finish(); },
        /** A --cull page: the traversal for an eye given in the input's units. */
        cull(eye) {
            const out = cullTree(v.tree, eye.map((x) => Math.fround(x) * model.scale));
            return { segments: out.ranges.length, drawn: out.drawn, culled: out.culled, visited: out.visited, ranges: out.ranges };
        },
        /** A .sets (or .lodseq, at the current frame) page: moves to `level` and returns its non-empty strips. */
        level(level) { setLevel(v, level); return v.cursor.strips(); },
        /** A .sets page: one level per animation frame, as a slider dragged; resolves to the frames' intervals (ms). */
        sweepFrames(levels) {
            return new Promise((done) => {
                const times = [];
                let i = 0, last = null;
                function step(now) {
                    if (last !== null) times.push(now - last);
                    last = now;
                    if (i === levels.length) { done(times); return; }
                    setLevel(v, levels[i++]);
                    draw(v);
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
                setLevel(v, l);
                const t = performance.now();
                draw(v);
                gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
                return [v.lod.extractMs, v.lod.uploadMs, performance.now() - t, v.lod.changed];
            });
        },
        /** The canvas's pixels, RGBA, bottom row first. */
        pixels() {
            const px = new Uint8Array(canvas.width * canvas.height * 4);
            gl.readPixels(0, 0, canvas.width, canvas.height, gl.RGBA, gl.UNSIGNED_BYTE, px);
            return Array.from(px);
        },
    };
}
