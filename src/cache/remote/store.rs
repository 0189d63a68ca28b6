//! [`RemoteStore`] through `object_store` (the `remote-cache` feature).

use std::fs;
use std::io::{self, Read};
use std::path::Path;
use std::sync::{Arc, Once};
use std::time::{Duration, SystemTime};

use futures_util::StreamExt;
use object_store::path::Path as Key;
use object_store::{ObjectStore, ObjectStoreExt, RetryConfig, WriteMultipart};

use super::{Listed, RemoteLocation, Scheme};
use crate::cache::verified_memo::VerifiedMemo;

/// A cache stored in a bucket. Every call blocks on the store's own runtime, so the
/// cache's callers (rayon's workers) stay synchronous.
pub struct RemoteStore {
    store: Arc<dyn ObjectStore>,
    prefix: String,
    runtime: tokio::runtime::Runtime,
    /// Objects verified while checking entries, for the folder writes that follow.
    pub(in crate::cache) verified: VerifiedMemo,
}

impl std::fmt::Debug for RemoteStore {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "RemoteStore({}, {:?})", self.store, self.prefix)
    }
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
