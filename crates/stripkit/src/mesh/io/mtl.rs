//! OBJ material libraries (`.mtl`) as glTF metallic-roughness materials, the way
//! obj2gltf converts them: `Kd` the base colour, `d` (or `1 - Tr`) its alpha, `Ns`
//! the roughness where `Ks` gives a highlight, `map_Kd` the base colour texture,
//! `map_Bump` / `bump` / `norm` the normal texture. Every other statement is kept as
//! a note, never dropped in silence.
//!
//! `mtllib` names and texture paths come from the file and are untrusted: like a
//! glTF's buffers they must be relative paths inside the OBJ's folder (no scheme, no
//! `..` out of it, no link leading out, checked again on the opened file), and each
//! file read is at most [`ReadOptions::max_external_bytes`].

use super::ReadOptions;
use crate::error::{Error, Result};
use std::collections::BTreeMap;
use std::io::Read;
use std::path::{Component, Path, PathBuf};

/// An image a material refers to, read from the OBJ's folder.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Texture {
    /// The path as the `.mtl` file wrote it.
    pub uri: String,
    /// `image/png` or `image/jpeg`, from the file's first bytes.
    pub mime: &'static str,
    /// The file's bytes.
    pub bytes: Vec<u8>,
}

/// One `newmtl` material, in glTF's metallic-roughness terms (metallic 0: OBJ
/// materials are dielectric).
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Material {
    /// The `newmtl` name (what `usemtl` names).
    pub name: String,
    /// `Kd` and the alpha of `d` (or `1 - Tr`). Default opaque white.
    pub base_color: [f32; 4],
    /// Perceptual roughness from `Ns` where `Ks` is not black: `(2 / (Ns + 2))^(1/4)`
    /// (the Blinn-Phong exponent's Beckmann width, square-rooted); `None` (glTF's
    /// default 1) without a highlight.
    pub roughness: Option<f32>,
    /// `map_Kd`.
    pub base_color_texture: Option<Texture>,
    /// `map_Bump`, `bump` or `norm`.
    pub normal_texture: Option<Texture>,
}

impl Material {
    fn new(name: &str) -> Self {
        Material { name: name.into(), base_color: [1.0; 4], roughness: None, base_color_texture: None, normal_texture: None }
    }
}

/// The materials of an OBJ's material libraries, and what was not used of them.
#[derive(Clone, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct Materials {
    /// Every material, in the order of the libraries and of their `newmtl`s (a later
    /// one of the same name replaces an earlier one).
    pub materials: Vec<Material>,
    /// Statements and files not carried into glTF, one line each (a library or
    /// texture not found, a statement with no glTF counterpart and how often).
    pub notes: Vec<String>,
}

impl Materials {
    /// The material named `name`, if a library defines it.
    pub fn get(&self, name: &str) -> Option<&Material> {
        self.materials.iter().find(|m| m.name == name)
    }

    /// Reads the libraries `libraries` (an OBJ's `mtllib` names,
    /// [`Mesh::material_libraries`](crate::Mesh::material_libraries)) of the OBJ file
    /// `obj` and the textures they name. A library or texture that does not exist is
    /// a note; one outside the OBJ's folder is [`Error::Format`], as a glTF buffer
    /// would be. Cost: the files' sizes.
    pub fn read_for_obj(obj: &Path, libraries: &[String], options: &ReadOptions) -> Result<Materials> {
        let mut out = Materials::default();
        if libraries.is_empty() {
            return Ok(out);
        }
        let folder = Folder::of(obj)?;
        for lib in libraries {
            let Some(text) = folder.read(obj, lib, options, &mut out.notes)? else { continue };
            let text = String::from_utf8_lossy(&text);
            parse(obj, &folder, lib, &text, options, &mut out)?;
        }
        Ok(out)
    }
}

/// Parses one library into `out`.
fn parse(obj: &Path, folder: &Folder, lib: &str, text: &str, options: &ReadOptions, out: &mut Materials) -> Result<()> {
    let mut unused: BTreeMap<String, usize> = BTreeMap::new();
    let mut current: Option<Material> = None;
    // Ks and Ns may come in either order: settled at the end of each material.
    let mut highlight = (false, None::<f32>);
    let finish = |m: Option<Material>, highlight: (bool, Option<f32>), out: &mut Materials| {
        if let Some(mut m) = m {
            if let (true, Some(ns)) = highlight {
                m.roughness = Some((2.0 / (ns.max(0.0) + 2.0)).powf(0.25));
            }
            out.materials.retain(|x| x.name != m.name);
            out.materials.push(m);
        }
    };
    for line in text.lines() {
        let line = line.split('#').next().unwrap_or("").trim();
        let mut words = line.split_whitespace();
        let Some(key) = words.next() else { continue };
        let args: Vec<&str> = words.collect();
        let numbers: Vec<f32> = args.iter().filter_map(|w| w.parse().ok()).collect();
        if key == "newmtl" {
            finish(current.take(), highlight, out);
            current = Some(Material::new(&args.join(" ")));
            highlight = (false, None);
            continue;
        }
        let Some(m) = current.as_mut() else {
            *unused.entry(format!("{key} (before any newmtl)")).or_default() += 1;
            continue;
        };
        match key {
            "Kd" if numbers.len() >= 3 => m.base_color[..3].copy_from_slice(&numbers[..3].iter().map(|x| x.clamp(0.0, 1.0)).collect::<Vec<_>>()),
            "d" if !numbers.is_empty() => m.base_color[3] = numbers[numbers.len() - 1].clamp(0.0, 1.0),
            "Tr" if !numbers.is_empty() => m.base_color[3] = (1.0 - numbers[numbers.len() - 1]).clamp(0.0, 1.0),
            "Ks" if numbers.len() >= 3 => highlight.0 = numbers[..3].iter().any(|&x| x > 0.0),
            "Ns" if !numbers.is_empty() => highlight.1 = Some(numbers[0]),
            "map_Kd" | "map_Bump" | "map_bump" | "bump" | "norm" if !args.is_empty() => {
                // Options (`-bm 1.0`, `-s ...`) come first; the file name is last.
                let uri = args[args.len() - 1];
                let texture = folder.texture(obj, lib, uri, options, &mut out.notes)?;
                if key == "map_Kd" {
                    m.base_color_texture = texture;
                } else {
                    m.normal_texture = texture;
                }
                if args.len() > 1 {
                    *unused.entry(format!("{key} options")).or_default() += 1;
                }
            }
            _ => *unused.entry(key.to_string()).or_default() += 1,
        }
    }
    finish(current.take(), highlight, out);
    if !unused.is_empty() {
        let list: Vec<String> = unused.iter().map(|(k, n)| format!("{k} ({n})")).collect();
        out.notes.push(format!("{lib}: not carried into glTF: {}", list.join(", ")));
    }
    Ok(())
}

/// The OBJ's folder, inside which every library and texture must lie.
struct Folder {
    root: PathBuf,
}

impl Folder {
    fn of(obj: &Path) -> Result<Folder> {
        let parent = match obj.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => Path::new("."),
        };
        let root = std::fs::canonicalize(parent).map_err(|e| Error::Io { path: parent.to_path_buf(), source: e })?;
        Ok(Folder { root })
    }

    fn refusal(obj: &Path, what: &str, name: &str) -> Error {
        Error::Format {
            path: obj.to_path_buf(),
            at: what.to_string(),
            what: format!("must be a relative path inside the OBJ's folder, not {name:?}"),
        }
    }

    /// The bytes of the file `name` (relative to the OBJ's folder), `None` with a
    /// note where it does not exist; refused where it lies outside.
    fn read(&self, obj: &Path, name: &str, options: &ReadOptions, notes: &mut Vec<String>) -> Result<Option<Vec<u8>>> {
        let what = format!("mtllib {name}");
        let refuse = || Folder::refusal(obj, &what, name);
        let first = name.split(['/', '\\']).next().unwrap_or("");
        if first.contains(':') || name.contains('\0') {
            return Err(refuse());
        }
        let mut lexical = self.root.clone();
        for c in Path::new(name).components() {
            match c {
                Component::Normal(part) => lexical.push(part),
                Component::CurDir => {}
                Component::ParentDir => {
                    lexical.pop();
                }
                Component::RootDir | Component::Prefix(_) => return Err(refuse()),
            }
        }
        if !lexical.starts_with(&self.root) {
            return Err(refuse());
        }
        let real = match std::fs::canonicalize(&lexical) {
            Ok(real) => real,
            Err(_) if std::fs::symlink_metadata(&lexical).is_ok() => return Err(refuse()),
            Err(_) => {
                notes.push(format!("{name}: not found beside the OBJ; its materials are left out"));
                return Ok(None);
            }
        };
        if !real.starts_with(&self.root) {
            return Err(refuse());
        }
        let file = std::fs::File::open(&real).map_err(|e| Error::Io { path: real.clone(), source: e })?;
        #[cfg(target_os = "linux")]
        {
            use std::os::unix::io::AsRawFd;
            if let Ok(opened) = std::fs::read_link(format!("/proc/self/fd/{}", file.as_raw_fd())) {
                if !opened.starts_with(&self.root) {
                    return Err(refuse());
                }
            }
        }
        let limit = options.max_external_bytes;
        let mut bytes = Vec::new();
        file.take(limit.saturating_add(1)).read_to_end(&mut bytes).map_err(|e| Error::Io { path: real.clone(), source: e })?;
        if bytes.len() as u64 > limit {
            return Err(Error::Format {
                path: obj.to_path_buf(),
                at: what,
                what: format!("{name} is larger than the {limit} bytes allowed for a file an input names (--max-memory)"),
            });
        }
        Ok(Some(bytes))
    }

    /// A texture named in library `lib` (paths relative to the OBJ's folder, where
    /// the libraries are): PNG and JPEG only, others a note.
    fn texture(&self, obj: &Path, lib: &str, uri: &str, options: &ReadOptions, notes: &mut Vec<String>) -> Result<Option<Texture>> {
        let base = Path::new(lib).parent().unwrap_or(Path::new(""));
        let name = base.join(uri).to_string_lossy().replace('\\', "/");
        let Some(bytes) = self.read(obj, &name, options, notes)? else { return Ok(None) };
        let mime = if bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
            "image/png"
        } else if bytes.starts_with(&[0xff, 0xd8, 0xff]) {
            "image/jpeg"
        } else {
            notes.push(format!("{lib}: {uri} is neither PNG nor JPEG, which glTF takes: left out"));
            return Ok(None);
        };
        Ok(Some(Texture { uri: uri.to_string(), mime, bytes }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn statements_become_pbr_values_and_the_rest_a_note() {
        let dir = stripkit_testkit::scratch_dir("mtl");
        let mtl = "newmtl red\nKd 1 0 0\nd 0.5\nNs 98\nKs 0.5 0.5 0.5\nillum 2\nKa 0 0 0\nnewmtl plain\nKd 0 0 1\nTr 0.25\nKs 0 0 0\nNs 10\n";
        std::fs::write(dir.join("a.mtl"), mtl).unwrap();
        let m = Materials::read_for_obj(&dir.join("m.obj"), &["a.mtl".into(), "missing.mtl".into()], &ReadOptions::default())
            .unwrap();
        let red = m.get("red").unwrap();
        assert_eq!(red.base_color, [1.0, 0.0, 0.0, 0.5]);
        assert!((red.roughness.unwrap() - (2.0f32 / 100.0).powf(0.25)).abs() < 1e-6);
        let plain = m.get("plain").unwrap();
        assert_eq!((plain.base_color, plain.roughness), ([0.0, 0.0, 1.0, 0.75], None));
        assert_eq!(m.notes.len(), 2, "{:?}", m.notes);
        assert!(m.notes.iter().any(|n| n == "a.mtl: not carried into glTF: Ka (1), illum (1)"), "{:?}", m.notes);
        assert!(m.notes.iter().any(|n| n.starts_with("missing.mtl: not found")), "{:?}", m.notes);
        for bad in ["../a.mtl", "/etc/passwd", "file:a.mtl"] {
            let e = Materials::read_for_obj(&dir.join("m.obj"), &[bad.into()], &ReadOptions::default()).unwrap_err();
            assert!(e.to_string().contains("inside the OBJ's folder"), "{bad}: {e}");
        }
        let small = ReadOptions { max_external_bytes: 10, ..ReadOptions::default() };
        assert!(Materials::read_for_obj(&dir.join("m.obj"), &["a.mtl".into()], &small).is_err());
        let _ = std::fs::remove_dir_all(&dir);
    }
}
