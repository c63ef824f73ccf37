//! FNV-1a, 64 bits (offset basis 0xcbf29ce484222325, prime 0x100000001b3), written out here
//! because std's `DefaultHasher` is not stable across Rust releases: shard assignment
//! ([`crate::shard`]) and the experiment files' hash depend on it, and so does the source hash
//! of the code revision (`reproduce/build.rs` includes this file). Std only.

/// FNV-1a 64 of `bytes`.
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in bytes {
        h ^= u64::from(*b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv1a64_is_the_published_function() {
        // Test vectors of the FNV reference (draft-eastlake-fnv).
        assert_eq!(fnv1a64(b""), 0xcbf29ce484222325);
        assert_eq!(fnv1a64(b"a"), 0xaf63dc4c8601ec8c);
        assert_eq!(fnv1a64(b"foobar"), 0x85944171f73967e8);
    }
}
