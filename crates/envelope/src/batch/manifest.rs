//! The manifest: one JSON object per line, every line checked before any item runs.
//!
//! Keys of an item: `id` (required: 1 to 128 of `A-Z a-z 0-9 . _ -`, not starting with a
//! dot, unique), `input` (required: a mesh file, relative to the manifest's folder), `epsilon`
//! (a number, absolute, or a string such as `"1%"`; required unless the batch has a default
//! or the item has `lod`), `lod` (a list of epsilons: a chain of levels instead of one
//! output), `method`, `placement`, `repair` (a boolean), `format` (`obj`, `off`, `ply`,
//! `stl`: the outputs' format, by default the input's). Any other key is refused, so a typo
//! cannot silently fall back to a default. Blank lines are skipped.

use std::collections::HashMap;
use std::fmt;
use std::path::{Path, PathBuf};

use serde_json::{Map, Value};

pub use crate::error::ManifestError;
use crate::{Epsilon, Method, Placement, defaults};

/// One item of a manifest, checked.
#[derive(Clone, Debug, PartialEq)]
pub struct Item {
    /// Its name: the folder of its outputs under the batch's output folder.
    pub id: String,
    /// The input file as the manifest wrote it.
    pub input_as_written: String,
    /// The input file, relative paths taken from the manifest's folder.
    pub input: PathBuf,
    /// What to make.
    pub job: Job,
    /// The simplification algorithm.
    pub method: Method,
    /// Where output vertices may lie.
    pub placement: Placement,
    /// Repair the input first (without moving its surface).
    pub repair: bool,
    /// The outputs' extension (`obj`, `off`, `ply`, `stl`); `None`: the input's.
    pub format: Option<String>,
    /// Its line in the manifest, from 1.
    pub line: usize,
}

/// What an item makes.
#[derive(Clone, Debug, PartialEq)]
pub enum Job {
    /// One simplification within this epsilon.
    Simplify(Epsilon),
    /// A chain of levels at these epsilons (each a bound to the input).
    Lod(Vec<Epsilon>),
}

/// The keys an item may have.
const KEYS: [&str; 8] = [
    "id",
    "input",
    "epsilon",
    "lod",
    "method",
    "placement",
    "repair",
    "format",
];

/// The output formats an item may ask for.
const FORMATS: [&str; 4] = ["obj", "off", "ply", "stl"];

/// Parses and checks every line of `text`, the manifest at `path` (relative inputs are taken
/// from its folder), as [`Batch::open`](super::Batch::open) does; `epsilon` is the batch's
/// default for items that give none.
///
/// ```
/// use std::path::Path;
/// let text = r#"{"id": "cup", "input": "cup.obj", "epsilon": "1%"}"#;
/// let items = envelope::batch::parse_manifest(text, Path::new("jobs/m.jsonl"), None)?;
/// assert_eq!(items[0].input, Path::new("jobs/cup.obj"));
/// let err = envelope::batch::parse_manifest("{}", Path::new("m.jsonl"), None).unwrap_err();
/// assert_eq!(err.to_string(), "m.jsonl: line 1: `id` is missing");
/// # Ok::<(), envelope::batch::ManifestError>(())
/// ```
///
/// # Errors
/// The first line that cannot be run, with its number and what is wrong.
pub fn parse(
    text: &str,
    path: &Path,
    epsilon: Option<Epsilon>,
) -> Result<Vec<Item>, ManifestError> {
    let base = path.parent().unwrap_or(Path::new(""));
    let mut items: Vec<Item> = Vec::new();
    let mut lines_of: HashMap<String, usize> = HashMap::new();
    for (i, line) in text.lines().enumerate() {
        let n = i + 1;
        if line.trim().is_empty() {
            continue;
        }
        let fail = |message: String| ManifestError {
            manifest: path.to_path_buf(),
            line: n,
            message,
        };
        let item = parse_item(line, base, epsilon, n).map_err(fail)?;
        if let Some(first) = lines_of.insert(item.id.clone(), n) {
            return Err(fail(format!(
                "id {:?} is already the id of line {first}",
                item.id
            )));
        }
        items.push(item);
    }
    if items.is_empty() {
        return Err(ManifestError {
            manifest: path.to_path_buf(),
            line: 0,
            message: "no item (one JSON object per line is expected)".into(),
        });
    }
    Ok(items)
}

fn parse_item(
    line: &str,
    base: &Path,
    default_epsilon: Option<Epsilon>,
    n: usize,
) -> Result<Item, String> {
    let value: Value = serde_json::from_str(line).map_err(|e| format!("not a JSON object: {e}"))?;
    let Value::Object(object) = value else {
        return Err(format!("expected a JSON object, found {}", kind(&value)));
    };
    if let Some(key) = object.keys().find(|k| !KEYS.contains(&k.as_str())) {
        return Err(format!("unknown key {key:?} (known: {})", KEYS.join(", ")));
    }
    let id = string(&object, "id")?.ok_or("`id` is missing")?;
    check_id(&id)?;
    let input_as_written = string(&object, "input")?.ok_or("`input` is missing")?;
    if input_as_written.is_empty() {
        return Err("`input` is empty".into());
    }
    let lod = match object.get("lod") {
        None => None,
        Some(Value::Array(list)) if !list.is_empty() => Some(
            list.iter()
                .enumerate()
                .map(|(i, v)| epsilon(v).map_err(|e| format!("`lod` item {}: {e}", i + 1)))
                .collect::<Result<Vec<_>, _>>()?,
        ),
        Some(other) => {
            return Err(format!(
                "`lod` must be a non-empty list of epsilons, found {}",
                kind(other)
            ));
        }
    };
    let own_epsilon = object
        .get("epsilon")
        .map(|v| epsilon(v).map_err(|e| format!("`epsilon`: {e}")))
        .transpose()?;
    let job = match (lod, own_epsilon) {
        (Some(_), Some(_)) => {
            return Err(
                "`epsilon` and `lod` together: give one (a chain's epsilons are in \
                        `lod`)"
                    .into(),
            );
        }
        (Some(list), None) => Job::Lod(list),
        (None, Some(e)) => Job::Simplify(e),
        (None, None) => Job::Simplify(
            default_epsilon
                .ok_or("`epsilon` is missing (and the batch has no default epsilon: --epsilon)")?,
        ),
    };
    let method = match string(&object, "method")? {
        None => defaults::METHOD,
        Some(s) => Method::parse(&s)
            .ok_or_else(|| format!("`method`: {s:?} is not local, global or hybrid"))?,
    };
    let placement = match string(&object, "placement")? {
        None => defaults::PLACEMENT,
        Some(s) => Placement::parse(&s)
            .ok_or_else(|| format!("`placement`: {s:?} is not subset, slide, collapse or auto"))?,
    };
    let repair = match object.get("repair") {
        None => false,
        Some(Value::Bool(b)) => *b,
        Some(other) => {
            return Err(format!(
                "`repair` must be true or false, found {}",
                kind(other)
            ));
        }
    };
    let format = string(&object, "format")?;
    if let Some(f) = &format
        && !FORMATS.contains(&f.as_str())
    {
        return Err(format!("`format`: {f:?} is not {}", FORMATS.join(", ")));
    }
    Ok(Item {
        input: base.join(&input_as_written),
        id,
        input_as_written,
        job,
        method,
        placement,
        repair,
        format,
        line: n,
    })
}

/// Ids name folders: short, portable, and never `.`/`..` or hidden.
fn check_id(id: &str) -> Result<(), String> {
    let ok_char = |c: char| c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-');
    if id.is_empty() || id.len() > 128 {
        return Err(format!("`id` {id:?} must have 1 to 128 characters"));
    }
    if let Some(c) = id.chars().find(|&c| !ok_char(c)) {
        return Err(format!(
            "`id` {id:?} has {c:?}: ids name folders, so only letters, digits, '.', '_' and '-'"
        ));
    }
    if id.starts_with('.') {
        return Err(format!("`id` {id:?} starts with a dot"));
    }
    if id == super::SUMMARY {
        return Err(format!("`id` {id:?} is the summary's file name"));
    }
    Ok(())
}

fn string(object: &Map<String, Value>, key: &str) -> Result<Option<String>, String> {
    match object.get(key) {
        None => Ok(None),
        Some(Value::String(s)) => Ok(Some(s.clone())),
        Some(other) => Err(format!("`{key}` must be a string, found {}", kind(other))),
    }
}

/// A number is an absolute length; a string has the command line's syntax.
fn epsilon(value: &Value) -> Result<Epsilon, String> {
    let e = match value {
        Value::Number(x) => Epsilon::absolute(x.as_f64().ok_or("not a finite number")?),
        Value::String(s) => s.parse().map_err(|e: crate::Error| e.to_string())?,
        other => {
            return Err(format!(
                "expected a number or a string, found {}",
                kind(other)
            ));
        }
    };
    e.validate().map_err(|e| e.to_string())
}

fn kind(value: &Value) -> Kind<'_> {
    Kind(value)
}

/// A JSON value's kind, for messages.
struct Kind<'a>(&'a Value);

impl fmt::Display for Kind<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self.0 {
            Value::Null => "null",
            Value::Bool(_) => "a boolean",
            Value::Number(_) => "a number",
            Value::String(_) => "a string",
            Value::Array(_) => "a list",
            Value::Object(_) => "an object",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn one(line: &str) -> Result<Item, String> {
        parse(line, Path::new("dir/m.jsonl"), None)
            .map(|mut items| items.remove(0))
            .map_err(|e| e.to_string())
    }

    #[test]
    fn a_full_item_parses() {
        let item = one(
            r#"{"id":"a-1","input":"x.off","epsilon":"1%","method":"hybrid","placement":"subset","repair":true,"format":"ply"}"#,
        )
        .unwrap();
        assert_eq!(item.input, Path::new("dir/x.off"));
        assert_eq!(item.job, Job::Simplify(Epsilon::percent(1.0)));
        assert_eq!(
            (item.method, item.placement, item.repair),
            (Method::Hybrid, Placement::Subset, true)
        );
        let lod = one(r#"{"id":"b","input":"/abs/y.obj","lod":[0.5,"1/64%"]}"#).unwrap();
        assert_eq!(lod.input, Path::new("/abs/y.obj"));
        assert_eq!(
            lod.job,
            Job::Lod(vec![Epsilon::absolute(0.5), Epsilon::percent(1.0 / 64.0)])
        );
    }

    #[test]
    fn every_mistake_is_named_with_its_line() {
        for (line, says) in [
            ("[1]", "expected a JSON object, found a list"),
            ("{", "not a JSON object"),
            (
                r#"{"id":"a","input":"x","epsilon":1,"eps":2}"#,
                "unknown key \"eps\"",
            ),
            (r#"{"input":"x","epsilon":1}"#, "`id` is missing"),
            (
                r#"{"id":"a/b","input":"x","epsilon":1}"#,
                "ids name folders",
            ),
            (
                r#"{"id":"..","input":"x","epsilon":1}"#,
                "starts with a dot",
            ),
            (
                r#"{"id":"summary.jsonl","input":"x","epsilon":1}"#,
                "summary",
            ),
            (r#"{"id":"a","epsilon":1}"#, "`input` is missing"),
            (r#"{"id":"a","input":"x"}"#, "`epsilon` is missing"),
            (r#"{"id":"a","input":"x","epsilon":-1}"#, "positive finite"),
            (r#"{"id":"a","input":"x","epsilon":"big"}"#, "\"big\""),
            (
                r#"{"id":"a","input":"x","epsilon":1,"lod":[1]}"#,
                "together",
            ),
            (r#"{"id":"a","input":"x","lod":[]}"#, "non-empty list"),
            (r#"{"id":"a","input":"x","lod":[1,"x%"]}"#, "`lod` item 2"),
            (
                r#"{"id":"a","input":"x","epsilon":1,"method":"fast"}"#,
                "`method`",
            ),
            (
                r#"{"id":"a","input":"x","epsilon":1,"placement":"move"}"#,
                "`placement`",
            ),
            (
                r#"{"id":"a","input":"x","epsilon":1,"repair":"yes"}"#,
                "`repair`",
            ),
            (
                r#"{"id":"a","input":"x","epsilon":1,"format":"glb"}"#,
                "`format`",
            ),
            (
                r#"{"id":1,"input":"x","epsilon":1}"#,
                "`id` must be a string",
            ),
        ] {
            let text = format!("\n{line}\n");
            let err = one(&text).unwrap_err();
            assert!(
                err.starts_with("dir/m.jsonl: line 2: ") && err.contains(says),
                "{line}: {err}"
            );
        }
    }

    #[test]
    fn duplicate_ids_and_empty_manifests_are_refused() {
        let err = one("{\"id\":\"a\",\"input\":\"x\",\"epsilon\":1}\n{\"id\":\"a\",\"input\":\"y\",\"epsilon\":1}").unwrap_err();
        assert!(
            err.contains("line 2: id \"a\" is already the id of line 1"),
            "{err}"
        );
        assert!(one("\n\n").unwrap_err().contains("no item"));
    }

    #[test]
    fn the_batch_default_epsilon_fills_in() {
        let items = parse(
            r#"{"id":"a","input":"x"}"#,
            Path::new("m.jsonl"),
            Some(Epsilon::percent(2.0)),
        )
        .unwrap();
        assert_eq!(items[0].job, Job::Simplify(Epsilon::percent(2.0)));
    }
}
