//! Peak memory and allocation counts by a counting global allocator: every allocation of the process goes
//! through [`Counting`]. Inside a measured section ([`track`]) it counts bytes allocated minus bytes freed,
//! the peak of that balance and the number of allocations; outside, it only forwards to the system
//! allocator (one relaxed load), so timings elsewhere — and threads of a parallel batch — pay nothing.
//! The balance is exactly the change of live memory since the section began, so memory held before it
//! (the model, earlier results) is not counted, and memory of it freed inside is.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicBool, AtomicIsize, AtomicU64, Ordering};

static ENABLED: AtomicBool = AtomicBool::new(false);
static BALANCE: AtomicIsize = AtomicIsize::new(0);
static PEAK: AtomicIsize = AtomicIsize::new(0);
static ALLOCATIONS: AtomicU64 = AtomicU64::new(0);

/// The system allocator with live-byte, peak and allocation counters.
#[derive(Debug)]
pub struct Counting;

fn grew(bytes: usize) {
    if ENABLED.load(Ordering::Relaxed) {
        let bytes = bytes as isize;
        let balance = BALANCE.fetch_add(bytes, Ordering::Relaxed) + bytes;
        PEAK.fetch_max(balance, Ordering::Relaxed);
    }
}

fn shrank(bytes: usize) {
    if ENABLED.load(Ordering::Relaxed) {
        BALANCE.fetch_sub(bytes as isize, Ordering::Relaxed);
    }
}

fn counted() {
    if ENABLED.load(Ordering::Relaxed) {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
    }
}

// SAFETY: every method forwards to `System` with the caller's pointer and layout unchanged, so `System`'s
// guarantees hold; the counters are plain atomics and never touch the memory.
#[allow(unsafe_code, reason = "a global allocator is an unsafe trait; the impl only forwards to System")]
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = System.alloc(layout);
        if !p.is_null() {
            counted();
            grew(layout.size());
        }
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        let p = System.alloc_zeroed(layout);
        if !p.is_null() {
            counted();
            grew(layout.size());
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout);
        shrank(layout.size());
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let p = System.realloc(ptr, layout, new_size);
        if !p.is_null() {
            counted();
            if new_size >= layout.size() {
                grew(new_size - layout.size());
            } else {
                shrank(layout.size() - new_size);
            }
        }
        p
    }
}

/// Memory used by a measured section.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Usage {
    /// Peak of the live bytes during the section above the live bytes at its start.
    pub peak_bytes: usize,
    /// Live bytes at its end above those at its start: what the section kept, e.g. the value it returns
    /// (negative when it freed older memory).
    pub balance_bytes: isize,
    /// Allocations (including reallocations) made during the section.
    pub allocations: u64,
}

/// Runs `f` and reports its peak memory and allocation count. One section at a time (sections do not
/// nest), and another thread allocating meanwhile is counted too.
pub fn track<R>(f: impl FnOnce() -> R) -> (R, Usage) {
    BALANCE.store(0, Ordering::Relaxed);
    PEAK.store(0, Ordering::Relaxed);
    ALLOCATIONS.store(0, Ordering::Relaxed);
    ENABLED.store(true, Ordering::SeqCst);
    let out = f();
    ENABLED.store(false, Ordering::SeqCst);
    let usage = Usage {
        peak_bytes: PEAK.load(Ordering::Relaxed).max(0) as usize,
        balance_bytes: BALANCE.load(Ordering::Relaxed),
        allocations: ALLOCATIONS.load(Ordering::Relaxed),
    };
    (out, usage)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One test only, as sections do not nest. Other tests run on other threads meanwhile and may add a
    /// little (small strings), never megabytes.
    #[test]
    fn a_section_counts_its_own_memory_only() {
        let held = vec![7u8; 8 << 20];
        let ((), usage) = track(|| {
            let v = vec![1u8; 4 << 20];
            std::hint::black_box(&v);
        });
        assert!(usage.peak_bytes >= 4 << 20 && usage.peak_bytes < 8 << 20, "{usage:?}");
        assert!(usage.balance_bytes.abs() < 1 << 20, "freed inside, nothing kept: {usage:?}");
        assert!(usage.allocations >= 1);
        let (kept, keeping) = track(|| vec![2u8; 2 << 20]);
        // The counters see every thread of the process, and tests run in parallel: another test's small
        // allocations and frees during the section move the balance by bytes (94 fewer in one CI run), so
        // the kept vector is judged to within 1 MiB, as the other balances here are.
        assert!((keeping.balance_bytes - (2 << 20)).abs() < 1 << 20, "the returned vector is kept: {keeping:?}");
        drop(kept);
        let ((), freeing) = track(|| drop(held));
        assert!(freeing.peak_bytes < 1 << 20, "freeing older memory is no peak: {freeing:?}");
        assert!(freeing.balance_bytes <= -(7 << 20), "freeing older memory is a negative balance: {freeing:?}");
    }
}
