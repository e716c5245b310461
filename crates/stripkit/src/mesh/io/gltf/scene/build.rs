//! Writing a [`Scene`]: [`Build`] merges the buffers, appends the stripped primitives'
//! reordered vertex data and indices, sets their restart groups and describes the one
//! buffer. The document model and its reading are in the parent.

use super::*;

/// A document being written by [`Scene::build`]: its JSON and its one binary buffer,
/// each step of the build one method.
pub(super) struct Build<'s> {
    scene: &'s Scene,
    garbage: Garbage,
    /// The scene's buffers and views with its held-out views' bytes made again.
    pub(super) buffers: Vec<Buffer>,
    pub(super) views: Vec<View>,
    json: Value,
    bin: Vec<u8>,
    /// Dead views' numbers, which new views take first.
    free_views: VecDeque<usize>,
}

impl<'s> Build<'s> {
    pub(super) fn new(scene: &'s Scene) -> Build<'s> {
        let garbage = scene.garbage();
        let free_views = garbage.dead_views.iter().copied().collect();
        let whole = (!garbage.collect && !scene.held.is_empty()).then_some(scene.made_views.as_slice());
        let (buffers, views) = if scene.held.is_empty() {
            (scene.buffers.clone(), scene.views.clone())
        } else {
            super::super::held::restore(
                &scene.buffers,
                &scene.views,
                &scene.held,
                &scene.primitives,
                &garbage.dead_views,
                whole,
            )
        };
        Build { scene, garbage, buffers, views, json: scene.json.clone(), bin: Vec::new(), free_views }
    }

    /// Merges the buffers into `bin`, rewriting the views' `buffer` and `byteOffset`:
    /// when garbage is collected each live view's bytes one after the other (the old
    /// index data of stripped primitives, and bytes no view covers, are left out),
    /// else every old buffer whole.
    pub(super) fn merge_buffers(&mut self) {
        let collect = self.garbage.collect;
        let (buffers, scene_views) = (&self.buffers, &self.views);
        // The offsets the JSON names: a held view's bytes are made again at offset 0 of
        // a buffer of their own, while its JSON keeps the offset it was made at.
        let named = if self.scene.held.is_empty() { &self.scene.views } else { &self.scene.made_views };
        let bin = &mut self.bin;
        // Where each old buffer starts in `bin`, when they are copied whole.
        let mut base = Vec::new();
        if !collect {
            for b in buffers {
                pad4(bin);
                base.push(bin.len());
                bin.extend_from_slice(b);
            }
        }
        let Some(Value::Array(views)) = self.json.get_mut("bufferViews") else { return };
        for (k, (v, view)) in views.iter_mut().zip(scene_views).enumerate() {
            let offset = if collect {
                if self.garbage.dead_views.binary_search(&k).is_ok() {
                    continue;
                }
                pad4(bin);
                let offset = bin.len();
                bin.extend_from_slice(&buffers[view.buffer][view.offset..view.offset + view.length]);
                offset
            } else {
                base[view.buffer] + view.offset
            };
            v["buffer"] = 0.into();
            if offset != named[k].offset {
                v["byteOffset"] = offset.into();
            }
        }
    }

    /// The accessor list of the document being written.
    fn accessors(&mut self) -> &mut Vec<Value> {
        if !self.json["accessors"].is_array() {
            self.json["accessors"] = json!([]);
        }
        self.json["accessors"].as_array_mut().expect("made an array above")
    }

    /// Adds `view` to the document, at a dead view's number where there is one.
    fn add_view(&mut self, view: Value) -> usize {
        match self.free_views.pop_front() {
            Some(v) => {
                self.json["bufferViews"][v] = view;
                v
            }
            None => push_array(&mut self.json, "bufferViews", view),
        }
    }

    /// Writes the vertex data of `sp` (its attributes and morph targets) gathered in
    /// `order` to new views and accessors (`min` / `max` recomputed; an accessor only
    /// this primitive used keeps its number), points the primitive at them, and returns
    /// its strips in the new vertex ids.
    pub(super) fn write_reordered(&mut self, doc: &Doc, sp: &ScenePrimitive, order: &[u32]) -> Result<StripSet> {
        for (target, name, a) in vertex_accessors(&self.scene.json, sp) {
            let (acc, data) = doc.read_packed(a, &mut |_| Ok(()))?;
            let elem = acc.component_size() * acc.components;
            let stride = elem.next_multiple_of(4);
            pad4(&mut self.bin);
            let start = self.bin.len();
            for &v in order {
                self.bin.extend_from_slice(&data[v as usize * elem..][..elem]);
                self.bin.resize(self.bin.len() + stride - elem, 0);
            }
            let mut view =
                json!({"buffer": 0, "byteOffset": start, "byteLength": self.bin.len() - start, "target": 34962});
            if stride != elem {
                view["byteStride"] = stride.into();
            }
            let view = self.add_view(view);
            let reuse = self.garbage.reused.binary_search(&a).is_ok();
            let list = self.accessors();
            let mut new = list[a].clone();
            if let Some(o) = new.as_object_mut() {
                o.remove("byteOffset");
                o.remove("sparse");
            }
            new["bufferView"] = view.into();
            new["count"] = order.len().into();
            if new.get("min").is_some() || new.get("max").is_some() {
                let (lo, hi) = bounds(&acc, &data, order);
                new["min"] = lo;
                new["max"] = hi;
            }
            let k = if reuse {
                list[a] = new;
                a
            } else {
                list.push(new);
                list.len() - 1
            };
            let prim = &mut self.json["meshes"][sp.mesh_index]["primitives"][sp.primitive_index];
            match target {
                None => prim["attributes"][name.as_str()] = k.into(),
                Some(t) => prim["targets"][t][name.as_str()] = k.into(),
            }
        }
        let new_id = ids_of(order, sp.mesh.vertex_count());
        let set = sp.strips.as_ref().expect("only stripped primitives are written");
        // The same strips renamed in place of a list of lists (one allocation per strip).
        Ok(StripSet {
            indices: set.indices.iter().map(|&v| new_id[v as usize]).collect(),
            offsets: set.offsets.clone(),
        })
    }

    /// Writes every stripped primitive's stitched indices (mode 5, taking its old index
    /// accessor's number where garbage is collected) and, where it gets one, its
    /// restart list, all in one new view (at a dead view's number where there is one;
    /// the other dead views keep their numbers over it). `remapped`: each primitive's
    /// strips in its new vertex ids, if reordered. Returns the restart groups to add as
    /// (mesh, primitive, restart accessor).
    pub(super) fn write_indices(&mut self, stripped: &[&ScenePrimitive], remapped: &[Option<StripSet>]) -> Vec<[usize; 3]> {
        pad4(&mut self.bin);
        let view_start = self.bin.len();
        let view = match self.free_views.pop_front() {
            Some(v) => v,
            None => push_array(&mut self.json, "bufferViews", Value::Null),
        };
        let mut groups = Vec::new();
        // Room for every index at once (stitching adds at most 3 per strip, restart 1),
        // so that the binary is not grown by doubling while they are appended.
        let room: usize = (stripped.iter().zip(remapped))
            .map(|(sp, remapped)| {
                let set = remapped.as_ref().or(sp.strips.as_ref()).expect("only stripped primitives are written");
                let vertices = sp.order.as_ref().map_or(sp.mesh.vertex_count(), Vec::len);
                let copies = if self.scene.restart_groups && sp.targets == 0 { 2 } else { 1 };
                copies * (set.indices.len() + 3 * set.len() + 2) * if vertices >= u16::MAX as usize { 4 } else { 2 }
            })
            .sum();
        self.bin.reserve(room);
        for (sp, remapped) in stripped.iter().zip(remapped) {
            let set = remapped.as_ref().or(sp.strips.as_ref()).expect("only stripped primitives are written");
            // 65535 is the u16 restart value, never a vertex id.
            let vertices = sp.order.as_ref().map_or(sp.mesh.vertex_count(), Vec::len);
            let wide = vertices >= u16::MAX as usize;
            let old = self.scene.json["meshes"][sp.mesh_index]["primitives"][sp.primitive_index]["indices"].as_u64();
            let slot = old.map(|a| a as usize).filter(|a| self.garbage.reused.binary_search(a).is_ok());
            let at = IndexView { view, start: view_start, wide };
            let stitched = self.add_indices(at, &strip::encode_stitched(set), slot);
            let prim = &mut self.json["meshes"][sp.mesh_index]["primitives"][sp.primitive_index];
            prim["indices"] = stitched.into();
            prim["mode"] = 5.into();
            if self.scene.restart_groups && sp.targets == 0 {
                let restart = if wide { u32::MAX } else { u16::MAX as u32 };
                // Strips of fewer than 3 indices draw nothing and are left out (a copy
                // of the set only where there are any).
                let short = set.iter().any(|s| s.len() < 3);
                let list =
                    short.then(|| StripSet::from_strips(&set.iter().filter(|s| s.len() >= 3).collect::<Vec<_>>()));
                let acc = self.add_indices(at, &strip::encode_restart(list.as_ref().unwrap_or(set), restart), None);
                groups.push([sp.mesh_index, sp.primitive_index, acc]);
            }
        }
        let new_view = json!({
            "buffer": 0, "byteOffset": view_start, "byteLength": self.bin.len() - view_start, "target": 34963,
        });
        // Other dead views keep their numbers, over the new indices (nothing uses them).
        for &v in &self.free_views {
            self.json["bufferViews"][v] = new_view.clone();
        }
        self.json["bufferViews"][view] = new_view;
        groups
    }

    /// Appends `indices` to the index view `at` and returns their accessor: `slot`, an
    /// old index accessor to replace (its name kept), else a new one.
    fn add_indices(&mut self, at: IndexView, indices: &[u32], slot: Option<usize>) -> usize {
        pad4(&mut self.bin);
        let offset = self.bin.len() - at.start;
        for &i in indices {
            if at.wide {
                self.bin.extend_from_slice(&i.to_le_bytes());
            } else {
                self.bin.extend_from_slice(&(i as u16).to_le_bytes());
            }
        }
        let mut acc = json!({
            "bufferView": at.view, "byteOffset": offset, "componentType": if at.wide { 5125 } else { 5123 },
            "count": indices.len(), "type": "SCALAR",
        });
        let list = self.accessors();
        match slot {
            Some(k) => {
                if let Some(name) = list[k].get("name") {
                    acc["name"] = name.clone();
                }
                list[k] = acc;
                k
            }
            None => {
                list.push(acc);
                list.len() - 1
            }
        }
    }

    /// Sets the restart groups of every mesh with a stripped primitive: `groups`
    /// (mesh, primitive, accessor) added, old groups naming a rewritten primitive
    /// dropped (they would draw stale indices), the extension object removed when no
    /// group is left.
    pub(super) fn write_restart_groups(&mut self, stripped: &[&ScenePrimitive], groups: &[[usize; 3]]) {
        // Per mesh: its rewritten primitives (sorted) and its new groups, gathered in
        // one pass (a scan per mesh was quadratic in primitives over many meshes).
        let mut meshes: BTreeMap<usize, (Vec<usize>, Vec<[usize; 3]>)> = BTreeMap::new();
        for p in stripped {
            meshes.entry(p.mesh_index).or_default().0.push(p.primitive_index);
        }
        for &g in groups {
            meshes.entry(g[0]).or_default().1.push(g);
        }
        for (m, (mut rewritten, new_groups)) in meshes {
            rewritten.sort_unstable();
            let mesh = &mut self.json["meshes"][m];
            let mut kept: Vec<Value> = mesh
                .pointer(&format!("/extensions/{RESTART_EXTENSION}/primitiveGroups"))
                .and_then(Value::as_array)
                .map(|g| {
                    g.iter()
                        .filter(|g| {
                            !g.get("primitives").and_then(Value::as_array).is_some_and(|ps| {
                                ps.iter().any(|p| {
                                    p.as_u64().is_some_and(|p| rewritten.binary_search(&(p as usize)).is_ok())
                                })
                            })
                        })
                        .cloned()
                        .collect()
                })
                .unwrap_or_default();
            for [_, p, acc] in new_groups {
                kept.push(json!({"primitives": [p], "indices": acc}));
            }
            let has_ext = mesh.pointer(&format!("/extensions/{RESTART_EXTENSION}")).is_some();
            if kept.is_empty() {
                if has_ext {
                    if let Some(Value::Object(ext)) = mesh.get_mut("extensions") {
                        ext.remove(RESTART_EXTENSION);
                        if ext.is_empty() {
                            mesh.as_object_mut().expect("a mesh is an object").remove("extensions");
                        }
                    }
                }
            } else {
                if !mesh.get("extensions").is_some_and(Value::is_object) {
                    mesh["extensions"] = json!({});
                }
                mesh["extensions"][RESTART_EXTENSION] = json!({"primitiveGroups": kept});
            }
        }
    }

    /// Lists the restart extension in `extensionsUsed` exactly when a mesh uses it. An
    /// input's listing (in `extensionsRequired` too) goes when no mesh uses it any more,
    /// and a list left empty goes with it (the validator refuses an empty one).
    pub(super) fn list_restart_extension(&mut self) {
        let json = &mut self.json;
        let used = json
            .get("meshes")
            .and_then(Value::as_array)
            .is_some_and(|ms| ms.iter().any(|m| m.pointer(&format!("/extensions/{RESTART_EXTENSION}")).is_some()));
        let listed = json
            .get("extensionsUsed")
            .and_then(Value::as_array)
            .is_some_and(|l| l.iter().any(|e| e == RESTART_EXTENSION));
        if used && !listed {
            push_array(json, "extensionsUsed", RESTART_EXTENSION.into());
        } else if !used && listed {
            for key in ["extensionsUsed", "extensionsRequired"] {
                if let Some(Value::Array(l)) = json.get_mut(key) {
                    l.retain(|e| e != RESTART_EXTENSION);
                    if l.is_empty() {
                        json.as_object_mut().map(|o| o.remove(key));
                    }
                }
            }
        }
    }

    /// Leaves `EXT_meshopt_compression` out of the document: its views were decoded on
    /// reading and their bytes are written plain, so their extension objects (and an
    /// `extensions` left empty), and the extension's entries in `extensionsUsed` and
    /// `extensionsRequired` (and a list left empty), go.
    pub(super) fn drop_meshopt(&mut self) {
        let strip = |v: &mut Value| {
            if let Some(Value::Object(ext)) = v.get_mut("extensions") {
                ext.remove(MESHOPT_EXTENSION);
                if ext.is_empty() {
                    v.as_object_mut().map(|o| o.remove("extensions"));
                }
            }
        };
        if let Some(Value::Array(views)) = self.json.get_mut("bufferViews") {
            views.iter_mut().for_each(strip);
        }
        for key in ["extensionsUsed", "extensionsRequired"] {
            if let Some(Value::Array(l)) = self.json.get_mut(key) {
                l.retain(|e| e != MESHOPT_EXTENSION);
                if l.is_empty() {
                    self.json.as_object_mut().map(|o| o.remove(key));
                }
            }
        }
    }

    /// The JSON with its one buffer described (the first buffer's other properties
    /// kept, its `uri` left for the container to set), and the buffer's bytes.
    pub(super) fn finish(mut self) -> (Value, Vec<u8>) {
        if self.bin.is_empty() && self.buffers.is_empty() {
            return (self.json, self.bin);
        }
        let mut buffer = match self.scene.json.pointer("/buffers/0") {
            Some(Value::Object(b)) => b.clone(),
            _ => serde_json::Map::new(),
        };
        buffer.remove("uri");
        if let Some(Value::Object(ext)) = buffer.get_mut("extensions") {
            ext.remove(MESHOPT_EXTENSION);
            if ext.is_empty() {
                buffer.remove("extensions");
            }
        }
        pad4(&mut self.bin);
        buffer.insert("byteLength".into(), self.bin.len().into());
        self.json["buffers"] = json!([buffer]);
        (self.json, self.bin)
    }
}

/// Where [`Build::add_indices`] appends: the new index view, its start in the buffer,
/// and the index width (`u32` when wide, else `u16`).
#[derive(Clone, Copy)]
struct IndexView {
    view: usize,
    start: usize,
    wide: bool,
}

/// Pads to a multiple of 4 bytes.
fn pad4(bin: &mut Vec<u8>) {
    bin.resize(bin.len().next_multiple_of(4), 0);
}

/// Appends `value` to the array `key` of `json` (made if absent) and returns its index.
fn push_array(json: &mut Value, key: &str, value: Value) -> usize {
    if !json.get(key).is_some_and(Value::is_array) {
        json[key] = json!([]);
    }
    let list = json[key].as_array_mut().expect("made an array above");
    list.push(value);
    list.len() - 1
}
