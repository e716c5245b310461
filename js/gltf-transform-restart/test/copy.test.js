// `gltf-transform copy` with the extension registered keeps every restart group of
// the .glb files named in STRIPKIT_RESTART_GLBS (separated by the path delimiter;
// the stripkit CLI test crates/stripkit-cli/tests/cli_downstream.rs writes them with
// `stripkit strip`), index for index; without it the groups are gone; a renumbering
// of a primitive's vertices renumbers its group; a group whose primitive changed in
// any other way is left out with a warning; removing a primitive renumbers the
// groups of the others. Each copy
// is written beside its input as NAME.copy.glb for the validator.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { NodeIO, Logger } from '@gltf-transform/core';
import { EXTMeshPrimitiveRestart, EXT_MESH_PRIMITIVE_RESTART as NAME } from '../index.js';

const inputs = (process.env.STRIPKIT_RESTART_GLBS || '').split(path.delimiter).filter(Boolean);
const skip = inputs.length === 0 && 'STRIPKIT_RESTART_GLBS names no .glb (the stripkit CLI test sets it)';

/** The JSON and binary chunk of a .glb. */
function parseGlb(bytes) {
    const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    const jsonLength = view.getUint32(12, true);
    const json = JSON.parse(new TextDecoder().decode(bytes.subarray(20, 20 + jsonLength)));
    const binStart = 20 + jsonLength;
    const bin = binStart < bytes.length ? bytes.subarray(binStart + 8, binStart + 8 + view.getUint32(binStart, true)) : null;
    return { json, bin };
}

const ARRAYS = { 5121: Uint8Array, 5123: Uint16Array, 5125: Uint32Array };

/** An index accessor's values as numbers. */
function indexValues({ json, bin }, a) {
    const acc = json.accessors[a];
    const bv = json.bufferViews[acc.bufferView];
    const Array_ = ARRAYS[acc.componentType];
    const start = (bv.byteOffset || 0) + (acc.byteOffset || 0);
    return Array.from(new Array_(bin.slice(start, start + acc.count * Array_.BYTES_PER_ELEMENT).buffer));
}

/** Every mesh's groups: [{primitives, indices: [values], componentType, target}]. */
function groups(glb) {
    return (glb.json.meshes || []).map((mesh) =>
        ((mesh.extensions && mesh.extensions[NAME]) || { primitiveGroups: [] }).primitiveGroups.map((g) => ({
            primitives: g.primitives,
            indices: indexValues(glb, g.indices),
            componentType: glb.json.accessors[g.indices].componentType,
        })));
}

/** A logger that keeps the warnings. */
function recordingLogger() {
    const logger = new Logger(Logger.Verbosity.SILENT);
    logger.warnings = [];
    logger.warn = (text) => logger.warnings.push(text);
    return logger;
}

test('copy keeps every restart group, index for index', { skip }, async () => {
    for (const file of inputs) {
        const input = parseGlb(new Uint8Array(fs.readFileSync(file)));
        const before = groups(input);
        assert.ok(before.flat().length > 0, `${file} has no restart group`);
        const logger = recordingLogger();
        const io = new NodeIO().setLogger(logger).registerExtensions([EXTMeshPrimitiveRestart]);
        const out = await io.writeBinary(await io.readBinary(new Uint8Array(fs.readFileSync(file))));
        fs.writeFileSync(file.replace(/\.glb$/, '.copy.glb'), out);
        const copy = parseGlb(out);
        assert.ok(copy.json.extensionsUsed.includes(NAME));
        assert.ok(!(copy.json.extensionsRequired || []).includes(NAME));
        assert.deepEqual(groups(copy), before, `${file}: groups changed`);
        assert.deepEqual(logger.warnings, []);
        // The fallback primitives are unchanged too.
        copy.json.meshes.forEach((mesh, m) => mesh.primitives.forEach((p, k) => {
            const q = input.json.meshes[m].primitives[k];
            assert.equal(p.mode, q.mode);
            assert.deepEqual(indexValues(copy, p.indices), indexValues(input, q.indices));
        }));
        console.log(`${path.basename(file)}: ${before.flat().length} group(s), ${before.flat().reduce((n, g) => n + g.indices.length, 0)} restart indices kept`);
    }
});

test('without the extension the groups are lost (why this package exists)', { skip }, async () => {
    const io = new NodeIO().setLogger(recordingLogger());
    const out = await io.writeBinary(await io.readBinary(new Uint8Array(fs.readFileSync(inputs[0]))));
    assert.equal(groups(parseGlb(out)).flat().length, 0);
});

test('a renumbering of the vertices renumbers the group with them', { skip }, async () => {
    const logger = recordingLogger();
    const io = new NodeIO().setLogger(logger).registerExtensions([EXTMeshPrimitiveRestart]);
    const bytes = new Uint8Array(fs.readFileSync(inputs[0]));
    const doc = await io.readBinary(bytes);
    const prim = doc.getRoot().listMeshes().find((m) => m.getExtension(NAME)).getExtension(NAME)
        .listGroups()[0].listPrimitives()[0];
    // What reorder or weld do, without knowing the group: every vertex id v becomes
    // f(v) (here (v + 1) mod the vertex count) in the primitive's indices.
    const n = prim.getAttribute('POSITION').getCount();
    const f = (v) => (v + 1) % n;
    prim.getIndices().setArray(prim.getIndices().getArray().map(f));
    const input = groups(parseGlb(bytes));
    const cut = { 5121: 0xff, 5123: 0xffff, 5125: 0xffffffff };
    const expected = input.map((mesh, m) => mesh.map((g, k) => (m === 0 && k === 0
        ? { ...g, indices: g.indices.map((v) => (v === cut[g.componentType] ? v : f(v))) }
        : g)));
    assert.deepEqual(groups(parseGlb(await io.writeBinary(doc))), expected);
    assert.deepEqual(logger.warnings, []);
});

test('a group whose primitive changed otherwise is left out with a warning', { skip }, async () => {
    const logger = recordingLogger();
    const io = new NodeIO().setLogger(logger).registerExtensions([EXTMeshPrimitiveRestart]);
    const bytes = new Uint8Array(fs.readFileSync(inputs[0]));
    const doc = await io.readBinary(bytes);
    const prim = doc.getRoot().listMeshes().find((m) => m.getExtension(NAME)).getExtension(NAME)
        .listGroups()[0].listPrimitives()[0];
    // The last index dropped: one triangle fewer, no renumbering explains it.
    const indices = prim.getIndices();
    indices.setArray(indices.getArray().slice(0, indices.getCount() - 1));
    const before = groups(parseGlb(bytes)).flat().length;
    const copy = parseGlb(await io.writeBinary(doc));
    assert.equal(groups(copy).flat().length, before - 1);
    assert.equal(logger.warnings.length, 1);
    assert.match(logger.warnings[0], /no longer draw the triangles/);
});

test('removing a primitive renumbers the groups of the others', { skip }, async () => {
    const file = inputs.find((f) => groups(parseGlb(new Uint8Array(fs.readFileSync(f)))).some((g) => g.length >= 2));
    assert.ok(file, 'no input has a mesh with two restart groups');
    const input = parseGlb(new Uint8Array(fs.readFileSync(file)));
    const m = groups(input).findIndex((g) => g.length >= 2);
    const logger = recordingLogger();
    const io = new NodeIO().setLogger(logger).registerExtensions([EXTMeshPrimitiveRestart]);
    const doc = await io.readBinary(new Uint8Array(fs.readFileSync(file)));
    const mesh = doc.getRoot().listMeshes()[m];
    const [first] = mesh.getExtension(NAME).listGroups();
    // The first primitive goes, with its index accessors and its group: every later
    // primitive and accessor moves down.
    const gone = first.listPrimitives()[0];
    const accessors = [gone.getIndices(), first.getIndices()];
    gone.dispose();
    mesh.getExtension(NAME).removeGroup(first);
    first.dispose();
    accessors.forEach((a) => a.dispose());
    const copy = parseGlb(await io.writeBinary(doc));
    const expected = groups(input)[m].slice(1).map((g) => ({ ...g, primitives: g.primitives.map((p) => p - 1) }));
    assert.deepEqual(groups(copy)[m], expected);
    const before = input.json.meshes[m].extensions[NAME].primitiveGroups[1].indices;
    const after = copy.json.meshes[m].extensions[NAME].primitiveGroups[0].indices;
    assert.ok(after < before, `the accessor moved down: ${before} -> ${after}`);
    assert.deepEqual(logger.warnings, []);
});
