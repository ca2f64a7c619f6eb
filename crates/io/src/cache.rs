//! A small bounded cache: at most `entries` values weighing at most `bytes` in all; the
//! least recently used go first, and a value heavier than the whole budget is not kept.
//!
//! Eviction scans the entries (O(entries)); with a few hundred that is far below the cost of
//! the work cached (an analysis or a PNG).
//!
//! ```
//! use close_io::cache::Lru;
//! let mut c = Lru::new(2, 1000);
//! c.insert("a".into(), 1, 10);
//! c.insert("b".into(), 2, 10);
//! c.get("a");
//! c.insert("c".into(), 3, 10); // evicts "b", the least recently used
//! assert_eq!((c.get("a"), c.get("b"), c.get("c")), (Some(1), None, Some(3)));
//! ```

use std::collections::HashMap;
use std::hash::{DefaultHasher, Hash, Hasher};

/// A bounded least-recently-used map from string keys to cheap-to-clone values.
#[derive(Debug)]
pub struct Lru<V> {
    max_entries: usize,
    max_bytes: usize,
    bytes: usize,
    tick: u64,
    /// value, last use, weight in bytes
    entries: HashMap<String, (V, u64, usize)>,
}

impl<V: Clone> Lru<V> {
    pub fn new(max_entries: usize, max_bytes: usize) -> Self {
        Lru {
            max_entries: max_entries.max(1),
            max_bytes,
            bytes: 0,
            tick: 0,
            entries: HashMap::new(),
        }
    }

    pub fn get(&mut self, key: &str) -> Option<V> {
        self.tick += 1;
        let tick = self.tick;
        self.entries.get_mut(key).map(|(v, used, _)| {
            *used = tick;
            v.clone()
        })
    }

    /// Keep `value` (weighing `bytes`) under `key`, evicting the least recently used values
    /// until both budgets hold.
    pub fn insert(&mut self, key: String, value: V, bytes: usize) {
        if bytes > self.max_bytes {
            return;
        }
        if let Some((_, _, old)) = self.entries.remove(&key) {
            self.bytes -= old;
        }
        while self.entries.len() >= self.max_entries || self.bytes + bytes > self.max_bytes {
            let Some(oldest) =
                self.entries.iter().min_by_key(|(_, (_, used, _))| *used).map(|(k, _)| k.clone())
            else {
                break;
            };
            if let Some((_, _, w)) = self.entries.remove(&oldest) {
                self.bytes -= w;
            }
        }
        self.tick += 1;
        self.bytes += bytes;
        self.entries.insert(key, (value, self.tick, bytes));
    }

    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Total weight of the values kept.
    pub fn bytes(&self) -> usize {
        self.bytes
    }

    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }
}

/// A 128-bit content key (two SipHash digests with different seeds) of byte strings, in hex.
pub fn content_key(parts: &[&[u8]]) -> String {
    let digest = |seed: u8| {
        let mut h = DefaultHasher::new();
        seed.hash(&mut h);
        for p in parts {
            p.hash(&mut h);
        }
        h.finish()
    };
    format!("{:016x}{:016x}", digest(0), digest(1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stays_bounded_in_count() {
        let mut c = Lru::new(3, usize::MAX);
        for k in 0..10 {
            c.insert(k.to_string(), k, 1);
        }
        assert_eq!(c.len(), 3);
        assert_eq!(c.get("9"), Some(9));
        assert_eq!(c.get("0"), None);
    }

    #[test]
    fn stays_bounded_in_bytes() {
        let mut c = Lru::new(100, 100);
        for k in 0..10 {
            c.insert(k.to_string(), k, 30);
        }
        assert_eq!((c.len(), c.bytes()), (3, 90));
        c.insert("heavy".into(), 99, 101);
        assert_eq!(c.get("heavy"), None, "heavier than the budget: not kept");
        c.insert("9".into(), 9, 60);
        assert_eq!((c.len(), c.bytes()), (2, 90), "re-inserting replaces the old weight");
    }

    #[test]
    fn keys_separate_parts() {
        assert_ne!(content_key(&[b"ab", b"c"]), content_key(&[b"a", b"bc"]));
        assert_eq!(content_key(&[b"x"]), content_key(&[b"x"]));
    }
}
