//! Bytes of remote cache objects verified while an entry was checked, kept (up to
//! [`BUDGET`] bytes in all) until the output folder is written from them.
//!
//! A stage loaded by reference has every object of its entry downloaded and hashed, to
//! know the entry is whole, and its bytes dropped; writing the output folder then reads
//! each object again. On a local folder the second read comes from the page cache; on a
//! bucket it is a second download. With the memo, a warm build or a merge on a remote
//! cache downloads each object once, as long as what it checks before writing fits the
//! budget (a 200-frame street path is about 165 MiB); beyond that it reads the rest twice,
//! as before, and its memory stays bounded.

use std::collections::BTreeMap;
use std::sync::Mutex;

/// Most bytes kept at once.
pub(super) const BUDGET: usize = 256 << 20;

/// Verified objects by SHA-256, and their total size.
#[derive(Debug, Default)]
pub(super) struct VerifiedMemo {
    held: Mutex<(BTreeMap<String, Vec<u8>>, usize)>,
}

impl VerifiedMemo {
    /// Keeps the verified `bytes` of object `sha256`, unless the budget is spent.
    pub(super) fn keep(&self, sha256: &str, bytes: Vec<u8>) {
        let mut held = self.held.lock().unwrap_or_else(|e| e.into_inner());
        let (map, total) = &mut *held;
        if *total + bytes.len() <= BUDGET && !map.contains_key(sha256) {
            *total += bytes.len();
            map.insert(sha256.to_owned(), bytes);
        }
    }

    /// The kept bytes of object `sha256`, handed over (and forgotten).
    pub(super) fn take(&self, sha256: &str) -> Option<Vec<u8>> {
        let mut held = self.held.lock().unwrap_or_else(|e| e.into_inner());
        let (map, total) = &mut *held;
        let bytes = map.remove(sha256)?;
        *total -= bytes.len();
        Some(bytes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hands_each_object_over_once_and_keeps_within_the_budget() {
        let memo = VerifiedMemo::default();
        memo.keep("a", vec![1; 10]);
        assert_eq!(memo.take("a"), Some(vec![1; 10]));
        assert_eq!(memo.take("a"), None);
        memo.keep("big", vec![0; BUDGET - 5]);
        memo.keep("over", vec![0; 6]);
        assert_eq!(memo.take("over"), None, "kept beyond the budget");
        memo.keep("fits", vec![0; 5]);
        assert_eq!(memo.take("fits").map(|b| b.len()), Some(5));
        // Handing over frees room.
        assert!(memo.take("big").is_some());
        memo.keep("over", vec![0; 6]);
        assert!(memo.take("over").is_some());
    }
}
