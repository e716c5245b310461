//! Surfaceless EGL: finds a display without a window system, makes an OpenGL ES 3
//! context current, and hands glow its function pointers.
//!
//! The order of attempts is the same on every machine:
//! 1. `EGL_EXT_platform_device`: the first device (NVIDIA's driver, Mesa's software
//!    device);
//! 2. `EGL_MESA_platform_surfaceless` (Mesa llvmpipe without a display server);
//! 3. the default display.
//!
//! `libEGL.so.1` is loaded at run time, so a machine without EGL gets
//! [`RenderError::NoEgl`] instead of a link error or a crash.

use crate::RenderError;
use khronos_egl as egl;
use std::ffi::c_void;
use std::sync::{Mutex, MutexGuard};

type Egl = egl::DynamicInstance<egl::EGL1_4>;

const PLATFORM_DEVICE_EXT: egl::Enum = 0x313F;
const PLATFORM_SURFACELESS_MESA: egl::Enum = 0x31DD;
const OPENGL_ES3_BIT: egl::Int = 0x0040;
const CONTEXT_MAJOR_VERSION: egl::Int = 0x3098;
const CONTEXT_MINOR_VERSION: egl::Int = 0x30FB;

type QueryDevices = unsafe extern "system" fn(egl::Int, *mut *mut c_void, *mut egl::Int) -> egl::Boolean;
type GetPlatformDisplay = unsafe extern "system" fn(egl::Enum, *mut c_void, *const egl::Int) -> *mut c_void;

/// What to tell a user whose machine has no usable EGL.
pub(crate) const NO_EGL_HELP: &str = "stripkit renders through EGL and OpenGL ES 3 \
(libEGL.so.1 and libGLESv2.so.2). On Debian or Ubuntu, Mesa's software renderer comes with \
`apt-get install libegl1 libegl-mesa0 libgles2 libgl1-mesa-dri`. A machine with NVIDIA's driver \
(libEGL_nvidia.so.0 and its glvnd file 10_nvidia.json) but without the glvnd loader needs \
libEGL.so.1, libGLdispatch.so.0 and libGLESv2.so.2 on LD_LIBRARY_PATH";

/// Renderers alive per EGL display (its handle as an address). EGL gives every caller
/// of eglGetPlatformDisplay the same display for the same device, and eglInitialize is
/// not counted, so one renderer's eglTerminate would pull the display from under all
/// the others in the process: tests on other threads then failed with "EGL is not
/// initialized", "no OpenGL ES 3 configuration" or a segfault in Mesa. The display is
/// terminated with its last renderer instead.
static DISPLAY_USERS: Mutex<Vec<(usize, usize)>> = Mutex::new(Vec::new());

fn display_users() -> MutexGuard<'static, Vec<(usize, usize)>> {
    // A panic while the list was held cannot leave it half-written: go on with it.
    DISPLAY_USERS.lock().unwrap_or_else(|e| e.into_inner())
}

/// An EGL display with a current OpenGL ES context.
pub(crate) struct EglContext {
    egl: Egl,
    display: egl::Display,
    context: egl::Context,
    surface: Option<egl::Surface>,
    /// Which path found the display: "device", "surfaceless" or "default".
    pub platform: &'static str,
    /// The context's GLES version, (3, 1) where compute-style buffers exist.
    pub version: (i32, i32),
}

impl EglContext {
    pub fn new() -> Result<Self, RenderError> {
        // `STRIPKIT_EGL_LIBRARY` names another EGL library (tests use it to take EGL away).
        let name = std::env::var_os("STRIPKIT_EGL_LIBRARY").unwrap_or_else(|| "libEGL.so.1".into());
        // SAFETY: loading libEGL runs its initialisers; the library is the system's EGL.
        let egl = unsafe { Egl::load_required_from_filename(&name) }
            .map_err(|e| RenderError::NoEgl(format!("{} could not be loaded ({e})", name.to_string_lossy())))?;
        // Held until the display is counted, so that no other renderer's Drop
        // terminates it between eglInitialize and the context (see DISPLAY_USERS).
        let mut users = display_users();
        let mut tried = Vec::new();
        let (display, platform) = open_display(&egl, &mut tried).ok_or_else(|| {
            RenderError::NoEgl(format!("no EGL display could be initialised (tried {})", tried.join(", ")))
        })?;
        let made = (|| {
            egl.bind_api(egl::OPENGL_ES_API)
                .map_err(|e| RenderError::NoEgl(format!("OpenGL ES is not offered by EGL ({e})")))?;
            let attribs = [egl::RENDERABLE_TYPE, OPENGL_ES3_BIT, egl::SURFACE_TYPE, egl::PBUFFER_BIT, egl::NONE];
            let config = egl
                .choose_first_config(display, &attribs)
                .ok()
                .flatten()
                .or_else(|| egl.choose_first_config(display, &[egl::RENDERABLE_TYPE, OPENGL_ES3_BIT, egl::NONE]).ok().flatten())
                .ok_or_else(|| RenderError::NoEgl(format!("the {platform} EGL display has no OpenGL ES 3 configuration")))?;
            let mut made = None;
            for minor in [2, 1, 0] {
                let ctx_attribs = [CONTEXT_MAJOR_VERSION, 3, CONTEXT_MINOR_VERSION, minor, egl::NONE];
                if let Ok(c) = egl.create_context(display, config, None, &ctx_attribs) {
                    made = Some((c, minor));
                    break;
                }
            }
            let (context, minor) = made
                .ok_or_else(|| RenderError::NoEgl(format!("no OpenGL ES 3 context on the {platform} EGL display")))?;
            // Surfaceless first (EGL_KHR_surfaceless_context); a 1x1 pbuffer otherwise.
            let mut surface = None;
            if egl.make_current(display, None, None, Some(context)).is_err() {
                let pb = egl
                    .create_pbuffer_surface(display, config, &[egl::WIDTH, 1, egl::HEIGHT, 1, egl::NONE])
                    .map_err(|e| RenderError::NoEgl(format!("no surface for the context ({e})")))?;
                egl.make_current(display, Some(pb), Some(pb), Some(context))
                    .map_err(|e| RenderError::NoEgl(format!("the context could not be made current ({e})")))?;
                surface = Some(pb);
            }
            Ok((context, surface, minor))
        })();
        let key = display.as_ptr() as usize;
        match made {
            Ok((context, surface, minor)) => {
                match users.iter_mut().find(|(d, _)| *d == key) {
                    Some((_, n)) => *n += 1,
                    None => users.push((key, 1)),
                }
                Ok(EglContext { egl, display, context, surface, platform, version: (3, minor) })
            }
            Err(e) => {
                if !users.iter().any(|(d, _)| *d == key) {
                    let _ = egl.terminate(display);
                }
                Err(e)
            }
        }
    }

    /// glow's loader: core and extension GLES entry points through eglGetProcAddress.
    pub fn proc_address(&self, name: &str) -> *const c_void {
        self.egl.get_proc_address(name).map_or(std::ptr::null(), |f| f as *const c_void)
    }
}

fn open_display(egl: &Egl, tried: &mut Vec<String>) -> Option<(egl::Display, &'static str)> {
    let client_ext = egl.query_string(None, egl::EXTENSIONS).map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    let get_platform: Option<GetPlatformDisplay> = egl
        .get_proc_address("eglGetPlatformDisplayEXT")
        // SAFETY: the EGL_EXT_platform_base signature.
        .map(|f| unsafe { std::mem::transmute::<extern "system" fn(), GetPlatformDisplay>(f) });
    if let Some(get_platform) = get_platform {
        if client_ext.contains("EGL_EXT_platform_device") {
            if let Some(query) = egl.get_proc_address("eglQueryDevicesEXT") {
                // SAFETY: the EGL_EXT_device_enumeration signature.
                let query: QueryDevices = unsafe { std::mem::transmute::<extern "system" fn(), QueryDevices>(query) };
                let mut devices = [std::ptr::null_mut(); 16];
                let mut n = 0;
                // SAFETY: the array holds 16 entries and EGL writes at most that many.
                if unsafe { query(16, devices.as_mut_ptr(), &mut n) } == egl::TRUE && n > 0 {
                    for &device in devices.iter().take(n as usize) {
                        // SAFETY: a device handle returned by EGL, no attributes.
                        let d = unsafe { get_platform(PLATFORM_DEVICE_EXT, device, [egl::NONE].as_ptr()) };
                        if let Some(d) = initialised(egl, d) {
                            return Some((d, "device"));
                        }
                    }
                }
                tried.push(format!("{n} EGL device(s)"));
            }
        }
        if client_ext.contains("EGL_MESA_platform_surfaceless") {
            // SAFETY: the surfaceless platform takes EGL_DEFAULT_DISPLAY.
            let d = unsafe { get_platform(PLATFORM_SURFACELESS_MESA, std::ptr::null_mut(), [egl::NONE].as_ptr()) };
            if let Some(d) = initialised(egl, d) {
                return Some((d, "surfaceless"));
            }
            tried.push("the Mesa surfaceless platform".into());
        }
    }
    // SAFETY: EGL_DEFAULT_DISPLAY.
    if let Some(d) = unsafe { egl.get_display(egl::DEFAULT_DISPLAY) } {
        if egl.initialize(d).is_ok() {
            return Some((d, "default"));
        }
    }
    tried.push("the default display".into());
    None
}

fn initialised(egl: &Egl, ptr: *mut c_void) -> Option<egl::Display> {
    if ptr.is_null() {
        return None;
    }
    // SAFETY: a non-null display handle returned by eglGetPlatformDisplayEXT.
    let d = unsafe { egl::Display::from_ptr(ptr) };
    egl.initialize(d).ok().map(|_| d)
}

impl Drop for EglContext {
    fn drop(&mut self) {
        let _ = self.egl.make_current(self.display, None, None, None);
        if let Some(s) = self.surface {
            let _ = self.egl.destroy_surface(self.display, s);
        }
        let _ = self.egl.destroy_context(self.display, self.context);
        // The display goes with the last renderer of the process that uses it.
        let mut users = display_users();
        let key = self.display.as_ptr() as usize;
        if let Some(i) = users.iter().position(|(d, _)| *d == key) {
            users[i].1 -= 1;
            if users[i].1 == 0 {
                users.swap_remove(i);
                let _ = self.egl.terminate(self.display);
            }
        }
    }
}
