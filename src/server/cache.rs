//! A small bounded cache: at most `capacity` entries, the least recently used one goes first.
//!
//! Lookups and inserts are O(capacity) at eviction only; with a few hundred entries that is
//! far below the cost of the work cached (an analysis or a PNG).
//!
//! ```
//! use close::server::cache::Lru;
//! let mut c = Lru::new(2);
//! c.insert("a".into(), 1);
//! c.insert("b".into(), 2);
//! c.get("a");
//! c.insert("c".into(), 3); // evicts "b", the least recently used
//! assert_eq!((c.get("a"), c.get("b"), c.get("c")), (Some(1), None, Some(3)));
//! ```

use std::collections::HashMap;
use std::hash::{DefaultHasher, Hash, Hasher};

/// A bounded least-recently-used map from string keys to cheap-to-clone values.
#[derive(Debug)]
pub struct Lru<V> {
    capacity: usize,
    tick: u64,
    entries: HashMap<String, (V, u64)>,
}

impl<V: Clone> Lru<V> {
    pub fn new(capacity: usize) -> Self {
        Lru { capacity: capacity.max(1), tick: 0, entries: HashMap::new() }
    }

    pub fn get(&mut self, key: &str) -> Option<V> {
        self.tick += 1;
        let tick = self.tick;
        self.entries.get_mut(key).map(|(v, used)| {
            *used = tick;
            v.clone()
        })
    }

    pub fn insert(&mut self, key: String, value: V) {
        self.tick += 1;
        if !self.entries.contains_key(&key) && self.entries.len() >= self.capacity {
            if let Some(oldest) = self.entries.iter().min_by_key(|(_, (_, used))| *used).map(|(k, _)| k.clone()) {
                self.entries.remove(&oldest);
            }
        }
        self.entries.insert(key, (value, self.tick));
    }

    pub fn len(&self) -> usize {
        self.entries.len()
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
    fn stays_bounded() {
        let mut c = Lru::new(3);
        for k in 0..10 {
            c.insert(k.to_string(), k);
        }
        assert_eq!(c.len(), 3);
        assert_eq!(c.get("9"), Some(9));
        assert_eq!(c.get("0"), None);
    }

    #[test]
    fn keys_separate_parts() {
        assert_ne!(content_key(&[b"ab", b"c"]), content_key(&[b"a", b"bc"]));
        assert_eq!(content_key(&[b"x"]), content_key(&[b"x"]));
    }
}
