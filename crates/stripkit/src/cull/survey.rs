//! Culling along a camera path, view by view: what each view draws, culls and leaks,
//! and how long each traversal takes (a bench API: what `stripkit cull` and the
//! bench's `cull` comparison print). The times are wall-clock microseconds on this
//! machine; every other figure is exact and the same from run to run.

use super::count::FacingCounter;
use super::traverse::{CullOptions, Culled, RenderFront};
use super::tree::SegmentTree;
use crate::error::{Error, Result};
use std::time::Instant;

/// The figures of one view of [`survey`].
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct ViewFigures {
    /// Index ranges drawn (one multi-draw).
    pub segments: usize,
    /// Triangles drawn.
    pub drawn: usize,
    /// Back-facing triangles of the view, drawn or not.
    #[serde(skip)]
    pub back: usize,
    /// Back-facing triangles not drawn.
    pub back_culled: usize,
    /// Back-facing triangles drawn (in split leaves: the test's leak).
    pub back_drawn: usize,
    /// Front-facing triangles not drawn (0 without a frustum).
    pub front_missed: usize,
    /// Triangles skipped as outside the frustum ([`CullOptions::frustum`]).
    pub outside: usize,
    /// Nodes classified from the roots.
    pub visited_root: usize,
    /// Nodes classified from the render front (a front followed along the path).
    pub visited_front: usize,
    /// Front nodes kept without a test.
    pub reused_front: usize,
    /// Microseconds of the traversal from the roots, the best of the runs.
    pub us_root: f64,
    /// Microseconds of the traversal from the render front, the best of the runs.
    pub us_front: f64,
}

/// The figures of [`survey`] averaged over the views, and the slowest view from the
/// render front.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct PathMean {
    /// Mean [`ViewFigures::segments`].
    pub segments: f64,
    /// Mean [`ViewFigures::drawn`].
    pub drawn: f64,
    /// Mean [`ViewFigures::back`].
    pub back: f64,
    /// Mean [`ViewFigures::back_culled`].
    pub back_culled: f64,
    /// Mean [`ViewFigures::back_drawn`].
    pub back_drawn: f64,
    /// Mean [`ViewFigures::front_missed`].
    pub front_missed: f64,
    /// Mean [`ViewFigures::outside`].
    pub outside: f64,
    /// Mean [`ViewFigures::visited_root`].
    pub visited_root: f64,
    /// Mean [`ViewFigures::visited_front`].
    pub visited_front: f64,
    /// Mean [`ViewFigures::reused_front`].
    pub reused_front: f64,
    /// Mean [`ViewFigures::us_root`].
    pub us_root: f64,
    /// Mean [`ViewFigures::us_front`].
    pub us_front: f64,
    /// Largest [`ViewFigures::us_front`].
    pub us_front_max: f64,
}

/// Culls `tree` from every eye of `eyes` in turn (the options of each view from
/// `options`), from the roots and from a render front that follows the path, and
/// counts with `counter` (made from the same strips) what each view draws. The two
/// traversals must give the same ranges ([`Error::Verification`] otherwise). Then
/// times both traversals over the whole path `repeat` times (at least once), keeping
/// each view's best. [`Error::Invalid`] for more than [`super::MAX_VIEWS`] eyes.
pub fn survey(
    tree: &SegmentTree,
    counter: &FacingCounter,
    eyes: &[[f32; 3]],
    options: impl Fn([f32; 3]) -> CullOptions,
    repeat: usize,
) -> Result<Vec<ViewFigures>> {
    if eyes.len() > super::MAX_VIEWS {
        return Err(Error::Invalid(format!("{} views is more than {}", eyes.len(), super::MAX_VIEWS)));
    }
    let (mut out, mut check) = (Culled::default(), Culled::default());
    let mut front = RenderFront::new(tree);
    let mut views = Vec::with_capacity(eyes.len());
    for (v, &eye) in eyes.iter().enumerate() {
        let o = options(eye);
        tree.cull(eye, &o, &mut out);
        front.cull(tree, eye, &o, &mut check);
        if out.ranges != check.ranges {
            return Err(Error::Verification(format!("view {v}: the render front disagrees with the root traversal")));
        }
        let c = counter.count(eye, &out.ranges);
        views.push(ViewFigures {
            segments: out.ranges.len(),
            drawn: out.drawn_triangles,
            back: c.back,
            back_culled: c.back_culled(),
            back_drawn: c.back_drawn,
            front_missed: c.front - c.front_drawn,
            outside: out.outside_triangles,
            visited_root: out.visited,
            visited_front: check.visited,
            reused_front: check.reused,
            us_root: f64::MAX,
            us_front: f64::MAX,
        });
    }
    for _ in 0..repeat.max(1) {
        for (view, &eye) in views.iter_mut().zip(eyes) {
            let o = options(eye);
            let t = Instant::now();
            tree.cull(eye, &o, &mut out);
            view.us_root = view.us_root.min(t.elapsed().as_secs_f64() * 1e6);
        }
        let mut front = RenderFront::new(tree);
        for (view, &eye) in views.iter_mut().zip(eyes) {
            let o = options(eye);
            let t = Instant::now();
            front.cull(tree, eye, &o, &mut check);
            view.us_front = view.us_front.min(t.elapsed().as_secs_f64() * 1e6);
        }
    }
    Ok(views)
}

/// The figures of `views` averaged (zeros for no view).
pub fn mean(views: &[ViewFigures]) -> PathMean {
    if views.is_empty() {
        return PathMean::default();
    }
    let n = views.len() as f64;
    let mean = |f: fn(&ViewFigures) -> f64| views.iter().map(f).sum::<f64>() / n;
    PathMean {
        segments: mean(|v| v.segments as f64),
        drawn: mean(|v| v.drawn as f64),
        back: views.iter().map(|v| v.back).sum::<usize>() as f64 / n,
        back_culled: mean(|v| v.back_culled as f64),
        back_drawn: mean(|v| v.back_drawn as f64),
        front_missed: mean(|v| v.front_missed as f64),
        outside: mean(|v| v.outside as f64),
        visited_root: mean(|v| v.visited_root as f64),
        visited_front: mean(|v| v.visited_front as f64),
        reused_front: mean(|v| v.reused_front as f64),
        us_root: mean(|v| v.us_root),
        us_front: mean(|v| v.us_front),
        us_front_max: views.iter().map(|v| v.us_front).fold(0.0, f64::max),
    }
}
