//! The far field of the heat method, where the heat flow is below what
//! double precision resolves.
//!
//! Backward Euler heat flow from a point decays like exp(-d / sqrt(t)) with
//! the distance d (the screened-Poisson Green's function; Varadhan 1967 for
//! the heat kernel). With t = h^2 it loses about 0.42 decimal orders of
//! magnitude per mean edge length h: a unit source on a mesh of unit edges
//! spends the range of a double after about 770 h, and squaring the
//! gradient to normalize it, after about 370 h, where a plateau began. Scaled to start
//! at 2^1000 ([`super::HeatGeodesics`]) and normalized without squaring,
//! the flow is resolved, down to [`RESOLVED`] = 2^-1000, for about 1400 h.
//! Beyond that [`HeatFarField`] chooses the continuation.

use mesh_kernel::glam::DVec2;
use mesh_kernel::FaceId;

use super::{HeatDistance, HeatFarField, HeatGeodesics, HeatStatus};
use crate::error::Result;
use crate::fmm::{FastMarching, FmmOptions};

/// Heat values at or above 2^-1000 are normal doubles 22 bits above the
/// denormals, so their ratios, and the gradient direction, carry full
/// precision; negative values (a Laplacian with negative weights) are not
/// resolved either.
pub(crate) const RESOLVED: f64 = 9.332636185032189e-302;

/// Fast Marching restarts from vertices whose heat value is at least 2^-900,
/// 30 decimal orders (about 70 h) inside the resolved range, so that the
/// seam avoids the Poisson step's boundary layer at the edge of the field.
const TRUSTED: f64 = 1.1830521861667747e-271;

/// A restart's initial data: the heat values between [`RESOLVED`] and
/// 2^-800 (about 140 h wide).
const BAND_TOP: f64 = 1.499696813895631e-241;

/// Restarts at most this many times.
const MAX_RESTARTS: usize = 64;

impl HeatGeodesics {
    /// [`HeatFarField::Restart`]: restarts the heat flow from the last
    /// resolved band until every face with a gradient has a direction,
    /// nothing more is resolved, or [`MAX_RESTARTS`]. Fills `directions`
    /// and `resolved` in place. Cost one pair of triangular solves (Neumann,
    /// else Dirichlet) and O(F) per restart.
    pub(crate) fn restart(&self, u: &[f64], directions: &mut [Option<DVec2>], resolved: &mut [bool]) -> Result<()> {
        let Some(factor) = self.neumann.as_ref().or(self.dirichlet.as_ref()) else { return Ok(()) };
        let mut u = u.to_vec();
        for _ in 0..MAX_RESTARTS {
            if directions.iter().zip(&self.faces).all(|(d, f)| d.is_some() || f.w.is_none()) {
                break;
            }
            // Initial data M u on the band, scaled so that its top sits at
            // the ceiling (the bound u <= max delta_s / M_s of `heat_flow`).
            let mut next: Vec<f64> = u
                .iter()
                .zip(&self.mass)
                .map(|(x, m)| if (RESOLVED..=BAND_TOP).contains(x) { (x / BAND_TOP) * m * self.ceiling } else { 0.0 })
                .collect();
            if next.iter().all(|x| *x == 0.0) {
                break;
            }
            factor.solve_in_place(&mut next)?;
            u = next;
            let mut progress = false;
            for (face, d) in self.faces.iter().zip(directions.iter_mut()) {
                if d.is_none() {
                    *d = face.resolved_descent(&u);
                    progress |= d.is_some();
                }
            }
            for (r, x) in resolved.iter_mut().zip(&u) {
                *r |= *x >= RESOLVED;
            }
            if !progress {
                break;
            }
        }
        Ok(())
    }

    /// The status of every vertex from the Poisson step's distance `phi`
    /// and the mask of resolved vertices; with
    /// [`HeatFarField::FastMarching`], the march from the vertices whose
    /// heat value `u` is [`TRUSTED`] into the others.
    pub(crate) fn finish(
        &self,
        mut phi: Vec<f64>,
        u: &[f64],
        resolved: &[bool],
        sources: &[mesh_kernel::VertexId],
    ) -> Result<HeatDistance> {
        let mut status: Vec<HeatStatus> = (0..phi.len())
            .map(|v| match (phi[v].is_finite(), resolved[v]) {
                (false, _) => HeatStatus::Unreached,
                (true, true) => HeatStatus::Heat,
                (true, false) => HeatStatus::Unresolved,
            })
            .collect();
        for s in sources {
            status[s.idx()] = HeatStatus::Heat;
        }
        if self.far_field == HeatFarField::FastMarching {
            let mut far: Vec<bool> =
                (0..phi.len()).map(|v| status[v] != HeatStatus::Unreached && !(u[v] >= TRUSTED)).collect();
            for s in sources {
                far[s.idx()] = false;
            }
            if far.contains(&true) {
                let marched = self.march_far_field(&phi, &far)?;
                for v in 0..phi.len() {
                    if far[v] && marched[v].is_finite() {
                        phi[v] = marched[v];
                        status[v] = HeatStatus::FarField;
                    }
                }
            }
        }
        Ok(HeatDistance { distance: phi, status })
    }

    /// Fast Marching (Kimmel and Sethian 1998) from the known values of
    /// `phi` into the vertices marked `far`, on the piece of the mesh made
    /// of the faces within one ring of a far vertex (so that obtuse corners
    /// at the seam can still be unfolded). Returns the marched distance of
    /// every vertex, `+infinity` off the piece. Cost O(F) to find the piece,
    /// then stencils and march on the piece only.
    fn march_far_field(&self, phi: &[f64], far: &[bool]) -> Result<Vec<f64>> {
        let n = phi.len();
        let triangles = self.mesh.faces();
        let mut near = vec![false; n];
        for t in triangles.iter().filter(|t| t.iter().any(|&v| far[v as usize])) {
            t.iter().for_each(|&v| near[v as usize] = true);
        }
        let faces: Vec<FaceId> =
            (0..triangles.len()).filter(|&f| triangles[f].iter().any(|&v| near[v as usize])).map(FaceId::new).collect();
        let piece = self.mesh.submesh(&faces)?;
        let known: Vec<f64> =
            piece.vertices.iter().map(|v| if far[v.idx()] { f64::INFINITY } else { phi[v.idx()] }).collect();
        let marched = FastMarching::new(&piece.mesh, &FmmOptions::default())?.extend(&known);
        Ok(piece.scatter(&marched, n, f64::INFINITY)?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thresholds_are_the_powers_of_two_they_name() {
        assert_eq!(RESOLVED, 2f64.powi(-1000));
        assert_eq!(TRUSTED, 2f64.powi(-900));
        assert_eq!(BAND_TOP, 2f64.powi(-800));
        assert!(RESOLVED > f64::MIN_POSITIVE * 2f64.powi(21));
    }
}
