//! Names of the refinement schemes and of the wavelet constructions.

use crate::error::WaveletError;

/// A refinement rule for 4-to-1 splitting K^j -> K^{j+1} (the chapter's figure 2.13).
///
/// Every scheme inserts one vertex per edge and splits each triangle into
/// four; they differ in where vertices go. As the predictor of a filter bank
/// the scheme fixes the scaling functions: synthesis with all wavelet
/// coefficients zero is exactly this subdivision scheme.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[non_exhaustive]
pub enum Scheme {
    /// Midpoint (linear) splitting: new vertices at edge midpoints, old ones
    /// fixed. Its scaling functions are the hat functions of the chapter, so the
    /// filter bank is the piecewise-linear wavelet construction of Lounsbery,
    /// DeRose and Warren (1997) (eq. 2.36-2.39).
    #[default]
    Midpoint,
    /// Loop (1987) approximating subdivision with the boundary rules of Hoppe
    /// et al. (1994): odd `3/8 (a + b) + 1/8 (c + d)`, even
    /// `(1 - n beta) v + beta sum v_k` with
    /// `beta = (5/8 - (3/8 + cos(2 pi / n) / 4)^2) / n`; boundary edges split
    /// at the midpoint, boundary vertices `3/4 v + 1/8 (v_prev + v_next)`.
    Loop,
    /// Modified butterfly interpolating subdivision (Zorin, Schroeder and
    /// Sweldens 1996): the 8-point butterfly between regular vertices, the
    /// extraordinary-vertex masks otherwise, the 4-point rule along
    /// boundaries. Old vertices stay where they are.
    Butterfly,
}

impl Scheme {
    /// Every scheme; their [`name`](Self::name)s are what [`FromStr`](std::str::FromStr) accepts
    /// and [`Display`](std::fmt::Display) writes.
    pub const ALL: [Scheme; 3] = [Scheme::Midpoint, Scheme::Loop, Scheme::Butterfly];

    /// The name used on the command line: `midpoint`, `loop`, `butterfly`.
    pub fn name(self) -> &'static str {
        match self {
            Scheme::Midpoint => "midpoint",
            Scheme::Loop => "loop",
            Scheme::Butterfly => "butterfly",
        }
    }

    /// `true` when old vertices keep their positions (midpoint, butterfly).
    pub fn is_interpolating(self) -> bool {
        !matches!(self, Scheme::Loop)
    }
}

mesh_kernel::named_choice!(Scheme, "scheme", WaveletError);

/// Which wavelets complement the scaling functions of a [`Scheme`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum WaveletKind {
    /// The lazy wavelet: the wavelet of an odd vertex is its fine scaling
    /// function, `psi_m = phi^{j+1}_m`, so a coefficient is the odd vertex
    /// minus its prediction. Cheapest, far from orthogonal.
    Lazy,
    /// The lifted wavelet `psi_m = phi^{j+1}_m - sum_k s_{m,k} phi^j_k` over
    /// the four coarse vertices of the edge's diamond, with weights `s` that
    /// minimise `sum_i <psi_m, phi^j_i>^2` under the inner product of eq. 2.36
    /// (a local least-squares orthogonalisation in the spirit of Lounsbery et
    /// al. 1997 and of the lifting of Schroeder and Sweldens 1995).
    #[default]
    Lifted,
}

impl WaveletKind {
    /// Both kinds; their [`name`](Self::name)s are what [`FromStr`](std::str::FromStr) accepts
    /// and [`Display`](std::fmt::Display) writes.
    pub const ALL: [WaveletKind; 2] = [WaveletKind::Lazy, WaveletKind::Lifted];

    /// The name used on the command line: `lazy`, `lifted`.
    pub fn name(self) -> &'static str {
        match self {
            WaveletKind::Lazy => "lazy",
            WaveletKind::Lifted => "lifted",
        }
    }
}

mesh_kernel::named_choice!(WaveletKind, "wavelet", WaveletError);
