//! Local polynomial fits of the surface as a height field over the tangent
//! plane ("osculating jets", Cazals and Pouget 2005): the quadric (what
//! libigl's `principal_curvature` fits), the cubic through positions and
//! normals of Goldfeather and Interrante 2004, and the quartic, the
//! default. Curvatures come from the fundamental forms of the fitted height
//! field (eq. 2.21-2.24), so a tilted tangent plane costs no accuracy.
//!
//! A jet of degree `d` fitted to a neighbourhood of size `h` gives
//! curvatures with error `O(h^(d - 1))` (Cazals and Pouget), one order more
//! where the neighbourhood is symmetric. The least-squares normal equations
//! are assembled from power sums of the data (O(1) per point whatever the
//! degree) and solved by `L D L^T`, with a pivoted Cholesky rank test
//! deciding when the data cannot carry the polynomial (one-sided
//! neighbourhoods at a boundary, too few points), and a conditioning test
//! deciding when they carry it too loosely (a 2-ring of 14 points around a
//! valence-4 vertex nearly on a quartic curve through the centre, which the
//! quartic would interpolate with an O(1) error): the fit then grows the
//! neighbourhood by one ring, then lowers the degree. The conditioning is
//! measured in whitened tangent coordinates, so a stretched but well-spread
//! neighbourhood passes.

use glam::DVec3;
use mesh_kernel::TriMesh;

use crate::error::{CurvatureError, Result};
use crate::frame::{solve_spd, tangent_basis, InverseBlock, Sym2};
use crate::neighborhood::{Adjacency, Gatherer, Neighborhood};
use crate::status::{topological_status, VertexStatus};
use crate::tensor::LocalTensor;
use mesh_kernel::geometry::NormalWeighting;
use mesh_kernel::par;

/// Degree of the fitted height field.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Degree {
    /// `z = A x^2 / 2 + B x y + C y^2 / 2` (plus the linear terms when the
    /// normal is refined): curvature error `O(h)`, `O(h^2)` on symmetric
    /// neighbourhoods. Needs 3 (5) data.
    Quadric,
    /// The quadric plus the four cubic terms `x^3, x^2 y, x y^2, y^3`, which
    /// absorb the odd part of the surface: curvature error `O(h^2)` on any
    /// neighbourhood. Needs 7 (9) data.
    Cubic,
    /// The cubic plus the five quartic terms, which also absorb the even
    /// fourth-order part (a sphere's `r^4 / 8`): curvature error `O(h^3)`.
    /// Needs 12 (14) data: a 2-ring.
    #[default]
    Quartic,
}

impl Degree {
    /// Every degree; their [`name`](Self::name)s are what
    /// [`FromStr`](std::str::FromStr) accepts and
    /// [`Display`](std::fmt::Display) writes.
    pub const ALL: [Self; 3] = [Self::Quadric, Self::Cubic, Self::Quartic];

    /// The name used on the command line: `quadric`, `cubic`, `quartic`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Quadric => "quadric",
            Self::Cubic => "cubic",
            Self::Quartic => "quartic",
        }
    }

    /// The lower of two degrees.
    pub(crate) fn min_with(self, other: Self) -> Self {
        let rank = |d: Self| d as u8;
        if rank(self) <= rank(other) {
            self
        } else {
            other
        }
    }
}

mesh_kernel::named_choice!(Degree, "degree", CurvatureError);

/// Options of [`crate::TensorMethod::Fit`]. The default, a quartic through the
/// 2-ring positions with the tangent plane refined, is the most accurate
/// estimator of the crate on every validation surface (README).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitOptions {
    /// The points fitted (the centre vertex is the origin of the fit).
    pub neighborhood: Neighborhood,
    /// The polynomial.
    pub degree: Degree,
    /// Fit the neighbours' vertex normals too, two slope equations per
    /// neighbour (Goldfeather and Interrante 2004), which triples the data
    /// of a 1-ring but imports the normals' error: weighted face-normal
    /// averages are only first-order accurate at irregular vertices.
    pub use_normals: bool,
    /// Fit the linear terms too, tilting the tangent plane to the fitted
    /// surface instead of trusting the vertex normal (the output normal is
    /// the fitted one). Makes the result independent of the normal's error.
    pub refine_normal: bool,
}

impl Default for FitOptions {
    fn default() -> Self {
        Self { neighborhood: Neighborhood::Rings(2), degree: Degree::Quartic, use_normals: false, refine_normal: true }
    }
}

/// Exponents `(a, b)` of the monomial `x^a y^b` of each column of the full
/// design: `z = D x + E y + c20 x^2 + B x y + c02 y^2 + (cubic) + (quartic)`,
/// with `A = 2 c20`, `C = 2 c02` the second derivatives.
const MONOMIALS: [(usize, usize); 14] =
    [(1, 0), (0, 1), (2, 0), (1, 1), (0, 2), (3, 0), (2, 1), (1, 2), (0, 3), (4, 0), (3, 1), (2, 2), (1, 3), (0, 4)];

/// Number of columns of the full design.
const COLUMNS: usize = MONOMIALS.len();

/// The columns active for the options: the range `first .. last` of
/// [`MONOMIALS`] (the linear terms only when the normal is refined).
fn active_columns(options: &FitOptions) -> (usize, usize) {
    let first = if options.refine_normal { 0 } else { 2 };
    let last = match options.degree {
        Degree::Quadric => 5,
        Degree::Cubic => 9,
        Degree::Quartic => 14,
    };
    (first, last)
}

/// Rank test of the fits (see [`solve_spd`]): a column whose squared sine to
/// the span of the others is below this makes the fit ill-posed, and the
/// next fallback is tried. Pivoting makes the test insensitive to this
/// value over 1e-8..1e-14 on the validation shapes.
const PIVOT_TOLERANCE: f64 = 1e-10;

/// Conditioning test of the fits: the largest diagonal entry of the inverse
/// normal matrix over the gradient and Hessian coefficients, in whitened
/// coordinates (see `Moments::whitened_spread`). It bounds how much the residual of the
/// fit (the surface's terms beyond the polynomial, `O(h^(d + 1))`) is
/// amplified into the curvature: `|error| <= sqrt(spread) |residual|`.
/// Well-spread neighbourhoods give about 4 whatever the mesh (2-rings of
/// icospheres, grids, tori); a 2-ring whose points nearly lie on a quartic
/// curve through the centre (the 14 points around a valence-4 vertex of a
/// grid split along alternating diagonals) gives up to 1e12, and its fit is
/// off by O(1). Above this value the next fallback is tried; a fit with
/// `spread` below 100 or 1000 gives the same results on every validation
/// surface.
const MAX_SPREAD: f64 = 100.0;

/// Index of `x^a y^b` in a triangular table of monomials with `a + b <= d`
/// stored row by row (`a` major): row `a` starts at `a (2d + 3 - a) / 2`.
#[inline(always)]
const fn tri(d: usize, a: usize, b: usize) -> usize {
    a * (2 * d + 3 - a) / 2 + b
}

/// `POSITION_PRODUCTS[c][d]`: the power sum (index in [`Moments`]'s
/// position table) of the product of the monomials of columns `c` and `d`
/// of [`MONOMIALS`], so that assembling the normal equations does no index
/// arithmetic: the default fit on a 40,962-vertex icosphere took 47.3 ms
/// instead of 49.8 on one core (2026-12-06).
const POSITION_PRODUCTS: [[u8; COLUMNS]; COLUMNS] = {
    let mut table = [[0; COLUMNS]; COLUMNS];
    let mut c = 0;
    while c < COLUMNS {
        let mut d = 0;
        while d < COLUMNS {
            let ((ac, bc), (ad, bd)) = (MONOMIALS[c], MONOMIALS[d]);
            table[c][d] = tri(8, ac + ad, bc + bd) as u8;
            d += 1;
        }
        c += 1;
    }
    table
};

/// Positions added to [`Moments`] together: lane `l` of every power sum
/// takes points `l`, `l + LANES`, ..., so that a batch's products are
/// independent and the compiler runs them side by side in vector
/// registers. Two fill one SSE2 register, the baseline of x86-64: the
/// default fit on a 40,962-vertex icosphere took 43.8 ms on one core with
/// two lanes, 47.3 with four, 52.8 with eight and 56.4 with one
/// (2026-12-06).
const LANES: usize = 2;

/// Up to [`LANES`] positions `(x, y, z)` waiting to be added to [`Moments`].
#[derive(Default)]
struct Batch {
    x: [f64; LANES],
    y: [f64; LANES],
    z: [f64; LANES],
    len: usize,
}

/// Power sums of the data, from which the least-squares normal equations of
/// any set of monomial columns are assembled: a position row of column
/// `x^a y^b` times one of `x^c y^d` sums to `sum x^(a+c) y^(b+d)`, and the
/// slope rows (derivatives of the monomials) likewise. O(1) per point
/// whatever the number of columns.
struct Moments {
    /// `sum x^a y^b` over positions, `a + b <= 8` (triangular table), once
    /// the lanes are folded.
    pos: [f64; 45],
    /// `sum z x^a y^b`, `a + b <= 4`, likewise.
    z: [f64; 15],
    /// The sums of `pos` and `z` by lane, as they are accumulated.
    pos_lanes: [[f64; LANES]; 45],
    z_lanes: [[f64; LANES]; 15],
    /// `sum x^a y^b` over points with a usable normal, `a + b <= 6`.
    nrm: [f64; 28],
    /// `sum s_x x^a y^b`, `a + b <= 3` (slope along x).
    sx: [f64; 10],
    /// `sum s_y x^a y^b`, `a + b <= 3` (slope along y).
    sy: [f64; 10],
    /// Number of positions.
    points: usize,
    /// Number of equations.
    rows: usize,
}

impl Moments {
    fn new() -> Self {
        Self {
            pos: [0.0; 45],
            z: [0.0; 15],
            pos_lanes: [[0.0; LANES]; 45],
            z_lanes: [[0.0; LANES]; 15],
            nrm: [0.0; 28],
            sx: [0.0; 10],
            sy: [0.0; 10],
            points: 0,
            rows: 0,
        }
    }

    /// Adds the power sums of a batch of positions (lanes past
    /// `batch.len` hold zeros and are given weight zero).
    #[inline]
    fn add_points(&mut self, batch: &Batch) {
        let mut xp = [[0.0; LANES]; 9];
        let mut yp = [[1.0; LANES]; 9];
        for l in 0..LANES {
            xp[0][l] = if l < batch.len { 1.0 } else { 0.0 };
        }
        for k in 1..9 {
            for l in 0..LANES {
                xp[k][l] = xp[k - 1][l] * batch.x[l];
                yp[k][l] = yp[k - 1][l] * batch.y[l];
            }
        }
        for a in 0..9 {
            for b in 0..9 - a {
                let sum = &mut self.pos_lanes[tri(8, a, b)];
                for l in 0..LANES {
                    sum[l] += xp[a][l] * yp[b][l];
                }
            }
        }
        for a in 0..5 {
            let mut zx = [0.0; LANES];
            for l in 0..LANES {
                zx[l] = batch.z[l] * xp[a][l];
            }
            for b in 0..5 - a {
                let sum = &mut self.z_lanes[tri(4, a, b)];
                for l in 0..LANES {
                    sum[l] += zx[l] * yp[b][l];
                }
            }
        }
        self.rows += batch.len;
        self.points += batch.len;
    }

    /// Folds the lanes of the position sums into `pos` and `z`.
    fn fold_lanes(&mut self) {
        for (sum, lanes) in self.pos.iter_mut().zip(&self.pos_lanes) {
            *sum = lanes.iter().sum();
        }
        for (sum, lanes) in self.z.iter_mut().zip(&self.z_lanes) {
            *sum = lanes.iter().sum();
        }
    }

    /// Slopes `(z_x, z_y)` at `(x, y)`.
    #[inline]
    fn add_slopes(&mut self, x: f64, y: f64, sx: f64, sy: f64) {
        let xp = powers::<7>(x);
        let yp = powers::<7>(y);
        for a in 0..7 {
            for b in 0..7 - a {
                self.nrm[tri(6, a, b)] += xp[a] * yp[b];
            }
        }
        for a in 0..4 {
            let (px, py) = (sx * xp[a], sy * xp[a]);
            for b in 0..4 - a {
                self.sx[tri(3, a, b)] += px * yp[b];
                self.sy[tri(3, a, b)] += py * yp[b];
            }
        }
        self.rows += 2;
    }

    /// Least-squares solution over the active columns (see
    /// [`active_columns`]), as coefficients of the full design (inactive
    /// ones zero); `None` when rank deficient.
    fn solve(&self, options: &FitOptions) -> Option<([f64; COLUMNS], f64)> {
        let (first, last) = active_columns(options);
        // One monomorphized solver per size: fixed-size loops unroll.
        match last - first {
            3 => self.solve_range::<3>(first),
            5 => self.solve_range::<5>(first),
            7 => self.solve_range::<7>(first),
            9 => self.solve_range::<9>(first),
            12 => self.solve_range::<12>(first),
            _ => self.solve_range::<14>(first),
        }
    }

    /// The solve over columns `first .. first + N`.
    fn solve_range<const N: usize>(&self, first: usize) -> Option<([f64; COLUMNS], f64)> {
        if self.rows < N {
            return None;
        }
        let mut m = [[0.0; N]; N];
        let mut rhs = [0.0; N];
        // Columns in reverse order (highest degree first), so that the
        // gradient and Hessian unknowns come last, where the conditioning
        // test of `solve_spd` is cheapest.
        let column = |i: usize| MONOMIALS[first + N - 1 - i];
        for i in 0..N {
            let products = &POSITION_PRODUCTS[first + N - 1 - i];
            for j in 0..=i {
                let v = self.pos[products[first + N - 1 - j] as usize];
                m[i][j] = v;
                m[j][i] = v;
            }
            let (ai, bi) = column(i);
            rhs[i] = self.z[tri(4, ai, bi)];
        }
        // The slope rows, when there are any.
        if self.rows > self.points {
            for i in 0..N {
                let (ai, bi) = column(i);
                for j in 0..=i {
                    let (aj, bj) = column(j);
                    let mut v = 0.0;
                    if ai > 0 && aj > 0 {
                        v += (ai * aj) as f64 * self.nrm[tri(6, ai + aj - 2, bi + bj)];
                    }
                    if bi > 0 && bj > 0 {
                        v += (bi * bj) as f64 * self.nrm[tri(6, ai + aj, bi + bj - 2)];
                    }
                    m[i][j] += v;
                    if j < i {
                        m[j][i] += v;
                    }
                }
                if ai > 0 {
                    rhs[i] += ai as f64 * self.sx[tri(3, ai - 1, bi)];
                }
                if bi > 0 {
                    rhs[i] += bi as f64 * self.sy[tri(3, ai, bi - 1)];
                }
            }
        }
        // The gradient and Hessian columns are the last `5 - first`.
        let watch = 5 - first;
        let inverse = solve_spd(&m, &mut rhs, PIVOT_TOLERANCE, watch)?;
        let mut full = [0.0; COLUMNS];
        for (i, x) in rhs.iter().enumerate() {
            full[first + N - 1 - i] = *x;
        }
        Some((full, self.whitened_spread(&inverse, first)?))
    }

    /// The largest variance factor of the gradient and Hessian coefficients
    /// (from columns `first` on) in whitened coordinates (see [`MAX_SPREAD`]),
    /// given their block `inverse` of the inverse normal matrix in the fit's
    /// coordinates (local index `k` for column `4 - k`, as the solve orders
    /// them): the polynomial space is invariant under the linear map
    /// `(x, y) = A (u, v)` to whitened `(u, v)`, whose coefficients are
    /// `c_w = T c` (gradient `A^T g`, Hessian `A^T H A`), so their variance
    /// factors are the diagonal of `T C T^T`. `None` when the points span
    /// less than a plane (principal variances in a ratio below 1e-12).
    fn whitened_spread(&self, inverse: &InverseBlock, first: usize) -> Option<f64> {
        let count = self.points.max(1) as f64;
        let second =
            Sym2::new(self.pos[tri(8, 2, 0)], self.pos[tri(8, 1, 1)], self.pos[tri(8, 0, 2)]).scaled(1.0 / count);
        let (l1, l2, [c, s]) = second.eigen();
        if !(l1.is_finite() && l2 > 1e-12 * l1) {
            return None;
        }
        // Covariance factor of columns i, j (both >= first).
        let cov = |i: usize, j: usize| inverse[4 - i][4 - j];
        // A = [e1 sigma1, e2 sigma2], principal axes e1 = (c, s), e2 = (-s, c).
        let (s1, s2) = (l1.sqrt(), l2.sqrt());
        let a = [[c * s1, -s * s2], [s * s1, c * s2]];
        let form = |t: &[f64], at: usize| -> f64 {
            let mut v = 0.0;
            for (j, tj) in t.iter().enumerate() {
                for (k, tk) in t.iter().enumerate() {
                    v += tj * tk * cov(at + j, at + k);
                }
            }
            v
        };
        // Hessian coefficients (c20, c11, c02), H = [[2 c20, c11], [c11, 2 c02]].
        let mut spread = form(&[a[0][0] * a[0][0], a[0][0] * a[1][0], a[1][0] * a[1][0]], 2)
            .max(form(&[2.0 * a[0][0] * a[0][1], a[0][0] * a[1][1] + a[1][0] * a[0][1], 2.0 * a[1][0] * a[1][1]], 2))
            .max(form(&[a[0][1] * a[0][1], a[0][1] * a[1][1], a[1][1] * a[1][1]], 2));
        if first == 0 {
            // Gradient (D, E)_w = A^T (D, E).
            spread = spread.max(form(&[a[0][0], a[1][0]], 0)).max(form(&[a[0][1], a[1][1]], 0));
        }
        Some(spread)
    }
}

/// `[1, t, t^2, ..., t^(N-1)]`.
#[inline]
fn powers<const N: usize>(t: f64) -> [f64; N] {
    let mut p = [1.0; N];
    for k in 1..N {
        p[k] = p[k - 1] * t;
    }
    p
}

/// Fits the height field at one vertex, with the conditioning of its
/// curvature coefficients ([`MAX_SPREAD`]); `None` when the system is rank
/// deficient. Coordinates are scaled by the RMS neighbour distance.
fn fit_vertex(
    p: &[DVec3],
    nv: &[DVec3],
    centre: usize,
    ring: &[u32],
    options: &FitOptions,
) -> Option<(LocalTensor, f64)> {
    let n = nv[centre];
    let (t1, t2) = tangent_basis(n);
    let c = p[centre];
    let neighbours = ring.get(1..).unwrap_or(&[]);
    // Root-mean-square neighbour distance: one square root per fit.
    let mean_square =
        neighbours.iter().map(|&q| p[q as usize].distance_squared(c)).sum::<f64>() / neighbours.len().max(1) as f64;
    let scale = mean_square.sqrt();
    if scale.is_nan() || scale <= 0.0 {
        return None;
    }
    let inv = 1.0 / scale;
    let mut mom = Moments::new();
    let mut batch = Batch::default();
    for &q in neighbours {
        let q = q as usize;
        let d = (p[q] - c) * inv;
        let (x, y) = (d.dot(t1), d.dot(t2));
        let l = batch.len;
        (batch.x[l], batch.y[l], batch.z[l]) = (x, y, d.dot(n));
        batch.len += 1;
        if batch.len == LANES {
            mom.add_points(&batch);
            batch = Batch::default();
        }
        if options.use_normals {
            let m = nv[q];
            let mz = m.dot(n);
            if mz > 0.2 {
                mom.add_slopes(x, y, -m.dot(t1) / mz, -m.dot(t2) / mz);
            }
        }
    }
    if batch.len > 0 {
        mom.add_points(&batch);
    }
    mom.fold_lanes();
    let (s, spread) = mom.solve(options)?;
    let hessian = Sym2::new(2.0 * s[2], s[3], 2.0 * s[4]).scaled(inv);
    Some((height_field_tensor(n, t1, t2, [s[0], s[1]], hessian), spread))
}

/// The curvature tensor at the origin of the height field
/// `z = g . (x, y) + (x, y) H (x, y)^T / 2` over the frame `(t1, t2, n)`,
/// from its fundamental forms (eq. 2.21-2.22): `s_u = (1, 0, g_x)`,
/// `s_v = (0, 1, g_y)`, second derivatives `H`, normal `(-g, 1) / w`.
fn height_field_tensor(n: DVec3, t1: DVec3, t2: DVec3, g: [f64; 2], hess: Sym2) -> LocalTensor {
    let w = (1.0 + g[0] * g[0] + g[1] * g[1]).sqrt();
    let normal_local = DVec3::new(-g[0], -g[1], 1.0) / w;
    let su = DVec3::new(1.0, 0.0, g[0]);
    let sv = DVec3::new(0.0, 1.0, g[1]);
    // Second fundamental form in (s_u, s_v): L, M, N = n . s_uu, ... (eq. 2.22).
    let second = hess.scaled(1.0 / w);
    // Orthonormal tangent basis: e1 along s_u, e2 = n x e1; s_u = a11 e1,
    // s_v = a12 e1 + a22 e2, and II in e-coordinates is J^-T II J^-1.
    let a11 = su.length();
    let e1 = su / a11;
    let e2 = normal_local.cross(e1);
    let (a12, a22) = (sv.dot(e1), sv.dot(e2));
    let (i11, i12, i22) = (1.0 / a11, -a12 / (a11 * a22), 1.0 / a22);
    // Columns of J^-1 are (i11, 0) and (i12, i22).
    let x = [i11, 0.0];
    let y = [i12, i22];
    // Curvature is positive where the surface bends away from the normal: -II.
    let form = Sym2::new(-second.form(x, x), -second.form(x, y), -second.form(y, y));
    let to_world = |v: DVec3| v.x * t1 + v.y * t2 + v.z * n;
    LocalTensor {
        normal: to_world(normal_local),
        t1: to_world(e1),
        t2: to_world(e2),
        form,
        status: VertexStatus::Valid,
    }
}

/// The fit estimator over every vertex. When the data cannot carry the
/// polynomial (rank test), carry it ill-conditioned ([`MAX_SPREAD`]) or the
/// fitted normal turns more than 60 degrees from the start, retries on the
/// neighbourhood grown by a ring (or 1.5x the radius), then with lower
/// degrees; keeps the best-conditioned fit when none passes (flagged
/// ill-conditioned), and flags the vertex degenerate when nothing fits. O(sum of neighbourhood sizes), parallel over vertices.
pub(crate) fn estimate(mesh: &TriMesh, normals: NormalWeighting, options: &FitOptions) -> Result<Vec<LocalTensor>> {
    let nbh = options.neighborhood.validate()?;
    let nv = mesh.geometry().vertex_normals(normals);
    let adj = Adjacency::new(mesh);
    let status = topological_status(mesh);
    let p = mesh.positions();
    let grown = match nbh {
        Neighborhood::Rings(k) => Neighborhood::Rings(k + 1),
        Neighborhood::Ball(r) => Neighborhood::Ball(1.5 * r),
    };
    let attempts = [
        (*options, nbh),
        (*options, grown),
        (FitOptions { degree: Degree::Cubic.min_with(options.degree), ..*options }, grown),
        (FitOptions { degree: Degree::Quadric, ..*options }, grown),
        (FitOptions { degree: Degree::Quadric, use_normals: true, refine_normal: false, ..*options }, grown),
    ];
    Ok(par::map_with(mesh.vertex_count(), Gatherer::default, |g, i| {
        let n = nv[i];
        if status[i] == VertexStatus::Isolated || n == DVec3::ZERO {
            let s = if status[i] == VertexStatus::Isolated { status[i] } else { VertexStatus::Degenerate };
            return LocalTensor::empty(n, s);
        }
        let mut gathered = None;
        // The best-conditioned fit so far, used when none is well-conditioned.
        let mut best: Option<(LocalTensor, f64)> = None;
        for (f, region) in &attempts {
            if gathered != Some(*region) {
                g.gather(&adj, p, i, *region);
                gathered = Some(*region);
            }
            let Some((mut t, spread)) = fit_vertex(p, nv, i, &g.vertices, f) else { continue };
            if !(t.form.is_finite() && t.normal.is_finite() && t.normal.dot(n) > 0.5) {
                continue;
            }
            t.status = status[i];
            if spread <= MAX_SPREAD {
                return t;
            }
            if best.is_none_or(|(_, s)| spread < s) {
                best = Some((t, spread));
            }
        }
        best.map_or_else(
            || LocalTensor::empty(n, VertexStatus::Degenerate),
            |(mut t, _)| {
                if !matches!(t.status, VertexStatus::NonManifold) {
                    t.status = VertexStatus::IllConditioned;
                }
                t
            },
        )
    }))
}
