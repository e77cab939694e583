//! Reading and writing scene files.
//!
//! Loading parses with the JSON path of any failure and then validates. Saving writes a temporary
//! file beside the target and renames it over the target, so a crash never leaves half a file.
//! Output is pretty JSON with number arrays kept on one line, byte-identical for equal scenes.

use super::{Scene, SceneError, validate};
use serde_json::Value;
use std::io::Write;
use std::path::{Path, PathBuf};

impl Scene {
    /// Reads, parses and validates the scene in `file`.
    ///
    /// # Errors
    /// [`SceneError::Io`] when the file cannot be read, [`SceneError::Parse`] for malformed JSON or
    /// a wrong shape (with the JSON path), [`SceneError::Invalid`] when a rule of the format is broken.
    pub fn load(file: impl AsRef<Path>) -> Result<Scene, SceneError> {
        let file = file.as_ref();
        let text = std::fs::read_to_string(file).map_err(|error| SceneError::Io { file: file.to_path_buf(), error })?;
        Scene::from_json(&text, file)
    }

    /// The scene files under `dir`, recursively and sorted: every `.json` but a dataset's
    /// `stats.json` and `calibration.json`. Reads nothing inside them.
    ///
    /// # Errors
    /// [`SceneError::Io`] naming the folder that cannot be read.
    pub fn files_in(dir: &Path) -> Result<Vec<PathBuf>, SceneError> {
        let mut out = Vec::new();
        let mut stack = vec![dir.to_path_buf()];
        while let Some(d) = stack.pop() {
            let io = |error| SceneError::Io { file: d.clone(), error };
            for entry in std::fs::read_dir(&d).map_err(io)? {
                let p = entry.map_err(io)?.path();
                let meta = p.file_name().is_some_and(|n| n == "stats.json" || n == "calibration.json");
                if p.is_dir() {
                    stack.push(p);
                } else if p.extension().is_some_and(|x| x == "json") && !meta {
                    out.push(p);
                }
            }
        }
        out.sort();
        Ok(out)
    }

    /// Parses and validates scene JSON; `origin` names the source in errors.
    ///
    /// # Errors
    /// As [`Scene::load`], without the I/O case.
    pub fn from_json(text: &str, origin: &Path) -> Result<Scene, SceneError> {
        let de = &mut serde_json::Deserializer::from_str(text);
        let parse_error = |path: String, inner: serde_json::Error| {
            let message = match (inner.is_eof(), text.trim().is_empty()) {
                (true, true) => "the file is empty".to_string(),
                (true, false) => format!("the file ends inside the document ({})", strip_position(&inner.to_string())),
                (false, _) => strip_position(&inner.to_string()),
            };
            SceneError::Parse { file: origin.to_path_buf(), path, message, line: inner.line(), column: inner.column() }
        };
        let scene: Scene = serde_path_to_error::deserialize(&mut *de).map_err(|e| {
            let path = failed_path(&e);
            parse_error(path, e.into_inner())
        })?;
        // Only whitespace may follow the document: a scene with bytes after it is not one scene.
        de.end().map_err(|e| parse_error(String::new(), e))?;
        let problems = validate(&scene);
        if problems.is_empty() { Ok(scene) } else { Err(SceneError::Invalid { file: origin.to_path_buf(), problems }) }
    }

    /// The scene as JSON text (see the module header for the layout).
    pub fn to_json(&self) -> String {
        let value = serde_json::to_value(self).expect("a scene always serialises");
        let mut out = String::new();
        write_value(&mut out, &value, 0);
        out.push('\n');
        out
    }

    /// Validates the scene and writes it atomically to `file`.
    ///
    /// # Errors
    /// [`SceneError::Invalid`] for a scene that breaks the format (nothing is written),
    /// [`SceneError::Io`] when writing fails (the previous file, if any, is untouched).
    pub fn save(&self, file: impl AsRef<Path>) -> Result<(), SceneError> {
        let file = file.as_ref();
        let problems = validate(self);
        if !problems.is_empty() {
            return Err(SceneError::Invalid { file: file.to_path_buf(), problems });
        }
        write_atomic(file, self.to_json().as_bytes())
            .map_err(|error| SceneError::Io { file: file.to_path_buf(), error })
    }
}

/// Writes `bytes` to a temporary file next to `file`, syncs it and renames it over `file`.
///
/// # Errors
/// Any I/O error; the temporary file is removed and `file` keeps its previous content.
pub fn write_atomic(file: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let dir = match file.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let name = file.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let tmp = dir.join(format!(".{name}.{}.tmp", std::process::id()));
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        std::fs::rename(&tmp, file)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// The JSON path of the value a parse failed at, empty for the document itself: serde_path_to_error
/// names a value it never reached (a syntax error, a document cut short) `?`.
pub(crate) fn failed_path<E>(error: &serde_path_to_error::Error<E>) -> String {
    let path = error.path().to_string();
    if path == "?" { String::new() } else { path }
}

/// serde_json appends " at line L column C"; the error carries those separately.
fn strip_position(message: &str) -> String {
    match message.rfind(" at line ") {
        Some(i) => message[..i].to_string(),
        None => message.to_string(),
    }
}

/// Pretty-prints like serde_json, except that arrays holding only numbers (or arrays of numbers)
/// stay on one line: a frame of 19 joints is one line, not 76.
fn write_value(out: &mut String, value: &Value, indent: usize) {
    match value {
        Value::Array(items) if items.iter().all(is_flat) => {
            out.push_str(&serde_json::to_string(value).expect("JSON values serialise"));
        }
        Value::Array(items) => {
            write_container(out, '[', ']', indent, items.iter().map(|v| (None, v)));
        }
        Value::Object(map) => {
            write_container(out, '{', '}', indent, map.iter().map(|(k, v)| (Some(k), v)));
        }
        scalar => out.push_str(&serde_json::to_string(scalar).expect("JSON values serialise")),
    }
}

fn write_container<'a>(
    out: &mut String,
    open: char,
    close: char,
    indent: usize,
    items: impl ExactSizeIterator<Item = (Option<&'a String>, &'a Value)>,
) {
    if items.len() == 0 {
        out.push(open);
        out.push(close);
        return;
    }
    out.push(open);
    let n = items.len();
    for (i, (key, v)) in items.enumerate() {
        out.push('\n');
        out.push_str(&"  ".repeat(indent + 1));
        if let Some(k) = key {
            out.push_str(&serde_json::to_string(k).expect("strings serialise"));
            out.push_str(": ");
        }
        write_value(out, v, indent + 1);
        if i + 1 < n {
            out.push(',');
        }
    }
    out.push('\n');
    out.push_str(&"  ".repeat(indent));
    out.push(close);
}

fn is_flat(v: &Value) -> bool {
    match v {
        Value::Number(_) => true,
        Value::Array(items) => items.iter().all(|x| matches!(x, Value::Number(_))),
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scene_files_are_found_below_a_folder_in_order_without_a_datasets_own_files() {
        let dir = tempfile::tempdir().unwrap();
        let root = dir.path();
        std::fs::create_dir(root.join("val")).unwrap();
        for name in ["b.json", "a.json", "stats.json", "calibration.json", "notes.txt", "val/c.json"] {
            std::fs::write(root.join(name), "{}").unwrap();
        }
        let found = Scene::files_in(root).unwrap();
        assert_eq!(found, vec![root.join("a.json"), root.join("b.json"), root.join("val/c.json")]);
        let missing = root.join("none");
        match Scene::files_in(&missing) {
            Err(SceneError::Io { file, .. }) => assert_eq!(file, missing),
            other => panic!("{other:?}"),
        }
    }
}
