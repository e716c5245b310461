#!/usr/bin/env node
// Draws glTF (GLTFLoader) and OBJ (OBJLoader) files with three.js in headless Chromium (playwright-core,
// Debian's chromium, SwiftShader WebGL) and compares each candidate's pixels with its
// reference's, all in one browser launch.
//   node .ci/threejs-pixels.mjs REF.obj=CAND.glb [REF=CAND ...]
// Each pair is drawn from 3 views framed on the reference's bounds, 256 x 256, twice
// per view: flat face normals (the triangles and their winding) and the UV coordinates
// as colour (when the reference has UVs). A candidate with EXT_mesh_primitive_restart
// groups is drawn twice: as three.js loads it (the stitched fallback) and from the
// groups' restart strips. Prints one JSON line per pair: {"reference", "candidate",
// "pixels", "drawn" (the reference's lit pixels), "differing": {"fallback normals",
// "fallback uv", "restart normals", "restart uv"}}; exit status 1 when a pair differs.
// Needs CHROMIUM (default /usr/bin/chromium) and the npm packages three and
// playwright-core in .ci/node_modules (.ci/run installs them).
import http from 'node:http';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const { chromium } = await import(path.join(here, 'node_modules/playwright-core/index.mjs'));
const pairs = process.argv.slice(2).map((a) => a.split('='));
if (pairs.length === 0 || pairs.some((p) => p.length !== 2)) {
    console.error('usage: threejs-pixels.mjs REF.glb=CAND.glb ...');
    process.exit(2);
}
const files = pairs.flat();

const page = `<!doctype html><html><body><script type="importmap">
{"imports": {"three": "/three/build/three.module.js", "three/addons/": "/three/examples/jsm/"}}
</script><script type="module">
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { OBJLoader } from 'three/addons/loaders/OBJLoader.js';
import { DRACOLoader } from 'three/addons/loaders/DRACOLoader.js';
import { MeshoptDecoder } from 'three/addons/libs/meshopt_decoder.module.js';
const SIZE = 256;
const renderer = new THREE.WebGLRenderer({ antialias: false, preserveDrawingBuffer: true });
renderer.setSize(SIZE, SIZE);
const normals = new THREE.MeshNormalMaterial({ flatShading: true });
// OBJ's texture origin is the bottom left, glTF's the top left: v is flipped for OBJ.
const uvMaterial = (flip) => new THREE.ShaderMaterial({
    uniforms: { flip: { value: flip ? 1 : 0 } },
    vertexShader: 'uniform int flip; varying vec2 v; void main() { v = flip == 1 ? vec2(uv.x, 1.0 - uv.y) : uv; gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0); }',
    fragmentShader: 'varying vec2 v; void main() { gl_FragColor = vec4(fract(v), 0.5, 1.0); }',
});
// Compressed sources (a corpus of real assets) decode as three.js users decode them.
const gltf = new GLTFLoader().setMeshoptDecoder(MeshoptDecoder)
    .setDRACOLoader(new DRACOLoader().setDecoderPath('/three/examples/jsm/libs/draco/gltf/'));
const obj = new OBJLoader();
const RESTART = 'EXT_mesh_primitive_restart';
/** The file's scene, and (glTF with restart groups) a second copy drawn from the
 * groups' restart strips instead of their fallback primitives (three.js does not read
 * the extension: the strips are cut at the restart value into a triangle list here). */
async function load(url) {
    if (url.endsWith('.obj')) return { scene: await obj.loadAsync(url), restart: null };
    const { scene, parser } = await gltf.loadAsync(url);
    const groups = (parser.json.meshes || []).flatMap((m, mesh) =>
        ((m.extensions && m.extensions[RESTART]) || { primitiveGroups: [] }).primitiveGroups.map((g) => ({ mesh, ...g })));
    if (groups.length === 0) return { scene, restart: null };
    const restart = scene.clone();
    const byPrimitive = new Map();
    const originals = [], copies = [];
    scene.traverse((o) => originals.push(o));
    restart.traverse((o) => copies.push(o)); // the same order: clone() keeps the tree
    originals.forEach((o, k) => {
        const a = o.isMesh && parser.associations.get(o);
        if (a) byPrimitive.set(a.meshes + '/' + a.primitives, copies[k]);
    });
    for (const g of groups) {
        const accessor = await parser.getDependency('accessor', g.indices);
        const strips = accessor.array, cut = 2 ** (8 * strips.BYTES_PER_ELEMENT) - 1, list = [];
        for (let start = 0, end = 0; end <= strips.length; end++) {
            if (end < strips.length && strips[end] !== cut) continue;
            for (let i = start; i + 2 < end; i++) {
                const [a, b, c] = (i - start) % 2 ? [strips[i + 1], strips[i], strips[i + 2]] : [strips[i], strips[i + 1], strips[i + 2]];
                if (a !== b && b !== c && a !== c) list.push(a, b, c);
            }
            start = end + 1;
        }
        g.primitives.forEach((p, k) => {
            const mesh = byPrimitive.get(g.mesh + '/' + p);
            if (k > 0) { mesh.visible = false; return; }
            mesh.geometry = mesh.geometry.clone();
            mesh.geometry.setIndex(list);
        });
    }
    return { scene, restart };
}
function draw(scene, camera, material) {
    scene.traverse((o) => { if (o.isMesh) o.material = material; });
    renderer.setClearColor(0x000000, 1);
    renderer.render(scene, camera);
    const gl = renderer.getContext();
    const px = new Uint8Array(SIZE * SIZE * 4);
    gl.readPixels(0, 0, SIZE, SIZE, gl.RGBA, gl.UNSIGNED_BYTE, px);
    return px;
}
function hasUv(scene) {
    let uv = false;
    scene.traverse((o) => { if (o.isMesh && o.geometry.attributes.uv) uv = true; });
    return uv;
}
function views(box) {
    const c = box.getCenter(new THREE.Vector3());
    const r = box.getSize(new THREE.Vector3()).length() * 0.6;
    return [[0, 0, 1], [1, 0.5, 0], [0.3, 1, 0.4]].map((d) => {
        const cam = new THREE.PerspectiveCamera(40, 1, r * 0.1, r * 10);
        cam.position.copy(c).add(new THREE.Vector3(...d).normalize().multiplyScalar(r * 2.5));
        cam.lookAt(c);
        return cam;
    });
}
function compareScenes(a, b, materials, cams, counts, key) {
    for (const cam of cams) {
        for (const [name, ma, mb] of materials) {
            const pa = draw(a, cam, ma), pb = draw(b, cam, mb);
            let differing = 0;
            for (let i = 0; i < pa.length; i += 4) {
                if (key === 'fallback') { counts.pixels++; if (pa[i] | pa[i + 1] | pa[i + 2]) counts.drawn++; }
                if (pa[i] !== pb[i] || pa[i + 1] !== pb[i + 1] || pa[i + 2] !== pb[i + 2]) differing++;
            }
            counts.differing[key + ' ' + name] = (counts.differing[key + ' ' + name] || 0) + differing;
        }
    }
}
window.compare = async (ref, cand) => {
    const a = await load(ref), b = await load(cand);
    const box = new THREE.Box3().setFromObject(a.scene);
    const materials = [['normals', normals, normals]];
    if (hasUv(a.scene)) materials.push(['uv', uvMaterial(ref.endsWith('.obj')), uvMaterial(cand.endsWith('.obj'))]);
    const counts = { pixels: 0, drawn: 0, differing: {} };
    compareScenes(a.scene, b.scene, materials, views(box), counts, 'fallback');
    if (b.restart) compareScenes(a.scene, b.restart, materials, views(box), counts, 'restart');
    return counts;
};
window.ready = true;
</script></body></html>`;

const threeRoot = path.join(here, 'node_modules/three');
const server = http.createServer((req, res) => {
    const url = decodeURIComponent(req.url.split('?')[0]);
    let file = null, type = 'application/octet-stream';
    if (url === '/') { res.setHeader('content-type', 'text/html'); return res.end(page); }
    if (url.startsWith('/three/')) {
        file = path.join(threeRoot, path.normalize(url.slice(7)));
        if (!file.startsWith(threeRoot + path.sep)) file = null;
        type = url.endsWith('.wasm') ? 'application/wasm' : 'text/javascript';
    }
    else if (url.startsWith('/f/')) {
        // /f/K/NAME: file K itself, or a file beside it (a .gltf's buffers and images).
        const [, , k, ...rest] = url.split('/');
        const dir = path.dirname(path.resolve(files[Number(k)] || '.'));
        file = path.resolve(dir, rest.join('/'));
        if (!file.startsWith(dir + path.sep)) file = null;
    }
    if (!file || !fs.existsSync(file) || !fs.statSync(file).isFile()) { res.statusCode = 404; return res.end(); }
    res.setHeader('content-type', type);
    fs.createReadStream(file).pipe(res);
});
await new Promise((r) => server.listen(0, '127.0.0.1', r));
const base = `http://127.0.0.1:${server.address().port}`;
const browser = await chromium.launch({
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    args: ['--use-gl=angle', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--no-sandbox'],
});
let failed = false;
try {
    const tab = await browser.newPage();
    tab.on('pageerror', (e) => console.error(String(e)));
    await tab.goto(base + '/');
    await tab.waitForFunction(() => window.ready === true);
    for (const [k, [ref, cand]] of pairs.entries()) {
        const r = await tab.evaluate(([a, b]) => window.compare(a, b), [`/f/${2 * k}/${path.basename(ref)}`, `/f/${2 * k + 1}/${path.basename(cand)}`]);
        failed = failed || Object.values(r.differing).some((n) => n > 0) || r.drawn === 0;
        console.log(JSON.stringify({ reference: ref, candidate: cand, ...r }));
    }
} finally {
    await browser.close();
    server.close();
}
process.exit(failed ? 1 : 0);
