// EXT_mesh_primitive_restart for gltf-transform (@gltf-transform/core 4).
//
// The extension (KhronosGroup glTF, extensions/2.0/Vendor/EXT_mesh_primitive_restart)
// sits on a mesh: `primitiveGroups`, each naming primitives of that mesh by position
// and one index accessor whose strips are separated by the restart value (the largest
// value of its component type). A viewer that knows it draws the group's accessor
// instead of those primitives; any other viewer draws the primitives (stripkit writes
// one stitched TRIANGLE_STRIP per group as that fallback).
//
// Without this module gltf-transform drops the groups on every read/write. With it a
// group is kept as a property of its mesh that refers to its primitives and its index
// accessor, so that pruning, merging or reordering accessors and primitives renumbers
// the group on write like any core reference. A transform that renumbers the
// primitives' vertices (reorder, weld: every index i of the fallback replaced by
// f(i)) is followed: before writing, a group whose primitives' indices changed one
// for one from those read gets f applied to its restart indices too. Then each group
// is checked: its primitives must still be in the mesh, share mode, attributes and
// material, have no morph targets, and its restart strips must draw exactly the
// triangles (winding included) that its primitives draw. A group that fails is left
// out with a warning rather than written stale.
//
//   import { NodeIO } from '@gltf-transform/core';
//   import { EXTMeshPrimitiveRestart } from 'gltf-transform-restart';
//   const io = new NodeIO().registerExtensions([EXTMeshPrimitiveRestart]);
//   await io.write('out.glb', await io.read('in.glb'));

import { Extension, ExtensionProperty, PropertyType, RefList } from '@gltf-transform/core';

/** The extension's name, as in `extensionsUsed` and `mesh.extensions`. */
export const EXT_MESH_PRIMITIVE_RESTART = 'EXT_mesh_primitive_restart';
const NAME = EXT_MESH_PRIMITIVE_RESTART;

/** The restart groups of one mesh (attached with `mesh.setExtension`). */
export class PrimitiveRestart extends ExtensionProperty {
    static EXTENSION_NAME = NAME;

    init() {
        this.extensionName = NAME;
        this.propertyType = 'PrimitiveRestart';
        this.parentTypes = [PropertyType.MESH];
    }

    getDefaults() {
        return Object.assign(super.getDefaults(), { groups: new RefList() });
    }

    /** The groups, in file order. */
    listGroups() {
        return this.listRefs('groups');
    }

    /** Appends `group`. */
    addGroup(group) {
        return this.addRef('groups', group);
    }

    /** Removes `group`. */
    removeGroup(group) {
        return this.removeRef('groups', group);
    }
}

/** One group: primitives of the mesh and the restart index accessor drawn instead. */
export class PrimitiveRestartGroup extends ExtensionProperty {
    static EXTENSION_NAME = NAME;

    init() {
        this.extensionName = NAME;
        this.propertyType = 'PrimitiveRestartGroup';
        this.parentTypes = ['PrimitiveRestart'];
    }

    getDefaults() {
        return Object.assign(super.getDefaults(), { indices: null, primitives: new RefList(), readIndices: null });
    }

    /** The primitives' indices (concatenated) when the group was read or last synced. */
    getReadIndices() {
        return this.get('readIndices');
    }

    /** Records the primitives' current indices as those the restart indices match. */
    setReadIndices(indices) {
        return this.set('readIndices', indices);
    }

    /** The index accessor holding the strips, separated by the restart value. */
    getIndices() {
        return this.getRef('indices');
    }

    /** Sets the index accessor (grouped with the other index data on write). */
    setIndices(accessor) {
        return this.setRef('indices', accessor, { usage: 'ELEMENT_ARRAY_BUFFER' });
    }

    /** The primitives this group draws, in file order. */
    listPrimitives() {
        return this.listRefs('primitives');
    }

    /** Adds a primitive of the mesh to the group. */
    addPrimitive(primitive) {
        return this.addRef('primitives', primitive);
    }
}

/** The extension: register it on an I/O (`registerExtensions([EXTMeshPrimitiveRestart])`). */
export class EXTMeshPrimitiveRestart extends Extension {
    static EXTENSION_NAME = NAME;
    extensionName = NAME;

    /** A new (detached) set of groups for a mesh. */
    createPrimitiveRestart() {
        return new PrimitiveRestart(this.document.getGraph());
    }

    /** A new (detached) group. */
    createPrimitiveRestartGroup() {
        return new PrimitiveRestartGroup(this.document.getGraph());
    }

    prewriteTypes = [PropertyType.ACCESSOR];

    /** Before the accessors are written: renumbered primitives renumber their groups. */
    prewrite() {
        for (const mesh of this.document.getRoot().listMeshes()) {
            const restart = mesh.getExtension(NAME);
            for (const group of restart ? restart.listGroups() : []) followRenumbering(group);
        }
        return this;
    }

    read(context) {
        const meshDefs = context.jsonDoc.json.meshes || [];
        meshDefs.forEach((meshDef, m) => {
            const def = meshDef.extensions && meshDef.extensions[NAME];
            if (!def) return;
            const mesh = context.meshes[m];
            const primitives = mesh.listPrimitives();
            const restart = this.createPrimitiveRestart();
            for (const groupDef of def.primitiveGroups || []) {
                const group = this.createPrimitiveRestartGroup();
                const accessor = context.accessors[groupDef.indices];
                if (accessor) group.setIndices(accessor);
                for (const p of groupDef.primitives || []) {
                    if (primitives[p]) group.addPrimitive(primitives[p]);
                }
                group.setReadIndices(memberIndices(group));
                restart.addGroup(group);
            }
            mesh.setExtension(NAME, restart);
        });
        return this;
    }

    write(context) {
        const json = context.jsonDoc.json;
        for (const mesh of this.document.getRoot().listMeshes()) {
            const restart = mesh.getExtension(NAME);
            const meshIndex = context.meshIndexMap.get(mesh);
            if (!restart || meshIndex === undefined) continue;
            const primitives = mesh.listPrimitives();
            const groupDefs = [];
            for (const group of restart.listGroups()) {
                const problem = groupProblem(group, primitives);
                if (problem) {
                    context.logger.warn(`${NAME}: mesh ${meshIndex}: restart group left out: ${problem}`);
                    continue;
                }
                groupDefs.push({
                    primitives: group.listPrimitives().map((p) => primitives.indexOf(p)),
                    indices: context.accessorIndexMap.get(group.getIndices()),
                });
            }
            if (groupDefs.length === 0) continue;
            const meshDef = json.meshes[meshIndex];
            meshDef.extensions = meshDef.extensions || {};
            meshDef.extensions[NAME] = { primitiveGroups: groupDefs };
        }
        return this;
    }
}

/** Why `group` cannot be written as it stands, or null when it can. */
export function groupProblem(group, meshPrimitives) {
    const indices = group.getIndices();
    const members = group.listPrimitives();
    if (!indices) return 'it has no index accessor';
    if (members.length === 0) return 'it names no primitive';
    if (members.some((p) => !meshPrimitives.includes(p))) return 'a primitive it names is no longer in the mesh';
    const first = members[0];
    for (const p of members) {
        if (p.listTargets().length > 0) return 'a primitive has morph targets (the extension forbids them)';
        if (p.getMode() !== first.getMode()) return 'its primitives differ in mode';
        if (p.getMaterial() !== first.getMaterial()) return 'its primitives differ in material';
        const semantics = p.listSemantics();
        if (semantics.length !== first.listSemantics().length
            || semantics.some((s) => p.getAttribute(s) !== first.getAttribute(s))) {
            return 'its primitives differ in vertex attributes';
        }
    }
    const mode = first.getMode();
    if (mode !== 4 && mode !== 5) return null; // only triangle lists and strips are compared
    const restartValue = RESTART_VALUE[indices.getComponentType()];
    if (restartValue === undefined) return 'its index accessor is not of an unsigned integer type';
    const drawn = new Map();
    for (const p of members) {
        const own = p.getIndices();
        const list = own ? own.getArray() : sequence(p.getAttribute('POSITION').getCount());
        countTriangles(drawn, list, mode, undefined, 1);
    }
    countTriangles(drawn, indices.getArray(), mode, restartValue, -1);
    for (const n of drawn.values()) {
        if (n !== 0) return 'its restart strips no longer draw the triangles of its primitives (a transform changed their vertices or indices)';
    }
    return null;
}

/** The group's primitives' indices, concatenated (a primitive without indices counts
 * as 0, 1, ..., n - 1), or null when a primitive has no POSITION. */
function memberIndices(group) {
    const out = [];
    for (const p of group.listPrimitives()) {
        const own = p.getIndices();
        const position = p.getAttribute('POSITION');
        if (!own && !position) return null;
        out.push(...(own ? own.getArray() : sequence(position.getCount())));
    }
    return out;
}

/** Applies to the group's restart indices the renumbering its primitives' indices went
 * through since they were read: where index k was v and is now w, every v becomes w.
 * Nothing changes when the indices are as read, or when they changed in any other way
 * (another count, one v given two w's, a restart index without an image). */
export function followRenumbering(group) {
    const before = group.getReadIndices();
    const now = memberIndices(group);
    const accessor = group.getIndices();
    if (!before || !now || !accessor || before.length !== now.length) return false;
    const image = new Map();
    let changed = false;
    for (let k = 0; k < before.length; k++) {
        const seen = image.get(before[k]);
        if (seen !== undefined && seen !== now[k]) return false;
        image.set(before[k], now[k]);
        changed = changed || before[k] !== now[k];
    }
    if (!changed) return false;
    const restartValue = RESTART_VALUE[accessor.getComponentType()];
    const old = accessor.getArray();
    const renumbered = new old.constructor(old.length);
    for (let k = 0; k < old.length; k++) {
        const w = old[k] === restartValue ? restartValue : image.get(old[k]);
        if (w === undefined || (old[k] !== restartValue && w === restartValue)) return false;
        renumbered[k] = w;
    }
    accessor.setArray(renumbered);
    group.setReadIndices(now);
    return true;
}

/** The restart value of each index component type: its largest value. */
const RESTART_VALUE = { 5121: 0xff, 5123: 0xffff, 5125: 0xffffffff };

function sequence(n) {
    return Uint32Array.from({ length: n }, (_, i) => i);
}

/** Adds `sign` to the count of every non-degenerate triangle `list` draws in `mode`
 * (4 list, 5 strip), split at `restartValue` when given; a triangle is keyed by its
 * corners rotated to start at the smallest, so winding counts. */
function countTriangles(counts, list, mode, restartValue, sign) {
    const add = (a, b, c) => {
        if (a === b || b === c || a === c) return;
        const key = a < b && a < c ? `${a},${b},${c}` : b < c ? `${b},${c},${a}` : `${c},${a},${b}`;
        counts.set(key, (counts.get(key) || 0) + sign);
    };
    let start = 0;
    for (let end = 0; end <= list.length; end++) {
        if (end < list.length && list[end] !== restartValue) continue;
        if (mode === 4) {
            for (let i = start; i + 2 < end; i += 3) add(list[i], list[i + 1], list[i + 2]);
        } else {
            for (let i = start; i + 2 < end; i++) {
                if ((i - start) % 2 === 0) add(list[i], list[i + 1], list[i + 2]);
                else add(list[i + 1], list[i], list[i + 2]);
            }
        }
        start = end + 1;
    }
}
