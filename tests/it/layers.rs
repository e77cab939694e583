//! The crate's layers as docs/ARCHITECTURE.md draws them: every `crate::<module>` path in a
//! module's non-test code must name a module it may depend on. A forbidden import fails here with
//! the file that has it; an exception that is no longer needed fails too, so the list stays true.

use super::root;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// The base every module above it may use.
const BASE: &[&str] = &["scene", "geom", "human", "furniture", "measure", "physics"];

/// What each module may import (`cli`, `main` and `lib` may import anything).
fn allowed(module: &str) -> Option<Vec<&'static str>> {
    let above_base = |extra: &[&'static str]| BASE.iter().chain(extra).copied().collect();
    Some(match module {
        "geom" | "alloc_tuning" => vec![],
        "scene" => vec!["geom"],
        "human" | "furniture" | "physics" => vec!["geom", "scene"],
        "measure" => vec!["geom", "scene", "human", "furniture"],
        "motion" => vec!["geom", "scene", "human"],
        "data" => above_base(&[]),
        "generator" | "repair" | "sim" | "eval" | "export" => above_base(&["data"]),
        "pipeline" => above_base(&["data", "generator", "repair", "sim", "motion"]),
        "lib" | "cli" | "main" => return None,
        other => panic!("src/{other}: a module this test does not know; give it a layer"),
    })
}

/// Imports that break the layers today, each with why; to be cut (docs/ARCHITECTURE.md).
const EXCEPTIONS: &[(&str, &str, &str)] =
    &[("sim", "export", "the MuJoCo replay loads the MJCF export (feature mujoco)")];

/// A module's name from its path under `src/` (the folder `gen` is the module `generator`).
fn module_of(rel: &Path) -> String {
    let first = rel.components().next().unwrap().as_os_str().to_string_lossy().into_owned();
    let name = first.trim_end_matches(".rs").to_string();
    if name == "gen" { "generator".into() } else { name }
}

/// The `crate::<module>` names used in `text` before its unit tests.
fn imports(text: &str) -> BTreeSet<String> {
    let code = text.split("#[cfg(test)]\nmod tests").next().unwrap();
    let mut out = BTreeSet::new();
    for (i, _) in code.match_indices("crate::") {
        let rest = &code[i + "crate::".len()..];
        let name: String = rest.chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '_').collect();
        let line_start = code[..i].rfind('\n').map_or(0, |n| n + 1);
        let line = code[line_start..i].trim_start();
        // Doc links and comments name modules without importing them.
        if !line.starts_with("//") && !name.is_empty() {
            out.insert(name);
        }
    }
    out
}

fn rust_files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn every_module_imports_only_what_its_layer_allows() {
    let src = root().join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    files.sort();
    let mut used: BTreeMap<(String, String), String> = BTreeMap::new();
    let mut broken = Vec::new();
    for file in &files {
        let rel = file.strip_prefix(&src).unwrap();
        let module = module_of(rel);
        let Some(may) = allowed(&module) else { continue };
        // A folder's own unit-test files are test code.
        if rel.file_name().is_some_and(|n| n == "tests.rs") {
            continue;
        }
        for target in imports(&std::fs::read_to_string(file).unwrap()) {
            if target == module {
                continue;
            }
            let excepted = EXCEPTIONS.iter().any(|(f, t, _)| *f == module && *t == target);
            if !may.contains(&target.as_str()) && !excepted {
                broken.push(format!("src/{}: {module} imports {target}", rel.display()));
            }
            used.entry((module.clone(), target)).or_insert_with(|| rel.display().to_string());
        }
    }
    assert!(broken.is_empty(), "forbidden imports:\n{}", broken.join("\n"));
    for (from, to, why) in EXCEPTIONS {
        assert!(
            used.contains_key(&(from.to_string(), to.to_string())),
            "the exception {from} → {to} ({why}) is no longer needed: remove it from EXCEPTIONS"
        );
    }
    // The rules themselves: the generator sees neither repair, sim, eval nor export (but the
    // listed exception), repair sees neither the generator, sim nor eval.
    for (from, to) in [
        ("generator", "repair"),
        ("generator", "sim"),
        ("generator", "eval"),
        ("repair", "generator"),
        ("repair", "sim"),
        ("repair", "eval"),
    ] {
        assert!(!used.contains_key(&(from.to_string(), to.to_string())), "{from} imports {to}");
    }
}

#[test]
fn the_import_reader_sees_uses_and_skips_comments_and_unit_tests() {
    let text = "use crate::geom::OBox;\n/// See [`crate::sim`].\nfn f() { crate::eval::x(); }\n#[cfg(test)]\nmod tests {\n    use crate::data::y;\n}\n";
    assert_eq!(imports(text), ["eval", "geom"].iter().map(|s| s.to_string()).collect());
}
