//! Spec stage: TOML text → validated [`Spec`].

mod spec;

pub use spec::{
    BuildingsSpec, Color, GenerateSpec, LampsSpec, LayoutSpec, Palette, SPEC_VERSION, Spec,
};
