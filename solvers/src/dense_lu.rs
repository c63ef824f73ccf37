//! Dense LU factorisation with partial pivoting, P A = L U, on one of two backends, chosen by the
//! matrix size against a crossover measured by the cost harness (`reproduce::cost`, `reproduce cost`):
//!
//! - [`Backend::Nalgebra`]: the in-place, unblocked Doolittle elimination of
//!   [`crate::neural::lu`] on a nalgebra `DMatrix` (what the networks and the KKT solve used
//!   alone before), cheapest for the papers' small systems (n <= 20 or so);
//! - [`Backend::Faer`]: faer's blocked, SIMD partial-pivoting LU
//!   (`faer::linalg::lu::partial_pivoting`), single-threaded (called with `Par::Seq`: the
//!   reproduction runs one simulation per core; faer's `rayon` feature is compiled in all the
//!   same, since diffsol-la enables it, but nothing here asks for threads), on the same
//!   column-major storage viewed as a `faer::MatMut`, so no copy between the two.
//!
//! [`Backend::for_size`] takes faer for n >= [`FAER_CROSSOVER`] = 64, read from the network
//! Jacobian's LU (`network-lu`) of `results/dof-cost.csv` (see the report's "Cost against the
//! number of joints"): in two measurements faer was faster at every size from 64 on (jia2019's
//! N = 20 and 30, LVI-PDNN states of 64 and 94; kong2019's N = 70 to 200, sizes 73 to 203,
//! 2.6-2.8 times at 203), at parity or slower at 43-53 (0.76-1.01 times), and slower below.
//! Users: the VP-RNN-PF network's W (eq. 2.30) and any dense, unstructured matrix. Not the KKT solve ([`crate::solve_equality_kkt`]): its matrix
//! `[[P, A'], [A, 0]]` is mostly P's identity or diagonal block and zeros, which the in-place
//! elimination skips (an update column whose pivot-row entry is 0 costs nothing), so nalgebra
//! stayed faster there at every measured N up to 200 (`kkt-floor`). Both backends give the same
//! solution to rounding (`tests/dense_lu.rs`).
//!
//! [`DenseLu`] holds the factors and faer's scratch, preallocated for one size, so factorising
//! and solving allocate nothing.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::lu::partial_pivoting::{factor, solve};
use faer::{MatMut, MatRef, Par};
use nalgebra::DMatrix;

use settings::FAER_CROSSOVER;

/// Which library factorises.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Backend {
    /// The in-place elimination of [`crate::neural::lu`] on nalgebra storage.
    Nalgebra,
    /// faer's partial-pivoting LU.
    Faer,
}

impl Backend {
    /// Both backends, nalgebra first.
    pub const ALL: [Backend; 2] = [Backend::Nalgebra, Backend::Faer];

    /// `nalgebra`, `faer` (the `backend` column of `results/dof-cost.csv`).
    pub fn id(self) -> &'static str {
        match self {
            Backend::Nalgebra => "nalgebra",
            Backend::Faer => "faer",
        }
    }

    /// The backend named `id` ([`Self::id`]).
    pub fn from_id(id: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|b| b.id() == id)
    }

    /// The faster backend for an n x n system: faer from [`FAER_CROSSOVER`] on.
    pub fn for_size(n: usize) -> Self {
        if n >= FAER_CROSSOVER {
            Backend::Faer
        } else {
            Backend::Nalgebra
        }
    }
}

/// The LU factors of an n x n matrix on one backend, with every buffer preallocated.
pub struct DenseLu {
    backend: Backend,
    /// L (strict lower triangle, unit diagonal implied) and U (upper triangle), in place.
    lu: DMatrix<f64>,
    /// nalgebra: row k swapped with `piv[k]`, in order; faer: the forward row permutation.
    piv: Vec<usize>,
    /// faer: the inverse row permutation.
    piv_inv: Vec<usize>,
    /// faer's scratch for factorising and solving (empty for nalgebra).
    scratch: MemBuffer,
    factored: bool,
}

impl DenseLu {
    /// Buffers for n x n systems on `backend`.
    pub fn new(n: usize, backend: Backend) -> Self {
        DenseLu {
            backend,
            lu: DMatrix::zeros(n, n),
            piv: vec![0; n],
            piv_inv: vec![0; n],
            scratch: scratch(n, backend),
            factored: false,
        }
    }

    /// Buffers for n x n systems on the faster backend ([`Backend::for_size`]).
    pub fn for_size(n: usize) -> Self {
        Self::new(n, Backend::for_size(n))
    }

    /// The backend these buffers factorise on.
    pub fn backend(&self) -> Backend {
        self.backend
    }

    /// The size n.
    pub fn size(&self) -> usize {
        self.lu.nrows()
    }

    /// Factorises `a` (n x n, copied); false when a pivot is zero or not finite (the matrix is
    /// singular to working precision), and then [`Self::solve`] must not be called.
    pub fn factor(&mut self, a: &DMatrix<f64>) -> bool {
        assert_eq!(
            a.shape(),
            self.lu.shape(),
            "DenseLu: matrix of another size"
        );
        self.lu.copy_from(a);
        let n = self.size();
        self.factored = match self.backend {
            Backend::Nalgebra => crate::neural::lu::factor(&mut self.lu, &mut self.piv),
            Backend::Faer => {
                factor::lu_in_place(
                    faer_mut(&mut self.lu),
                    &mut self.piv,
                    &mut self.piv_inv,
                    Par::Seq,
                    MemStack::new(&mut self.scratch),
                    Default::default(),
                );
                (0..n).all(|k| {
                    let u = self.lu[(k, k)];
                    u != 0.0 && u.is_finite()
                })
            }
        };
        self.factored
    }

    /// min_k |u_kk| / max_k |u_kk| over U's diagonal of the last [`Self::factor`] (1 for an
    /// empty matrix): a cheap singularity indicator, tiny (to rounding, about 1e-16) when the
    /// factored matrix is singular but rounding left every pivot nonzero.
    pub fn pivot_ratio(&self) -> f64 {
        let (lo, hi) = (0..self.size())
            .map(|k| self.lu[(k, k)].abs())
            .fold((f64::INFINITY, 0.0f64), |(lo, hi), u| {
                (lo.min(u), hi.max(u))
            });
        if hi > 0.0 {
            lo / hi
        } else if self.size() == 0 {
            1.0
        } else {
            0.0
        }
    }

    /// Solves A x = b in place (`b` becomes x) with the factors of the last successful
    /// [`Self::factor`].
    pub fn solve(&mut self, b: &mut [f64]) {
        assert!(self.factored, "DenseLu::solve without a successful factor");
        let n = self.size();
        assert_eq!(b.len(), n, "DenseLu: right-hand side of another size");
        match self.backend {
            Backend::Nalgebra => crate::neural::lu::solve(&self.lu, &self.piv, b),
            Backend::Faer => {
                let lu = MatRef::from_column_major_slice(self.lu.as_slice(), n, n);
                let perm = faer::perm::PermRef::new_checked(&self.piv, &self.piv_inv, n);
                solve::solve_in_place(
                    lu,
                    lu,
                    perm,
                    MatMut::from_column_major_slice_mut(b, n, 1),
                    Par::Seq,
                    MemStack::new(&mut self.scratch),
                );
            }
        }
    }
}

impl DenseLu {
    /// Solves A X = B in place for every column of `b` (n rows), with the same factors.
    pub fn solve_columns(&mut self, b: &mut DMatrix<f64>) {
        let n = b.nrows();
        for j in 0..b.ncols() {
            // A DMatrix is stored column-major: column j is one contiguous slice.
            self.solve(&mut b.as_mut_slice()[j * n..(j + 1) * n]);
        }
    }
}

impl Clone for DenseLu {
    fn clone(&self) -> Self {
        DenseLu {
            backend: self.backend,
            lu: self.lu.clone(),
            piv: self.piv.clone(),
            piv_inv: self.piv_inv.clone(),
            scratch: scratch(self.size(), self.backend),
            factored: self.factored,
        }
    }
}

impl std::fmt::Debug for DenseLu {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("DenseLu")
            .field("backend", &self.backend)
            .field("size", &self.size())
            .field("factored", &self.factored)
            .finish_non_exhaustive()
    }
}

/// faer's scratch for factorising and solving an n x n system (none for nalgebra).
fn scratch(n: usize, backend: Backend) -> MemBuffer {
    MemBuffer::new(match backend {
        Backend::Nalgebra => StackReq::EMPTY,
        Backend::Faer => {
            factor::lu_in_place_scratch::<usize, f64>(n, n, Par::Seq, Default::default())
                .or(solve::solve_in_place_scratch::<usize, f64>(n, 1, Par::Seq))
        }
    })
}

/// `a` viewed as a faer matrix (same column-major storage).
fn faer_mut(a: &mut DMatrix<f64>) -> MatMut<'_, f64> {
    let (m, n) = a.shape();
    MatMut::from_column_major_slice_mut(a.as_mut_slice(), m, n)
}
