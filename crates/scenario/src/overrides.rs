//! `--set PATH=VALUE`: change one field of a scenario without editing the file.
//!
//! PATH is a dotted JSON path (`surface.summit_sd`, `actuators.clamp.plates`); it is checked
//! against the format's JSON Schema, so a misspelt name is an error that lists the near names.
//! VALUE is read as JSON when it parses as JSON (`3`, `true`, `"x"`, `[1,2]`, `{"value": ...}`)
//! and as a string otherwise (`40 nm`).
//!
//! A file path in VALUE (a field the schema marks with [`PATH_KEYWORD`], also inside an object
//! value such as `measured={"voltages_csv": "m.csv"}`) was typed on the command line, so a
//! relative one is relative to the current directory: it is made absolute here. Paths written in
//! the scenario file stay relative to the file's folder.

use serde_json::{Map, Value};

use crate::error::ScenarioError;
use crate::scenario::Scenario;

/// Splits `PATH=VALUE` into the path segments and the JSON value.
pub fn parse_set(set: &str) -> Result<(Vec<String>, Value), ScenarioError> {
    let err = |message: String| ScenarioError::Set { set: set.to_string(), message };
    let (path, raw) =
        set.split_once('=').ok_or_else(|| err("expected PATH=VALUE, like surface.summit_sd=\"40 nm\"".into()))?;
    let path = path.trim();
    if path.is_empty() {
        return Err(err("the PATH before `=` is empty".into()));
    }
    let segments: Vec<String> = path.split('.').map(str::to_string).collect();
    if segments.iter().any(String::is_empty) {
        return Err(err(format!("`{path}` has an empty segment")));
    }
    let raw = raw.trim();
    let value = crate::strict_json::from_str(raw).unwrap_or_else(|_| Value::String(raw.to_string()));
    Ok((segments, value))
}

/// The JSON Schema keyword (`"x-stiction-path": true`) on the fields that hold a file path.
pub const PATH_KEYWORD: &str = "x-stiction-path";

/// Applies one `PATH=VALUE` override to a scenario's JSON, after checking PATH against the schema.
/// A relative file path in VALUE is made absolute against the current directory.
pub fn apply_set(root: &mut Value, set: &str) -> Result<(), ScenarioError> {
    let (segments, mut value) = parse_set(set)?;
    let err = |message: String| ScenarioError::Set { set: set.to_string(), message };
    if segments == ["material", "relative_humidity"] {
        return Err(err(format!("at `material.relative_humidity`: {}", crate::error::RELATIVE_HUMIDITY_MESSAGE)));
    }
    let target = check_path(&segments).map_err(err)?;
    // `PATH=null` removes the field (its default, or the quantity derived instead, applies).
    if value.is_null() {
        let (last, parents) = segments.split_last().ok_or_else(|| err("empty path".into()))?;
        let mut node = &mut *root;
        for seg in parents {
            match node.get_mut(seg.as_str()) {
                Some(next) => node = next,
                None => return Ok(()),
            }
        }
        if let Some(map) = node.as_object_mut() {
            map.remove(last.as_str());
        }
        return Ok(());
    }
    let cwd = std::env::current_dir()
        .map_err(|e| err(format!("cannot read the current directory to resolve a relative path: {e}")))?;
    let defs = Scenario::schema().get("$defs").cloned().unwrap_or(Value::Null);
    absolutize_paths(&mut value, &target, &defs, &cwd);
    let mut node = root;
    for (i, seg) in segments.iter().enumerate() {
        let last = i + 1 == segments.len();
        node = match node {
            Value::Object(map) => {
                if last {
                    map.insert(seg.clone(), value);
                    return Ok(());
                }
                map.entry(seg.clone()).or_insert_with(|| Value::Object(Map::new()))
            }
            Value::Array(items) => {
                let index: usize = seg.parse().map_err(|_| err(format!("`{seg}` is not an index into a list")))?;
                let len = items.len();
                let slot = items
                    .get_mut(index)
                    .ok_or_else(|| err(format!("index {index} is past the end of a list of {len}")))?;
                if last {
                    *slot = value;
                    return Ok(());
                }
                slot
            }
            other => {
                return Err(err(format!("`{}` is {}, not an object", segments[..i].join("."), kind(other))));
            }
        };
    }
    Ok(())
}

/// Makes every relative file path of a whole scenario tree (the fields with [`PATH_KEYWORD`])
/// absolute against `base` (the scenario file's folder): a scenario printed by `stiction scenario`
/// then runs from any folder.
pub fn absolutize_file_paths(root: &mut Value, base: &std::path::Path) {
    let schema = Scenario::schema();
    let defs = schema.get("$defs").cloned().unwrap_or(Value::Null);
    let base = if base.is_relative() {
        std::env::current_dir().map(|d| d.join(base)).unwrap_or_else(|_| base.to_path_buf())
    } else {
        base.to_path_buf()
    };
    absolutize_paths(root, std::slice::from_ref(schema), &defs, &base);
}

fn kind(v: &Value) -> &'static str {
    match v {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "a list",
        Value::Object(_) => "an object",
    }
}

/// Makes every relative path in `value` (where a schema node of `nodes` has [`PATH_KEYWORD`])
/// absolute against `cwd`, walking objects and lists along the schema.
fn absolutize_paths(value: &mut Value, nodes: &[Value], defs: &Value, cwd: &std::path::Path) {
    let nodes = expand(nodes, defs);
    match value {
        Value::String(s) => {
            let is_path = nodes.iter().any(|n| n.get(PATH_KEYWORD).and_then(Value::as_bool) == Some(true));
            if is_path && std::path::Path::new(s.as_str()).is_relative() {
                *s = cwd.join(s.as_str()).to_string_lossy().into_owned();
            }
        }
        Value::Object(map) => {
            for (key, v) in map.iter_mut() {
                let mut child = Vec::new();
                for n in &nodes {
                    if let Some(s) = n.get("properties").and_then(|p| p.get(key)) {
                        child.push(s.clone());
                    }
                    if let Some(s @ Value::Object(_)) = n.get("additionalProperties") {
                        child.push(s.clone());
                    }
                }
                if !child.is_empty() {
                    absolutize_paths(v, &child, defs, cwd);
                }
            }
        }
        Value::Array(items) => {
            let child: Vec<Value> = nodes.iter().filter_map(|n| n.get("items").cloned()).collect();
            if !child.is_empty() {
                for v in items {
                    absolutize_paths(v, &child, defs, cwd);
                }
            }
        }
        _ => {}
    }
}

/// Whether the field at the dotted `path` is typed `integer` in every schema alternative that is
/// not null (see [`Scenario::field_is_integer`]).
pub(crate) fn field_is_integer(path: &str) -> bool {
    let segments: Vec<String> = path.split('.').map(str::to_string).collect();
    let Ok(nodes) = check_path(&segments) else { return false };
    let defs = Scenario::schema().get("$defs").cloned().unwrap_or(Value::Null);
    let types: Vec<Value> = expand(&nodes, &defs)
        .iter()
        .flat_map(|n| match n.get("type") {
            Some(Value::Array(t)) => t.clone(),
            Some(t) => vec![t.clone()],
            None => Vec::new(),
        })
        .filter(|t| t != "null")
        .collect();
    !types.is_empty() && types.iter().all(|t| t == "integer")
}

/// Walks the JSON Schema of [`Scenario`] along `segments`; on a wrong name, lists the near ones.
/// Returns the schema nodes of the target field.
fn check_path(segments: &[String]) -> Result<Vec<Value>, String> {
    let schema = Scenario::schema();
    let defs = schema.get("$defs").cloned().unwrap_or(Value::Null);
    let mut nodes = vec![schema.clone()];
    for (i, seg) in segments.iter().enumerate() {
        let mut next = Vec::new();
        let mut names = Vec::new();
        let mut any_key = false;
        for node in expand(&nodes, &defs) {
            if let Some(props) = node.get("properties").and_then(Value::as_object) {
                names.extend(props.keys().cloned());
                if let Some(s) = props.get(seg) {
                    next.push(s.clone());
                }
            }
            match node.get("additionalProperties") {
                Some(Value::Object(s)) => {
                    any_key = true;
                    next.push(Value::Object(s.clone()));
                }
                Some(Value::Bool(true)) => any_key = true,
                _ => {}
            }
            if let Some(items) = node.get("items").filter(|_| seg.parse::<usize>().is_ok()) {
                next.push(items.clone());
            }
        }
        if next.is_empty() && !any_key {
            let at = if i == 0 { "the top level".to_string() } else { format!("`{}`", segments[..i].join(".")) };
            names.sort();
            names.dedup();
            if names.is_empty() {
                return Err(format!("{at} has no field `{seg}`: it is not an object"));
            }
            let mut near: Vec<&String> = names.iter().collect();
            near.sort_by_key(|n| edit_distance(n, seg));
            let near: Vec<String> = near.iter().take(4).map(|n| format!("`{n}`")).collect();
            return Err(format!("{at} has no field `{seg}`; nearest: {}; all: {}", near.join(", "), names.join(", ")));
        }
        nodes = next;
    }
    Ok(nodes)
}

/// Resolves `$ref`, `anyOf`, `oneOf` and `allOf` into the plain schema objects they stand for.
fn expand(nodes: &[Value], defs: &Value) -> Vec<Value> {
    let mut out = Vec::new();
    let mut stack: Vec<Value> = nodes.to_vec();
    let mut guard = 0;
    while let Some(node) = stack.pop() {
        guard += 1;
        if guard > 10_000 {
            break;
        }
        if let Some(r) = node.get("$ref").and_then(Value::as_str)
            && let Some(name) = r.strip_prefix("#/$defs/")
            && let Some(def) = defs.get(name)
        {
            stack.push(def.clone());
        }
        for key in ["anyOf", "oneOf", "allOf"] {
            if let Some(list) = node.get(key).and_then(Value::as_array) {
                stack.extend(list.iter().cloned());
            }
        }
        out.push(node);
    }
    out
}

/// Levenshtein distance, for suggesting near names.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut cur = vec![i + 1; b.len() + 1];
        for (j, cb) in b.iter().enumerate() {
            cur[j + 1] = (prev[j] + usize::from(ca != *cb)).min(prev[j + 1] + 1).min(cur[j] + 1);
        }
        prev = cur;
    }
    prev[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_parse_as_json_or_as_strings() {
        let (p, v) = parse_set("surface.summit_sd=40 nm").unwrap();
        assert_eq!(p, vec!["surface", "summit_sd"]);
        assert_eq!(v, Value::String("40 nm".into()));
        let (_, v) = parse_set("contact.contacts=3").unwrap();
        assert_eq!(v, Value::from(3));
        assert!(parse_set("no-equals").is_err());
        assert!(parse_set("a..b=1").is_err());
    }

    /// A path typed with --set is relative to the current directory, also inside an object value;
    /// other strings are left alone.
    #[test]
    fn set_paths_are_relative_to_the_current_directory() {
        let cwd = std::env::current_dir().unwrap();
        let mut root = serde_json::json!({"surface": {"apparent_length": "20 um"}});
        apply_set(&mut root, "measured={\"voltages_csv\": \"data/m.csv\"}").unwrap();
        assert_eq!(root["measured"]["voltages_csv"], cwd.join("data/m.csv").to_string_lossy().as_ref());
        apply_set(&mut root, "surface.csv_path=s.csv").unwrap();
        assert_eq!(root["surface"]["csv_path"], cwd.join("s.csv").to_string_lossy().as_ref());
        apply_set(&mut root, "surface.height_map.file=/abs/map.npy").unwrap();
        assert_eq!(root["surface"]["height_map"]["file"], "/abs/map.npy");
        apply_set(&mut root, "surface.summit_sd=40 nm").unwrap();
        assert_eq!(root["surface"]["summit_sd"], "40 nm");
    }

    #[test]
    fn edit_distance_is_levenshtein() {
        assert_eq!(edit_distance("summit_sd", "sumit_sd"), 1);
        assert_eq!(edit_distance("kitten", "sitting"), 3);
    }
}
