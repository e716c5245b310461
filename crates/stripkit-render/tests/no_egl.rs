//! A machine without EGL gets `RenderError::NoEgl`, whose message names the library and
//! what to install; no crash, no link error. `STRIPKIT_EGL_LIBRARY` takes EGL away for
//! the whole process, so this is the only test of its binary.

use stripkit_render::{RenderError, Renderer};

#[test]
fn no_egl_is_a_clear_error() {
    // The only test of this binary: no other thread reads the environment meanwhile.
    std::env::set_var("STRIPKIT_EGL_LIBRARY", "/nonexistent/libEGL.so.1");
    let result = Renderer::new(64, 64);
    std::env::remove_var("STRIPKIT_EGL_LIBRARY");
    let err = match result {
        Err(e) => e,
        Ok(r) => panic!("a renderer without EGL: {:?}", r.info()),
    };
    let text = err.to_string();
    println!("no EGL: {text}");
    assert!(matches!(err, RenderError::NoEgl(_)), "{err:?}");
    assert!(text.contains("/nonexistent/libEGL.so.1"), "names the library it tried: {text}");
    assert!(text.contains("libEGL.so.1") && text.contains("libGLESv2"), "names the libraries: {text}");
    assert!(text.contains("apt-get install libegl1 libegl-mesa0 libgles2 libgl1-mesa-dri"), "says what to install: {text}");
}
