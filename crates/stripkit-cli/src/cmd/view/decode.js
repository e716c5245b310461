// The model's decoding: the JSON block's base64 buffers, or the `.sets` / `.lodseq`
// file decoded by the runtime, into the strips' places (a mesh's strips laid out as a
// cursor lays out a level: strip s at [places[s] + s, places[s + 1] + s + 1)).

/** The restart index, always on in WebGL2; also the label of an unused place. */
const RESTART = 0xffffffff;

/** The bytes of a base64 string, as an ArrayBuffer. */
function bytes(b64) {
    const s = atob(b64), out = new Uint8Array(s.length);
    for (let i = 0; i < s.length; i++) out[i] = s.charCodeAt(i);
    return out.buffer;
}

/**
 * The page's view of `model`: `sets` / `seq` and their `cursor` (or null), the scaled
 * `positions`, `uv` (or null), the strips' `places`, the place `labels` (vertex or
 * RESTART), `strips` and `n` (labels). A `.lodseq` opens at `model.frame`; its frames
 * share one strip layout, and positions change with the frame.
 */
async function decodeModel(model) {
    const v = { model, sets: null, seq: null, cursor: null, uv: null };
    v.scaled = (p) => p.map((x) => x * model.scale);
    if (model.lodseq) {
        v.seq = await decodeLodSeq(bytes(model.lodseq));
        v.cursor = new LodSeqCursor(v.seq, model.frame || 0, 0);
        v.positions = v.scaled(v.cursor.positions());
        v.places = v.seq.models[0].stripSlots;
        v.labels = v.cursor.buffer;
    } else if (model.sets) {
        v.sets = decodeSets(bytes(model.sets));
        v.cursor = new SetsCursor(v.sets, 0);
        v.positions = v.sets.positions.map((x) => x * model.scale);
        v.places = v.sets.stripSlots;
        v.labels = v.cursor.buffer;
    } else {
        v.positions = new Float32Array(bytes(model.positions));
        v.uv = model.uv ? new Float32Array(bytes(model.uv)) : null;
        const lengths = new Uint32Array(bytes(model.lengths));
        const places = new Uint32Array(lengths.length + 1);
        for (let s = 0; s < lengths.length; s++) places[s + 1] = places[s] + lengths[s];
        const labels = new Uint32Array(places[lengths.length] + lengths.length).fill(RESTART);
        const indices = new Uint32Array(bytes(model.strip_indices));
        for (let s = 0; s < lengths.length; s++) labels.set(indices.subarray(places[s], places[s + 1]), places[s] + s);
        v.places = places;
        v.labels = labels;
    }
    v.strips = v.places.length - 1;
    v.n = v.labels.length;
    return v;
}

/** Strip s's place [start, end) in the labels. */
function placeOf(v, s) { return [v.places[s] + s, v.places[s + 1] + s + 1]; }
