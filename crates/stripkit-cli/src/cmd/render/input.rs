//! The inputs of `stripkit render`: a mesh (and its `--morph` target), or a level of a
//! `.sets` / `.lodseq` model; and the strips' triangles as drawn.

use super::Args;
use stripkit::Error;

/// The strips' triangles in strip order, each with the number of its strip; those with
/// a repeated index (swaps, stitches) draw nothing and are left out, as the GPU leaves
/// them out.
pub fn strip_triangles(strips: &stripkit::StripSet) -> Vec<(usize, [u32; 3])> {
    let mut triangles = Vec::with_capacity(strips.index_count());
    for (k, s) in strips.iter().enumerate() {
        stripkit::for_each_triangle(s, |t| triangles.push((k, t)));
    }
    triangles
}

/// A level (and frame) of a `.sets` / `.lodseq` input: the mesh its strips index
/// (every vertex of the model, with its attributes, the level's triangles as faces),
/// its strips, and a description.
pub type Level = (stripkit::Mesh, stripkit::StripSet, String);

/// The strips of a `.sets` or `.lodseq` input at `--level` / `--ratio` (and
/// `--frame`, default 0 for an animation); `None` for a mesh (or standard input).
pub fn read_lod(args: &Args) -> anyhow::Result<Option<Level>> {
    use anyhow::Context;
    use stripkit::lod::{LevelSpec, Model};
    let model = if args.input.as_os_str() == "-" { None } else { Model::try_read(&args.input)? };
    let Some(model) = model else {
        if args.level.is_some() || args.ratio.is_some() || args.frame.is_some() {
            return Err(Error::Invalid("--level, --ratio and --frame apply to .sets and .lodseq inputs".into()).into());
        }
        return Ok(None);
    };
    if args.morph.is_some() {
        return Err(Error::Invalid("--morph applies to meshes; a .lodseq morphs with --frame".into()).into());
    }
    let spec = match (args.level, args.ratio) {
        (_, Some(r)) => LevelSpec::Ratio(r as f64),
        (l, None) => LevelSpec::Level(l.unwrap_or(0)),
    };
    let frame = match model {
        Model::Seq(_) => Some(args.frame.unwrap_or(0.0)),
        Model::Sets(_) => args.frame,
    };
    let x = model.extract(spec, frame).with_context(|| format!("{} (--frame)", args.input.display()))?;
    let level = format!("level {} of {}, {} triangles", x.level, x.levels, x.triangles);
    let what = match x.frame {
        Some((t, key)) => format!("frame {t} (key frame {key}), {level}"),
        None => level,
    };
    // The asset as it is: the level's triangles over the model's vertices, with
    // every attribute the model carries.
    let triangles = x.checked_triangles()?;
    let mut mesh = stripkit::Mesh::from_triangles(x.positions, &triangles);
    mesh.attributes = x.attributes;
    Ok(Some((mesh, x.strips, what)))
}

/// The mesh, and the `--morph` mesh when given (same vertex count).
pub fn read_meshes(args: &Args) -> anyhow::Result<(stripkit::Mesh, Option<stripkit::Mesh>)> {
    let mesh = args.read.read(&args.input)?;
    let Some(path) = &args.morph else { return Ok((mesh, None)) };
    let other = args.read.read(path)?;
    if other.vertex_count() != mesh.vertex_count() {
        return Err(Error::Invalid(format!(
            "--morph {}: {} vertices, but {} has {}; a morph needs the same vertices",
            path.display(),
            other.vertex_count(),
            args.input.display(),
            mesh.vertex_count()
        ))
        .into());
    }
    Ok((mesh, Some(other)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strip_triangles_keep_strip_order_winding_and_skip_swaps() {
        // Two strips: [0 1 2 3] (two triangles) and [4 4 5 6] (one swap, then the odd
        // triangle (5, 4, 6)).
        let strips = stripkit::StripSet::from_strips(&[vec![0, 1, 2, 3], vec![4, 4, 5, 6]]);
        assert_eq!(strip_triangles(&strips), [(0, [0, 1, 2]), (0, [2, 1, 3]), (1, [5, 4, 6])]);
    }
}
