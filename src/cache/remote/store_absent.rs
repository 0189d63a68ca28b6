//! [`RemoteStore`] in a build without the `remote-cache` feature: it cannot be opened, so
//! no value of it exists and its operations are never reached.

use std::convert::Infallible;
use std::io;
use std::path::Path;

use super::{Listed, RemoteLocation};
use crate::cache::verified_memo::VerifiedMemo;

/// A cache stored in a bucket; this build has no client for one (see [`RemoteStore::open`]).
pub struct RemoteStore {
    never: Infallible,
    pub(in crate::cache) verified: VerifiedMemo,
}

impl std::fmt::Debug for RemoteStore {
    fn fmt(&self, _: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.never {}
    }
}

impl RemoteStore {
    /// Always an error: this cityspec was built without the cloud clients.
    pub fn open(location: &RemoteLocation) -> Result<RemoteStore, String> {
        Err(format!(
            "a cache in a bucket ({:?}://{}) needs cityspec built with the `remote-cache` feature (on by default; this build has --no-default-features)",
            location.scheme, location.bucket
        ))
    }

    pub fn get(&self, _: &str) -> io::Result<Option<Vec<u8>>> {
        match self.never {}
    }

    pub fn put(&self, _: &str, _: &[u8]) -> io::Result<()> {
        match self.never {}
    }

    pub fn put_file(&self, _: &str, _: &Path) -> io::Result<()> {
        match self.never {}
    }

    pub fn delete(&self, _: &str) -> io::Result<()> {
        match self.never {}
    }

    pub fn list(&self, _: &str) -> io::Result<Vec<Listed>> {
        match self.never {}
    }
}
