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

use std::fs;
use std::io::{self, Read};
use std::path::Path;
use std::sync::{Arc, Once};
use std::time::{Duration, SystemTime};

use futures_util::StreamExt;
use object_store::path::Path as Key;
use object_store::{ObjectStore, ObjectStoreExt, RetryConfig, WriteMultipart};

use super::verified_memo::VerifiedMemo;

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

/// A cache stored in a bucket. Every call blocks on the store's own runtime, so the
/// cache's callers (rayon's workers) stay synchronous.
pub struct RemoteStore {
    store: Arc<dyn ObjectStore>,
    prefix: String,
    runtime: tokio::runtime::Runtime,
    /// Objects verified while checking entries, for the folder writes that follow.
    pub(super) verified: VerifiedMemo,
}

impl std::fmt::Debug for RemoteStore {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "RemoteStore({}, {:?})", self.store, self.prefix)
    }
}

/// One file of the store, as listed.
pub struct Listed {
    /// The path under the prefix (`entries/<key>.json`, `objects/ab/<sha256>`).
    pub name: String,
    pub bytes: u64,
    pub modified: SystemTime,
}

/// Objects larger than this are uploaded in parts of this size.
const PART: usize = 16 << 20;

impl RemoteStore {
    /// Connects to `location` with credentials from the environment, and lists the
    /// prefix once, so a wrong endpoint, bucket or credential fails here, clearly, not
    /// as a cache miss per stage.
    pub fn open(location: &RemoteLocation) -> Result<RemoteStore, String> {
        // reqwest is built without a crypto provider of its own: ring's, once per process.
        static PROVIDER: Once = Once::new();
        PROVIDER.call_once(|| {
            let _ = rustls::crypto::ring::default_provider().install_default();
        });
        // Fail within seconds, not the default three minutes of retries.
        let retry = RetryConfig {
            backoff: Default::default(),
            max_retries: 3,
            retry_timeout: Duration::from_secs(20),
        };
        let store: Arc<dyn ObjectStore> = match location.scheme {
            Scheme::S3 => Arc::new(
                object_store::aws::AmazonS3Builder::from_env()
                    .with_bucket_name(&location.bucket)
                    .with_retry(retry)
                    .build()
                    .map_err(|e| e.to_string())?,
            ),
            Scheme::Gcs => Arc::new(
                object_store::gcp::GoogleCloudStorageBuilder::from_env()
                    .with_bucket_name(&location.bucket)
                    .with_retry(retry)
                    .build()
                    .map_err(|e| e.to_string())?,
            ),
            Scheme::Azure => Arc::new(
                object_store::azure::MicrosoftAzureBuilder::from_env()
                    .with_container_name(&location.bucket)
                    .with_retry(retry)
                    .build()
                    .map_err(|e| e.to_string())?,
            ),
        };
        let runtime = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(2)
            .thread_name("cityspec-cache")
            .enable_all()
            .build()
            .map_err(|e| format!("cannot start the cache's I/O threads: {e}"))?;
        let remote = RemoteStore {
            store,
            prefix: location.prefix.clone(),
            runtime,
            verified: VerifiedMemo::default(),
        };
        let probe = remote.key("entries");
        remote
            .runtime
            .block_on(remote.store.list_with_delimiter(Some(&probe)))
            .map_err(|e| format!("cannot list it: {e}"))?;
        Ok(remote)
    }

    fn key(&self, name: &str) -> Key {
        if self.prefix.is_empty() {
            Key::from(name)
        } else {
            Key::from(format!("{}/{name}", self.prefix))
        }
    }

    /// The bytes stored under `name`, `None` when there are none.
    pub fn get(&self, name: &str) -> io::Result<Option<Vec<u8>>> {
        let key = self.key(name);
        let got = self.runtime.block_on(async {
            match self.store.get(&key).await {
                Ok(result) => result.bytes().await.map(Some),
                Err(object_store::Error::NotFound { .. }) => Ok(None),
                Err(e) => Err(e),
            }
        });
        got.map(|bytes| bytes.map(|b| b.to_vec()))
            .map_err(io::Error::other)
    }

    /// Stores `bytes` under `name`, replacing what was there, in one PUT.
    pub fn put(&self, name: &str, bytes: &[u8]) -> io::Result<()> {
        let key = self.key(name);
        let payload = object_store::PutPayload::from(bytes.to_vec());
        self.runtime
            .block_on(self.store.put(&key, payload))
            .map(drop)
            .map_err(io::Error::other)
    }

    /// Stores the file at `path` under `name`: one PUT, or a multipart upload of parts
    /// read one at a time when it is large (COCO files grow with the frames).
    pub fn put_file(&self, name: &str, path: &Path) -> io::Result<()> {
        let mut file = fs::File::open(path)?;
        let size = file.metadata()?.len();
        if size <= PART as u64 {
            let mut bytes = Vec::with_capacity(size as usize);
            file.read_to_end(&mut bytes)?;
            return self.put(name, &bytes);
        }
        let key = self.key(name);
        self.runtime.block_on(async {
            let upload = self
                .store
                .put_multipart(&key)
                .await
                .map_err(io::Error::other)?;
            let mut writer = WriteMultipart::new_with_chunk_size(upload, PART);
            let mut part = vec![0; PART];
            loop {
                let n = read_full(&mut file, &mut part)?;
                if n == 0 {
                    break;
                }
                writer
                    .wait_for_capacity(2)
                    .await
                    .map_err(io::Error::other)?;
                writer.write(&part[..n]);
            }
            writer.finish().await.map(drop).map_err(io::Error::other)
        })
    }

    /// Removes `name` (already gone is no error: another gc may have removed it).
    pub fn delete(&self, name: &str) -> io::Result<()> {
        let key = self.key(name);
        match self.runtime.block_on(self.store.delete(&key)) {
            Ok(()) | Err(object_store::Error::NotFound { .. }) => Ok(()),
            Err(e) => Err(io::Error::other(e)),
        }
    }

    /// Every file under `folder` (`entries`, `objects`), at any depth.
    pub fn list(&self, folder: &str) -> io::Result<Vec<Listed>> {
        let key = self.key(folder);
        let skip = if self.prefix.is_empty() {
            0
        } else {
            self.prefix.len() + 1
        };
        self.runtime.block_on(async {
            let mut listed = Vec::new();
            let mut stream = self.store.list(Some(&key));
            while let Some(meta) = stream.next().await {
                let meta = meta.map_err(io::Error::other)?;
                let seconds = meta.last_modified.timestamp().max(0) as u64;
                listed.push(Listed {
                    name: meta.location.as_ref()[skip..].to_owned(),
                    bytes: meta.size,
                    modified: SystemTime::UNIX_EPOCH + Duration::from_secs(seconds),
                });
            }
            Ok(listed)
        })
    }
}

/// Reads until `buf` is full or the file ends; the number of bytes read.
fn read_full(file: &mut fs::File, buf: &mut [u8]) -> io::Result<usize> {
    let mut filled = 0;
    while filled < buf.len() {
        match file.read(&mut buf[filled..])? {
            0 => break,
            n => filled += n,
        }
    }
    Ok(filled)
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
