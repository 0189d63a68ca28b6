//! Build errors → exit codes: 2 when the spec or its input files are to blame, 1 when the
//! build itself failed. Decided by the typed cause, never by the message.

use crate::driver::BuildError;
use crate::render::RenderError;

/// Exit code 2: invalid spec, input or usage.
pub const INPUT: u8 = 2;
/// Exit code 3: `--locked`, and the artifacts differ from the lock file (or there is none).
pub const LOCKED: u8 = 3;
/// Exit code 1: the build failed (an unwritable folder, a damaged cache, a cityspec bug).
pub const BUILD: u8 = 1;

/// The exit code `error` calls for.
pub fn exit_code(error: &BuildError) -> u8 {
    match error {
        BuildError::ReadSpec { .. }
        | BuildError::SpecFile { .. }
        | BuildError::Spec(_)
        | BuildError::Input { .. }
        | BuildError::Layout { .. }
        | BuildError::Facades { .. }
        | BuildError::Objects { .. }
        | BuildError::Classes { .. }
        | BuildError::Strict { .. }
        | BuildError::DuplicateName { .. }
        | BuildError::OsmFile { .. }
        | BuildError::Osm { .. }
        | BuildError::OutNotAFolder { .. }
        | BuildError::NotACache { .. } => INPUT,
        // The spec asked for more objects than instance ids can tell apart.
        BuildError::Render {
            source: RenderError::TooManyObjects { .. },
            ..
        } => INPUT,
        // Anything else the renderer refuses is a scene cityspec built wrong.
        BuildError::Locked { .. } => LOCKED,
        BuildError::Render { .. }
        | BuildError::Output { .. }
        | BuildError::Pack { .. }
        | BuildError::OutputFolder { .. }
        | BuildError::Cache { .. }
        | BuildError::Decode { .. } => BUILD,
    }
}

/// The exit code of a command that failed with `errors`: 3 when any artifact differs from
/// its lock, 2 only when every one is the input's fault.
pub fn exit_code_of(errors: &[BuildError]) -> u8 {
    if errors.iter().any(|e| exit_code(e) == LOCKED) {
        LOCKED
    } else if errors.iter().all(|e| exit_code(e) == INPUT) {
        INPUT
    } else {
        BUILD
    }
}

#[cfg(test)]
mod tests {
    use std::path::PathBuf;

    use super::*;

    #[test]
    fn too_many_objects_is_the_spec_s_fault() {
        let spec = PathBuf::from("specs/big.toml");
        let too_many = BuildError::Render {
            spec: spec.clone(),
            source: RenderError::TooManyObjects { count: 1 << 24 },
        };
        assert_eq!(exit_code(&too_many), INPUT);
        let bug = BuildError::Render {
            spec,
            source: RenderError::MissingTexture {
                material: "wall".into(),
                texture: 3,
                count: 1,
            },
        };
        assert_eq!(exit_code(&bug), BUILD);
        assert_eq!(exit_code_of(&[too_many, bug]), BUILD);
        // The cause is kept for callers that walk the chain.
        let err = BuildError::Render {
            spec: "s.toml".into(),
            source: RenderError::TooManyObjects { count: 1 << 24 },
        };
        let cause = std::error::Error::source(&err).expect("a source");
        assert!(cause.to_string().contains("16777215"), "{cause}");
    }
}
