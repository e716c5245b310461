#!/usr/bin/env node
// Opens pages written by `stripkit view` in headless Chromium (playwright-core, Debian's
// chromium, software WebGL) and saves each canvas's first frame.
//   node .ci/viewer-page.mjs [--gl=BACKEND] [--eyes=X,Y,Z;...] [--levels=L,L,...] [--frames=F:L,...] [--play=MS] [--sweep=N] PAGE.html[#color=none&shading=smooth]=OUT.rgba [PAGE=OUT ...]
// --gl picks Chromium's WebGL backend: llvmpipe (default: ANGLE on Mesa's OpenGL ES
// through EGL, the rasterizer `stripkit render` uses, so that first frames match its
// pictures to within 8 levels everywhere), or swiftshader (ANGLE on SwiftShader's Vulkan).
// For a `.lodseq` page, --frames writes OUT.frames.json ({"F:L": {"frame", "level",
// "strips", "positions"}: the runtime's strips and the frame's decoded positions}) and
// --play=MS presses play for MS milliseconds, adding "play": {"played", "frame"} to the line.
// A `.lodseq` page's line has "frame": [the frame shown first, the frame slider's value].
// For a --cull page, --eyes=X,Y,Z;X,Y,Z;... adds "cull": [{"segments", "drawn",
// "culled", "visited"} per eye] (eyes in the input's units) to the line.
// For a `.sets` page, --levels writes OUT.levels.json ({"L": strips, ...}: the page's
// runtime's strips at each level, as `stripkit lod extract`'s JSON), and --sweep moves
// the slider's level across N steps from the finest to the coarsest and back, adding
// "sweep": {"steps", "extract_ms", "upload_ms" and "frame_ms" (extract + upload + draw
// + finish as the page sees them): median and max, "changed_strips" max, and
// "frame_interval_ms": median, 95th percentile and max between animation frames when
// the same moves are made one per frame} to the line.
// OUT gets the canvas's pixels, RGBA, top row first. Prints one JSON line per page:
// {"page", "width", "height", "first_frame_ms" (navigation start to the first frame
// drawn and finished), "setup_ms" (the page's script, decoding to first frame),
// "renderer" (WebGL's unmasked renderer), "errors" (console errors and uncaught
// exceptions), "requests" (every address the page asked for besides itself)}.
// Needs CHROMIUM (default /usr/bin/chromium) and playwright-core in .ci/node_modules.
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const { chromium } = await import(path.join(here, 'node_modules/playwright-core/index.mjs'));
const options = Object.fromEntries(process.argv.slice(2).filter((a) => a.startsWith('--')).map((a) => a.slice(2).split('=')));
// Split at the last '=': the page's address may hold some.
const pairs = process.argv.slice(2).filter((a) => !a.startsWith('--')).map((a) => [a.slice(0, a.lastIndexOf('=')), a.slice(a.lastIndexOf('=') + 1)]);
if (pairs.length === 0 || pairs.some((p) => !p[0] || !p[1])) {
    console.error('usage: viewer-page.mjs PAGE.html=OUT.rgba ...');
    process.exit(2);
}
const BACKENDS = {
    swiftshader: ['--use-gl=angle', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
    llvmpipe: ['--use-gl=angle', '--use-angle=gl-egl', '--ignore-gpu-blocklist'],
};
const backend = BACKENDS[options.gl || 'llvmpipe'];
if (!backend) {
    console.error(`--gl: one of ${Object.keys(BACKENDS).join(', ')}`);
    process.exit(2);
}
const browser = await chromium.launch({
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    args: [...backend, '--no-sandbox'],
});
try {
    for (const [page, out] of pairs) {
        const tab = await browser.newPage();
        const errors = [];
        tab.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
        tab.on('pageerror', (e) => errors.push(String(e)));
        const [file, hash] = page.split('#');
        const address = pathToFileURL(path.resolve(file)).href;
        const requests = [];
        tab.on('request', (q) => { if (q.url().split('#')[0] !== address) requests.push(q.url()); });
        await tab.goto(address + (hash ? '#' + hash : ''));
        await tab.waitForFunction(() => window.stripkitView && window.stripkitView.ready, null, { timeout: 60000 });
        const r = await tab.evaluate(() => {
            const v = window.stripkitView, c = document.getElementById('view');
            const frame = v.frames ? [v.played().frame, Number(document.getElementById('frame').value)] : undefined;
            return { width: c.width, height: c.height, first_frame_ms: v.firstFrameMs, setup_ms: v.setupMs, renderer: v.renderer, pixels: v.pixels(), frame };
        });
        const row = r.width * 4, flipped = Buffer.alloc(r.pixels.length);
        for (let y = 0; y < r.height; y++) flipped.set(r.pixels.slice((r.height - 1 - y) * row, (r.height - y) * row), y * row);
        fs.writeFileSync(out, flipped);
        const line = { page, width: r.width, height: r.height, first_frame_ms: r.first_frame_ms, setup_ms: r.setup_ms, renderer: r.renderer, errors, requests };
        if (r.frame) line.frame = r.frame;
        if (options.eyes) {
            const eyes = options.eyes.split(';').map((e) => e.split(',').map(Number));
            line.cull = await tab.evaluate((es) => es.map((e) => { const c = window.stripkitView.cull(e); delete c.ranges; return c; }), eyes);
        }
        if (options.levels) {
            const levels = options.levels.split(',').map(Number);
            const strips = await tab.evaluate((ls) => Object.fromEntries(ls.map((l) => [l, window.stripkitView.level(l)])), levels);
            fs.writeFileSync(out + '.levels.json', JSON.stringify(strips));
        }
        if (options.frames) {
            const pairs = options.frames.split(',');
            const got = await tab.evaluate((ps) => Object.fromEntries(ps.map((p) => [p, window.stripkitView.frame(...p.split(':').map(Number))])), pairs);
            fs.writeFileSync(out + '.frames.json', JSON.stringify(got));
        }
        if (options.play) {
            await tab.click('#play');
            await tab.waitForTimeout(Number(options.play));
            await tab.click('#play');
            line.play = await tab.evaluate(() => window.stripkitView.played());
        }
        if (options.sweep) {
            line.sweep = await tab.evaluate((steps) => {
                const v = window.stripkitView, top = v.levels;
                const ls = [];
                for (let i = 0; i <= steps; i++) ls.push(Math.round((top * i) / steps));
                for (let i = steps - 1; i >= 0; i--) ls.push(Math.round((top * i) / steps));
                const t = v.sweep(ls);
                const stat = (k) => { const x = t.map((r) => r[k]).sort((a, b) => a - b); return [x[x.length >> 1], x[x.length - 1]]; };
                const frame = t.map((r) => r[0] + r[1] + r[2]).sort((a, b) => a - b);
                return { steps: ls.length, extract_ms: stat(0), upload_ms: stat(1), frame_ms: [frame[frame.length >> 1], frame[frame.length - 1]], changed_strips: stat(3)[1], levels: ls };
            }, Number(options.sweep));
            // The same moves once per animation frame: the intervals between frames.
            const intervals = await tab.evaluate((ls) => window.stripkitView.sweepFrames(ls), line.sweep.levels);
            intervals.sort((a, b) => a - b);
            delete line.sweep.levels;
            line.sweep.frame_interval_ms = [intervals[intervals.length >> 1], intervals[Math.floor(intervals.length * 0.95)], intervals[intervals.length - 1]];
            line.errors = errors;
        }
        console.log(JSON.stringify(line));
        await tab.close();
    }
} finally {
    await browser.close();
}
