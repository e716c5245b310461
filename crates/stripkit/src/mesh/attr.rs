//! Vertex attributes and face groups: what a real asset carries besides positions.
//!
//! An [`Attribute`] holds one value per vertex (`components` scalars of one
//! [`Scalar`] type), stored as the file gave it, little-endian, so that a value read and
//! written back is the same bytes. Names follow glTF's semantics where the data has one
//! (`NORMAL`, `TANGENT`, `TEXCOORD_n`, `COLOR_n`, `JOINTS_n`, `WEIGHTS_n`); other data
//! keeps the file's own name (a PLY property such as `quality`).
//!
//! A [`Group`] is a set of faces drawn with one material (an OBJ `usemtl`/`g` run, a
//! glTF primitive, ...). `Mesh::face_groups` gives each face its group; strips never
//! cross from one group to another.
//!
//! Vertices are GPU vertices: a position with one value of every attribute. Readers of
//! formats that index attributes per corner (OBJ's `v/vt/vn`) weld corners into one
//! vertex only where every attribute agrees, so a seam gives two vertices.

use crate::error::{Error, Result};

/// The scalar type of an attribute's components.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Scalar {
    /// `i8` (PLY `char`, glTF `BYTE`).
    I8,
    /// `u8` (PLY `uchar`, glTF `UNSIGNED_BYTE`).
    U8,
    /// `i16` (PLY `short`, glTF `SHORT`).
    I16,
    /// `u16` (PLY `ushort`, glTF `UNSIGNED_SHORT`).
    U16,
    /// `i32` (PLY `int`).
    I32,
    /// `u32` (PLY `uint`, glTF `UNSIGNED_INT`).
    U32,
    /// `f32` (PLY `float`, glTF `FLOAT`).
    F32,
    /// `f64` (PLY `double`).
    F64,
}

impl Scalar {
    /// Bytes per component.
    pub fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    /// True for `F32` and `F64`.
    pub fn is_float(self) -> bool {
        matches!(self, Scalar::F32 | Scalar::F64)
    }

    /// The largest magnitude of an integer type (what a normalized value divides by).
    fn max(self) -> f64 {
        match self {
            Scalar::I8 => 127.0,
            Scalar::U8 => 255.0,
            Scalar::I16 => 32767.0,
            Scalar::U16 => 65535.0,
            Scalar::I32 => i32::MAX as f64,
            Scalar::U32 => u32::MAX as f64,
            Scalar::F32 | Scalar::F64 => 1.0,
        }
    }

    fn decode(self, b: &[u8]) -> f64 {
        match self {
            Scalar::I8 => b[0] as i8 as f64,
            Scalar::U8 => b[0] as f64,
            Scalar::I16 => i16::from_le_bytes([b[0], b[1]]) as f64,
            Scalar::U16 => u16::from_le_bytes([b[0], b[1]]) as f64,
            Scalar::I32 => i32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            Scalar::U32 => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            Scalar::F32 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            Scalar::F64 => f64::from_le_bytes(b[..8].try_into().unwrap_or([0; 8])),
        }
    }

    /// Writes `x` rounded to the nearest value of this type (clamped to its range).
    fn encode(self, x: f64, b: &mut [u8]) {
        let int = |lo: f64, hi: f64| x.round().clamp(lo, hi);
        match self {
            Scalar::I8 => b[0] = int(-128.0, 127.0) as i8 as u8,
            Scalar::U8 => b[0] = int(0.0, 255.0) as u8,
            Scalar::I16 => b[..2].copy_from_slice(&(int(-32768.0, 32767.0) as i16).to_le_bytes()),
            Scalar::U16 => b[..2].copy_from_slice(&(int(0.0, 65535.0) as u16).to_le_bytes()),
            Scalar::I32 => b[..4].copy_from_slice(&(int(i32::MIN as f64, i32::MAX as f64) as i32).to_le_bytes()),
            Scalar::U32 => b[..4].copy_from_slice(&(int(0.0, u32::MAX as f64) as u32).to_le_bytes()),
            Scalar::F32 => b[..4].copy_from_slice(&(x as f32).to_le_bytes()),
            Scalar::F64 => b[..8].copy_from_slice(&x.to_le_bytes()),
        }
    }
}

/// One named per-vertex attribute.
#[derive(Clone, Debug, PartialEq)]
pub struct Attribute {
    /// glTF semantic (`NORMAL`, `TEXCOORD_0`, ...) or the file's own name.
    pub name: String,
    /// Scalar type of each component.
    pub scalar: Scalar,
    /// Components per vertex (1 to 4 for the formats read here).
    pub components: u8,
    /// Integer values stand for `[0, 1]` (unsigned) or `[-1, 1]` (signed), as glTF's
    /// `normalized`. [`Attribute::get`] returns the stored number either way.
    pub normalized: bool,
    /// `vertex_count * components * scalar.size()` bytes, little-endian, vertex after vertex.
    pub data: Vec<u8>,
}

impl Attribute {
    /// An `f32` attribute from flat values (`values.len()` a multiple of `components`).
    pub fn from_f32(name: impl Into<String>, components: u8, values: &[f32]) -> Self {
        let data = values.iter().flat_map(|x| x.to_le_bytes()).collect();
        Attribute { name: name.into(), scalar: Scalar::F32, components, normalized: false, data }
    }

    /// An empty attribute of this name and type, with room for `vertices` vertices.
    pub fn empty_like(&self, vertices: usize) -> Self {
        Attribute {
            name: self.name.clone(),
            scalar: self.scalar,
            components: self.components,
            normalized: self.normalized,
            data: Vec::with_capacity(vertices.saturating_mul(self.stride())),
        }
    }

    /// Bytes per vertex.
    pub fn stride(&self) -> usize {
        self.components as usize * self.scalar.size()
    }

    /// Number of vertices the data holds (whole vertices only).
    pub fn len(&self) -> usize {
        self.data.len().checked_div(self.stride()).unwrap_or(0)
    }

    /// True when no vertex is stored.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The bytes of vertex `v`.
    pub fn bytes(&self, v: usize) -> &[u8] {
        let s = self.stride();
        &self.data[v * s..(v + 1) * s]
    }

    /// Component `c` of vertex `v` as stored (not scaled by `normalized`).
    pub fn get(&self, v: usize, c: usize) -> f64 {
        let k = self.scalar.size();
        let at = v * self.stride() + c * k;
        self.scalar.decode(&self.data[at..at + k])
    }

    /// Vertex `v`'s components as `f64`, as stored.
    pub fn value(&self, v: usize) -> Vec<f64> {
        (0..self.components as usize).map(|c| self.get(v, c)).collect()
    }

    /// Sets component `c` of vertex `v`, rounded to the type.
    pub fn set(&mut self, v: usize, c: usize, x: f64) {
        let k = self.scalar.size();
        let at = v * self.stride() + c * k;
        self.scalar.encode(x, &mut self.data[at..at + k]);
    }

    /// Appends vertex `v` of `other` (an attribute of the same type) unchanged.
    pub fn push_from(&mut self, other: &Attribute, v: usize) {
        self.data.extend_from_slice(other.bytes(v));
    }

    /// Appends a copy of this attribute's vertex `v`.
    pub fn push_from_self(&mut self, v: usize) {
        let s = self.stride();
        self.data.extend_from_within(v * s..(v + 1) * s);
    }

    /// Appends the blend `(1 - t) * a + t * b` of vertices `a` and `b` of this
    /// attribute. Floats and normalized integers are interpolated; other integers
    /// (joint indices, ids) cannot be, so the nearer vertex's value is copied.
    pub fn push_lerp(&mut self, a: usize, b: usize, t: f64) {
        if !(self.scalar.is_float() || self.normalized) {
            let src = if t <= 0.5 { a } else { b };
            let s = self.stride();
            self.data.extend_from_within(src * s..(src + 1) * s);
            return;
        }
        let v = self.len();
        self.data.resize(self.data.len() + self.stride(), 0);
        for c in 0..self.components as usize {
            let x = (1.0 - t) * self.get(a, c) + t * self.get(b, c);
            self.set(v, c, x);
        }
    }

    /// Appends a weighted sum of vertices (weights summing to 1), with the same rule
    /// for integers as [`Attribute::push_lerp`] (the heaviest vertex's value).
    pub fn push_blend(&mut self, parts: &[(usize, f64)]) {
        if parts.is_empty() {
            self.data.resize(self.data.len() + self.stride(), 0);
            return;
        }
        if !(self.scalar.is_float() || self.normalized) {
            let mut best = parts[0];
            for &p in parts {
                if p.1 > best.1 {
                    best = p;
                }
            }
            let s = self.stride();
            self.data.extend_from_within(best.0 * s..(best.0 + 1) * s);
            return;
        }
        let v = self.len();
        self.data.resize(self.data.len() + self.stride(), 0);
        for c in 0..self.components as usize {
            let x: f64 = parts.iter().map(|&(u, w)| w * self.get(u, c)).sum();
            self.set(v, c, x);
        }
    }

    /// The attribute of the vertices `map[0], map[1], ...` (a renumbering or a subset).
    pub fn gather(&self, map: &[u32]) -> Attribute {
        let mut out = self.empty_like(map.len());
        for &v in map {
            out.push_from(self, v as usize);
        }
        out
    }

    /// Largest normalized magnitude: what one unit of a normalized value is worth.
    pub fn unit(&self) -> f64 {
        if self.normalized {
            1.0 / self.scalar.max()
        } else {
            1.0
        }
    }
}

/// A set of faces drawn with one material.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Group {
    /// The group's name (OBJ `g`/`o`, glTF mesh and primitive), may be empty.
    pub name: String,
    /// The material's name (OBJ `usemtl`, glTF material index as text), if any.
    pub material: Option<String>,
}

/// Checks the attributes and groups of a mesh of `vertices` vertices and `faces` faces.
pub(crate) fn check(
    attributes: &[Attribute],
    face_groups: &[u32],
    groups: &[Group],
    vertices: usize,
    faces: usize,
) -> Result<()> {
    for a in attributes {
        if a.components == 0 || a.stride() == 0 {
            return Err(Error::Invalid(format!("attribute {} has no components", a.name)));
        }
        if a.data.len() != vertices.saturating_mul(a.stride()) {
            return Err(Error::Invalid(format!(
                "attribute {} holds {} bytes; {vertices} vertices of {} bytes need {}",
                a.name,
                a.data.len(),
                a.stride(),
                vertices.saturating_mul(a.stride())
            )));
        }
    }
    if !face_groups.is_empty() {
        if face_groups.len() != faces {
            return Err(Error::Invalid(format!(
                "{} face groups given for {faces} faces (give one per face, or none)",
                face_groups.len()
            )));
        }
        if let Some((f, &g)) = face_groups.iter().enumerate().find(|(_, &g)| g as usize >= groups.len().max(1)) {
            return Err(Error::Invalid(format!("face {f} is in group {g} but the mesh has {} groups", groups.len())));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Mesh;

    #[test]
    fn values_round_trip_and_blend_by_kind() {
        let mut uv = Attribute::from_f32("TEXCOORD_0", 2, &[0.0, 0.0, 1.0, 0.5]);
        uv.push_lerp(0, 1, 0.25);
        assert_eq!(uv.len(), 3);
        assert_eq!(uv.value(2), vec![0.25, 0.125]);
        let mut joints = Attribute {
            name: "JOINTS_0".into(),
            scalar: Scalar::U16,
            components: 1,
            normalized: false,
            data: vec![3, 0, 9, 0],
        };
        joints.push_lerp(0, 1, 0.7);
        joints.push_blend(&[(0, 0.6), (1, 0.4)]);
        assert_eq!((joints.get(2, 0), joints.get(3, 0)), (9.0, 3.0));
        let mut colour = Attribute {
            name: "COLOR_0".into(),
            scalar: Scalar::U8,
            components: 1,
            normalized: true,
            data: vec![0, 255],
        };
        colour.push_lerp(0, 1, 0.5);
        assert_eq!(colour.get(2, 0), 128.0);
        assert_eq!(colour.gather(&[2, 0]).data, vec![128, 0]);
    }

    #[test]
    fn compact_carries_attributes_and_groups() {
        let mut m = Mesh::from_triangles(vec![[0.0; 3], [1.0; 3], [2.0; 3], [3.0; 3]], &[[0, 2, 3]]);
        m.attributes.push(Attribute::from_f32("NORMAL", 1, &[10.0, 11.0, 12.0, 13.0]));
        m.groups = vec![Group::default(), Group { name: "b".into(), material: Some("red".into()) }];
        m.face_groups = vec![1];
        m.check_faces().unwrap();
        let (c, ids) = m.compact();
        c.check_faces().unwrap();
        assert_eq!(ids, vec![0, u32::MAX, 1, 2]);
        assert_eq!(c.face(0), &[0, 1, 2]);
        assert_eq!(c.attribute("NORMAL").unwrap().value(1), vec![12.0]);
        assert_eq!((c.group_of(0), c.groups[1].material.as_deref()), (1, Some("red")));
        let mut bad = m.clone();
        bad.attributes[0].data.pop();
        assert!(bad.check_faces().is_err());
        bad = m.clone();
        bad.face_groups = vec![5];
        assert!(bad.check_faces().is_err());
    }
}
