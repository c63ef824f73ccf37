//! The one counting allocator of the workspace, for tests and benches that show a code path
//! allocates nothing (or how much it allocates): linking this crate installs, as the
//! `#[global_allocator]`, the system allocator with a per-thread counter, so a binary that
//! calls [`count`] cannot forget to install it, and a second allocator in the same binary is a
//! compile error rather than a silent zero.
//!
//! What is counted: every `alloc`, `alloc_zeroed` and `realloc` (a reallocation is one
//! allocation; `dealloc` is not counted), made by the current thread. Per thread, so that a
//! test harness running other tests on other threads does not disturb the count; code that
//! hands work to other threads has that work's allocations uncounted. The cost is one
//! thread-local increment per allocation.
//!
//! A dev-dependency only (and a dependency of `driftbench-benches`, whose bench binaries are
//! not programs of the suite): `reproduce/tests/layering.rs` checks that no other crate links it.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

/// The system allocator, counting each thread's allocations in [`ALLOCATIONS`].
struct CountingAllocator;

thread_local! {
    /// This thread's allocations so far (a `Cell` with a const initialiser, which itself
    /// never allocates).
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

/// Adds one to this thread's count (nothing once the thread's locals are destroyed).
fn tick() {
    let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
}

// SAFETY: every call is forwarded to `System` unchanged; the counter never allocates.
unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        tick();
        // SAFETY: the caller's contract is passed on.
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        tick();
        // SAFETY: the caller's contract is passed on.
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        tick();
        // SAFETY: the caller's contract is passed on.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: the caller's contract is passed on.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: CountingAllocator = CountingAllocator;

/// `f`'s value and the allocations the current thread made while `f` ran.
pub fn count_with<R>(f: impl FnOnce() -> R) -> (R, usize) {
    let before = ALLOCATIONS.with(Cell::get);
    let r = f();
    (r, ALLOCATIONS.with(Cell::get) - before)
}

/// The allocations the current thread makes while `f` runs.
pub fn count(f: impl FnOnce()) -> usize {
    count_with(f).1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_this_threads_allocations_and_reallocations() {
        assert_eq!(count(|| ()), 0);
        assert_eq!(count(|| drop(std::hint::black_box(Box::new(1u64)))), 1);
        let n = count(|| {
            let mut v: Vec<u8> = std::hint::black_box(Vec::with_capacity(1));
            v.extend_from_slice(&[0; 64]);
        });
        assert_eq!(n, 2, "one allocation, one reallocation");
        let (v, n) = count_with(|| std::hint::black_box(vec![0u8; 16]));
        assert_eq!((v.len(), n), (16, 1));
    }

    #[test]
    fn another_threads_allocations_are_not_counted() {
        use std::sync::atomic::{AtomicUsize, Ordering};
        let done = AtomicUsize::new(0);
        std::thread::scope(|s| {
            let worker = s.spawn(|| {
                count(|| {
                    for _ in 0..1000 {
                        drop(std::hint::black_box(Box::new(0u64)));
                        done.fetch_add(1, Ordering::Release);
                    }
                })
            });
            // This thread waits, allocating nothing, while the other allocates 1000 times.
            let here = count(|| while done.load(Ordering::Acquire) < 1000 {});
            assert_eq!(here, 0);
            assert_eq!(worker.join().unwrap(), 1000);
        });
    }
}
