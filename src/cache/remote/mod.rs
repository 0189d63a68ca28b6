//! The cache's storage on S3, Google Cloud Storage or Azure Blob Storage (`--cache
//! s3://bucket/prefix`, `gs://…`, `az://container/prefix`), through `object_store`.
//!
//! The layout under the prefix is the local folder's (`entries/<key>.json`,
//! `objects/ab/<sha256>`), so a folder can be copied up with any sync tool. No locks: an
//! object is named by its bytes' hash and an entry is one whole-object PUT, which the
//! three services make atomic (a reader sees the old entry or the new one). Concurrent
//! writers of one entry write the same bytes, since a key fixes what its stage makes.
//!
//! Credentials and endpoints come from the environment as each cloud's SDK reads them
//! (`AWS_ACCESS_KEY_ID`, `AWS_REGION`, `AWS_ENDPOINT_URL` and `AWS_ALLOW_HTTP=true` for an
//! S3-compatible server; `GOOGLE_APPLICATION_CREDENTIALS` / `GOOGLE_SERVICE_ACCOUNT`;
//! `AZURE_STORAGE_ACCOUNT_NAME` and `AZURE_STORAGE_ACCOUNT_KEY`, …).
//!
//! The store itself needs the `remote-cache` feature (on by default): without it
//! (`--no-default-features`, a build without the cloud clients, about a third less to
//! compile) [`RemoteStore::open`] refuses every bucket URL with an error saying so.

use std::time::SystemTime;

#[cfg(feature = "remote-cache")]
mod store;
#[cfg(not(feature = "remote-cache"))]
#[path = "store_absent.rs"]
mod store;

pub use store::RemoteStore;

/// A parsed `--cache` URL.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RemoteLocation {
    pub scheme: Scheme,
    /// The bucket (S3, GCS) or container (Azure).
    pub bucket: String,
    /// The folder inside it, without leading or trailing `/` (may be empty).
    pub prefix: String,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scheme {
    S3,
    Gcs,
    Azure,
}

impl RemoteLocation {
    /// `Ok(None)` for a local folder (no `://`), the location for `s3://`, `gs://` and
    /// `az://` URLs, and an error for any other URL or one without a bucket.
    pub fn parse(text: &str) -> Result<Option<RemoteLocation>, String> {
        let Some((scheme, rest)) = text.split_once("://") else {
            return Ok(None);
        };
        let scheme = match scheme {
            "s3" => Scheme::S3,
            "gs" => Scheme::Gcs,
            "az" => Scheme::Azure,
            other => {
                return Err(format!(
                    "{text:?}: unknown scheme {other:?}; a cache is a folder or an s3://, gs:// or az:// URL"
                ));
            }
        };
        let (bucket, prefix) = rest.split_once('/').unwrap_or((rest, ""));
        let bucket_ok = !bucket.is_empty()
            && bucket
                .bytes()
                .all(|b| b.is_ascii_alphanumeric() || b"-._".contains(&b));
        if !bucket_ok {
            return Err(format!(
                "{text:?}: expected {}://BUCKET/PREFIX, with a bucket name of letters, digits, '-', '.' or '_'",
                &text[..text.find("://").unwrap_or(0)]
            ));
        }
        let prefix = prefix.trim_matches('/');
        if prefix
            .split('/')
            .any(|part| part == "." || part == ".." || (part.is_empty() && !prefix.is_empty()))
        {
            return Err(format!(
                "{text:?}: the prefix must be folder names separated by single '/'"
            ));
        }
        Ok(Some(RemoteLocation {
            scheme,
            bucket: bucket.to_owned(),
            prefix: prefix.to_owned(),
        }))
    }
}

/// `--cache`'s parser: a folder, or a remote cache's URL checked for its form (whether the
/// store answers is found out when a command opens it).
pub fn cache_location(text: &str) -> Result<std::path::PathBuf, String> {
    RemoteLocation::parse(text).map(|_| std::path::PathBuf::from(text))
}

/// One file of the store, as listed.
pub struct Listed {
    /// The path under the prefix (`entries/<key>.json`, `objects/ab/<sha256>`).
    pub name: String,
    pub bytes: u64,
    pub modified: SystemTime,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cache_urls_parse_and_bad_ones_are_refused() {
        assert_eq!(RemoteLocation::parse(".cityspec-cache"), Ok(None));
        assert_eq!(RemoteLocation::parse("/shared/cache"), Ok(None));
        assert_eq!(
            RemoteLocation::parse("s3://bucket/team/cache/"),
            Ok(Some(RemoteLocation {
                scheme: Scheme::S3,
                bucket: "bucket".into(),
                prefix: "team/cache".into(),
            }))
        );
        assert_eq!(RemoteLocation::parse("gs://b").unwrap().unwrap().prefix, "");
        assert_eq!(
            RemoteLocation::parse("az://container/c")
                .unwrap()
                .unwrap()
                .scheme,
            Scheme::Azure
        );
        for bad in [
            "http://host/x",
            "s3://",
            "s3:///prefix",
            "s3://bu cket/x",
            "gs://b/a//c",
            "az://b/../c",
        ] {
            assert!(RemoteLocation::parse(bad).is_err(), "{bad}");
        }
    }
}
