#![no_main]
//! The front door on a small index list: the first byte picks the algorithm and the
//! join, every further byte gives two indices (its nibbles, so below 16) for 16
//! vertices. `stripify_indices` then `unstripify` must give back the same multiset of
//! oriented non-degenerate triangles, within `stripify_bound`.

use libfuzzer_sys::fuzz_target;
use stripkit_fuzz::oriented;
use stripkit::{stripify_bound, stripify_indices, unstripify, Algorithm, Error, Join, StripOptions};

const VERTICES: usize = 16;

fuzz_target!(|data: &[u8]| {
    let Some((&first, rest)) = data.split_first() else { return };
    let algorithm = match first % 7 {
        0 => Algorithm::auto(),
        1 => Algorithm::greedy(),
        2 => Algorithm::qstrip(),
        3 => Algorithm::cache(),
        4 => Algorithm::Cache { refine: true },
        5 => Algorithm::balanced(0.8),
        _ => Algorithm::batch(),
    };
    let join = if (first / 7) % 2 == 0 { Join::Restart } else { Join::Degenerate };
    let mut indices: Vec<u32> =
        rest.iter().take(300).flat_map(|&b| [u32::from(b & 15), u32::from(b >> 4)]).collect();
    indices.truncate(indices.len() / 3 * 3);
    if indices.is_empty() {
        return;
    }
    let want = oriented(&indices);
    let restart = VERTICES as u32;
    let options = StripOptions::default().algorithm(algorithm.clone()).join(join).restart_index(restart);
    let buf = match stripify_indices(&indices, VERTICES, &options) {
        Ok(buf) => buf,
        // Only a list of nothing but degenerate triangles may be refused.
        Err(Error::Invalid(_)) if want.is_empty() => return,
        Err(e) => panic!("{} {join:?}: {e}", algorithm.name()),
    };
    assert!(buf.len() <= stripify_bound(indices.len()), "{} {join:?}: over the bound", algorithm.name());
    let back = unstripify(&buf, if join == Join::Restart { restart } else { u32::MAX });
    assert_eq!(oriented(&back), want, "{} {join:?}: triangles differ", algorithm.name());
});
