//! No allocation per step: once a KKT pattern is analysed and its first system factorized and solved,
//! every further numeric factorization and refined solve of the same pattern allocates nothing, on every
//! backend. Counted by a global allocator of this test's own process, on the thread that factorizes and
//! solves (the backends run sequentially on the caller's thread): the test harness's own thread, which
//! may allocate meanwhile on a loaded machine, is not counted (a full workspace run once saw 4 of its
//! allocations counted as the simplicial LDLᵀ's).

#[path = "../../crates/solver/tests/common/mod.rs"]
mod common;

use common::{random_j, random_spd, random_vec, to_sparse, Rng};
use elastokin_solver::kkt::{
    Accuracy, AutoKkt, BackendChoice, DenseLu, FactorKind, KktBackend, KktFactor, KktOptions, KktValues,
};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicU64, Ordering};

thread_local! {
    /// Whether this thread's allocations are counted (a constant-initialized cell: reading it allocates
    /// nothing, so the allocator may).
    static COUNTING: Cell<bool> = const { Cell::new(false) };
}
static ALLOCATIONS: AtomicU64 = AtomicU64::new(0);

/// Counts an allocation when this thread counts.
fn count() {
    if COUNTING.with(Cell::get) {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
    }
}

/// The system allocator, counting the allocations of a thread while its [`COUNTING`] is set.
struct Counting;

// SAFETY: every method forwards to `System` with the caller's pointer and layout unchanged; the counter is
// a plain atomic and the flag a constant-initialized thread-local, neither touches the memory.
#[allow(unsafe_code, reason = "a global allocator is an unsafe trait; the impl only forwards to System")]
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        System.alloc(layout)
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        System.realloc(ptr, layout, new_size)
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations made by `f` on this thread.
fn allocations(f: impl FnOnce()) -> u64 {
    ALLOCATIONS.store(0, Ordering::Relaxed);
    COUNTING.with(|c| c.set(true));
    f();
    COUNTING.with(|c| c.set(false));
    ALLOCATIONS.load(Ordering::Relaxed)
}

#[test]
fn factorizing_and_solving_a_pattern_again_allocates_nothing_on_any_backend() {
    let mut rng = Rng(0xa110c);
    let (n, m) = (60usize, 25usize);
    let k = random_spd(&mut rng, n, 0.1);
    let j = random_j(&mut rng, m, n, 4);
    let (pattern, kv, jv) = to_sparse(&k, &j);
    // The values of 50 steps along a path, made before counting.
    let steps: Vec<Vec<f64>> = (0..50).map(|s| kv.iter().map(|v| v * (1.0 + s as f64 / 10.0)).collect()).collect();
    let rhs = random_vec(&mut rng, n + m);
    let mut z = rhs.clone();
    let options = |kind| KktOptions { kind, ..KktOptions::default() };
    let mut backends: Vec<(&str, Box<dyn KktBackend>)> = vec![
        ("simplicial LDLᵀ", Box::new(KktFactor::analyze(&pattern, options(FactorKind::Simplicial)).unwrap())),
        ("supernodal LDLᵀ", Box::new(KktFactor::analyze(&pattern, options(FactorKind::Supernodal)).unwrap())),
        ("dense LU", Box::new(DenseLu::analyze(&pattern, KktOptions::default()).unwrap())),
        ("automatic", Box::new(AutoKkt::analyze(&pattern, KktOptions::default(), BackendChoice::Auto).unwrap())),
    ];
    for (name, backend) in &mut backends {
        // Warm-up: the first factorization and solve may size what the analysis could not know.
        backend.factorize(KktValues { k: &steps[0], k_skew: None, j: &jv }).unwrap();
        z.copy_from_slice(&rhs);
        backend.solve_in_place(&mut z, Accuracy::Refined).unwrap();
        let counted = allocations(|| {
            for k in &steps[1..] {
                let report = backend.factorize(KktValues { k, k_skew: None, j: &jv }).unwrap();
                assert!(report.suspect_body_dofs.is_empty() && report.suspect_constraint_rows.is_empty());
                z.copy_from_slice(&rhs);
                backend.solve_in_place(&mut z, Accuracy::Refined).unwrap();
            }
        });
        assert_eq!(counted, 0, "{name}: {counted} allocations over 49 factorizations and solves");
        // The solves were real: each step's solution satisfies its own system.
        let last = nalgebra::DMatrix::from_fn(n, n, |r, c| k[(r, c)] * (1.0 + 49.0 / 10.0));
        let x = nalgebra::DVector::from_column_slice(&z[..n]);
        let y = nalgebra::DVector::from_column_slice(&z[n..]);
        let jm = &j;
        let force = &last * &x + jm.transpose() * &y - nalgebra::DVector::from_column_slice(&rhs[..n]);
        let constraint = jm * &x - nalgebra::DVector::from_column_slice(&rhs[n..]);
        // Measured: force residual at most 6.7e-15, constraint residual 2.2e-16 (all four backends).
        assert!(force.amax() < 5e-13 && constraint.amax() < 2e-14, "{name}: {} {}", force.amax(), constraint.amax());
    }
}
