//! Schema bounds of the weather and sensor keys that take a number or a range
//! ([`ValueRange`](super::ValueRange)), for `#[schemars(schema_with = ...)]`.

use schemars::{Schema, SchemaGenerator};

use super::value_range::range_schema;

/// One schema function per bound the weather and sensor keys use.
macro_rules! bounded {
    ($($name:ident: $min:expr, $max:expr;)*) => {
        $(pub(crate) fn $name(_: &mut SchemaGenerator) -> Schema {
            range_schema($min, $max)
        })*
    };
}

bounded! {
    unit: 0.0, 1.0;
    ev: -16.0, 16.0;
    density: 0.0, 1.0;
    fog_height: 0.5, 1000.0;
    noise: 0.0, 0.5;
    jpeg_quality: 1.0, 100.0;
    aberration: 0.0, 16.0;
    travel: 0.0, 10.0;
}
