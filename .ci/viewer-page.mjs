#!/usr/bin/env node
// Opens pages written by `stripkit view` in headless Chromium (playwright-core, Debian's
// chromium, SwiftShader WebGL: software rendering) and saves each canvas's first frame.
//   node .ci/viewer-page.mjs PAGE.html[#color=none&shading=smooth]=OUT.rgba [PAGE=OUT ...]
// OUT gets the canvas's pixels, RGBA, top row first. Prints one JSON line per page:
// {"page", "width", "height", "first_frame_ms" (navigation start to the first frame
// drawn and finished), "setup_ms" (the page's script, decoding to first frame),
// "errors" (console errors and uncaught exceptions)}.
// Needs CHROMIUM (default /usr/bin/chromium) and playwright-core in .ci/node_modules.
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const { chromium } = await import(path.join(here, 'node_modules/playwright-core/index.mjs'));
// Split at the last '=': the page's address may hold some.
const pairs = process.argv.slice(2).map((a) => [a.slice(0, a.lastIndexOf('=')), a.slice(a.lastIndexOf('=') + 1)]);
if (pairs.length === 0 || pairs.some((p) => !p[0] || !p[1])) {
    console.error('usage: viewer-page.mjs PAGE.html=OUT.rgba ...');
    process.exit(2);
}
const browser = await chromium.launch({
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    args: ['--use-gl=angle', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--no-sandbox'],
});
try {
    for (const [page, out] of pairs) {
        const tab = await browser.newPage();
        const errors = [];
        tab.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
        tab.on('pageerror', (e) => errors.push(String(e)));
        const [file, hash] = page.split('#');
        await tab.goto(pathToFileURL(path.resolve(file)).href + (hash ? '#' + hash : ''));
        await tab.waitForFunction(() => window.stripkitView && window.stripkitView.ready, null, { timeout: 60000 });
        const r = await tab.evaluate(() => {
            const v = window.stripkitView, c = document.getElementById('view');
            return { width: c.width, height: c.height, first_frame_ms: v.firstFrameMs, setup_ms: v.setupMs, pixels: v.pixels() };
        });
        const row = r.width * 4, flipped = Buffer.alloc(r.pixels.length);
        for (let y = 0; y < r.height; y++) flipped.set(r.pixels.slice((r.height - 1 - y) * row, (r.height - y) * row), y * row);
        fs.writeFileSync(out, flipped);
        console.log(JSON.stringify({ page, width: r.width, height: r.height, first_frame_ms: r.first_frame_ms, setup_ms: r.setup_ms, errors }));
        await tab.close();
    }
} finally {
    await browser.close();
}
