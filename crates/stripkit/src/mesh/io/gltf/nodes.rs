//! Node transforms, for the one place the mesh reader applies them: quantized positions
//! (`KHR_mesh_quantization`), whose dequantization (scale and offset) tools such as
//! gltfpack move into the transform of the node that draws the mesh.

use serde_json::Value;

/// A column-major 4x4 matrix, as glTF writes `matrix`.
pub(super) type Mat4 = [f64; 16];

const IDENTITY: Mat4 = [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0];

fn mul(a: &Mat4, b: &Mat4) -> Mat4 {
    let mut m = [0.0; 16];
    for c in 0..4 {
        for r in 0..4 {
            m[c * 4 + r] = (0..4).map(|k| a[k * 4 + r] * b[c * 4 + k]).sum();
        }
    }
    m
}

fn numbers<const N: usize>(v: Option<&Value>) -> Option<[f64; N]> {
    let a = v?.as_array()?;
    if a.len() != N {
        return None;
    }
    let mut out = [0.0; N];
    for (o, x) in out.iter_mut().zip(a) {
        *o = x.as_f64().filter(|x| x.is_finite())?;
    }
    Some(out)
}

/// The node's local matrix: `matrix`, or translation x rotation x scale (missing or
/// malformed members read as the identity's).
fn local(node: &Value) -> Mat4 {
    if let Some(m) = numbers::<16>(node.get("matrix")) {
        return m;
    }
    let t = numbers::<3>(node.get("translation")).unwrap_or([0.0; 3]);
    let [x, y, z, w] = numbers::<4>(node.get("rotation")).unwrap_or([0.0, 0.0, 0.0, 1.0]);
    let s = numbers::<3>(node.get("scale")).unwrap_or([1.0; 3]);
    let r = [
        1.0 - 2.0 * (y * y + z * z),
        2.0 * (x * y + z * w),
        2.0 * (x * z - y * w),
        2.0 * (x * y - z * w),
        1.0 - 2.0 * (x * x + z * z),
        2.0 * (y * z + x * w),
        2.0 * (x * z + y * w),
        2.0 * (y * z - x * w),
        1.0 - 2.0 * (x * x + y * y),
    ];
    let mut m = IDENTITY;
    for c in 0..3 {
        for row in 0..3 {
            m[c * 4 + row] = r[c * 3 + row] * s[c];
        }
    }
    m[12..15].copy_from_slice(&t);
    m
}

/// The world matrix of the first node (in the order of `nodes`) that draws mesh `m`,
/// its parents' transforms applied; `None` when no node draws it. A cycle or a chain
/// longer than the node count stops the walk up (the file is malformed; the matrix
/// found so far is used).
pub(super) fn world_of_mesh(json: &Value, m: usize) -> Option<Mat4> {
    let nodes = json.get("nodes").and_then(Value::as_array)?;
    let mut parent = vec![None; nodes.len()];
    for (p, node) in nodes.iter().enumerate() {
        for c in node.get("children").and_then(Value::as_array).into_iter().flatten() {
            if let Some(c) = c.as_u64().map(|c| c as usize).filter(|&c| c < nodes.len()) {
                parent[c] = Some(p);
            }
        }
    }
    let first = nodes.iter().position(|n| n.get("mesh").and_then(Value::as_u64) == Some(m as u64))?;
    let mut world = local(&nodes[first]);
    let mut at = first;
    for _ in 0..nodes.len() {
        let Some(p) = parent[at] else { break };
        world = mul(&local(&nodes[p]), &world);
        at = p;
    }
    Some(world)
}

/// `p` transformed by `m` (a point: translation applied), back in `f32`.
pub(super) fn apply(m: &Mat4, p: [f32; 3]) -> [f32; 3] {
    let [x, y, z] = p.map(f64::from);
    let mut out = [0.0f32; 3];
    for (r, o) in out.iter_mut().enumerate() {
        *o = (m[r] * x + m[4 + r] * y + m[8 + r] * z + m[12 + r]) as f32;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn the_drawing_node_and_its_parents_are_applied() {
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let doc = json!({"nodes": [
            {"children": [1], "translation": [10.0, 0.0, 0.0]},
            {"mesh": 0, "scale": [2.0, 2.0, 2.0], "rotation": [0.0, 0.0, h, h]}
        ]});
        let m = world_of_mesh(&doc, 0).unwrap();
        // (1, 0, 0) scaled to (2, 0, 0), turned a quarter about z to (0, 2, 0), moved by 10 in x.
        let p = apply(&m, [1.0, 0.0, 0.0]);
        assert!((p[0] - 10.0).abs() < 1e-6 && (p[1] - 2.0).abs() < 1e-6 && p[2].abs() < 1e-6, "{p:?}");
        assert!(world_of_mesh(&doc, 1).is_none());
    }
}
