//! Run keys held in a few bytes each, for the steps that must know a set of runs without
//! holding their keys (a shard, a merge: docs/cluster.md, "What a shard and a merge hold").
//!
//! - **A key's print** ([`print`]): FNV-1a 128 of the key as written (`experiment / variant /
//!   solver`): offset basis 0x6c62272e07bb014262b821756295c58d, prime 2^88 + 2^8 + 0x3b
//!   (0x0000000001000000000000000000013b), each byte XORed in then multiplied. Two distinct
//!   keys share a print with probability about 2^-128 per pair: for 10^7 keys, about
//!   n^2 / 2^129 ~ 10^-25 that any two do. Std only, stable across Rust releases.
//! - **A set of keys** ([`KeySet`]): their prints, sorted: 16 bytes a key instead of ~200
//!   (a key's three strings and a hash table's slot), membership by binary search.
//! - **A multiset's sum** ([`KeySum`]): the count of the keys and the sum of their prints
//!   mod 2^128, which neither order nor grouping changes: two multisets with the same sum and
//!   count are equal but with probability about 2^-128 (a difference of multisets sums to zero
//!   only if the prints of the keys it adds and removes cancel). A shard's manifest records
//!   the sum of the keys assigned to it, and the merge compares each shard's rows with the
//!   selection's by their sums, in memory independent of the number of runs.

/// FNV-1a 128 of `key` (module docs).
pub fn print(key: &str) -> u128 {
    let mut h: u128 = 0x6c62_272e_07bb_0142_62b8_2175_6295_c58d;
    for b in key.as_bytes() {
        h ^= u128::from(*b);
        h = h.wrapping_mul(0x0000_0000_0100_0000_0000_0000_0000_013b);
    }
    h
}

/// A set of run keys by their prints (module docs): 16 bytes a key.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct KeySet {
    /// The prints, sorted, each once.
    prints: Vec<u128>,
}

impl KeySet {
    /// Whether the set holds `key`.
    pub fn contains(&self, key: &str) -> bool {
        self.prints.binary_search(&print(key)).is_ok()
    }

    /// How many keys the set holds.
    pub fn len(&self) -> usize {
        self.prints.len()
    }

    /// Whether the set holds no key.
    pub fn is_empty(&self) -> bool {
        self.prints.is_empty()
    }
}

impl<S: AsRef<str>> FromIterator<S> for KeySet {
    fn from_iter<I: IntoIterator<Item = S>>(keys: I) -> Self {
        let mut prints: Vec<u128> = keys.into_iter().map(|k| print(k.as_ref())).collect();
        prints.sort_unstable();
        prints.dedup();
        prints.shrink_to_fit();
        KeySet { prints }
    }
}

/// The count and the sum of the prints of a multiset of run keys (module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct KeySum {
    /// How many keys.
    pub count: usize,
    /// The sum of their prints, mod 2^128.
    pub sum: u128,
}

impl KeySum {
    /// Adds `key` to the multiset.
    pub fn add(&mut self, key: &str) {
        self.count += 1;
        self.sum = self.sum.wrapping_add(print(key));
    }

    /// The sum as 32 lower-case hex digits (as a shard's manifest writes it).
    pub fn hex(&self) -> String {
        format!("{:032x}", self.sum)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn print_is_the_published_fnv1a_128() {
        // Test vectors of the FNV reference (draft-eastlake-fnv, FNV-1a 128).
        assert_eq!(print(""), 0x6c62272e07bb014262b821756295c58d);
        assert_eq!(print("a"), 0xd228cb696f1a8caf78912b704e4a8964);
        assert_eq!(print("foobar"), 0x343e1662793c64bf6f0d3597ba446f18);
    }

    /// The set holds exactly what it was made of, whatever the order and repeats.
    #[test]
    fn a_set_holds_its_keys_and_no_other() {
        let keys: Vec<String> = (0..1000).map(|i| format!("e / v-{i} / exact")).collect();
        let set: KeySet = keys.iter().rev().chain(&keys[..10]).collect();
        assert_eq!(set.len(), 1000);
        assert!(keys.iter().all(|k| set.contains(k)));
        assert!(!set.contains("e / v-1000 / exact"));
        assert!(!set.contains("e / v-1 / znn"));
        assert!(KeySet::default().is_empty());
    }

    /// The sum does not depend on the order, and a missing, an extra, a repeated or a swapped
    /// key changes it.
    #[test]
    fn a_sum_tells_multisets_apart_in_any_order() {
        let keys: Vec<String> = (0..100).map(|i| format!("e / v-{i} / exact")).collect();
        let sum = |ks: &[&String]| {
            let mut s = KeySum::default();
            for k in ks {
                s.add(k);
            }
            s
        };
        let all: Vec<&String> = keys.iter().collect();
        let reversed: Vec<&String> = keys.iter().rev().collect();
        assert_eq!(sum(&all), sum(&reversed));
        assert_eq!(sum(&all).count, 100);
        let missing: Vec<&String> = keys[1..].iter().collect();
        assert_ne!(sum(&missing).sum, sum(&all).sum);
        let mut repeated = missing.clone();
        repeated.push(&keys[1]);
        assert_eq!(sum(&repeated).count, 100);
        assert_ne!(sum(&repeated), sum(&all));
        let other = "e / v-100 / exact".to_string();
        let mut swapped = missing.clone();
        swapped.push(&other);
        assert_ne!(sum(&swapped), sum(&all));
        assert_eq!(sum(&all).hex().len(), 32);
    }
}
