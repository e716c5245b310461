//! Messages of issue #16 seen from the command line: each refusal is exit status 2
//! with the file and what is wrong (the library tests cover the same inputs through
//! the API: gltf_references.rs, io_hostile.rs).

mod support;

use support::{stripkit_1gib, tmp};

/// Runs under the 1 GiB limit, expects exit 2 and returns stderr.
fn refused(args: &[&str]) -> String {
    let (out, _) = stripkit_1gib(args);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(out.stdout.is_empty(), "{args:?}");
    err
}

/// A `.gltf` drawing one triangle from a data: URI, with a second buffer at `uri`.
fn gltf_with_second_buffer(uri: &str) -> String {
    format!(
        r#"{{"asset":{{"version":"2.0"}},"buffers":[{{"byteLength":36,"uri":"data:;base64,{}"}},{{"byteLength":6,"uri":"{uri}"}}],
        "bufferViews":[{{"buffer":0,"byteLength":36}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}}}}]}}]}}"#,
        "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"
    )
}

#[test]
fn external_gltf_buffer_errors_name_the_gltf_and_the_buffer_and_nothing_outside() {
    let base = tmp("messages", "ext");
    let asset = base.join("asset");
    std::fs::create_dir_all(&asset).unwrap();
    std::fs::write(base.join("outside.bin"), b"secret").unwrap();
    let gltf = asset.join("a.gltf");
    let name = gltf.to_str().unwrap();
    let mut outside = Vec::new();
    for uri in ["../outside.bin", "../missing.bin"] {
        std::fs::write(&gltf, gltf_with_second_buffer(uri)).unwrap();
        let err = refused(&["stats", name]);
        assert!(err.contains(&format!("{name}: buffers[1].uri: ")), "{err}");
        outside.push(err.replace(uri, "URI"));
    }
    // An existing and a missing file outside the folder read the same.
    assert_eq!(outside[0], outside[1]);
    let abs = base.join("outside.bin");
    std::fs::write(&gltf, gltf_with_second_buffer(abs.to_str().unwrap())).unwrap();
    assert_eq!(refused(&["stats", name]).replace(abs.to_str().unwrap(), "URI"), outside[0]);
    // Inside the folder, a missing file is named as such.
    std::fs::write(&gltf, gltf_with_second_buffer("missing.bin")).unwrap();
    let err = refused(&["stats", name]);
    assert!(err.contains(&format!("{name}: buffers[1].uri: cannot open \"missing.bin\" in the asset's folder")), "{err}");
}

#[test]
fn homogeneous_off_coordinates_that_overflow_are_refused_naming_the_file() {
    // w = 1e-45 turned 1 into an infinite coordinate before the check after the division.
    let f = tmp("messages", "w.off");
    std::fs::write(&f, "4OFF\n3 1 0\n0 0 0 1\n1 0 0 1\n0 1 0 1e-45\n3 0 1 2\n").unwrap();
    let name = f.to_str().unwrap();
    let err = refused(&["stats", name]);
    assert!(
        err.contains(&format!("{name}: line 5: vertex 2: dividing by its homogeneous coordinate 1e-45")),
        "{err}"
    );
    assert!(err.contains("NaN or infinite"), "{err}");
}

#[cfg(unix)]
#[test]
fn a_folder_run_skips_links_out_of_the_folder() {
    // A link in the folder to a text file outside it: the run used to read it and
    // quote its first line in the error. Now it is skipped, named in a note; a link
    // to a mesh inside the folder is still taken.
    let base = tmp("messages", "linkrun");
    let (dir, out) = (base.join("in"), base.join("out"));
    std::fs::create_dir_all(&dir).unwrap();
    let secret = base.join("secret.txt");
    std::fs::write(&secret, "the-secret-first-line\n").unwrap();
    std::fs::write(dir.join("a.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    for (name, to) in [("x.obj", secret.clone()), ("y.off", secret.clone()), ("b.obj", dir.join("a.obj"))] {
        let _ = std::fs::remove_file(dir.join(name));
        std::os::unix::fs::symlink(to, dir.join(name)).unwrap();
    }
    let run = support::stripkit(&["strip", dir.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(0), "{err}");
    assert!(!err.contains("secret-first"), "{err}");
    assert!(err.contains("skipped 2 symbolic link(s)") && err.contains("x.obj") && err.contains("y.off"), "{err}");
    assert!(out.join("a.glb").is_file() && out.join("b.glb").is_file());
    assert!(!out.join("x.glb").exists());
    // Only links out of the folder: nothing to do.
    std::fs::remove_file(dir.join("a.obj")).unwrap();
    std::fs::remove_file(dir.join("b.obj")).unwrap();
    let err = refused(&["strip", dir.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert!(err.contains("no mesh files") && !err.contains("secret-first"), "{err}");
}
