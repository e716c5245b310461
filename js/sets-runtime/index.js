// A JavaScript runtime for stripkit's `.sets` files (docs/sets-format.md): decodes a
// SETS multiresolution strip model and walks its strips at any level of detail, the
// way `stripkit lod extract` and stripkit's `lod::Cursor` do. No dependencies; works
// in browsers and node. Also reads `.lodseq` animations (decodeLodSeq, LodSeqCursor).
// `stripkit view MODEL.sets` (or ANIM.lodseq) inlines this file into its page
// (with the `export` keywords dropped), so keep every export at a line's start.
//
//   import { decodeSets, SetsCursor } from 'stripkit-sets';
//   const sets = decodeSets(bytes);              // an ArrayBuffer or Uint8Array
//   const cursor = new SetsCursor(sets, 0);
//   const changed = cursor.setLevel(1000);       // the strips whose indices changed
//   // cursor.buffer: every strip at its fixed place, padded with the restart index,
//   // ready for drawElements(TRIANGLE_STRIP); cursor.stripRange(s) is strip s's place.
//
// Versions: decodeSets reads the header, then hands the rest to the decoder of the
// file's version (DECODERS); a new version is one more entry there.
//
// decodeBody is about 150 lines long: it reads the sections in file order, checking
// each as lod/file.rs does, so that the two readers can be compared line by line.

/** The restart index the buffers use (WebGL2's fixed one for 32-bit indices). */
export const SETS_RESTART = 0xffffffff;
/** A slot's successor or a strip's beginning that is none. */
export const SETS_END = 0xffffffff;

const MAGIC = 'SKLODSET';

/** A `.sets` (or `.lodseq`) file that cannot be read: `at` is the byte offset where it went wrong. */
export class SetsFormatError extends Error {
    constructor(at, what, kind = '.sets') {
        super(`${kind} byte ${at}: ${what}`);
        this.at = at;
    }
}

let crcTable = null;
/** CRC-32 (IEEE, as gzip) of `bytes`. */
export function crc32(bytes) {
    if (!crcTable) {
        crcTable = new Uint32Array(256);
        for (let n = 0; n < 256; n++) {
            let c = n;
            for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
            crcTable[n] = c >>> 0;
        }
    }
    let c = 0xffffffff;
    for (let i = 0; i < bytes.length; i++) c = crcTable[(c ^ bytes[i]) & 0xff] ^ (c >>> 8);
    return (c ^ 0xffffffff) >>> 0;
}

/** Reads little-endian numbers and LEB128 varints, refusing to run past `end`. */
class Reader {
    constructor(bytes, end, kind = '.sets') {
        this.bytes = bytes;
        this.view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
        this.at = 0;
        this.end = end;
        this.kind = kind;
    }
    fail(what) { throw new SetsFormatError(this.at, what, this.kind); }
    need(n, what) { if (this.end - this.at < n) this.fail(`the file ends inside ${what}`); }
    u32(what) { this.need(4, what); const v = this.view.getUint32(this.at, true); this.at += 4; return v; }
    f32(what) { this.need(4, what); const v = this.view.getFloat32(this.at, true); this.at += 4; return v; }
    u8(what) { this.need(1, what); return this.bytes[this.at++]; }
    /** A varint as a number (exact up to 2^53). */
    varint(what) {
        let v = 0, scale = 1;
        for (let i = 0; i < 10; i++) {
            if (this.at >= this.end) this.fail(`the file ends inside ${what}`);
            const b = this.bytes[this.at++];
            v += (b & 0x7f) * scale;
            if ((b & 0x80) === 0) return v;
            scale *= 128;
        }
        this.fail(`${what}: a number longer than 64 bits`);
    }
    /** A varint below `limit`. */
    below(limit, what) {
        const v = this.varint(what);
        if (v >= limit) this.fail(`${what} ${v} is not below ${limit}`);
        return v;
    }
    /** Room for `count` records of at least one byte each. */
    records(count, what) { if (count > this.end - this.at) this.fail(`${count} ${what} cannot fit in the ${this.end - this.at} bytes left`); }
}

/** Vertex attributes (versions 2 and 3): name, scalar type, components, normalized, raw values. */
function readAttributes(r, positions, version3) {
    const SIZES = [1, 1, 2, 2, 4, 4, 4, 8];
    const count = r.u32('the attribute count');
    const least = version3 ? 0 : 1;
    if (count < least || count > 64) r.fail(`${count} attributes (${least} to 64)`);
    const attributes = [];
    for (let i = 0; i < count; i++) {
        const len = r.varint('an attribute name');
        if (len > 256) r.fail(`an attribute name of ${len} bytes (at most 256)`);
        r.need(len, 'an attribute name');
        const name = new TextDecoder('utf-8', { fatal: true }).decode(r.bytes.subarray(r.at, r.at + len));
        r.at += len;
        const scalar = r.u8('a scalar type'), components = r.u8('a component count'), normalized = r.u8('a normalized flag');
        if (scalar > 7) r.fail(`scalar type ${scalar}`);
        if (components < 1 || components > 4) r.fail(`${components} components (1 to 4)`);
        if (normalized > 1 || (normalized === 1 && scalar >= 6)) r.fail('normalized only for integers');
        attributes.push({ name, scalar, components, normalized: normalized === 1, size: SIZES[scalar] });
    }
    for (const a of attributes) {
        const n = positions * a.components * a.size;
        r.need(n, `the values of ${a.name}`);
        a.data = r.bytes.slice(r.at, r.at + n);
        r.at += n;
    }
    return attributes;
}

/**
 * Versions 1 to 3: positions, (versions 2 and 3) attributes, then the five varint
 * sections. Version 3 (re-stripped models) writes each strip's beginning count as
 * `count << 1 | empty0`, empty0 saying that the strip draws nothing at level 0.
 */
function decodeBody(r, h) {
    const optimal = (h.flags & 1) !== 0;
    const positionless = (h.flags & 2) !== 0;
    const expected = optimal ? h.inputVertices + h.levels : h.inputVertices;
    if (h.positions !== expected) r.fail(`${h.positions} positions; the placement needs ${expected}`);
    const stored = positionless ? 0 : h.positions;
    r.need(12 * stored, 'the positions');
    const positions = new Float32Array(3 * stored);
    for (let i = 0; i < 3 * stored; i++) {
        positions[i] = r.view.getFloat32(r.at, true);
        r.at += 4;
        if (!Number.isFinite(positions[i])) r.fail('a position that is not finite');
    }
    const attributes = h.version >= 2 && !positionless ? readAttributes(r, h.positions, h.version === 3) : [];
    const { levels, strips, slots } = h;
    // 1. Collapses.
    r.records(levels, 'collapses');
    const targets = new Uint32Array(levels), removed = new Uint32Array(levels);
    let triangles = h.triangles0;
    const triangleCount = new Float64Array(levels + 1);
    triangleCount[0] = triangles;
    for (let i = 0; i < levels; i++) {
        targets[i] = optimal ? h.inputVertices + i : r.below(h.positions, 'a collapse target');
        removed[i] = r.varint('a triangle count');
        triangles -= removed[i];
        if (triangles < 0) r.fail('the triangle count goes below zero');
        triangleCount[i + 1] = triangles;
    }
    // 2. Strip lengths.
    r.records(strips, 'strip lengths');
    const stripSlots = new Uint32Array(strips + 1);
    for (let s = 0; s < strips; s++) {
        stripSlots[s + 1] = stripSlots[s] + r.varint('a strip length');
        if (stripSlots[s + 1] > slots) r.fail(`the strips take more than the ${slots} slots`);
    }
    if (stripSlots[strips] !== slots) r.fail(`the strips take ${stripSlots[strips]} slots, not ${slots}`);
    // 3. Level-0 vertices: zigzag differences (versions 1, 2) or candidate codes (3).
    r.records(slots, 'slots');
    const vertex0 = h.version === 3 ? readLabels3(r, slots, h.positions) : new Uint32Array(slots);
    let previous = 0;
    for (let i = 0; h.version !== 3 && i < slots; i++) {
        const z = r.varint('a slot vertex');
        previous += z % 2 === 0 ? z / 2 : -(z + 1) / 2;
        if (previous < 0 || previous >= h.positions) r.fail(`vertex ${previous} is not below ${h.positions}`);
        vertex0[i] = previous;
    }
    // Version 3: every slot's version count, 2 bits each (3: a varint of the rest follows).
    let packed = null;
    if (h.version === 3) {
        const len = Math.ceil(slots / 4);
        r.need(len, 'the version counts');
        packed = r.bytes.subarray(r.at, r.at + len);
        if (slots % 4 !== 0 && packed[len - 1] >> (2 * (slots % 4)) !== 0) r.fail('bits set past the last version count');
        r.at += len;
    } else {
        r.records(slots, 'slot versions');
    }
    // 4. Slot versions: level 0 implied, then (level step, successor << 1 | relabelled).
    const versionOffsets = new Uint32Array(slots + 1);
    let verLevel = new Uint32Array(Math.max(h.versions, slots)), verLabel = new Uint32Array(verLevel.length);
    let verNext = new Uint32Array(verLevel.length);
    let v = 0;
    for (let s = 0; s < strips; s++) {
        for (let x = stripSlots[s]; x < stripSlots[s + 1]; x++) {
            versionOffsets[x] = v;
            if (v >= verLevel.length) r.fail(`more than the ${h.versions} versions the header gives`);
            verLevel[v] = 0;
            verLabel[v] = vertex0[x];
            verNext[v] = x + 1 < stripSlots[s + 1] ? x + 1 : SETS_END;
            v++;
            const two = packed ? (packed[x >> 2] >> (2 * (x & 3))) & 3 : 0;
            const n = !packed ? r.varint('a version count') : two === 3 ? 3 + r.varint('a version count') : two;
            r.records(n, 'versions');
            let level = 0, label = vertex0[x];
            for (let k = 0; k < n; k++) {
                const step = r.varint('a version level');
                level += step;
                if (step < 1 || level > levels) r.fail(`version level ${level} is not in ${verLevel[v - 1] + 1}..=${levels}`);
                const code = r.varint('a successor');
                const successor = Math.floor(code / 2);
                if (code % 2 === 1) label = targets[level - 1];
                const next = successor === 0 ? SETS_END : x + successor;
                if (successor !== 0 && next >= stripSlots[s + 1]) r.fail(`a successor leaves its strip`);
                if (v >= verLevel.length) r.fail(`more than the ${h.versions} versions the header gives`);
                verLevel[v] = level;
                verLabel[v] = label;
                verNext[v] = next;
                v++;
            }
        }
    }
    versionOffsets[slots] = v;
    if (v !== h.versions) r.fail(`${v} versions, not the ${h.versions} the header gives`);
    // 5. Strip beginnings: level 0 implied, then (level step, 0 or 1 + offset).
    const beginOffsets = new Uint32Array(strips + 1);
    const beginLevel = new Uint32Array(h.beginnings), beginSlot = new Uint32Array(h.beginnings);
    let b = 0, lastStart = 0;
    for (let s = 0; s < strips; s++) {
        beginOffsets[s] = b;
        if (b >= h.beginnings) r.fail(`more than the ${h.beginnings} beginnings the header gives`);
        beginLevel[b] = 0;
        const code0 = r.varint('a beginning count');
        const empty0 = h.version === 3 && code0 % 2 === 1;
        const n = h.version === 3 ? Math.floor(code0 / 2) : code0;
        beginSlot[b] = stripSlots[s + 1] > stripSlots[s] && !empty0 ? stripSlots[s] : SETS_END;
        b++;
        r.records(n, 'beginnings');
        let level = 0;
        const restripped = empty0 && stripSlots[s + 1] > stripSlots[s];
        for (let k = 0; k < n; k++) {
            let step;
            if (restripped && k === 0) {
                // Against the previous re-stripped strip's first beginning.
                const z = r.varint('a beginning level');
                lastStart += z % 2 === 0 ? z / 2 : -(z + 1) / 2;
                step = lastStart;
            } else {
                step = r.varint('a beginning level');
            }
            level += step;
            if (step < 1 || level > levels) r.fail(`beginning level ${level} is not in 1..=${levels}`);
            const code = r.varint('a beginning');
            if (code > stripSlots[s + 1] - stripSlots[s]) r.fail('a beginning outside its strip');
            if (b >= h.beginnings) r.fail(`more than the ${h.beginnings} beginnings the header gives`);
            beginLevel[b] = level;
            beginSlot[b] = code === 0 ? SETS_END : stripSlots[s] + code - 1;
            b++;
        }
    }
    beginOffsets[strips] = b;
    if (b !== h.beginnings) r.fail(`${b} beginnings, not the ${h.beginnings} the header gives`);
    if (r.at !== r.end) r.fail(`${r.end - r.at} bytes left over`);
    // The levels at which each strip changes: its beginnings' and its slots' versions'.
    const changeOffsets = new Uint32Array(strips + 1);
    const changeLevel = new Uint32Array(h.versions + h.beginnings);
    let c = 0;
    for (let s = 0; s < strips; s++) {
        const v0 = versionOffsets[stripSlots[s]], v1 = versionOffsets[stripSlots[s + 1]];
        const all = new Uint32Array(v1 - v0 + beginOffsets[s + 1] - beginOffsets[s]);
        all.set(verLevel.subarray(v0, v1));
        all.set(beginLevel.subarray(beginOffsets[s], beginOffsets[s + 1]), v1 - v0);
        all.sort();
        changeOffsets[s] = c;
        for (let i = 0; i < all.length; i++) if (i === 0 || all[i] !== all[i - 1]) changeLevel[c++] = all[i];
    }
    changeOffsets[strips] = c;
    return {
        ...h, optimal, positionless, positions, attributes, targets, removed, triangleCount, stripSlots,
        versionOffsets, verLevel, verLabel, verNext, beginOffsets, beginLevel, beginSlot,
        changeOffsets, changeLevel: changeLevel.subarray(0, c),
    };
}

/**
 * Version 3's level-0 vertices (the library's LabelCoder): a code below 12 names one
 * of the candidates near the earlier occurrences of the two vertices before (3 slots
 * on each side, after before before, nearest first), below 76 one of the 64 vertices
 * named last (most recent first), else the zigzag difference plus 76 from the last
 * vertex so coded.
 */
function readLabels3(r, slots, vertices) {
    const NEAR = 3, CANDIDATES = 12, RECENT = 64;
    const labels = new Uint32Array(slots), before = new Float64Array(slots);
    const last = new Map();
    let recent = [], lastNew = 0;
    const candidates = [];
    for (let x = 0; x < slots; x++) {
        candidates.length = 0;
        for (let back = 1; back <= 2 && x >= back; back++) {
            const p = before[x - back];
            if (p < 0) continue;
            for (let d = 1; d <= NEAR; d++) {
                if (p + d < x) candidates.push(labels[p + d]);
                if (p >= d) candidates.push(labels[p - d]);
            }
        }
        const code = r.varint('a slot vertex');
        let v;
        if (code < CANDIDATES) {
            if (code >= candidates.length) r.fail(`slot ${x} names candidate ${code} of ${candidates.length}`);
            v = candidates[code];
        } else if (code < CANDIDATES + RECENT) {
            if (code - CANDIDATES >= recent.length) r.fail(`slot ${x} names recent vertex ${code - CANDIDATES} of ${recent.length}`);
            v = recent[code - CANDIDATES];
        } else {
            const z = code - CANDIDATES - RECENT;
            v = lastNew + (z % 2 === 0 ? z / 2 : -(z + 1) / 2);
            if (v < 0 || v >= vertices) r.fail(`vertex ${v} is not below ${vertices}`);
            lastNew = v;
        }
        labels[x] = v;
        const p = last.get(v);
        before[x] = p === undefined ? -1 : p;
        last.set(v, x);
        const i = recent.indexOf(v);
        if (i >= 0) recent.splice(i, 1);
        else if (recent.length === RECENT) recent.pop();
        recent.unshift(v);
    }
    return labels;
}

/** The body decoder of each format version. */
export const DECODERS = { 1: decodeBody, 2: decodeBody, 3: decodeBody };

/**
 * Decodes a `.sets` file (ArrayBuffer or Uint8Array). Checks what docs/sets-format.md
 * lists (magic, version, flags, checksum, counts against the bytes left, vertices,
 * levels, successors, beginnings, triangle counts) and throws SetsFormatError.
 */
export function decodeSets(data) {
    const bytes = data instanceof Uint8Array ? data : new Uint8Array(data);
    const r = new Reader(bytes, bytes.length);
    if (bytes.length < 52 || String.fromCharCode(...bytes.subarray(0, 8)) !== MAGIC) r.fail('not a .sets file (magic SKLODSET)');
    r.at = bytes.length - 4;
    const stored = r.u32('the checksum');
    if (crc32(bytes.subarray(0, bytes.length - 4)) !== stored) { r.at = bytes.length - 4; r.fail('the checksum does not match (a damaged or truncated file)'); }
    r.at = 8;
    r.end = bytes.length - 4;
    const version = r.u32('the version');
    const decode = DECODERS[version];
    if (!decode) { r.at -= 4; r.fail(`format version ${version} is not known (${Object.keys(DECODERS).join(', ')})`); }
    const flags = r.u32('the flags');
    if (flags & ~3) { r.at -= 4; r.fail(`unknown flags ${flags}`); }
    const h = { version, flags };
    for (const k of ['inputVertices', 'positions', 'levels', 'strips', 'slots', 'versions', 'beginnings', 'triangles0']) h[k] = r.u32(k);
    return decode(r, h);
}

/**
 * The strips of a decoded model at one level, kept up to date as the level moves:
 * `buffer` holds every strip at its fixed place (strip s from stripSlots[s] + s, its
 * level-0 length plus one), the rest of its place the restart index, so that the
 * whole buffer draws with one drawElements(TRIANGLE_STRIP). setLevel rewalks only the
 * strips that change between the two levels and returns their numbers.
 */
export class SetsCursor {
    constructor(sets, level = 0) {
        this.sets = sets;
        this.level = Math.min(level, sets.levels);
        const strips = sets.strips;
        this.buffer = new Uint32Array(sets.slots + strips).fill(SETS_RESTART);
        this.lengths = new Uint32Array(strips);
        this.validFrom = new Uint32Array(strips);
        this.validTo = new Float64Array(strips);
        this.changed = [];
        for (let s = 0; s < strips; s++) this.rewalk(s);
    }
    /** Buffer positions [start, end) of strip s's place. */
    stripRange(s) { return [this.sets.stripSlots[s] + s, this.sets.stripSlots[s + 1] + s + 1]; }
    /** Moves to `level`; returns the strips whose indices changed. */
    setLevel(level) {
        level = Math.min(Math.max(0, level | 0), this.sets.levels);
        this.level = level;
        const changed = [];
        for (let s = 0; s < this.lengths.length; s++) {
            if (level < this.validFrom[s] || level >= this.validTo[s]) { this.rewalk(s); changed.push(s); }
        }
        this.changed = changed;
        return changed;
    }
    /** Triangles the current level draws (the file's counts). */
    triangles() { return this.sets.triangleCount[this.level]; }
    rewalk(s) {
        const S = this.sets, level = this.level, buffer = this.buffer;
        const base = S.stripSlots[s] + s;
        let pos = base;
        let k = S.beginOffsets[s];
        while (k + 1 < S.beginOffsets[s + 1] && S.beginLevel[k + 1] <= level) k++;
        let x = S.beginSlot[k];
        while (x !== SETS_END) {
            const lo = S.versionOffsets[x];
            let i = S.versionOffsets[x + 1] - 1;
            while (i > lo && S.verLevel[i] > level) i--;
            buffer[pos++] = S.verLabel[i];
            x = S.verNext[i];
        }
        const old = this.lengths[s];
        if (pos - base < old) buffer.fill(SETS_RESTART, pos, base + old);
        this.lengths[s] = pos - base;
        const c0 = S.changeOffsets[s], c1 = S.changeOffsets[s + 1];
        let j = c0;
        while (j + 1 < c1 && S.changeLevel[j + 1] <= level) j++;
        this.validFrom[s] = S.changeLevel[j];
        this.validTo[s] = j + 1 < c1 ? S.changeLevel[j + 1] : Infinity;
    }
    /** The non-empty strips, each an array of vertices (as `stripkit lod extract`'s JSON). */
    strips() {
        const out = [];
        for (let s = 0; s < this.lengths.length; s++) {
            if (this.lengths[s] > 0) {
                const [a] = this.stripRange(s);
                out.push(Array.from(this.buffer.subarray(a, a + this.lengths[s])));
            }
        }
        return out;
    }
}

/** The first level with at most ceil(ratio x triangles0) triangles (as `--ratio`). */
export function levelForRatio(sets, ratio) {
    const want = Math.ceil(ratio * sets.triangles0);
    for (let l = 0; l <= sets.levels; l++) if (sets.triangleCount[l] <= want) return l;
    return sets.levels;
}

const SEQ_MAGIC = 'SKLODSEQ';

/**
 * The raw deflate stream `packed` inflated, at most `limit` bytes (more throws). Async:
 * DecompressionStream('deflate-raw'), in browsers and node 20.
 */
async function inflateRaw(packed, limit, r) {
    const chunks = [];
    let length = 0;
    try {
        const stream = new Blob([packed]).stream().pipeThrough(new DecompressionStream('deflate-raw'));
        for await (const chunk of stream) {
            length += chunk.length;
            if (length > limit) r.fail(`the positions inflate past the ${limit} bytes their counts allow`);
            chunks.push(chunk);
        }
    } catch (e) {
        if (e instanceof SetsFormatError) throw e;
        r.fail(`the positions do not inflate: ${e.message}`);
    }
    const raw = new Uint8Array(length);
    let at = 0;
    for (const c of chunks) { raw.set(c, at); at += c.length; }
    return raw;
}

/**
 * Quantized positions (`position_bits` 8 to 20): the grid, then the deflated zigzag
 * varints (the first frame against the previous vertex, each later frame against the
 * frame before), each coordinate `lo + q x step` in single precision as the library
 * computes it. Returns one Float32Array (3 per vertex) per frame.
 */
async function readQuantized(r, frames, vertices, bits) {
    const f = Math.fround;
    const grid = [];
    for (let i = 0; i < 6; i++) grid.push(r.f32('the position grid'));
    const lo = grid.slice(0, 3), step = grid.slice(3);
    if (!grid.every(Number.isFinite) || step.some((s) => s <= 0)) r.fail('the position grid is not finite and positive');
    const top = 2 ** bits - 1;
    const value = (q, d) => f(lo[d] + f(q * step[d]));
    for (let d = 0; d < 3; d++) if (!Number.isFinite(value(top, d))) r.fail(`the position grid's far corner is not finite (axis ${d})`);
    const len = r.varint("the positions' length");
    r.need(len, 'the positions');
    const packed = r.bytes.subarray(r.at, r.at + len);
    r.at += len;
    const total = frames * vertices;
    if (total * 12 > len * 64 + (1 << 20)) r.fail(`${frames} frames of ${vertices} vertices cannot come from ${len} bytes`);
    const raw = await inflateRaw(packed, total * 15, r);
    const v = new Reader(raw, raw.length, '.lodseq positions');
    const out = [];
    let prev = null;
    for (let fr = 0; fr < frames; fr++) {
        const cur = new Uint32Array(3 * vertices), pos = new Float32Array(3 * vertices);
        for (let i = 0; i < 3 * vertices; i++) {
            const base = fr > 0 ? prev[i] : i >= 3 ? cur[i - 3] : 0;
            const z = v.varint('a position');
            const x = base + (z % 2 === 0 ? z / 2 : -(z + 1) / 2);
            if (x < 0 || x > top) r.fail(`frame ${fr}: a position off its ${bits}-bit grid`);
            cur[i] = x;
            pos[i] = value(x, i % 3);
        }
        out.push(pos);
        prev = cur;
    }
    if (v.at !== raw.length) r.fail('bytes follow the last position');
    return out;
}

/**
 * Decodes a `.lodseq` file (an animation's level-of-detail strips, docs/sets-format.md),
 * versions 1 and 2, with the library's checks; throws SetsFormatError ('.lodseq byte N').
 * Async because quantized positions are deflated. Returns { version, frames, vertices,
 * names, frameModel (each frame's model), positions (a Float32Array per frame, 3 per
 * vertex, as the library decodes them), bits (0: exact), attributes (version 2: the
 * first frame's, shared), models (decoded positionless `.sets`, one strip layout) }.
 */
export async function decodeLodSeq(data) {
    const bytes = data instanceof Uint8Array ? data : new Uint8Array(data);
    const r = new Reader(bytes, bytes.length, '.lodseq');
    if (bytes.length < 32) r.fail(`${bytes.length} bytes is too short for a .lodseq file`);
    if (String.fromCharCode(...bytes.subarray(0, 8)) !== SEQ_MAGIC) r.fail('not a .lodseq file (magic SKLODSEQ)');
    r.at = bytes.length - 4;
    const stored = r.u32('the checksum');
    r.at = bytes.length - 4;
    if (crc32(bytes.subarray(0, bytes.length - 4)) !== stored) r.fail('the checksum does not match (a damaged or truncated file)');
    r.at = 8;
    r.end = bytes.length - 4;
    const version = r.u32('the version');
    if (version !== 1 && version !== 2) { r.at -= 4; r.fail(`format version ${version} is not known (1, 2)`); }
    const [frames, vertices, modelCount, bits] = ['frames', 'vertices', 'models', 'position bits'].map((k) => r.u32(k));
    if (frames === 0 || modelCount === 0) { r.at = 12; r.fail('a sequence needs at least one frame and one model'); }
    if (bits !== 0 && (bits < 8 || bits > 20)) { r.at = 24; r.fail(`${bits} bits per coordinate (0 for exact positions, else 8 to 20)`); }
    r.records(2 * frames, 'frame names');
    const names = [], frameModel = new Uint32Array(frames);
    for (let f = 0; f < frames; f++) {
        const len = r.varint("a frame name's length");
        if (len > 4096) r.fail(`a frame name of ${len} bytes (at most 4096)`);
        r.need(len, 'a frame name');
        names.push(new TextDecoder('utf-8').decode(bytes.subarray(r.at, r.at + len)));
        r.at += len;
        frameModel[f] = r.below(modelCount, "a frame's model");
    }
    let positions;
    if (bits === 0) {
        r.need(12 * frames * vertices, "the frames' positions");
        positions = [];
        for (let f = 0; f < frames; f++) {
            const p = new Float32Array(3 * vertices);
            for (let i = 0; i < p.length; i++) {
                p[i] = r.f32('a position');
                if (!Number.isFinite(p[i])) { r.at -= 4; r.fail(`frame ${f}: a NaN or infinite coordinate`); }
            }
            positions.push(p);
        }
    } else {
        positions = await readQuantized(r, frames, vertices, bits);
    }
    const attributes = version === 2 ? readAttributes(r, vertices, false) : [];
    r.records(modelCount, 'models');
    const models = [];
    for (let m = 0; m < modelCount; m++) {
        const len = r.varint("a model's length");
        r.need(len, 'a model');
        const at = r.at;
        let sets;
        try {
            sets = decodeSets(bytes.subarray(at, at + len));
        } catch (e) {
            if (e instanceof SetsFormatError) { r.at = at + e.at; r.fail(`model ${m}: ${e.message}`); }
            throw e;
        }
        r.at += len;
        const layout = models.length === 0 || sets.stripSlots.length === models[0].stripSlots.length && sets.stripSlots.every((x, i) => x === models[0].stripSlots[i]);
        if (sets.inputVertices !== vertices || !sets.positionless || sets.attributes.length > 0 || sets.optimal) {
            r.at = at;
            r.fail(`model ${m} is not a positionless endpoint model over ${vertices} vertices`);
        }
        if (!layout) { r.at = at; r.fail(`model ${m} lays its strips out unlike model 0`); }
        models.push(sets);
    }
    if (r.at !== r.end) r.fail(`${r.end - r.at} bytes follow the last model`);
    return { version, frames, vertices, names, frameModel, positions, bits, attributes, models };
}

/**
 * The strips of one (frame, level) of a decoded `.lodseq`, kept up to date as either
 * moves, like the library's SeqCursor: one `buffer` in the layout of SetsCursor (the
 * same for every model), a SetsCursor per model made when first needed. `set` returns
 * the strips whose place changed: a new level re-walks only the strips that change,
 * a frame with another model copies only the strips that differ. The level is clamped
 * to the frame's model (as `stripkit lod extract --frame F --level L`).
 */
export class LodSeqCursor {
    constructor(seq, frame = 0, level = 0) {
        this.seq = seq;
        const m0 = seq.models[0];
        this.buffer = new Uint32Array(m0.slots + m0.strips).fill(SETS_RESTART);
        this.cursors = seq.models.map(() => null);
        this.frame = -1;
        this.model = -1;
        this.changed = [];
        this.set(frame, level);
    }
    /** Buffer positions [start, end) of strip s's place. */
    stripRange(s) { return [this.seq.models[0].stripSlots[s] + s, this.seq.models[0].stripSlots[s + 1] + s + 1]; }
    /** The current frame's positions (a Float32Array, 3 per vertex). */
    positions() { return this.seq.positions[this.frame]; }
    /** The current frame's level (clamped to its model's levels). */
    get level() { return this.cursors[this.model].level; }
    /** Triangles the current frame and level draw. */
    triangles() { return this.cursors[this.model].triangles(); }
    /** Moves to frame `frame` (clamped) at `level`; returns the strips whose place changed. */
    set(frame, level) {
        const seq = this.seq;
        const f = Math.min(Math.max(0, frame | 0), seq.frames - 1), m = seq.frameModel[f];
        const fresh = this.cursors[m] === null;
        if (fresh) this.cursors[m] = new SetsCursor(seq.models[m], level);
        const cursor = this.cursors[m];
        const changed = [];
        const copy = (s) => { const [a, b] = this.stripRange(s); this.buffer.set(cursor.buffer.subarray(a, b), a); changed.push(s); };
        if (m === this.model && !fresh) {
            for (const s of cursor.setLevel(level)) copy(s);
        } else {
            if (!fresh) cursor.setLevel(level);
            for (let s = 0; s < cursor.lengths.length; s++) {
                const [a, b] = this.stripRange(s);
                let same = true;
                for (let i = a; i < b && same; i++) same = this.buffer[i] === cursor.buffer[i];
                if (!same) copy(s);
            }
            this.model = m;
        }
        this.frame = f;
        this.changed = changed;
        return changed;
    }
    /** The non-empty strips, each an array of vertices (as `stripkit lod extract`'s JSON). */
    strips() { return this.cursors[this.model].strips(); }
}
