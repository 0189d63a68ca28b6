//! Bytes of stage outputs: PNG for images, JSON for values. Deterministic encoders only.

use image::RgbImage;
use serde::Serialize;
use serde::de::DeserializeOwned;
use serde_json::Value;
use std::sync::Arc;

use super::decode_error::DecodeError;
use crate::cache::{Blob, Outputs};
use crate::model::FacadeSet;

/// Bump when any encoding here changes its bytes: it is part of every stage key.
pub const VERSION: u32 = 3;

/// PNG bytes of an RGB image, with the same fixed settings as every texture.
pub fn encode_png(image: &RgbImage) -> Vec<u8> {
    crate::model::encode_png(image)
}

/// Decodes PNG bytes this module wrote.
pub fn decode_png(bytes: &[u8]) -> Result<RgbImage, DecodeError> {
    image::load_from_memory_with_format(bytes, image::ImageFormat::Png)
        .map(|image| image.to_rgb8())
        .map_err(DecodeError::Png)
}

/// A facade set as cache outputs: `facades.json` (without pixels) and every texture as
/// `textures/<name>.png`.
pub fn facade_set_outputs(set: &FacadeSet) -> Outputs {
    let mut outputs = Outputs::new();
    outputs.insert("facades.json".to_owned(), Blob::from(to_json(set)));
    let textures = set
        .facades
        .iter()
        .map(|f| &f.texture)
        .chain(set.roofs.iter().map(|r| &r.texture));
    for texture in textures {
        outputs.insert(
            format!("textures/{}.png", texture.name),
            Blob::Bytes(Arc::clone(&texture.png)),
        );
    }
    outputs
}

/// The facade set back from [`facade_set_outputs`].
pub fn facade_set_from_outputs(outputs: &Outputs) -> Result<FacadeSet, DecodeError> {
    let mut set: FacadeSet = from_json(output(outputs, "facades.json")?)?;
    let textures = set.facades.iter_mut().map(|f| &mut f.texture);
    for texture in textures.chain(set.roofs.iter_mut().map(|r| &mut r.texture)) {
        let name = format!("textures/{}.png", texture.name);
        texture.png = Arc::clone(output(outputs, &name)?);
    }
    Ok(set)
}

/// The in-memory bytes of output `name`.
pub fn output<'o>(outputs: &'o Outputs, name: &str) -> Result<&'o Arc<Vec<u8>>, DecodeError> {
    outputs
        .get(name)
        .and_then(Blob::bytes)
        .ok_or_else(|| DecodeError::Missing {
            name: name.to_owned(),
        })
}

/// Compact JSON for values only the cache reads.
pub fn to_json(value: &impl Serialize) -> Vec<u8> {
    serde_json::to_vec(value).expect("stage values serialize to JSON")
}

/// JSON for artifacts people read: objects one key a line, but short arrays of numbers (a
/// point, a box) and short lists of points on one line. Trailing newline.
pub fn to_pretty_json(value: &impl Serialize) -> Vec<u8> {
    let value = serde_json::to_value(value).expect("stage values serialize to JSON");
    let mut out = String::new();
    write_pretty(&value, 0, &mut out);
    out.push('\n');
    out.into_bytes()
}

fn write_pretty(value: &Value, depth: usize, out: &mut String) {
    let pad = |out: &mut String, depth: usize| out.extend(std::iter::repeat_n("  ", depth));
    match value {
        Value::Object(map) if !map.is_empty() && !fits_one_line(value) => {
            out.push_str("{\n");
            for (i, (key, item)) in map.iter().enumerate() {
                pad(out, depth + 1);
                out.push_str(&Value::String(key.clone()).to_string());
                out.push_str(": ");
                write_pretty(item, depth + 1, out);
                out.push_str(if i + 1 < map.len() { ",\n" } else { "\n" });
            }
            pad(out, depth);
            out.push('}');
        }
        Value::Array(items) if !items.is_empty() && !fits_one_line(value) => {
            out.push_str("[\n");
            for (i, item) in items.iter().enumerate() {
                pad(out, depth + 1);
                write_pretty(item, depth + 1, out);
                out.push_str(if i + 1 < items.len() { ",\n" } else { "\n" });
            }
            pad(out, depth);
            out.push(']');
        }
        other => write_inline(other, out),
    }
}

/// Decodes JSON this module wrote.
pub fn from_json<T: DeserializeOwned>(bytes: &[u8]) -> Result<T, DecodeError> {
    serde_json::from_slice(bytes).map_err(DecodeError::Json)
}

/// One line, with a space after every comma and colon.
fn write_inline(value: &Value, out: &mut String) {
    match value {
        Value::Object(map) => {
            out.push('{');
            for (i, (key, item)) in map.iter().enumerate() {
                if i > 0 {
                    out.push_str(", ");
                }
                out.push_str(&Value::String(key.clone()).to_string());
                out.push_str(": ");
                write_inline(item, out);
            }
            out.push('}');
        }
        Value::Array(items) => {
            out.push('[');
            for (i, item) in items.iter().enumerate() {
                if i > 0 {
                    out.push_str(", ");
                }
                write_inline(item, out);
            }
            out.push(']');
        }
        scalar => out.push_str(&scalar.to_string()),
    }
}

/// What goes on one line: a short array of numbers (a point), a short list of points, or
/// an object of scalars and such arrays (a building, a lamp) that stays under 96 columns.
fn fits_one_line(value: &Value) -> bool {
    let scalar = |v: &Value| !v.is_array() && !v.is_object();
    let short_array = |items: &Vec<Value>| {
        items.len() <= 8
            && items.iter().all(|item| match item {
                Value::Array(inner) => inner.len() <= 4 && inner.iter().all(scalar),
                other => scalar(other),
            })
    };
    match value {
        Value::Array(items) => short_array(items),
        Value::Object(map) => {
            let flat = map.len() <= 8
                && map.values().all(|v| match v {
                    Value::Array(items) => short_array(items),
                    other => scalar(other),
                });
            if !flat {
                return false;
            }
            let mut line = String::new();
            write_inline(value, &mut line);
            line.len() <= 96
        }
        _ => true,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pretty_json_keeps_points_on_one_line_and_round_trips() {
        let value = serde_json::json!({
            "size": [768.0, 768.0],
            "outline": [[8.5, 8.5], [8.5, 118.5], [89.5, 118.5]],
            "roads": [{"id": 0, "axis": "horizontal"}],
            "block": {"id": 3, "outline": [[100.5, 200.5], [300.5, 400.5], [500.5, 600.5], [700.5, 800.5], [900.5, 1.5]]},
            "lamp": {"id": 7, "position": [50.0, 123.0], "road": 0},
            "empty": [],
            "long": [1, 2, 3, 4, 5, 6, 7, 8, 9]
        });
        let text = String::from_utf8(to_pretty_json(&value)).unwrap();
        let expected = r#"{
  "size": [768.0, 768.0],
  "outline": [[8.5, 8.5], [8.5, 118.5], [89.5, 118.5]],
  "roads": [
    {"id": 0, "axis": "horizontal"}
  ],
  "block": {
    "id": 3,
    "outline": [[100.5, 200.5], [300.5, 400.5], [500.5, 600.5], [700.5, 800.5], [900.5, 1.5]]
  },
  "lamp": {"id": 7, "position": [50.0, 123.0], "road": 0},
  "empty": [],
  "long": [
    1,
    2,
    3,
    4,
    5,
    6,
    7,
    8,
    9
  ]
}
"#;
        assert_eq!(text, expected);
        let back: Value = serde_json::from_str(&text).unwrap();
        assert_eq!(back, value);
    }

    #[test]
    fn png_round_trips_and_is_stable() {
        let image = RgbImage::from_fn(7, 5, |x, y| image::Rgb([x as u8 * 30, y as u8 * 40, 9]));
        let bytes = encode_png(&image);
        assert_eq!(bytes, encode_png(&image));
        assert_eq!(decode_png(&bytes).unwrap(), image);
        assert!(decode_png(b"not a png").is_err());
    }
}
