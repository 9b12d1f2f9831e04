//! The layer table of ARCHITECTURE.md, enforced: every `crate::` path in a source file of the
//! engine (`crates/dqsym-engine/src`) or of the library (`src`) names a module of a lower layer
//! than the file's own module, or the file's own module. Names re-exported at a crate's top
//! (`crate::Scalar`) are resolved to the module they come from through the crate's `lib.rs`.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The layer table: module name to layer number, read from ARCHITECTURE.md's "Layers" section
/// (rows `| N | `a`, `b` | ... |`).
fn layer_table(root: &Path) -> BTreeMap<String, u32> {
    let text = std::fs::read_to_string(root.join("ARCHITECTURE.md")).expect("ARCHITECTURE.md");
    let section = text
        .split("\n## ")
        .find(|s| s.starts_with("Layers"))
        .expect("ARCHITECTURE.md has a `## Layers` section");
    let mut table = BTreeMap::new();
    for line in section.lines() {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        if cells.len() < 4 {
            continue;
        }
        let Ok(layer) = cells[1].parse::<u32>() else {
            continue;
        };
        for module in cells[2].split(',') {
            let module = module.trim().trim_matches('`');
            assert!(!module.is_empty(), "empty module in layer row: {line}");
            assert!(
                table.insert(module.to_owned(), layer).is_none(),
                "module `{module}` appears twice in the layer table"
            );
        }
    }
    assert!(table.len() >= 8, "the layer table is too short: {table:?}");
    table
}

/// Code without comments: `//` to the end of the line is dropped (no source line of these
/// crates has `//` inside a string where a `crate::` path would follow).
fn code(text: &str) -> String {
    text.lines()
        .map(|l| l.find("//").map_or(l, |i| &l[..i]))
        .collect::<Vec<_>>()
        .join("\n")
}

fn ident(s: &str) -> &str {
    let end = s
        .find(|c: char| !(c.is_alphanumeric() || c == '_'))
        .unwrap_or(s.len());
    &s[..end]
}

/// The first path segment of every item under each `crate::` in `code`: `crate::a::b` gives
/// `a`, `crate::{a, b::c}` gives `a` and `b`.
fn crate_paths(code: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = code;
    while let Some(i) = rest.find("crate::") {
        let dollar = i > 0 && rest.as_bytes()[i - 1] == b'$';
        let after = &rest[i + "crate::".len()..];
        rest = after;
        if dollar {
            continue;
        }
        if let Some(group) = after.strip_prefix('{') {
            let mut depth = 0;
            let mut item_start = true;
            for (k, c) in group.char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => break,
                    '}' => depth -= 1,
                    ',' if depth == 0 => item_start = true,
                    c if item_start && !c.is_whitespace() => {
                        item_start = false;
                        out.push(ident(&group[k..]).to_owned());
                    }
                    _ => {}
                }
            }
        } else {
            out.push(ident(after).to_owned());
        }
    }
    out.retain(|s| !s.is_empty() && s != "self");
    out
}

/// A crate's top-level re-exports: name to the module it comes from, read from the
/// `pub use module::{...};` statements of its `lib.rs` (attributes before them allowed).
fn reexports(lib: &Path) -> BTreeMap<String, String> {
    let text = code(&std::fs::read_to_string(lib).expect("lib.rs"));
    let mut map = BTreeMap::new();
    for stmt in text.split(';') {
        let Some(at) = stmt.find("pub use ") else {
            continue;
        };
        let body = &stmt[at + "pub use ".len()..];
        let module = ident(body).to_owned();
        let tail = &body[module.len()..];
        let names: Vec<&str> = match tail.find('{') {
            Some(b) => tail[b + 1..].trim_end_matches('}').split(',').collect(),
            None => vec![tail.rsplit("::").next().unwrap_or("")],
        };
        for n in names {
            let n = n.trim();
            let name = n.rsplit(" as ").next().unwrap_or(n).trim();
            let name = name.rsplit("::").next().unwrap_or(name);
            if !name.is_empty() && name != "*" {
                map.insert(name.to_owned(), module.clone());
            }
        }
    }
    map
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("source folder") {
        let path = entry.expect("entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn every_crate_import_goes_down_the_layer_table() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let layers = layer_table(root);
    let engine_src = root.join("crates/dqsym-engine/src");
    let engine = reexports(&engine_src.join("lib.rs"));
    let library = reexports(&root.join("src/lib.rs"));
    let mut violations = Vec::new();
    let mut checked = 0;
    for (src, top, fallback) in [
        (engine_src.clone(), &engine, None),
        (root.join("src"), &library, Some(&engine)),
    ] {
        let mut files = Vec::new();
        rust_files(&src, &mut files);
        files.sort();
        for file in files {
            let rel = file.strip_prefix(&src).expect("under src");
            let first = rel.components().next().expect("a component");
            let module = first.as_os_str().to_string_lossy();
            let module = module.trim_end_matches(".rs");
            // lib.rs only declares and re-exports; main.rs, repl.rs, allocator.rs, fast_args.rs
            // and start.rs are the binary, which reaches the library through `dqsym::`.
            if matches!(
                module,
                "lib" | "main" | "repl" | "allocator" | "fast_args" | "start"
            ) {
                continue;
            }
            let own = *layers.get(module).unwrap_or_else(|| {
                panic!(
                    "{}: module `{module}` is not in the layer table",
                    file.display()
                )
            });
            let text = std::fs::read_to_string(&file).expect("source");
            for name in crate_paths(&code(&text)) {
                let target = if layers.contains_key(&name) {
                    name.clone()
                } else if let Some(m) = top.get(&name).or(fallback.and_then(|f| f.get(&name))) {
                    m.clone()
                } else {
                    panic!(
                        "{}: `crate::{name}` is neither a module of the layer table nor a re-export",
                        file.display()
                    )
                };
                let layer = *layers.get(&target).unwrap_or_else(|| {
                    panic!(
                        "{}: module `{target}` is not in the layer table",
                        file.display()
                    )
                });
                checked += 1;
                if target != module && layer >= own {
                    violations.push(format!(
                        "{}: `crate::{name}` reaches `{target}` (layer {layer}) from `{module}` (layer {own})",
                        file.display()
                    ));
                }
            }
        }
    }
    assert!(checked > 100, "only {checked} imports were read");
    assert!(
        violations.is_empty(),
        "imports against the layer table of ARCHITECTURE.md:\n{}",
        violations.join("\n")
    );
}

#[test]
fn the_import_reader_sees_groups_and_paths() {
    let paths =
        crate_paths("use crate::{a, b::{c, d}, e as f};\nlet x = crate::g::h();\n$crate::i");
    assert_eq!(paths, ["a", "b", "e", "g"]);
    let lib = Path::new(env!("CARGO_TARGET_TMPDIR")).join("layers_lib.rs");
    std::fs::write(
        &lib,
        "//! doc\npub mod a;\n#[doc(hidden)]\npub use a::{B as C, d};\npub use e::f::G;\n",
    )
    .expect("write a lib.rs");
    let map = reexports(&lib);
    let map: Vec<(&str, &str)> = map.iter().map(|(k, v)| (&k[..], &v[..])).collect();
    assert_eq!(map, [("C", "a"), ("G", "e"), ("d", "a")]);
    let library = reexports(Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/src/lib.rs"
    )));
    assert_eq!(library.get("Session").map(String::as_str), Some("lang"));
}

/// The engine, and the library without its default `cli` feature, have none of the command
/// line's dependencies (`cargo tree`, normal edges only): python/ and fuzz/ build without them.
#[test]
fn the_library_has_no_command_line_dependencies() {
    let cli = ["clap", "rustyline", "ctrlc", "libmimalloc-sys"];
    for args in [
        &["-p", "dqsym-engine"][..],
        &["-p", "dqsym", "--no-default-features"][..],
        &["-p", "dqsym"][..],
    ] {
        let out = std::process::Command::new(env!("CARGO"))
            .args([
                "tree",
                "--locked",
                "--offline",
                "-e",
                "normal",
                "--prefix",
                "none",
            ])
            .args(args)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .output()
            .expect("cargo runs");
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success(),
            "cargo tree {args:?} failed: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let crates: Vec<&str> = text
            .lines()
            .filter_map(|l| l.split_whitespace().next())
            .collect();
        assert!(
            crates.contains(&"num-bigint"),
            "cargo tree {args:?}:\n{text}"
        );
        let found: Vec<&str> = cli.into_iter().filter(|c| crates.contains(c)).collect();
        if args.len() == 2 && args[1] == "dqsym" {
            // The control: with the default features the binary's dependencies are there.
            assert_eq!(found, cli, "cargo tree {args:?}:\n{text}");
        } else {
            assert!(
                found.is_empty(),
                "cargo tree {args:?} lists {found:?}:\n{text}"
            );
        }
    }
}
