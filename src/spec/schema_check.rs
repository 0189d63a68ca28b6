//! Schema check: the spec as JSON + the committed JSON schema → one diagnostic per violation.
//!
//! The instance is validated with a real JSON-schema validator against
//! `schemas/cityspec.schema.json` as committed (embedded at compile time), so what editors
//! check with that file and what `cityspec` checks are the same rules. Each validator error
//! is turned into an "expected …, found …" message pointing at the offending key or value.

use std::sync::LazyLock;

use jsonschema::error::TypeKind;
use jsonschema::error::ValidationErrorKind;
use jsonschema::{ValidationError, Validator};
use serde_json::Value;

use super::closest::closest;
use super::diagnostic::Diagnostic;
use super::key_path::{KeyPath, Segment};
use super::locator::Locator;
use super::toml_json::{describe, show};

/// The schema file as committed; a test keeps it equal to what the types generate.
pub(crate) const COMMITTED_SCHEMA: &str = include_str!("../../schemas/cityspec.schema.json");

struct CompiledSchema {
    document: Value,
    validator: Result<Validator, String>,
}

static SCHEMA: LazyLock<CompiledSchema> =
    LazyLock::new(|| match serde_json::from_str::<Value>(COMMITTED_SCHEMA) {
        Ok(document) => {
            let validator = jsonschema::draft202012::new(&document).map_err(|e| e.to_string());
            CompiledSchema {
                document,
                validator,
            }
        }
        Err(e) => CompiledSchema {
            document: Value::Null,
            validator: Err(e.to_string()),
        },
    });

/// Every schema violation of `instance`, except at `skip` (values already reported).
pub(crate) fn check(
    instance: &Value,
    locator: &Locator<'_>,
    text: &str,
    skip: &[KeyPath],
) -> Vec<Diagnostic> {
    let validator = match &SCHEMA.validator {
        Ok(v) => v,
        Err(e) => {
            return vec![Diagnostic::new(
                text,
                0..0,
                "",
                format!("internal error: the committed schema does not compile: {e}"),
            )];
        }
    };
    let mut out = Vec::new();
    let errors: Vec<(ValidationError<'_>, KeyPath)> = validator
        .iter_errors(instance)
        .map(|error| {
            let path = locator.pointer_path(error.instance_path().as_str());
            (error, path)
        })
        .filter(|(_, path)| !skip.contains(path))
        .collect();
    // A key that does not apply to its object's kind is reported as that alone, not also
    // for the value it holds.
    let refused: Vec<&KeyPath> = errors
        .iter()
        .filter(|(error, _)| matches!(error.kind(), ValidationErrorKind::FalseSchema))
        .map(|(_, path)| path)
        .collect();
    for (error, path) in &errors {
        let refused_value = !matches!(error.kind(), ValidationErrorKind::FalseSchema)
            && refused.iter().any(|r| path.0.starts_with(&r.0));
        if !refused_value {
            diagnose(error, path, locator, text, &mut out);
        }
    }
    out
}

fn diagnose(
    error: &ValidationError<'_>,
    path: &KeyPath,
    locator: &Locator<'_>,
    text: &str,
    out: &mut Vec<Diagnostic>,
) {
    let subschema = schema_parent(error.schema_path().as_str());
    let at_value = |message: String| Diagnostic::new(text, locator.span(path), path, message);
    let diagnostic = match error.kind() {
        ValidationErrorKind::AdditionalProperties { unexpected } => {
            let known = known_keys(subschema);
            for key in unexpected {
                let key_path = path.key(key);
                let message = unknown_key_message(key, &known);
                out.push(Diagnostic::new(
                    text,
                    locator.key_span(&key_path),
                    key_path,
                    message,
                ));
            }
            return;
        }
        ValidationErrorKind::Required { property } => {
            let name = property.as_str().unwrap_or_default();
            let place = if path.0.is_empty() {
                "at the top level".to_string()
            } else {
                format!("in [{path}]")
            };
            Diagnostic::new(
                text,
                locator.span(path),
                path.key(name),
                format!("expected a `{name}` key {place}, found none"),
            )
        }
        ValidationErrorKind::Type { kind } => {
            let found = locator
                .value(path)
                .map_or_else(|| "nothing".to_string(), |v| describe(v.get_ref()));
            at_value(format!("expected {}, found {found}", type_kind_noun(kind)))
        }
        // The only `false` schemas are the per-kind rules of `[[objects]]` (`kind_rules`).
        ValidationErrorKind::FalseSchema => Diagnostic::new(
            text,
            locator.key_span(path),
            path,
            inapplicable_key_message(path, locator),
        ),
        _ => at_value(value_message(error, subschema, path, locator)),
    };
    out.push(diagnostic);
}

/// "expected …, found …" for a value the schema refuses: out of bounds, too many or too
/// few, not matching a pattern, not one of the options or the constant.
fn value_message(
    error: &ValidationError<'_>,
    subschema: Option<&Value>,
    path: &KeyPath,
    locator: &Locator<'_>,
) -> String {
    let found = || {
        locator
            .value(path)
            .map_or_else(|| "nothing".to_string(), |v| show(v.get_ref()))
    };
    let noun = || type_noun(subschema.and_then(|s| s.get("type")));
    let expected = |what: String| value_hint(path).map_or(what, str::to_string);
    let bound = |what: String| format!("expected {}, found {}", expected(what), found());
    match error.kind() {
        ValidationErrorKind::Minimum { limit } => bound(format!("{} at least {limit}", noun())),
        ValidationErrorKind::Maximum { limit } => bound(format!("{} at most {limit}", noun())),
        ValidationErrorKind::ExclusiveMinimum { limit } => {
            bound(format!("{} greater than {limit}", noun()))
        }
        ValidationErrorKind::ExclusiveMaximum { limit } => {
            bound(format!("{} less than {limit}", noun()))
        }
        ValidationErrorKind::MinItems { limit } => format!(
            "expected at least {} in the array, found {}",
            items(*limit),
            found()
        ),
        ValidationErrorKind::MaxItems { limit } => format!(
            "expected at most {} in the array, found {}",
            items(*limit),
            found()
        ),
        ValidationErrorKind::MinLength { limit: 1 } => {
            format!("expected a non-empty string, found {}", found())
        }
        ValidationErrorKind::MinLength { limit } => format!(
            "expected a string of at least {limit} characters, found {}",
            found()
        ),
        ValidationErrorKind::MaxLength { limit } => format!(
            "expected a string of at most {limit} characters, found {}",
            found()
        ),
        ValidationErrorKind::Pattern { pattern } => {
            format!("expected {}, found {}", pattern_noun(pattern), found())
        }
        ValidationErrorKind::Enum { options } => enum_message(options, path, locator, found()),
        ValidationErrorKind::Constant { expected_value } => {
            format!("expected {expected_value}, found {}", found())
        }
        _ => format!("expected a value the schema allows: {error}"),
    }
}

/// "expected one of …, found …", with the nearest option when one is near.
fn enum_message(options: &Value, path: &KeyPath, locator: &Locator<'_>, found: String) -> String {
    let listed = match options.as_array() {
        Some(items) => items
            .iter()
            .map(|o| o.to_string())
            .collect::<Vec<_>>()
            .join(", "),
        None => options.to_string(),
    };
    let mut message = format!("expected one of {listed}, found {found}");
    if let Some(near) = closest_option(locator, path, options) {
        message.push_str(&format!(" (did you mean \"{near}\"?)"));
    }
    message
}

/// The subschema holding the failed keyword (`/$defs/GenerateSpec/properties/width/maximum`
/// → the `width` subschema).
fn schema_parent(schema_path: &str) -> Option<&'static Value> {
    let parent = schema_path.rsplit_once('/').map_or("", |(p, _)| p);
    SCHEMA.document.pointer(parent)
}

fn known_keys(subschema: Option<&Value>) -> Vec<&str> {
    subschema
        .and_then(|s| s.get("properties"))
        .and_then(Value::as_object)
        .map(|p| p.keys().map(String::as_str).collect())
        .unwrap_or_default()
}

fn unknown_key_message(key: &str, known: &[&str]) -> String {
    let list = known
        .iter()
        .map(|k| format!("`{k}`"))
        .collect::<Vec<_>>()
        .join(", ");
    let mut message = format!("expected one of {list}, found unknown key `{key}`");
    if let Some(near) = closest(key, known.iter().copied()) {
        message.push_str(&format!(" (did you mean `{near}`?)"));
    }
    message
}

/// Why the key at `path` (`objects[2].model`) may not be written for its table's `kind`.
fn inapplicable_key_message(path: &KeyPath, locator: &Locator<'_>) -> String {
    let (key, table) = match path.0.split_last() {
        Some((Segment::Key(key), table)) => (key.as_str(), KeyPath(table.to_vec())),
        _ => return "expected no value here, found one".to_string(),
    };
    let kind = match locator.value(&table.key("kind")).map(|v| v.get_ref()) {
        Some(toml::de::DeValue::String(kind)) => format!("kind \"{kind}\""),
        _ => "this kind".to_string(),
    };
    let applies = match super::object_spec::kinds_of_key(key) {
        Some(kinds) => {
            let names: Vec<String> = kinds.iter().map(|k| format!("\"{}\"", k.name())).collect();
            let plural = if names.len() == 1 { "kind" } else { "kinds" };
            let listed = match names.split_last() {
                Some((last, [])) => last.clone(),
                Some((last, rest)) => format!("{} and {last}", rest.join(", ")),
                None => String::new(),
            };
            format!(", which applies only to {plural} {listed}")
        }
        None => String::new(),
    };
    format!("expected only keys that apply to {kind}, found `{key}`{applies}")
}

/// The allowed string nearest to the string written at `path`, when it is near enough to
/// be a typo (as [`closest`] judges for unknown keys).
fn closest_option<'v>(
    locator: &Locator<'_>,
    path: &KeyPath,
    options: &'v Value,
) -> Option<&'v str> {
    let written = locator.value(path)?;
    let toml::de::DeValue::String(written) = written.get_ref() else {
        return None;
    };
    let allowed = options.as_array()?.iter().filter_map(Value::as_str);
    closest(written, allowed)
}

/// A friendlier "expected" for values whose range has a meaning beyond the numbers.
fn value_hint(path: &KeyPath) -> Option<&'static str> {
    match path.0.as_slice() {
        [
            Segment::Key(layout),
            Segment::Key(mirror),
            Segment::Index(_),
        ] if layout == "layout" && mirror == "mirror" => {
            Some("a mirror operation 1, 2 or 3 (1 flips vertically, 2 horizontally, 3 both)")
        }
        [Segment::Key(version)] if version == "version" => Some("version 1"),
        _ => None,
    }
}

fn pattern_noun(pattern: &str) -> String {
    match pattern {
        "^#[0-9a-fA-F]{6}$" => "a colour written \"#rrggbb\", like \"#80a0ff\"".to_string(),
        p if p.starts_with("^[A-Za-z0-9][A-Za-z0-9_.-]") => {
            "a name of letters, digits, '_', '.' and '-' (at most 64, starting with a letter or digit)"
                .to_string()
        }
        "^[A-Za-z0-9][A-Za-z0-9_-]{0,63}$" => "a camera name of letters, digits, '_' and '-' \
                                                (at most 64, starting with a letter or digit; \
                                                no '.', where a WebDataset sample's key ends)"
            .to_string(),
        p => format!("a string matching `{p}`"),
    }
}

fn items(n: u64) -> String {
    if n == 1 {
        "1 item".to_string()
    } else {
        format!("{n} items")
    }
}

fn type_noun(ty: Option<&Value>) -> &'static str {
    match ty.and_then(Value::as_str) {
        Some("integer") => "an integer",
        Some("number") => "a number",
        Some("string") => "a string",
        Some("array") => "an array",
        Some("object") => "a table",
        Some("boolean") => "a boolean",
        _ => "a value",
    }
}

fn type_kind_noun(kind: &TypeKind) -> String {
    let one = |t: jsonschema::JsonType| type_noun(Some(&Value::from(t.as_str())));
    match kind {
        TypeKind::Single(t) => one(*t).to_string(),
        TypeKind::Multiple(set) => set.iter().map(one).collect::<Vec<_>>().join(" or "),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spec::key_path::pointer_tokens;
    use toml::de::DeTable;

    /// The schema's known keys of the table at a JSON pointer into the instance.
    fn keys_at(pointer: &str) -> Vec<String> {
        let mut node = &SCHEMA.document;
        for token in pointer_tokens(pointer) {
            node = &node["properties"][&token];
            if let Some(r) = node.get("$ref").and_then(Value::as_str) {
                node = SCHEMA
                    .document
                    .pointer(r.trim_start_matches('#'))
                    .unwrap_or(&Value::Null);
            }
        }
        known_keys(Some(node))
            .into_iter()
            .map(str::to_string)
            .collect()
    }

    fn messages(text: &str) -> Vec<String> {
        let table = DeTable::parse(text).unwrap().into_inner();
        let (json, _) = super::super::toml_json::to_json(&table);
        let locator = Locator::new(table);
        let mut got: Vec<String> = check(&json, &locator, text, &[])
            .into_iter()
            .map(|d| format!("{}:{} {}: {}", d.line, d.column, d.key, d.message))
            .collect();
        got.sort();
        got
    }

    #[test]
    fn committed_schema_compiles() {
        assert!(
            SCHEMA.validator.is_ok(),
            "{:?}",
            SCHEMA.validator.as_ref().err()
        );
        assert!(keys_at("/layout/generate").contains(&"road_width".to_string()));
    }

    #[test]
    fn violations_become_expected_found_messages() {
        const HEAD: &str = "version = 1\nname = \"a\"\n";
        let cases: &[(&str, &str)] = &[
            (
                "[layout.generate]\nroad_width = 1000\n",
                "4:14 layout.generate.road_width: expected an integer at most 256, found 1000",
            ),
            (
                "[layout.generate]\nroad_widht = 40\n",
                "4:1 layout.generate.road_widht: expected one of `width`, `height`, `road_width`, `strip_width`, `horizontal_roads`, `vertical_roads`, `min_block`, found unknown key `road_widht` (did you mean `road_width`?)",
            ),
            (
                "[layout.generate]\nwidth = \"768\"\n",
                "4:9 layout.generate.width: expected an integer, found a string \"768\"",
            ),
            (
                "[layout]\nmirror = [1, 4]\n",
                "4:14 layout.mirror[1]: expected a mirror operation 1, 2 or 3 (1 flips vertically, 2 horizontally, 3 both), found 4",
            ),
            (
                "[layout]\nmetres_per_pixel = 0\n",
                "4:20 layout.metres_per_pixel: expected a number at least 0.05, found 0",
            ),
            (
                "[layout.palette]\nroad = \"grey\"\n",
                "4:8 layout.palette.road: expected a colour written \"#rrggbb\", like \"#80a0ff\", found \"grey\"",
            ),
            (
                "[layout]\n[buildings]\nwidths = []\n",
                "5:10 buildings.widths: expected at least 1 item in the array, found an array of 0 items",
            ),
            (
                "[layout]\nimage = \"\"\n",
                "4:9 layout.image: expected a non-empty string, found \"\"",
            ),
        ];
        for (body, want) in cases {
            let text = format!("{HEAD}{body}");
            assert_eq!(messages(&text), [want.to_string()], "{body}");
        }
    }

    #[test]
    fn missing_keys_point_at_their_table() {
        let got = messages("seed = 1\n[layout.generate]\n");
        assert_eq!(
            got,
            [
                "1:1 name: expected a `name` key at the top level, found none",
                "1:1 version: expected a `version` key at the top level, found none",
            ]
        );
        assert_eq!(
            messages("version = 1\nname = \"a\"\n[lamps]\n"),
            ["1:1 layout: expected a `layout` key at the top level, found none"]
        );
    }

    #[test]
    fn keys_that_do_not_apply_to_the_kind_are_refused_once() {
        const HEAD: &str = "version = 1\nname = \"a\"\n[layout.generate]\n";
        let cases: &[(&str, &[&str])] = &[
            (
                "[[objects]]\nkind = \"traffic_light\"\nmodel = \"a.obj\"\n",
                &[
                    "6:1 objects[0].model: expected only keys that apply to kind \"traffic_light\", found `model`, which applies only to kind \"mesh\"",
                ],
            ),
            // The value's own problem is not reported besides.
            (
                "[[objects]]\nkind = \"car\"\nheight = \"tall\"\n",
                &[
                    "6:1 objects[0].height: expected only keys that apply to kind \"car\", found `height`, which applies only to kinds \"tree\", \"person\" and \"bicycle\"",
                ],
            ),
            (
                "[[objects]]\nkind = \"mesh\"\nmodel = \"a.obj\"\nscale = [1, 2]\n",
                &[],
            ),
            // An unknown key is unknown, not also inapplicable; a bad kind matches no rule.
            (
                "[[objects]]\nkind = \"car\"\nmodle = 1\n",
                &["6:1 objects[0].modle: expected one of `kind`"],
            ),
            (
                "[[objects]]\nkind = \"cars\"\nmodel = \"a.obj\"\n",
                &["5:8 objects[0].kind: expected one of"],
            ),
        ];
        for (body, want) in cases {
            let got = messages(&format!("{HEAD}{body}"));
            assert_eq!(got.len(), want.len(), "{body}: {got:?}");
            for (got, want) in got.iter().zip(*want) {
                assert!(got.starts_with(want), "{body}: {got:?}");
            }
        }
    }

    #[test]
    fn enum_values_near_an_allowed_one_get_a_suggestion() {
        const HEAD: &str = "version = 1\nname = \"a\"\n[layout.generate]\n";
        let cases: &[(&str, &str)] = &[
            (
                "[[objects]]\nkind = \"texts\"\n",
                "found \"texts\" (did you mean \"text\"?)",
            ),
            (
                "[[objects]]\nkind = \"traffic_lights\"\n",
                "(did you mean \"traffic_light\"?)",
            ),
            (
                "[[objects]]\nkind = \"sign\"\nsigns = [\"stpo\"]\n",
                "(did you mean \"stop\"?)",
            ),
            (
                "[[objects]]\nkind = \"car\"\nbodies = [\"Sedan\"]\n",
                "(did you mean \"sedan\"?)",
            ),
            (
                "[[objects]]\nkind = \"text\"\ncase = \"uper\"\n",
                "(did you mean \"upper\"?)",
            ),
            (
                "[facades]\non_error = \"skpi\"\n",
                "(did you mean \"skip\"?)",
            ),
        ];
        for (body, want) in cases {
            let got = messages(&format!("{HEAD}{body}"));
            assert_eq!(got.len(), 1, "{body}: {got:?}");
            assert!(got[0].ends_with(want), "{body}: {got:?}");
        }
        let far = messages(&format!("{HEAD}[[objects]]\nkind = \"poster\"\n"));
        assert!(!far[0].contains("did you mean"), "{far:?}");
    }

    #[test]
    fn unknown_keys_without_a_near_key_get_no_suggestion() {
        let got = messages("version = 1\nname = \"a\"\ncolour = 3\n[layout]\n");
        assert_eq!(got.len(), 1);
        assert!(
            got[0].starts_with("3:1 colour: expected one of `version`, `name`"),
            "{got:?}"
        );
        assert!(!got[0].contains("did you mean"), "{got:?}");
    }
}
