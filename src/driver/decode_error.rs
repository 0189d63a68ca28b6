//! DecodeError: why a cached value that verified by hash still did not decode (a cityspec
//! bug: the encoder and decoder disagree).

/// A cached stage output that is not what its decoder expects.
#[derive(Debug, thiserror::Error)]
pub enum DecodeError {
    /// The stage's entry has no output of this name.
    #[error("{name} missing")]
    Missing { name: String },
    #[error("not a PNG: {0}")]
    Png(#[source] image::ImageError),
    #[error("not the expected JSON: {0}")]
    Json(#[source] serde_json::Error),
    /// A stage's inputs (other stages' outputs) that do not read as those stages write them.
    #[error("{0}")]
    Inputs(String),
}
