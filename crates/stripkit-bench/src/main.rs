//! `stripkit-bench`: stripkit next to other libraries on a folder of meshes.
//! (Filled in by the comparison work.)
fn main() {
    eprintln!("stripkit-bench: no comparisons yet");
}
