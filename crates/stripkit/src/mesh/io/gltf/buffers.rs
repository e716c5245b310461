//! The buffers of a glTF document: the GLB binary chunk, `data:` URIs and external
//! files. External files are resolved inside the asset's folder (or an allowed root),
//! each opened once, its containment checked on the opened descriptor and its bytes
//! read from it (see [`super::ReadOptions`] for the rules and budgets).

use super::{array, at, base64_decode, required, Buffer, Shared};
use std::collections::HashMap;
use std::io::Read;
use crate::error::{Error, Result};
use crate::mesh::io::common::Src;
use crate::mesh::io::ReadOptions;
use serde_json::Value;
use std::path::{Component, Path, PathBuf};

/// Reads every buffer of the document: the GLB binary chunk, `data:` URIs, and
/// external files under the rules of [`ReadOptions`]. External files are resolved
/// first (every URI checked before anything is read), each distinct file is then read
/// once, up to the largest `byteLength` that names it, and the buffers naming it share
/// those bytes.
pub(super) fn load_buffers(src: Src, json: &Value, bin: Option<Shared>, options: &ReadOptions) -> Result<Vec<Buffer>> {
    enum Source {
        Bytes(Shared),
        File(usize),
    }
    struct External {
        path: PathBuf,
        /// The largest byteLength naming the file, and the first buffer asking for it.
        len: u64,
        buffer: usize,
        uri: String,
    }
    let list = array(src, json, "buffers")?;
    let mut sources = Vec::with_capacity(list.len());
    let mut files: Vec<External> = Vec::new();
    let mut file_of: HashMap<PathBuf, usize> = HashMap::new();
    let mut folders: Option<Folders> = None;
    for (i, b) in list.iter().enumerate() {
        let place = || at("buffers", i);
        let length = required(src, b, "byteLength", &place)?;
        let source = match b.get("uri") {
            None if i == 0 && bin.is_some() => Source::Bytes(bin.clone().unwrap_or_default()),
            // A fallback buffer of EXT_meshopt_compression holds no data: only the
            // compressed views name it, and they are decoded from their own buffers.
            None if b.pointer("/extensions/EXT_meshopt_compression/fallback") == Some(&Value::Bool(true)) => {
                sources.push((Source::Bytes(Shared::from(Vec::new())), 0));
                continue;
            }
            None => return Err(src.err(place(), "buffer without a 'uri' (only GLB buffer 0 may omit it)")),
            Some(Value::String(uri)) => match uri.strip_prefix("data:") {
                Some(rest) => Source::Bytes(Shared::from(decode_data_uri(src, rest, &place)?)),
                None => {
                    if length > options.max_external_bytes {
                        return Err(src.err(
                            place(),
                            format!(
                                "byteLength {length} exceeds the limit of {} bytes for external buffers \
                                 (ReadOptions::max_external_bytes; --max-memory on the command line raises it)",
                                options.max_external_bytes
                            ),
                        ));
                    }
                    let dirs = match folders.take() {
                        Some(f) => f,
                        None => Folders::new(src, options, i)?,
                    };
                    let path = dirs.resolve(src, uri, i);
                    folders = Some(dirs);
                    let path = path?;
                    let k = *file_of.entry(path.clone()).or_insert_with(|| {
                        files.push(External { path, len: 0, buffer: i, uri: uri.clone() });
                        files.len() - 1
                    });
                    if length > files[k].len {
                        files[k].len = length;
                        files[k].buffer = i;
                        files[k].uri = uri.clone();
                    }
                    Source::File(k)
                }
            },
            Some(_) => return Err(src.err(format!("buffers[{i}].uri"), "must be a string")),
        };
        sources.push((source, length));
    }
    let total = files.iter().fold(0u64, |t, f| t.saturating_add(f.len));
    if total > options.max_external_bytes {
        return Err(src.err(
            "buffers",
            format!(
                "the external buffer files hold {total} bytes in all, more than the limit of {} bytes \
                 (ReadOptions::max_external_bytes; --max-memory on the command line raises it)",
                options.max_external_bytes
            ),
        ));
    }
    let mut read = Vec::with_capacity(files.len());
    if let Some(dirs) = &folders {
        for f in &files {
            read.push(read_external(src, dirs, f.path.as_path(), f.len, f.buffer, &f.uri)?);
        }
    }
    let mut buffers = Vec::with_capacity(sources.len());
    for (i, (source, length)) in sources.into_iter().enumerate() {
        let bytes = match source {
            Source::Bytes(b) => b,
            Source::File(k) => read[k].clone(),
        };
        if (bytes.len() as u64) < length {
            return Err(src.err(
                at("buffers", i),
                format!("byteLength is {length} but the data holds {} bytes (truncated)", bytes.len()),
            ));
        }
        buffers.push(Buffer { bytes, len: length as usize });
    }
    Ok(buffers)
}

/// The bytes of a base64 `data:` URI (`rest` follows the `data:`).
fn decode_data_uri(src: Src, rest: &str, place: &dyn Fn() -> String) -> Result<Vec<u8>> {
    let (_, payload) =
        rest.split_once(";base64,").ok_or_else(|| src.err(place(), "only base64 data URIs are supported"))?;
    base64_decode(payload.as_bytes())
        .map_err(|k| src.err(place(), format!("invalid base64 character at position {k} of the data URI")))
}

/// The folders external buffers may come from, resolved (symbolic links followed).
struct Folders {
    /// The asset's own folder.
    asset: PathBuf,
    /// The asset's folder and [`ReadOptions::allowed_roots`].
    roots: Vec<PathBuf>,
}

impl Folders {
    fn new(src: Src, options: &ReadOptions, i: usize) -> Result<Folders> {
        let parent = match src.path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => Path::new("."),
        };
        let asset = std::fs::canonicalize(parent).map_err(|e| {
            src.err(
                format!("buffers[{i}].uri"),
                format!("cannot resolve the asset's folder {} to look for external buffers: {e}", parent.display()),
            )
        })?;
        let mut roots = vec![asset.clone()];
        for root in &options.allowed_roots {
            roots.push(std::fs::canonicalize(root).map_err(|e| Error::Io { path: root.clone(), source: e })?);
        }
        Ok(Folders { asset, roots })
    }

    fn root_of(&self, path: &Path) -> Option<&Path> {
        self.roots.iter().map(PathBuf::as_path).find(|r| path.starts_with(r))
    }

    /// The canonical path of the file `uri` names, or the same refusal whether it is
    /// outside the allowed folders, absent there or a link leading out of them.
    /// The refusal of `buffers[i]`'s `uri`, the same whether it is outside the allowed
    /// folders, absent there or a link leading out of them.
    fn refusal(&self, src: Src, uri: &str, i: usize) -> Error {
        let roots = if self.roots.len() > 1 { " (or an allowed root)" } else { "" };
        src.err(
            format!("buffers[{i}].uri"),
            format!("must be a relative path inside the asset's folder{roots} or a data: URI, not {uri:?}"),
        )
    }

    fn resolve(&self, src: Src, uri: &str, i: usize) -> Result<PathBuf> {
        let at = || format!("buffers[{i}].uri");
        let refuse = || self.refusal(src, uri, i);
        // A scheme (`file:`, `http:`, a drive letter `C:`) comes before the first '/'.
        let first = uri.split('/').next().unwrap_or("");
        if first.contains(':') {
            return Err(refuse());
        }
        let decoded = String::from_utf8(percent_decode_bytes(uri)).map_err(|_| refuse())?;
        if decoded.is_empty() || decoded.contains('\0') {
            return Err(refuse());
        }
        // `.` and `..` segments are removed from the path as written (as URI resolution
        // does), before anything is asked of the file system.
        let mut lexical = self.asset.clone();
        for c in Path::new(&decoded).components() {
            match c {
                Component::Normal(name) => lexical.push(name),
                Component::CurDir => {}
                Component::ParentDir => {
                    lexical.pop();
                }
                Component::RootDir | Component::Prefix(_) => return Err(refuse()),
            }
        }
        let Some(root) = self.root_of(&lexical) else {
            return Err(refuse());
        };
        match std::fs::canonicalize(&lexical) {
            Ok(real) if self.root_of(&real).is_some() => Ok(real),
            Ok(_) => Err(refuse()),
            Err(e) => {
                // A link on the way may lead outside: say nothing about where it leads.
                let link = lexical
                    .ancestors()
                    .take_while(|a| a.starts_with(root) && *a != root)
                    .any(|a| std::fs::symlink_metadata(a).is_ok_and(|m| m.file_type().is_symlink()));
                if link {
                    Err(refuse())
                } else {
                    Err(src.err(at(), format!("cannot open {decoded:?} in the asset's folder: {e}")))
                }
            }
        }
    }

    /// Checks that the opened `file` (opened by the name `path`) lies inside an allowed
    /// folder. The path was checked before it was opened, but a folder on the way may
    /// have been swapped for a link in between, so the check is made again on what was
    /// opened. On Linux the kernel names the opened file (`/proc/self/fd/N`): no race
    /// is left. Elsewhere (or without `/proc`) the path is resolved again and must
    /// still lie inside and name the same file (device and inode): a narrower window,
    /// not none.
    fn check_opened(&self, src: Src, file: &std::fs::File, path: &Path, uri: &str, i: usize) -> Result<()> {
        #[cfg(target_os = "linux")]
        {
            use std::os::unix::io::AsRawFd;
            if let Ok(real) = std::fs::read_link(format!("/proc/self/fd/{}", file.as_raw_fd())) {
                return match self.root_of(&real) {
                    Some(_) => Ok(()),
                    None => Err(self.refusal(src, uri, i)),
                };
            }
        }
        let real = std::fs::canonicalize(path).map_err(|_| self.refusal(src, uri, i))?;
        if self.root_of(&real).is_none() {
            return Err(self.refusal(src, uri, i));
        }
        #[cfg(unix)]
        {
            use std::os::unix::fs::MetadataExt;
            match (file.metadata(), std::fs::metadata(&real)) {
                (Ok(a), Ok(b)) if a.dev() == b.dev() && a.ino() == b.ino() => {}
                _ => return Err(self.refusal(src, uri, i)),
            }
        }
        #[cfg(not(unix))]
        let _ = file;
        Ok(())
    }
}

/// Reads exactly `len` bytes from the start of the regular file `path` (canonical,
/// inside an allowed folder when it was resolved), for `buffers[i]` whose URI is
/// `uri`. The file is opened once; its place ([`Folders::check_opened`]), type and
/// size are checked on the opened file and its bytes read from it, so nothing
/// swapped in after a check is read.
fn read_external(src: Src, dirs: &Folders, path: &Path, len: u64, i: usize, uri: &str) -> Result<Shared> {
    let at = || format!("buffers[{i}].uri");
    let fail = |e: std::io::Error| src.err(at(), format!("cannot read {uri:?}: {e}"));
    let not_regular =
        || src.err(at(), format!("{uri:?} is not a regular file (a directory, device or pipe is not read)"));
    let mut open = std::fs::OpenOptions::new();
    open.read(true);
    // Should the file be swapped for a pipe after the check above, opening it must
    // not wait for a writer (O_NONBLOCK; no effect on regular files).
    #[cfg(all(
        target_os = "linux",
        any(
            target_arch = "x86_64",
            target_arch = "x86",
            target_arch = "aarch64",
            target_arch = "arm",
            target_arch = "riscv64"
        )
    ))]
    {
        use std::os::unix::fs::OpenOptionsExt;
        open.custom_flags(0o4000);
    }
    let file = open.open(path).map_err(fail)?;
    dirs.check_opened(src, &file, path, uri, i)?;
    let meta = file.metadata().map_err(fail)?;
    if !meta.is_file() {
        return Err(not_regular());
    }
    if meta.len() < len {
        return Err(src.err(at(), format!("byteLength is {len} but {uri:?} holds {} bytes (truncated)", meta.len())));
    }
    let mut bytes = Vec::with_capacity(len as usize);
    file.take(len).read_to_end(&mut bytes).map_err(fail)?;
    if (bytes.len() as u64) < len {
        return Err(src.err(at(), format!("byteLength is {len} but {uri:?} holds {} bytes (truncated)", bytes.len())));
    }
    Ok(Shared::from(bytes))
}

#[cfg(test)]
fn percent_decode(s: &str) -> String {
    String::from_utf8_lossy(&percent_decode_bytes(s)).into_owned()
}

fn percent_decode_bytes(s: &str) -> Vec<u8> {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        let hex = |c: u8| (c as char).to_digit(16);
        if b[i] == b'%' && i + 2 < b.len() {
            if let (Some(h), Some(l)) = (hex(b[i + 1]), hex(b[i + 2])) {
                out.push((h * 16 + l) as u8);
                i += 3;
                continue;
            }
        }
        out.push(b[i]);
        i += 1;
    }
    out
}


#[cfg(test)]
mod tests {
    use super::*;

    /// Issue #30, class 4: the check is made on the opened file, not on a name that
    /// may lead elsewhere by then. Here the file opened lies outside the asset's
    /// folder while the name given for it resolves inside (as after a folder was
    /// swapped back by a race): it is refused. Before, only the name was checked.
    #[test]
    fn a_file_opened_outside_the_folder_is_refused_whatever_its_name() {
        let root = stripkit_testkit::scratch_dir("gltf-opened");
        let (asset, outside) = (root.join("asset"), root.join("outside"));
        std::fs::create_dir_all(asset.join("sub")).unwrap();
        std::fs::create_dir_all(&outside).unwrap();
        std::fs::write(asset.join("sub/mesh.bin"), [1u8; 36]).unwrap();
        std::fs::write(outside.join("mesh.bin"), [2u8; 36]).unwrap();
        let gltf = asset.join("scene.gltf");
        let src = Src { path: &gltf };
        let dirs = Folders::new(src, &ReadOptions::default(), 0).unwrap();
        let inside = dirs.resolve(src, "sub/mesh.bin", 0).unwrap();
        let opened_inside = std::fs::File::open(&inside).unwrap();
        assert!(dirs.check_opened(src, &opened_inside, &inside, "sub/mesh.bin", 0).is_ok());
        let opened_outside = std::fs::File::open(outside.join("mesh.bin")).unwrap();
        let err = dirs.check_opened(src, &opened_outside, &inside, "sub/mesh.bin", 0).unwrap_err().to_string();
        assert!(err.contains("buffers[0].uri") && err.contains("inside the asset's folder"), "{err}");
        let bytes = read_external(src, &dirs, &inside, 36, 0, "sub/mesh.bin").unwrap();
        assert_eq!(&bytes[..], &[1u8; 36]);
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn percent_escapes_are_decoded() {
        assert_eq!(percent_decode("my%20mesh.bin"), "my mesh.bin");
        assert_eq!(percent_decode("100%"), "100%");
        assert_eq!(percent_decode("a%2"), "a%2");
    }
}
