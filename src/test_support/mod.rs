//! Test fakes and fixtures shared by every stage's tests (compiled only under `cfg(test)`).
//!
//! Besides the driver, this is the one module allowed to run stages (`tests/integration/stage_imports.rs`
//! lists it so): a stage's tests that need another stage's output — a generated layout to
//! parse, a parsed city to build a scene on — get it from here instead of importing that
//! stage.

mod fake_world;
mod pixel_rows;
mod street_map;
mod test_city;

pub use fake_world::FakeWorld;
pub use pixel_rows::pixel_classes;
pub use street_map::street_map;
// The layout stage's output with the roads and blocks it drew, for the parse tests.
pub use crate::model::GeneratedLayout;
pub use test_city::{TestCity, decoded, generated, mirrored, parsed, scene, test_city};
