//! The entry points: [`parameterize`] a disk with any method and get UVs
//! plus a distortion report; [`parameterize_cut`] cuts any connected
//! manifold into a disk first and gives UVs per corner.

use glam::DVec2;
use mesh_kernel::{FaceId, TriMesh, VertexId};

use crate::arap::{Arap, ArapOptions};
use crate::boundary::{self, BoundaryMap};
use crate::cut::{cut_to_disk, CutMesh};
use crate::distortion::{distortion, DistortionReport};
use crate::error::{ParamError, Result};
use crate::fixed::{DegeneratePolicy, FixedBoundarySolver};
use crate::lscm::{lscm, normalize_to_unit_box, LscmOptions};
use crate::topology::require_disk;
use crate::weights::{Authalic, Harmonic, Intrinsic, MeanValue, Uniform, Weights};

/// Which parameterization. More methods may come: matches outside the crate
/// need a wildcard arm.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum ParamMethod {
    /// Tutte's barycentric embedding, w_ij = 1 / |N(i)| (eq. 2.12-2.13):
    /// bijective onto a convex boundary.
    Tutte,
    /// Floater's mean-value coordinates (2003): bijective onto a convex
    /// boundary, reproduces planar meshes.
    MeanValue,
    /// Discrete harmonic / conformal, cot alpha + cot beta (eq. 2.14-2.15).
    Harmonic,
    /// Discrete authalic (eq. 2.16; Desbrun, Meyer and Alliez 2002).
    Authalic,
    /// Intrinsic: lambda conformal + mu authalic (Desbrun et al. 2002).
    Intrinsic {
        /// Weight of the conformal part.
        lambda: f64,
        /// Weight of the authalic part.
        mu: f64,
    },
    /// Least-squares conformal maps with a free boundary (Levy et al. 2002).
    Lscm,
    /// As-rigid-as-possible (Liu et al. 2008) from the harmonic map, free
    /// boundary.
    Arap {
        /// Local/global iterations.
        iterations: usize,
    },
}

impl ParamMethod {
    /// Every method, with default parameters (intrinsic: lambda = mu = 1/2;
    /// ARAP: 20 iterations). Their [`name`](Self::name)s are what [`FromStr`](std::str::FromStr)
    /// accepts and [`Display`](std::fmt::Display) writes.
    pub const ALL: [Self; 7] = [
        Self::Tutte,
        Self::MeanValue,
        Self::Harmonic,
        Self::Authalic,
        Self::Intrinsic { lambda: 0.5, mu: 0.5 },
        Self::Lscm,
        Self::Arap { iterations: 20 },
    ];

    /// The command-line name: `tutte`, `mean-value`, `harmonic`, `authalic`,
    /// `intrinsic`, `lscm`, `arap`.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Tutte => "tutte",
            Self::MeanValue => "mean-value",
            Self::Harmonic => "harmonic",
            Self::Authalic => "authalic",
            Self::Intrinsic { .. } => "intrinsic",
            Self::Lscm => "lscm",
            Self::Arap { .. } => "arap",
        }
    }

    /// The weights of a fixed-boundary method (`None` for LSCM and ARAP).
    pub fn weights(&self) -> Option<Box<dyn Weights>> {
        Some(match *self {
            Self::Tutte => Box::new(Uniform),
            Self::MeanValue => Box::new(MeanValue),
            Self::Harmonic => Box::new(Harmonic),
            Self::Authalic => Box::new(Authalic),
            Self::Intrinsic { lambda, mu } => Box::new(Intrinsic { lambda, mu }),
            Self::Lscm | Self::Arap { .. } => return None,
        })
    }

    pub(crate) fn validate(&self) -> Result<()> {
        match *self {
            Self::Intrinsic { lambda, mu } => {
                let ok = |x: f64| x.is_finite() && x >= 0.0;
                if !(ok(lambda) && ok(mu) && lambda + mu > 0.0) {
                    return Err(ParamError::InvalidOption {
                        name: "lambda/mu",
                        reason: format!("need finite lambda, mu >= 0, not both 0 (got {lambda}, {mu})"),
                    });
                }
            }
            Self::Arap { iterations } if iterations > 10_000 => {
                return Err(ParamError::InvalidOption { name: "iterations", reason: format!("{iterations} > 10000") });
            }
            _ => {}
        }
        Ok(())
    }
}

mesh_kernel::named_choice!(ParamMethod, "method", ParamError);

/// Options of [`parameterize`].
#[derive(Debug, Clone, PartialEq)]
pub struct ParamOptions {
    /// The method (default: mean-value, bijective and reproducing planes).
    pub method: ParamMethod,
    /// Boundary of the fixed-boundary methods (default: circle, chord
    /// length). LSCM uses two entries of [`BoundaryMap::Fixed`] as its pins
    /// (and picks its own otherwise); ARAP starts from the harmonic map onto
    /// this boundary, then frees it.
    pub boundary: BoundaryMap,
    /// Zero-area faces: weighted uniformly (default) or refused.
    pub degenerate: DegeneratePolicy,
    /// Scale free-boundary results (LSCM, ARAP) into [0, 1]^2, uniformly.
    /// Default false, as in [`LscmOptions::normalize`]: the map keeps the
    /// surface's unit of length; set it for texture coordinates.
    pub normalize: bool,
}

impl Default for ParamOptions {
    fn default() -> Self {
        Self {
            method: ParamMethod::MeanValue,
            boundary: BoundaryMap::default(),
            degenerate: DegeneratePolicy::Uniform,
            normalize: false,
        }
    }
}

/// A parameterization: one UV per vertex and its distortion.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Parameterization {
    /// Parameter coordinates, one per vertex (unreferenced vertices sit at
    /// the centroid of the boundary, or at a pin for LSCM).
    pub uv: Vec<DVec2>,
    /// Distortion measures and the bijectivity check.
    pub report: DistortionReport,
    /// Zero-area faces that were weighted uniformly.
    pub degenerate_faces: Vec<FaceId>,
}

/// Parameterizes a disk (one boundary loop, chi = 1; otherwise
/// [`ParamError::NotADisk`] says what the mesh is) with `options.method`,
/// then measures the distortion. Cost: O(V + F) assembly, one sparse
/// factorization (Cholesky for Tutte, harmonic, LSCM, ARAP; LU for the
/// asymmetric mean-value, authalic and intrinsic weights) and O(F) per ARAP
/// iteration.
///
/// ```
/// use mesh_param::{parameterize, ParamMethod, ParamOptions};
///
/// let mesh = mesh_kernel::shapes::disk(8, 1)?;
/// let p = parameterize(&mesh, &ParamOptions { method: ParamMethod::Tutte, ..Default::default() })?;
/// assert!(p.report.summary.bijective);
/// # Ok::<(), mesh_param::ParamError>(())
/// ```
///
/// # Errors
/// `ParamError::InvalidOption` for the method's options (`lambda/mu`, `iterations`, `method`) or a fixed
/// boundary that does not list every boundary vertex (`boundary`); `ParamError::NotADisk` unless the mesh is
/// a topological disk; `ParamError::DegenerateFaces`, `ParamError::NonFinite` and `ParamError::Mesh`
/// (`MeshError::Solver`) from the solve.
pub fn parameterize(mesh: &TriMesh, options: &ParamOptions) -> Result<Parameterization> {
    let (uv, degenerate_faces) = map_disk(mesh, options)?;
    let report = distortion(mesh, &uv)?;
    Ok(Parameterization { uv, report, degenerate_faces })
}

/// The map of [`parameterize`] without its distortion report: UVs per
/// vertex and the zero-area faces weighted uniformly. Same cost but the O(F)
/// report.
pub(crate) fn map_disk(mesh: &TriMesh, options: &ParamOptions) -> Result<(Vec<DVec2>, Vec<FaceId>)> {
    options.method.validate()?;
    let boundary = require_disk(mesh)?.vertices.clone();
    // The weights' intermediates reach degree four in the coordinates: solve
    // in a unit where they cannot over- or underflow.
    let (mesh, unit) = mesh_kernel::units::normalized(mesh);
    let mesh = mesh.as_ref();
    let mut in_mesh_units = false;
    let (mut uv, degenerate_faces) = match options.method {
        ParamMethod::Lscm => {
            let pins = lscm_pins(&options.boundary)?;
            in_mesh_units = pins.is_none();
            let map = lscm(mesh, &LscmOptions { pins, normalize: false, degenerate: options.degenerate })?;
            (map.uv, map.degenerate_faces)
        }
        ParamMethod::Arap { iterations } => {
            in_mesh_units = true;
            let (mut start, degenerate) = fixed_boundary(mesh, &Harmonic, &boundary, options)?;
            scale_to_surface(mesh, &boundary, &mut start);
            let arap = Arap::new(mesh, &ArapOptions { degenerate: options.degenerate, iterations })?;
            (arap.solve(&start)?, degenerate)
        }
        method => {
            let weights = method.weights().ok_or(ParamError::InvalidOption {
                name: "method",
                reason: format!("{} has no fixed-boundary weights", method.name()),
            })?;
            fixed_boundary(mesh, weights.as_ref(), &boundary, options)?
        }
    };
    if options.normalize && matches!(options.method, ParamMethod::Lscm | ParamMethod::Arap { .. }) {
        normalize_to_unit_box(&mut uv);
    } else if in_mesh_units && unit != 1.0 {
        uv.iter_mut().for_each(|q| *q *= unit);
    }
    Ok((uv, degenerate_faces))
}

/// Scales `uv` so that the boundary loop is as long in it as on the surface:
/// an ARAP start of the surface's size makes the iterates, and the result,
/// scale with the surface whatever its unit of length. O(boundary + V).
fn scale_to_surface(mesh: &TriMesh, boundary: &[VertexId], uv: &mut [DVec2]) {
    let edges = || (0..boundary.len()).map(|k| (boundary[k], boundary[(k + 1) % boundary.len()]));
    let on_surface: f64 = edges().map(|(a, b)| mesh.position(a).distance(mesh.position(b))).sum();
    let in_uv: f64 = edges().map(|(a, b)| uv[a.idx()].distance(uv[b.idx()])).sum();
    let ratio = on_surface / in_uv;
    if ratio > 0.0 && ratio.is_finite() {
        uv.iter_mut().for_each(|q| *q *= ratio);
    }
}

/// The fixed-boundary solve: constraints from the boundary map, one solver.
fn fixed_boundary<W: Weights + ?Sized>(
    mesh: &TriMesh,
    weights: &W,
    boundary: &[VertexId],
    options: &ParamOptions,
) -> Result<(Vec<DVec2>, Vec<FaceId>)> {
    let (ids, positions) = match &options.boundary {
        BoundaryMap::Circle(spacing) => (boundary.to_vec(), boundary::circle(mesh, boundary, *spacing)),
        BoundaryMap::Square => (boundary.to_vec(), boundary::square(mesh, boundary)?),
        BoundaryMap::Fixed(list) => {
            let mut listed = vec![false; mesh.vertex_count()];
            for (v, _) in list {
                if let Some(slot) = listed.get_mut(v.idx()) {
                    *slot = true;
                }
            }
            if let Some(v) = boundary.iter().find(|v| !listed[v.idx()]) {
                return Err(ParamError::InvalidOption {
                    name: "boundary",
                    reason: format!("boundary vertex {v} has no given position"),
                });
            }
            list.iter().copied().unzip()
        }
    };
    let solver = FixedBoundarySolver::new(mesh, weights, &ids, options.degenerate)?;
    Ok((solver.solve(&positions)?, solver.degenerate_faces().to_vec()))
}

fn lscm_pins(boundary: &BoundaryMap) -> Result<Option<[(VertexId, DVec2); 2]>> {
    match boundary {
        BoundaryMap::Fixed(list) if list.len() == 2 => Ok(Some([list[0], list[1]])),
        BoundaryMap::Fixed(list) => Err(ParamError::InvalidOption {
            name: "boundary",
            reason: format!("LSCM takes exactly 2 pinned vertices, {} given", list.len()),
        }),
        _ => Ok(None),
    }
}

/// A parameterization of a mesh cut into a disk: UVs per vertex of the cut
/// mesh, i.e. per corner of the original faces.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct CutParameterization {
    /// The disk and its seam.
    pub cut: CutMesh,
    /// The parameterization of [`CutParameterization::cut`]'s mesh.
    pub param: Parameterization,
}

impl CutParameterization {
    /// UVs per corner of the original faces (`[f][k]` for corner k of face f).
    pub fn corner_uvs(&self) -> Vec<[DVec2; 3]> {
        self.cut.per_corner(&self.param.uv)
    }
}

/// Cuts a connected manifold into a disk if it is not one ([`cut_to_disk`])
/// and parameterizes the disk. [`BoundaryMap::Fixed`] refers to vertices of
/// the cut mesh. Cost: that of [`cut_to_disk`] plus [`parameterize`].
///
/// # Errors
/// The errors of [`crate::cut_to_disk`] and [`parameterize`].
pub fn parameterize_cut(mesh: &TriMesh, options: &ParamOptions) -> Result<CutParameterization> {
    let cut = cut_to_disk(mesh)?;
    let param = parameterize(&cut.mesh, options)?;
    Ok(CutParameterization { cut, param })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn method_names_round_trip() {
        for method in ParamMethod::ALL {
            assert_eq!(method.to_string().parse::<ParamMethod>(), Ok(method));
        }
        let names = ParamMethod::ALL.map(|m| m.name());
        assert!((1..names.len()).all(|i| !names[..i].contains(&names[i])), "{names:?}");
        assert!(matches!("magic".parse::<ParamMethod>(), Err(ParamError::InvalidOption { name: "method", .. })));
        assert!(ParamMethod::Lscm.weights().is_none() && ParamMethod::Tutte.weights().is_some());
    }
}
