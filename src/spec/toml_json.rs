//! TOML tree → JSON instance for the schema validator, and TOML values → "found …" text.
//!
//! The schema speaks JSON; the user wrote TOML. Values TOML has and JSON lacks (inf, nan,
//! datetimes) are reported here, and the "found" side of every message is described in
//! TOML's words (a table, not an object).

use serde_json::{Map, Number, Value};
use toml::de::{DeTable, DeValue};

use super::key_path::KeyPath;

/// The JSON form of a TOML document, and the values that have none.
pub(crate) fn to_json(table: &DeTable<'_>) -> (Value, Vec<(KeyPath, String)>) {
    let mut problems = Vec::new();
    let json = table_to_json(table, &KeyPath::root(), &mut problems);
    (json, problems)
}

fn table_to_json(
    table: &DeTable<'_>,
    path: &KeyPath,
    problems: &mut Vec<(KeyPath, String)>,
) -> Value {
    let mut map = Map::new();
    for (key, value) in table.iter() {
        let key = key.get_ref().to_string();
        let json = value_to_json(value.get_ref(), &path.key(&key), problems);
        map.insert(key, json);
    }
    Value::Object(map)
}

fn value_to_json(
    value: &DeValue<'_>,
    path: &KeyPath,
    problems: &mut Vec<(KeyPath, String)>,
) -> Value {
    match value {
        DeValue::String(s) => Value::String(s.to_string()),
        DeValue::Integer(i) => match i64::from_str_radix(i.as_str(), i.radix()) {
            Ok(n) => Value::Number(n.into()),
            Err(_) => {
                problems.push((
                    path.clone(),
                    format!("expected a 64-bit integer, found {i}"),
                ));
                Value::Null
            }
        },
        DeValue::Float(f) => match f.as_str().parse::<f64>().ok().and_then(Number::from_f64) {
            Some(n) => Value::Number(n),
            None => {
                problems.push((path.clone(), format!("expected a finite number, found {f}")));
                Value::Null
            }
        },
        DeValue::Boolean(b) => Value::Bool(*b),
        // No spec key takes a datetime; as a string it fails the schema's type check, and
        // the message then describes it from the TOML side as a datetime.
        DeValue::Datetime(d) => Value::String(d.to_string()),
        DeValue::Array(items) => Value::Array(
            items
                .iter()
                .enumerate()
                .map(|(i, v)| value_to_json(v.get_ref(), &path.index(i), problems))
                .collect(),
        ),
        DeValue::Table(t) => table_to_json(t, path, problems),
    }
}

/// A value with its TOML type, for "found …": `a string "768"`, `an array of 2 items`.
pub(crate) fn describe(value: &DeValue<'_>) -> String {
    match value {
        DeValue::String(_) => format!("a string {}", show(value)),
        DeValue::Integer(_) => format!("an integer {}", show(value)),
        DeValue::Float(_) => format!("a float {}", show(value)),
        DeValue::Boolean(_) => format!("a boolean {}", show(value)),
        DeValue::Datetime(_) => format!("a datetime {}", show(value)),
        DeValue::Array(_) | DeValue::Table(_) => show(value),
    }
}

/// A value as the user wrote it (strings quoted), or its kind for arrays and tables.
pub(crate) fn show(value: &DeValue<'_>) -> String {
    match value {
        DeValue::String(s) => format!("{s:?}"),
        DeValue::Integer(i) => i.to_string(),
        DeValue::Float(f) => f.to_string(),
        DeValue::Boolean(b) => b.to_string(),
        DeValue::Datetime(d) => d.to_string(),
        DeValue::Array(a) => match a.len() {
            1 => "an array of 1 item".to_string(),
            n => format!("an array of {n} items"),
        },
        DeValue::Table(_) => "a table".to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn value(text: &str) -> DeValue<'_> {
        DeTable::parse(text)
            .unwrap()
            .into_inner()
            .into_iter()
            .next()
            .unwrap()
            .1
            .into_inner()
    }

    #[test]
    fn converts_every_toml_type() {
        let table = DeTable::parse(
            "a = 0x10\nb = 1_000.5\nc = 'x'\nd = true\ne = [1, {f = 2}]\ng = 1979-05-27\n",
        )
        .unwrap();
        let (json, problems) = to_json(table.get_ref());
        assert!(problems.is_empty());
        assert_eq!(
            json,
            serde_json::json!({"a": 16, "b": 1000.5, "c": "x", "d": true, "e": [1, {"f": 2}], "g": "1979-05-27"})
        );
    }

    #[test]
    fn non_finite_floats_are_problems() {
        let table = DeTable::parse("a = [1.0, nan]\nb = -inf\n").unwrap();
        let (_, problems) = to_json(table.get_ref());
        let got: Vec<String> = problems.iter().map(|(p, m)| format!("{p}: {m}")).collect();
        assert_eq!(
            got,
            [
                "a[1]: expected a finite number, found nan",
                "b: expected a finite number, found -inf"
            ]
        );
    }

    #[test]
    fn found_values_are_described_in_toml_words() {
        let cases = [
            ("a = \"768\"", "a string \"768\""),
            ("a = 7", "an integer 7"),
            ("a = 7.5", "a float 7.5"),
            ("a = false", "a boolean false"),
            ("a = [1, 2]", "an array of 2 items"),
            ("a = [1]", "an array of 1 item"),
            ("a = {}", "a table"),
            ("a = 1979-05-27", "a datetime 1979-05-27"),
        ];
        for (text, want) in cases {
            assert_eq!(describe(&value(text)), want, "{text}");
        }
    }
}
