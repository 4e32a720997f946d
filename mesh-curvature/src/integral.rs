//! Integral curvature over a neighbourhood (the chapter's "integral curvature",
//! section 2.5): the integral of the Gaussian and mean curvature over the
//! union of the mixed Voronoi cells of a vertex's neighbourhood.

use mesh_kernel::TriMesh;

use crate::error::Result;
use crate::gaussian::{gaussian_curvature, GaussianOptions};
use crate::mean::{mean_curvature, MeanOptions};
use crate::neighborhood::{Adjacency, Gatherer, Neighborhood};
use mesh_kernel::operators::MassKind;
use mesh_kernel::par;

/// Curvature integrated over each vertex's neighbourhood.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct IntegralCurvature {
    /// Integral of the Gaussian curvature: the sum of the angle defects
    /// (eq. 2.25) of the neighbourhood's vertices (vertices on the mesh
    /// boundary contribute 0, see [`crate::GaussianCurvature`]): the area
    /// of the region's Gauss image.
    pub gaussian: Vec<f64>,
    /// Integral of the mean curvature: the sum of the integrated mean
    /// curvatures (eq. 2.26) of the neighbourhood's vertices.
    pub mean: Vec<f64>,
    /// Area of the neighbourhood (sum of the mixed Voronoi areas).
    pub area: Vec<f64>,
    /// Number of vertices in each neighbourhood.
    pub size: Vec<u32>,
}

impl IntegralCurvature {
    /// Average Gaussian curvature over each neighbourhood (`gaussian / area`,
    /// 0 where the area is 0). O(V).
    pub fn mean_gaussian(&self) -> Vec<f64> {
        self.gaussian.iter().zip(&self.area).map(|(k, a)| if *a > 0.0 { k / a } else { 0.0 }).collect()
    }

    /// Average mean curvature over each neighbourhood (`mean / area`). O(V).
    pub fn mean_mean(&self) -> Vec<f64> {
        self.mean.iter().zip(&self.area).map(|(h, a)| if *a > 0.0 { h / a } else { 0.0 }).collect()
    }
}

/// Options of [`integral_curvature`].
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct IntegralOptions {
    /// The region each vertex's curvature is integrated over (default: the
    /// 1-ring).
    pub neighborhood: Neighborhood,
}

/// Integral Gaussian and mean curvature over the neighbourhood
/// [`IntegralOptions::neighborhood`] of each vertex. A larger neighbourhood
/// smooths noise at the cost of resolution; the integrals are finite on any
/// mesh. Cost O(V + F) for the per-vertex quantities plus O(sum of
/// neighbourhood sizes), parallel over vertices.
///
/// # Errors
/// `CurvatureError::InvalidOption` (`rings`) for 0 rings or (`radius`) for a ball radius that is not finite
/// and positive; the errors of [`crate::gaussian_curvature`] and [`crate::mean_curvature`].
pub fn integral_curvature(mesh: &TriMesh, options: &IntegralOptions) -> Result<IntegralCurvature> {
    let nbh = options.neighborhood.validate()?;
    let (mesh, unit) = mesh_kernel::units::normalized(mesh);
    let mut out = integrate(&mesh, nbh.in_unit(unit))?;
    out.mean.iter_mut().for_each(|x| *x *= unit);
    out.area.iter_mut().for_each(|x| *x = *x * unit * unit);
    Ok(out)
}

/// [`integral_curvature`] in the mesh's own unit.
fn integrate(mesh: &TriMesh, nbh: Neighborhood) -> Result<IntegralCurvature> {
    let k = gaussian_curvature(mesh, &GaussianOptions { area: MassKind::MixedVoronoi })?;
    let h = mean_curvature(mesh, &MeanOptions::default())?;
    let adj = Adjacency::new(mesh);
    let p = mesh.positions();
    let sums: Vec<[f64; 4]> = par::map_with(mesh.vertex_count(), Gatherer::default, |g, i| {
        g.gather(&adj, p, i, nbh);
        let mut s = [0.0; 4];
        for &u in &g.vertices {
            let u = u as usize;
            s[0] += k.integrated[u];
            s[1] += h.integrated[u];
            s[2] += k.area[u];
        }
        s[3] = g.vertices.len() as f64;
        s
    });
    Ok(IntegralCurvature {
        gaussian: sums.iter().map(|s| s[0]).collect(),
        mean: sums.iter().map(|s| s[1]).collect(),
        area: sums.iter().map(|s| s[2]).collect(),
        size: sums.iter().map(|s| s[3] as u32).collect(),
    })
}
