//! The hand-written header `include/stripkit.h` against the Rust side: every exported
//! function's name, parameter names and types and return type, the `#[repr(C)]`
//! structs' fields, and the status and algorithm enums' values. A C compiler then checks
//! the header itself (scripts/test builds the examples and the sanitizer test with
//! -Wall -Werror).

use std::collections::BTreeMap;
use std::path::Path;

/// A declaration: its name and (type, name) pairs (parameters or fields) and its return type.
#[derive(Debug, PartialEq)]
struct Decl {
    ret: String,
    items: Vec<(String, String)>,
}

fn crate_dir() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn header() -> String {
    std::fs::read_to_string(crate_dir().join("include/stripkit.h")).unwrap()
}

fn rust_sources() -> String {
    let mut all = String::new();
    let mut files: Vec<_> = std::fs::read_dir(crate_dir().join("src")).unwrap().map(|e| e.unwrap().path()).collect();
    files.sort();
    for f in files {
        for line in std::fs::read_to_string(f).unwrap().lines() {
            let code = line.split("//").next().unwrap();
            all.push_str(code);
            all.push('\n');
        }
    }
    all
}

/// C text without comments or preprocessor lines, whitespace collapsed.
fn c_code(text: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(start) = rest.find("/*") {
        out.push_str(&rest[..start]);
        rest = &rest[start + 2..];
        rest = &rest[rest.find("*/").expect("unclosed comment") + 2..];
    }
    out.push_str(rest);
    let lines: Vec<&str> = out.lines().filter(|l| !l.trim_start().starts_with('#')).collect();
    let joined = lines.join(" ").replace("extern \"C\" {", " ").replace('}', " } ");
    joined.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// `const unsigned int * x` -> ("const unsigned int*", "x").
fn c_pair(decl: &str) -> (String, String) {
    let decl = decl.trim().replace(" *", "*").replace("* ", "*");
    let split = decl.rfind(['*', ' ']).expect("a type and a name");
    let (ty, name) = decl.split_at(split + 1);
    (ty.trim().to_string(), name.trim().to_string())
}

fn c_structs(code: &str) -> BTreeMap<String, Decl> {
    let mut out = BTreeMap::new();
    for part in code.split("typedef struct ").skip(1) {
        let Some(open) = part.find('{') else { continue };
        let name = part[..open].trim().to_string();
        let body = &part[open + 1..part.find('}').unwrap()];
        let items = body.split(';').filter(|f| !f.trim().is_empty()).map(c_pair).collect();
        // Structs return nothing: "void" against the Rust side's "" (no return type).
        out.insert(name, Decl { ret: "void".into(), items });
    }
    out
}

fn c_functions(code: &str) -> BTreeMap<String, Decl> {
    let mut out = BTreeMap::new();
    for statement in code.split(';') {
        // What follows the last closing brace: struct and enum bodies come before it.
        let s = statement.rsplit('}').next().unwrap().trim();
        if s.starts_with("typedef") || !s.contains('(') {
            continue;
        }
        let open = s.find('(').unwrap();
        let (ret, name) = c_pair(&s[..open]);
        let params = s[open + 1..s.rfind(')').unwrap()].trim();
        let items = if params == "void" { Vec::new() } else { params.split(',').map(c_pair).collect() };
        out.insert(name, Decl { ret, items });
    }
    out
}

/// The C spellings a Rust type may have in the header.
fn c_types(rust: &str) -> Vec<String> {
    let rust = rust.trim();
    if let Some(inner) = rust.strip_prefix("*const ") {
        return c_types(inner).into_iter().map(|t| format!("const {t}*")).collect();
    }
    if let Some(inner) = rust.strip_prefix("*mut ") {
        return c_types(inner).into_iter().map(|t| format!("{t}*")).collect();
    }
    let names: &[&str] = match rust {
        "u32" => &["unsigned int", "uint32_t"],
        "u16" => &["unsigned short", "uint16_t"],
        "i32" => &["int", "int32_t"],
        "i64" => &["int64_t"],
        "u64" => &["uint64_t"],
        "usize" => &["size_t"],
        "f32" => &["float"],
        "f64" => &["double"],
        "c_void" | "" => &["void"],
        "c_char" => &["char"],
        other if other.starts_with("stripkit_") => return vec![other.to_string()],
        other => panic!("no C spelling for the Rust type {other}"),
    };
    names.iter().map(|s| s.to_string()).collect()
}

fn rust_pair(item: &str) -> (String, String) {
    let item = item.trim().trim_start_matches("pub ");
    let (name, ty) = item.split_once(':').expect("name: type");
    (ty.trim().to_string(), name.trim().to_string())
}

fn rust_functions(src: &str) -> BTreeMap<String, Decl> {
    let mut out = BTreeMap::new();
    for part in src.split("extern \"C\" fn ").skip(1) {
        let open = part.find('(').unwrap();
        let name = part[..open].trim().to_string();
        let close = part.find(')').unwrap();
        let params = part[open + 1..close].trim();
        let items = params.split(',').filter(|p| !p.trim().is_empty()).map(rust_pair).collect();
        let tail = &part[close + 1..part.find('{').unwrap()];
        let ret = tail.trim().strip_prefix("->").unwrap_or("").trim().to_string();
        out.insert(name, Decl { ret, items });
    }
    out
}

fn rust_structs(src: &str) -> BTreeMap<String, Decl> {
    let mut out = BTreeMap::new();
    for part in src.split("#[repr(C)]").skip(1) {
        let Some(at) = part.find("pub struct ") else { continue };
        let rest = &part[at + "pub struct ".len()..];
        let open = rest.find('{').unwrap();
        let name = rest[..open].trim().to_string();
        let body = &rest[open + 1..rest.find('}').unwrap()];
        let items = body.split(',').filter(|f| f.contains(':')).map(rust_pair).collect();
        out.insert(name, Decl { ret: String::new(), items });
    }
    out
}

fn same(what: &str, name: &str, rust: &Decl, c: &Decl) {
    assert!(
        c_types(&rust.ret).contains(&c.ret),
        "{what} {name}: returns {} in Rust but {} in the header",
        rust.ret,
        c.ret
    );
    assert_eq!(rust.items.len(), c.items.len(), "{what} {name}: {:?} in Rust, {:?} in the header", rust.items, c.items);
    for ((rt, rn), (ct, cn)) in rust.items.iter().zip(&c.items) {
        assert_eq!(rn, cn, "{what} {name}: names differ");
        assert!(c_types(rt).contains(ct), "{what} {name}.{rn}: {rt} in Rust but {ct} in the header");
    }
}

#[test]
fn every_function_matches_the_header() {
    let rust = rust_functions(&rust_sources());
    let c = c_functions(&c_code(&header()));
    assert_eq!(rust.keys().collect::<Vec<_>>(), c.keys().collect::<Vec<_>>(), "exported functions differ");
    assert_eq!(rust.len(), 19);
    for (name, decl) in &rust {
        same("function", name, decl, &c[name]);
    }
}

#[test]
fn every_struct_matches_the_header() {
    let rust = rust_structs(&rust_sources());
    let c = c_structs(&c_code(&header()));
    assert_eq!(rust.keys().collect::<Vec<_>>(), vec!["stripkit_mesh_result", "stripkit_options"]);
    assert_eq!(rust.keys().collect::<Vec<_>>(), c.keys().collect::<Vec<_>>());
    for (name, decl) in &rust {
        same("struct", name, decl, &c[name]);
    }
}

/// `NAME = value` pairs of the header's enums.
fn c_constants(code: &str) -> BTreeMap<String, i64> {
    let mut out = BTreeMap::new();
    for part in code.split("typedef enum ").skip(1) {
        let body = &part[part.find('{').unwrap() + 1..part.find('}').unwrap()];
        for item in body.split(',') {
            let (name, value) = item.split_once('=').unwrap();
            out.insert(name.trim().to_string(), value.trim().parse().unwrap());
        }
    }
    out
}

#[test]
fn status_and_algorithm_values_match() {
    let c = c_constants(&c_code(&header()));
    let src = rust_sources();
    let body = src.split("pub enum Status {").nth(1).unwrap().split('}').next().unwrap();
    let mut statuses = 0;
    for item in body.split(',').filter(|i| i.contains('=')) {
        let (name, value) = item.split_once('=').unwrap();
        let mut snake = String::new();
        for (i, ch) in name.trim().chars().enumerate() {
            if ch.is_uppercase() && i > 0 {
                snake.push('_');
            }
            snake.push(ch.to_ascii_uppercase());
        }
        let value: i64 = value.trim().parse().unwrap();
        let c_name = if value == 0 { format!("STRIPKIT_{snake}") } else { format!("STRIPKIT_ERROR_{snake}") };
        assert_eq!(c.get(&c_name), Some(&value), "{c_name}");
        statuses += 1;
    }
    assert_eq!(statuses, 9);
    for (i, name) in libstripkit::Algorithm::NAMES.iter().enumerate() {
        let c_name = format!("STRIPKIT_ALGORITHM_{}", name.to_uppercase().replace('-', "_"));
        assert_eq!(c.get(&c_name), Some(&(i as i64)), "{c_name}");
    }
    assert_eq!(c["STRIPKIT_JOIN_RESTART"], 0);
    assert_eq!(c["STRIPKIT_JOIN_DEGENERATE"], 1);
    assert_eq!(c.len(), 9 + libstripkit::Algorithm::NAMES.len() + 2);
}
