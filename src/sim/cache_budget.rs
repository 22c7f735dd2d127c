//! The simulator's memory budget: what each cached entry holds, in bytes, and which was used
//! least recently — the entry to forget first when the caches together exceed the budget.

use std::collections::HashMap;
use std::hash::Hash;

/// The most bytes the simulator's caches hold together (parsed flights, CSV texts, drone runs,
/// remembered station predictions): the page keeps one simulator per worker, and a long session
/// must not grow without bound.
pub const MAX_CACHE_BYTES: usize = 256 << 20;

/// Bytes and last use of each cached entry.
pub(crate) struct Ledger<K> {
    entries: HashMap<K, (usize, u64)>,
    clock: u64,
    total: usize,
}

impl<K> Default for Ledger<K> {
    fn default() -> Self {
        Ledger {
            entries: HashMap::new(),
            clock: 0,
            total: 0,
        }
    }
}

impl<K: Clone + Eq + Hash> Ledger<K> {
    /// `key` was just used.
    pub fn touch(&mut self, key: &K) {
        self.clock += 1;
        if let Some(e) = self.entries.get_mut(key) {
            e.1 = self.clock;
        }
    }

    /// `key` now holds `bytes`.
    pub fn insert(&mut self, key: K, bytes: usize) {
        self.clock += 1;
        if let Some((old, _)) = self.entries.insert(key, (bytes, self.clock)) {
            self.total -= old;
        }
        self.total += bytes;
    }

    /// Forgets `key`.
    pub fn remove(&mut self, key: &K) {
        if let Some((bytes, _)) = self.entries.remove(key) {
            self.total -= bytes;
        }
    }

    /// Bytes held by every entry.
    pub fn total(&self) -> usize {
        self.total
    }

    /// While over `budget`, the least recently used entry other than `keep`.
    pub fn over_budget(&self, budget: usize, keep: &K) -> Option<K> {
        if self.total <= budget {
            return None;
        }
        self.entries
            .iter()
            .filter(|(k, _)| *k != keep)
            .min_by_key(|(_, (_, used))| *used)
            .map(|(k, _)| k.clone())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_least_recently_used_entry_goes_first_and_the_new_one_stays() {
        let mut l = Ledger::default();
        l.insert("a", 10);
        l.insert("b", 10);
        l.touch(&"a");
        l.insert("c", 10);
        assert_eq!(l.total(), 30);
        assert_eq!(l.over_budget(25, &"c"), Some("b"));
        l.remove(&"b");
        assert_eq!(l.over_budget(25, &"c"), None);
        assert_eq!(l.over_budget(5, &"c"), Some("a"));
    }
}
