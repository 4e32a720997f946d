"""meshkit: triangle-mesh geometry processing on numpy arrays.

The Python face of the mesh workspace (Rust crates mesh-kernel, mesh-io,
mesh-curvature, mesh-geodesic, mesh-param, mesh-spectral, mesh-wavelet).

Conventions
-----------
- ``V`` is a float64 array of shape (n, 3); other float and integer dtypes
  are converted. ``F`` is an integer array of shape (m, 3), int32 or int64
  (read in place); other integer dtypes are converted. Triangles are
  counter-clockwise seen from outside.
- Sparse operators are ``scipy.sparse.csr_matrix``. Laplacians are positive
  semi-definite: ``cotan_laplacian(V, F) == -igl.cotmatrix(V, F)``.
- Curvatures are positive where the surface bends away from its normal: a
  sphere of radius r with outward normals has k1 = k2 = H = 1/r, K = 1/r^2.
- Geodesic distances are 0 at the sources and +inf on vertices no source
  reaches; never NaN.
- Every error is a :class:`MeshkitError` (see ``meshkit._errors``) carrying
  the Rust error's text; bad input never crashes the interpreter.
- The GIL is released while Rust computes, so threads run meshkit calls in
  parallel. Ctrl-C is honoured between the stages of a call (mesh
  validation, factorization, solve): a long stage finishes first.
- Every function is a pure function of arrays or file paths, and the
  prepared objects (``HeatSolver``, ``FastMarchingSolver``, ``Harmonics``,
  ``Multiresolution``) pickle by their inputs, so they travel to Dask or
  multiprocessing workers.
"""

import numpy as np
import scipy.sparse

from . import _meshkit as _native
from ._errors import (
    DegenerateError,
    InvalidMeshError,
    InvalidOptionError,
    MeshFileNotFoundError,
    MeshIOError,
    MeshkitError,
    NotConvergedError,
    SolverError,
    TopologyError,
)

__version__ = _native.__version__

# --------------------------------------------------------------------------
# Argument checks: cheap, in numpy, so that messages name the argument. The
# Rust side checks again (shapes, indices, finiteness) whatever it is given.


def _vertices(V, name="V"):
    try:
        a = np.asarray(V)
    except Exception as e:  # ragged lists and other non-arrays
        raise InvalidMeshError(f"{name} is not an array: {e}") from None
    if a.dtype.kind not in "fiu":
        raise InvalidMeshError(f"{name} must hold numbers (float64), not dtype {a.dtype}")
    if a.ndim != 2 or a.shape[1] != 3:
        raise InvalidMeshError(f"{name} must have shape (n, 3), not {a.shape}")
    # No copy when V is already C-contiguous float64.
    return np.ascontiguousarray(a, dtype=np.float64)


def _faces(F, name="F"):
    try:
        a = np.asarray(F)
    except Exception as e:
        raise InvalidMeshError(f"{name} is not an array: {e}") from None
    if a.size == 0 and a.dtype.kind == "f":
        a = a.astype(np.int64)  # np.zeros((0, 3)) is an empty face list
    if a.dtype.kind not in "iu":
        raise InvalidMeshError(f"{name} must be an integer array (int32 or int64), not dtype {a.dtype}")
    if a.ndim != 2 or a.shape[1] != 3:
        raise InvalidMeshError(f"{name} must have shape (m, 3), not {a.shape}")
    if a.dtype == np.int32 or a.dtype == np.int64:
        return a
    if a.dtype.kind == "u" and a.size and a.max() > np.iinfo(np.int64).max:
        raise InvalidMeshError(f"{name} holds index {a.max()}, which is not a valid vertex index")
    return a.astype(np.int64)


def _mesh(V, F):
    return _vertices(V), _faces(F)


def _indices(s, name="sources"):
    a = np.atleast_1d(np.asarray(s))
    if a.dtype.kind not in "iu":
        raise InvalidOptionError(f"{name} must be vertex indices (integers), not dtype {a.dtype}")
    a = a.ravel()
    if a.dtype.kind == "u" and a.size and a.max() > np.iinfo(np.int64).max:
        raise InvalidOptionError(f"{name}: vertex {a.max()} is out of range")
    return a.astype(np.int64, copy=False)


def _field(x, name):
    try:
        a = np.asarray(x, dtype=np.float64)
    except (TypeError, ValueError) as e:
        raise InvalidOptionError(f"{name} must be an array of numbers: {e}") from None
    return np.ascontiguousarray(a)


def _csr(parts):
    data, indices, indptr, shape = parts
    return scipy.sparse.csr_matrix((data, indices, indptr), shape=shape)


# --------------------------------------------------------------------------
# Files


def read(path):
    """Reads a mesh file: ``(V, F)``, V float64 (n, 3), F int64 (m, 3).

    The format comes from the extension (.obj, .off, .ply, .stl, .gltf,
    .glb) and is checked against the content; polygons are triangulated.
    Raises :class:`MeshFileNotFoundError` for a missing file and
    :class:`MeshIOError` for any other reading problem.
    """
    return _native.read(str(path))


def read_attributes(path):
    """Reads a mesh file with everything it carries:
    ``(V, F, vertex_attributes, face_attributes, report)``.

    ``vertex_attributes`` maps names to arrays of one row per vertex:
    ``normals`` (n, 3), ``uvs`` (n, 2), ``colors`` (n, 4) float32 in [0, 1],
    named scalars (n,) float64, vectors (n, 3) float64 and labels (n,) int64.
    ``face_attributes`` holds the per-face ones (and per-corner ``uvs``,
    (m, 3, 2)). ``report`` says what reading changed (polygons triangulated,
    faces dropped, vertices welded, notes).
    """
    return _native.read_attributes(str(path))


def _attribute_arrays(attributes, what):
    out = {}
    for name, value in (attributes or {}).items():
        a = np.asarray(value)
        if a.dtype.kind in "iub":
            a = a.astype(np.int64, copy=False)
        elif a.dtype.kind == "f":
            a = a.astype(np.float64, copy=False)
        else:
            raise InvalidOptionError(f"{what} attribute `{name}` must hold numbers, not dtype {a.dtype}")
        out[str(name)] = np.ascontiguousarray(a)
    return out


def write(path, V, F, **vertex_attributes):
    """Writes a mesh file, with per-vertex attributes given as keywords.

    The format comes from the extension. ``normals=`` (n, 3), ``uvs=``
    (n, 2) and ``colors=`` (n, 3 or 4, in [0, 1]) are the formats' own
    attributes; any other name is a float scalar (n,), an integer label
    (n,) or a float vector (n, 3), stored where the format can hold named
    attributes (PLY, glTF) and otherwise listed in the returned report's
    ``dropped``. Returns the report (a dict). See :func:`write_mesh` for
    per-face attributes and options.
    """
    return write_mesh(path, V, F, vertex_attributes=vertex_attributes)


def write_mesh(path, V, F, vertex_attributes=None, face_attributes=None, *, ply_binary=None,
               allow_precision_loss=False):
    """Writes a mesh file with per-vertex and per-face attributes (dicts of
    arrays, see :func:`write`). ``ply_binary`` chooses binary (default) or
    ascii PLY; ``allow_precision_loss`` writes values a 32-bit format (STL,
    glTF) cannot hold instead of raising :class:`MeshIOError`. The write is
    atomic (temporary file, then rename). Returns the report: the largest
    relative rounding of 32-bit values, values lost, and what was dropped.
    """
    V, F = _mesh(V, F)
    return _native.write(str(path), V, F, _attribute_arrays(vertex_attributes, "vertex"),
                         _attribute_arrays(face_attributes, "face"), ply_binary, allow_precision_loss)


def shape(name, n):
    """A built-in shape with exact ground truth, as ``(V, F)``: ``icosphere``
    (unit sphere, n subdivisions of the icosahedron: 10 * 4^n + 2 vertices),
    ``uv-sphere`` (unit, 2n meridians, n bands), ``torus`` (R = 2, r = 0.5,
    4n x n), ``cylinder`` (radius 1, height 2, open), ``grid`` (unit square),
    ``disk`` (unit disk, n rings), ``cube`` ([-1, 1]^3); the shapes of
    ``mesh --shape NAME --res N``."""
    return _native.shape(str(name), int(n))


def info(V, F):
    """The measures of ``mesh info --json`` as a dict (same keys): counts,
    Euler characteristic, genus, components, boundary loops, manifoldness
    and defects, area, volume, mean edge length, bounding box.
    ``attributes`` is an empty list and ``read`` is None for arrays; see
    :func:`info_file`."""
    V, F = _mesh(V, F)
    return _native.info(V, F)


def info_file(path):
    """``mesh info PATH --json`` as a dict, with the file's attributes and
    what reading changed."""
    return _native.info_file(str(path))


# --------------------------------------------------------------------------
# Topology and repair


def clean(V, F, weld_tolerance=0.0, drop_degenerate=True, drop_duplicates=True, drop_unreferenced=True,
          manifold=False, orient=True):
    """Repairs a mesh (``mesh clean``): welds vertices closer than
    ``weld_tolerance`` (0: identical positions; None: no welding), drops
    collapsed, zero-area and duplicate faces and unreferenced vertices, with
    ``manifold`` cuts it into an oriented 2-manifold, and with ``orient``
    flips faces so that neighbours agree and closed parts face outward.
    Returns ``(V, F, report)``, the report counting every change. Triangles
    repeating a vertex are accepted here (and dropped)."""
    V = _vertices(V)
    F = _faces(F)
    (V2, F2), report = _native.clean_mesh(V, F, None if weld_tolerance is None else float(weld_tolerance),
                                          bool(drop_degenerate), bool(drop_duplicates), bool(drop_unreferenced),
                                          bool(manifold), bool(orient))
    return V2, F2, report


def edges(V, F):
    """The undirected edges (E, 2), smaller vertex first (``igl.edges``)."""
    V, F = _mesh(V, F)
    return _native.edges(V, F)


def boundary_loops(V, F):
    """The boundary loops of an oriented manifold, each an array of vertex
    indices in order (``igl.boundary_loop`` gives the longest); [] when closed."""
    V, F = _mesh(V, F)
    return _native.boundary_loops(V, F)


def connected_components(V, F):
    """Component label of every vertex (-1 for vertices no face uses)."""
    V, F = _mesh(V, F)
    return _native.connected_components(V, F)


# --------------------------------------------------------------------------
# Operators and normals


def cotan_laplacian(V, F):
    """The cotangent Laplacian L (eq. 2.15), n x n ``csr_matrix``.

    Convention: positive semi-definite, ``L_ij = -(cot a_ij + cot b_ij) / 2``
    off the diagonal, zero row sums, so ``x^T L x >= 0``. libigl's
    ``igl.cotmatrix`` is negative semi-definite: ``L == -igl.cotmatrix(V, F)``.
    Zero-area faces contribute nothing (see
    :func:`intrinsic_delaunay_laplacian` for degenerate meshes).
    """
    V, F = _mesh(V, F)
    return _csr(_native.cotan_laplacian(V, F))


def uniform_laplacian(V, F):
    """The graph Laplacian D - A of the edge graph (positive semi-definite)."""
    V, F = _mesh(V, F)
    return _csr(_native.uniform_laplacian(V, F))


def adjacency_matrix(V, F):
    """The vertex adjacency matrix (1 for every edge), ``csr_matrix``."""
    V, F = _mesh(V, F)
    return _csr(_native.adjacency_matrix(V, F))


def gradient(V, F):
    """The gradient of piecewise-linear functions, 3m x n: rows 3f..3f+2
    are the x, y, z components in face f (libigl's ``grad`` stacks all x
    rows first)."""
    V, F = _mesh(V, F)
    return _csr(_native.gradient(V, F))


def divergence(V, F):
    """The integrated divergence n x 3m (``D = G^T A``; ``D @ G`` is the
    cotangent Laplacian)."""
    V, F = _mesh(V, F)
    return _csr(_native.divergence(V, F))


def mass_matrix(V, F, kind="voronoi"):
    """The mass matrix, ``csr_matrix``: ``voronoi`` (mixed Voronoi areas of
    Meyer et al. 2003, libigl's ``MASSMATRIX_TYPE_VORONOI``, diagonal),
    ``barycentric`` (a third of each face, diagonal) or ``galerkin`` (the
    full matrix of hat-function products)."""
    V, F = _mesh(V, F)
    return _csr(_native.mass_matrix(V, F, kind))


def lumped_mass(V, F, kind="voronoi"):
    """The diagonal of the lumped mass matrix as a vector (galerkin: row sums)."""
    V, F = _mesh(V, F)
    return _native.lumped_mass(V, F, kind)


def intrinsic_delaunay_laplacian(V, F, mollify=1e-6):
    """``(L, M)``: the cotangent Laplacian of the intrinsic Delaunay
    triangulation of the mollified edge lengths (Sharp and Crane 2020;
    ``robust_laplacian.mesh_laplacian``), positive semi-definite with
    non-negative interior weights, and its lumped barycentric mass as a
    diagonal ``csr_matrix``. Well defined on zero-area faces."""
    V, F = _mesh(V, F)
    L, m = _native.intrinsic_delaunay_laplacian(V, F, float(mollify))
    return _csr(L), scipy.sparse.diags(m, format="csr")


def vertex_normals(V, F, weighting="area"):
    """Unit vertex normals (n, 3): face normals averaged by ``area``
    (libigl's default), ``angle``, ``uniform`` or ``max`` (Max 1999).
    Isolated vertices get zero."""
    V, F = _mesh(V, F)
    return _native.vertex_normals(V, F, weighting)


def face_normals(V, F):
    """Unit face normals (m, 3); zero for zero-area faces."""
    V, F = _mesh(V, F)
    return _native.face_normals(V, F)


def face_areas(V, F):
    """Face areas (m,) (``igl.doublearea / 2``)."""
    V, F = _mesh(V, F)
    return _native.face_areas(V, F)


# --------------------------------------------------------------------------
# Curvature


def gaussian_curvature(V, F, area="voronoi", integrated=False):
    """Gaussian curvature by angle defect (eq. 2.25): ``2 pi - sum of
    angles`` at interior vertices, divided by the vertex ``area``
    (``voronoi``, ``barycentric``) unless ``integrated``. Boundary vertices
    get 0. ``integrated=True`` equals ``igl.gaussian_curvature``; the
    integrated values sum to ``2 pi chi`` on a closed mesh."""
    V, F = _mesh(V, F)
    return _native.gaussian_curvature(V, F, area, bool(integrated))


def mean_curvature(V, F, area="voronoi", normals="area", integrated=False):
    """Mean curvature H = (k1 + k2) / 2 from the cotangent Laplacian
    (Meyer et al. 2003), signed by the vertex normal (positive on a sphere
    with outward normals), pointwise or integrated (H times the area)."""
    V, F = _mesh(V, F)
    return _native.mean_curvature(V, F, area, normals, bool(integrated))


def principal_curvature(V, F, method="fit"):
    """``(k1, k2, d1, d2)``: principal curvatures ``k1 >= k2`` (n,) and unit
    principal directions (n, 3), ``d1 x d2`` along the outward normal.

    ``method``: ``fit`` (quartic jet over the 2-ring, the most accurate),
    ``quadric`` (a quadric through the 1-ring, as ``igl.principal_curvature``),
    ``rusinkiewicz`` (per-face second fundamental forms, the fastest) or
    ``normal-cycle``. libigl returns ``(PD1, PD2, PV1, PV2)`` with PD1 the
    direction of the *maximal* curvature, as here.
    """
    V, F = _mesh(V, F)
    return _native.principal_curvature(V, F, method)


def shape_index_histogram(V, F, bins=16):
    """Area-weighted histogram (bins,) of Koenderink and van Doorn's shape
    index over ``bins`` equal bins of [-1, 1] (first: cups, middle: saddles,
    last: caps), from the pointwise curvature (quartic fit), vertices whose
    curvature is flagged untrustworthy or planar left out; sums to 1 (all
    zeros when no vertex counts). Independent of the unit of length: a global
    descriptor that compares meshes of any scale (as ``mesh batch --do
    curvature``)."""
    V, F = _mesh(V, F)
    return _native.shape_index_histogram(V, F, int(bins))


# --------------------------------------------------------------------------
# Geodesics


class HeatSolver:
    """The heat method (Crane, Weischedel and Wardetzky 2013), prepared like
    potpourri3d's ``MeshHeatMethodDistanceSolver``: the constructor factors
    the operators once; :meth:`distance` answers any set of sources with a
    few triangular solves.

    ``t_coef`` scales the time step ``t = t_coef h^2`` (h the mean edge
    length); ``laplacian`` is ``intrinsic`` (intrinsic Delaunay, robust on
    bad triangles, potpourri3d's ``use_robust=True``) or ``cotan``;
    ``boundary`` is ``mean`` (the average of Neumann and Dirichlet, as in the
    paper), ``neumann`` or ``dirichlet``; ``far_field`` (``fmm``, ``restart``,
    ``none``) continues the distance where the heat flow is below what
    double precision resolves (beyond about 1400 mean edge lengths).

    Pickles by its arguments (rebuilt on unpickling).
    """

    def __init__(self, V, F, t_coef=1.0, laplacian="intrinsic", boundary="mean", far_field="fmm"):
        V, F = _mesh(V, F)
        self._args = (V, F, float(t_coef), laplacian, boundary, far_field)
        self._native = _native.HeatSolver(*self._args)

    def distance(self, sources):
        """Distance from one vertex or a list of vertices (n,)."""
        return self._native.distance(_indices(sources))

    def distance_and_status(self, sources):
        """``(distance, status)``; status 0 resolved by the heat flow, 1
        continued by the far field, 2 unresolved."""
        return self._native.distance_and_status(_indices(sources))

    def compute_distance(self, v_ind):
        """potpourri3d's name: distance from one vertex."""
        return self.distance([int(v_ind)])

    def compute_distance_multisource(self, v_inds):
        """potpourri3d's name: distance from several vertices."""
        return self.distance(v_inds)

    @property
    def time(self):
        """The time step t of the heat flow."""
        return self._native.time

    def __getstate__(self):
        return self._args

    def __setstate__(self, args):
        self._args = args
        self._native = _native.HeatSolver(*args)


def heat_distance(V, F, sources, **options):
    """One heat-method query (see :class:`HeatSolver` for the options)."""
    return HeatSolver(V, F, **options).distance(sources)


class FastMarchingSolver:
    """Fast Marching (Kimmel and Sethian 1998), prepared: stencils and
    obtuse-angle unfoldings of one mesh for any source set. ``update`` is
    ``curved`` (default), ``point-source`` or ``plane-wave`` (eq. 2.34).
    Pickles by its arguments."""

    def __init__(self, V, F, update="curved"):
        V, F = _mesh(V, F)
        self._args = (V, F, update)
        self._native = _native.FastMarchingSolver(*self._args)

    def distance(self, sources):
        """Distance from one vertex or a list of vertices (n,)."""
        return self._native.distance(_indices(sources))

    def __getstate__(self):
        return self._args

    def __setstate__(self, args):
        self._args = args
        self._native = _native.FastMarchingSolver(*args)


def fmm_distance(V, F, sources, update="curved"):
    """Fast Marching distance from the source vertices (n,)."""
    V, F = _mesh(V, F)
    return _native.fmm_distance(V, F, _indices(sources), update)


def exact_distance(V, F, sources, max_windows=20_000_000):
    """Exact polyhedral geodesic distance (window propagation, Mitchell,
    Mount and Papadimitriou 1987; Surazhsky et al. 2005) from the source
    vertices (n,). Needs an oriented manifold without zero-area faces
    (:class:`TopologyError`, :class:`DegenerateError` otherwise);
    ``max_windows`` bounds the work (:class:`NotConvergedError` past it).
    ``igl.exact_geodesic(V, F, VS, FS, VT, FT)`` computes the same."""
    V, F = _mesh(V, F)
    return _native.exact_distance(V, F, _indices(sources), int(max_windows))


def dijkstra(V, F, sources, max_distance=np.inf):
    """Shortest paths along the edges: ``(distance (n,), predecessor (n,))``,
    predecessor -1 at sources and unreached vertices."""
    V, F = _mesh(V, F)
    return _native.dijkstra(V, F, _indices(sources), float(max_distance))


def trace_path(V, F, distance, sources, start=None, face=None, bary=None):
    """The path from vertex ``start`` (or the point ``bary`` of face
    ``face``) down the distance field (eq. 2.35) to the nearest source:
    ``(points (k, 3), length, source)``."""
    V, F = _mesh(V, F)
    d = _field(distance, "distance")
    b = None if bary is None else tuple(float(x) for x in np.asarray(bary, dtype=np.float64).ravel())
    if b is not None and len(b) != 3:
        raise InvalidOptionError(f"bary must hold 3 barycentric coordinates, not {len(b)}")
    return _native.trace_path(V, F, d, _indices(sources), None if start is None else int(start),
                              None if face is None else int(face), b)


def farthest_point_sampling(V, F, count, metric="fmm", start=None):
    """``count`` vertices by farthest-point sampling with their geodesic
    Voronoi regions: ``(samples, region, distance)``; ``metric`` is
    ``fmm`` or ``dijkstra``."""
    V, F = _mesh(V, F)
    return _native.farthest_point_sampling(V, F, int(count), metric, None if start is None else int(start))


# --------------------------------------------------------------------------
# Parameterization

PARAMETERIZATION_METHODS = ("tutte", "mean-value", "harmonic", "authalic", "intrinsic", "lscm", "arap")


def parameterize(V, F, method="harmonic", boundary="circle", spacing="chord", normalize=False,
                 lambda_=0.5, mu=0.5, iterations=20, fixed=None, return_report=False):
    """Flattens a disk-like mesh: UV (n, 2).

    ``method``: ``tutte``, ``mean-value``, ``harmonic`` (``igl.harmonic``
    with a circle boundary), ``authalic``, ``intrinsic`` (``lambda_``
    conformal + ``mu`` authalic), ``lscm`` (free boundary, ``igl.lscm``) or
    ``arap`` (``iterations`` local/global steps from the harmonic map).
    ``boundary``: ``circle`` (radius 1/2 around (1/2, 1/2), ``spacing``
    ``chord`` or ``uniform``) or ``square``; ``fixed=(indices, uv)`` pins
    given vertices instead (every boundary vertex for the fixed-boundary
    methods; two for LSCM). ``normalize`` scales free-boundary results into
    the unit square. With ``return_report`` returns ``(UV, summary)``, the
    distortion summary (flipped faces, angle/area distortion, bijectivity).
    Raises :class:`TopologyError` for a mesh that is not a disk (see
    :func:`parameterize_cut`).
    """
    V, F = _mesh(V, F)
    if fixed is not None:
        ids, uv = fixed
        fixed = (_indices(ids, "fixed indices"), np.ascontiguousarray(np.asarray(uv, dtype=np.float64)))
    uv, report = _native.parameterize(V, F, method, boundary, spacing, bool(normalize), float(lambda_),
                                      float(mu), int(iterations), fixed)
    return (uv, report) if return_report else uv


def parameterize_cut(V, F, method="harmonic", **options):
    """Cuts any manifold mesh into a disk along a seam (Erickson-Whittlesey
    2005) and flattens it: ``(V_cut, F_cut, UV, vertex_origin, summary)``,
    ``vertex_origin[i]`` the input vertex of cut vertex i."""
    V, F = _mesh(V, F)
    (Vc, Fc), uv, origin, summary = _native.parameterize_cut_mesh(V, F, method, **options)
    return Vc, Fc, uv, origin, summary


# --------------------------------------------------------------------------
# Remeshing


def remesh(V, F, edge_length=None, min_angle=28.0, max_vertices=4_000_000, smoothing_rounds=3,
           hausdorff=True, return_report=False):
    """Remeshes a manifold mesh to edges near ``edge_length`` (default: the
    input's mean edge length) through a parameterization (``mesh remesh``):
    low-distortion charts, seams sampled once, constrained Delaunay
    refinement per chart, lifted onto the input, stitched, then flips,
    collapses and ``smoothing_rounds`` rounds of tangential smoothing on the
    input. Returns ``(V, F)``; with ``return_report`` ``((V, F), report)``:
    angles, edge lengths against the target, the Hausdorff distance over
    the bounding-box diagonal (with ``hausdorff``), folds and the topology
    of both meshes. The topology (Euler characteristic, components,
    boundary loops) is kept; ``report["topology_changed"]`` says if not.
    Raises :class:`InvalidOptionError` for an edge length that needs more
    than ``max_vertices`` vertices, :class:`TopologyError` for a
    non-manifold input (see :func:`clean`)."""
    V, F = _mesh(V, F)
    h = None if edge_length is None else float(edge_length)
    (W, G), report = _native.remesh(V, F, h, float(min_angle), int(max_vertices), int(smoothing_rounds),
                                    bool(hausdorff))
    return ((W, G), report) if return_report else (W, G)


# --------------------------------------------------------------------------
# Spectral


def eigenpairs(V, F, k, laplacian="auto", mass="voronoi", component="all", tolerance=1e-11):
    """The ``k`` smallest eigenpairs of ``L x = lambda M x``: ``(evals (k,),
    evecs (n, k))``, eigenvalues ascending (one exact 0 per component),
    eigenvectors M-orthonormal. L is the positive semi-definite cotangent
    (``laplacian="cotan"``) or intrinsic Delaunay (``"intrinsic"``)
    Laplacian (``"auto"``: cotan unless the mesh has zero-area faces), M
    the lumped ``voronoi`` or ``barycentric`` mass. The same pairs as
    ``scipy.sparse.linalg.eigsh(-igl.cotmatrix(V, F), k, M, sigma=0)``.
    Raises :class:`NotConvergedError` when a residual misses ``tolerance``.
    """
    V, F = _mesh(V, F)
    return _native.eigenpairs(V, F, int(k), laplacian, mass, component, float(tolerance))


class Harmonics:
    """The manifold-harmonic basis (Vallet and Levy 2008) of a mesh: ``k``
    eigenpairs (see :func:`eigenpairs` for the options) with the transforms.

    Attributes ``eigenvalues``, ``frequencies`` (sqrt of the eigenvalues),
    ``basis`` (n, k) and ``mass`` (n,). Pickles by its arguments.
    """

    def __init__(self, V, F, k, laplacian="auto", mass="voronoi", component="all", tolerance=1e-11):
        V, F = _mesh(V, F)
        self._args = (V, F, int(k), laplacian, mass, component, float(tolerance))
        self._native = _native.Harmonics(*self._args)

    eigenvalues = property(lambda self: self._native.eigenvalues)
    frequencies = property(lambda self: self._native.frequencies)
    basis = property(lambda self: self._native.basis)
    mass = property(lambda self: self._native.mass)

    def __len__(self):
        return len(self._native)

    def forward(self, values):
        """Coefficients ``Phi^T M f`` (k,) of a per-vertex function."""
        return self._native.forward(_field(values, "values"))

    def inverse(self, coefficients):
        """The per-vertex function ``Phi c`` of k coefficients."""
        return self._native.inverse(_field(coefficients, "coefficients"))

    def filter(self, kind="low-pass", keep=None, cutoff=None, order=2, band=None, positions=None):
        """Filters the geometry (or the (n, 3) ``positions``): ``kind="keep"``
        with ``keep`` (ideal low-pass), ``"low-pass"`` with ``cutoff`` (a
        frequency) and ``order`` (Butterworth), or ``"band"`` with
        ``band=(low, high, gain)`` (exaggeration). Returns positions (n, 3)."""
        p = None if positions is None else _vertices(positions, "positions")
        return self._native.filter(kind, keep, cutoff, int(order), band, p)

    def compress(self, keep):
        """The mesh rebuilt from its first ``keep`` coefficients:
        ``((V, F), errors)`` with rms / vertex_rms / max relative to the
        bounding-box diagonal."""
        return self._native.compress(int(keep))

    def heat_kernel_signature(self, times=None, count=5):
        """``(hks (n, T), times (T,))``; see :func:`heat_kernel_signature`."""
        t = None if times is None else [float(x) for x in np.atleast_1d(times)]
        return self._native.heat_kernel_signature(t, int(count))

    def heat_trace(self, times=None, count=5):
        """``(trace (T,), times (T,))``: ``sum_i exp(-lambda_i t)`` over the
        basis, the area-weighted sum of the heat kernel signature (so
        ``trace / area`` is its mean), at ``times`` or at the ``count`` times
        of :meth:`heat_kernel_signature`. At those default times (inversely
        proportional to the eigenvalues) it does not depend on the unit of
        length."""
        t = None if times is None else [float(x) for x in np.atleast_1d(times)]
        return self._native.heat_trace(t, int(count))

    def __getstate__(self):
        return self._args

    def __setstate__(self, args):
        self._args = args
        self._native = _native.Harmonics(*args)


def spectral_filter(V, F, k, **transfer):
    """Filtered positions (n, 3) with the first ``k`` harmonics; see
    :meth:`Harmonics.filter` for the transfer function."""
    return Harmonics(V, F, k).filter(**transfer)


def spectral_compress(V, F, k, keep=None):
    """The mesh rebuilt from ``keep`` (default ``k``) of ``k`` harmonic
    coefficients: ``((V, F), errors)`` (Karni and Gotsman 2000)."""
    return Harmonics(V, F, k).compress(k if keep is None else keep)


def heat_kernel_signature(V, F, k=100, times=None, count=5, laplacian="auto", mass="voronoi"):
    """Heat kernel signature (Sun, Ovsjanikov and Guibas 2009) from ``k``
    eigenpairs: ``(hks (n, T), times (T,))``; without ``times``, ``count``
    times log-spaced from ``4 ln 10 / lambda_k`` to ``4 ln 10 / lambda_1``
    (as ``mesh spectral hks``)."""
    V, F = _mesh(V, F)
    t = None if times is None else [float(x) for x in np.atleast_1d(times)]
    return _native.heat_kernel_signature(V, F, int(k), t, int(count), laplacian, mass)


# --------------------------------------------------------------------------
# Subdivision and wavelets


def subdivide(V, F, levels=1, scheme="loop"):
    """``levels`` rounds of 4-to-1 subdivision: ``loop`` (Loop 1987),
    ``midpoint`` or ``butterfly`` (modified butterfly, Zorin et al. 1996).
    Returns ``(V, F)``; the input's vertices keep their indices."""
    V, F = _mesh(V, F)
    return _native.subdivide(V, F, int(levels), scheme)


def loop_subdivide(V, F, levels=1):
    """Loop subdivision, ``levels`` times: ``(V, F)`` (``igl.loop(V, F,
    number_of_subdivs)``)."""
    return subdivide(V, F, levels, "loop")


class Multiresolution:
    """The wavelet decomposition of a mesh with subdivision connectivity
    (Lounsbery, DeRose and Warren; lifted or lazy wavelets on the
    ``midpoint``, ``loop`` or ``butterfly`` scheme): a base mesh and one
    level of coefficients per subdivision. Vertices are numbered
    hierarchically, so returned meshes may number them differently from
    the input. Pickles by its arguments and current coefficients."""

    def __init__(self, V, F, scheme="midpoint", wavelet="lifted", max_levels=None):
        V, F = _mesh(V, F)
        self._args = (V, F, scheme, wavelet, max_levels)
        self._native = _native.Multiresolution(*self._args)

    @property
    def levels(self):
        """Number of levels J (level 0 is the base, level J the full mesh)."""
        return self._native.levels

    def level(self, j):
        """The mesh of level ``j`` as ``(V, F)``."""
        return self._native.level(int(j))

    def synthesize(self):
        """The full mesh from the base and the coefficients, ``(V, F)``."""
        return self._native.synthesize()

    @property
    def base_positions(self):
        """Positions of the base mesh (n0, 3); assign to edit the shape at
        the coarsest scale while keeping the details."""
        return self._native.base_positions

    @base_positions.setter
    def base_positions(self, positions):
        self._native.base_positions = _vertices(positions, "base_positions")

    def coefficients(self, level):
        """Wavelet coefficients of ``level`` (one 3-vector per vertex added at that level)."""
        return self._native.coefficients(int(level))

    def set_coefficients(self, level, values):
        """Replaces the coefficients of ``level``."""
        self._native.set_coefficients(int(level), _vertices(values, "coefficients"))

    def statistics(self):
        """Per level: count, mean, rms and max magnitude of the coefficients."""
        return self._native.statistics()

    def compress(self, keep_fraction=0.1):
        """Keeps the largest ``keep_fraction`` of the coefficients:
        ``((V, F), errors)`` with rms_error and max_error."""
        return self._native.compress(float(keep_fraction))

    def __getstate__(self):
        coefficients = [self.coefficients(j) for j in range(self.levels)]
        return self._args, self.base_positions, coefficients

    def __setstate__(self, state):
        args, base, coefficients = state
        self._args = args
        self._native = _native.Multiresolution(*args)
        self._native.base_positions = base
        for j, c in enumerate(coefficients):
            self._native.set_coefficients(j, c)


def wavelet_analysis(V, F, scheme="midpoint", wavelet="lifted", max_levels=None):
    """Analysis: the :class:`Multiresolution` of a semi-regular mesh."""
    return Multiresolution(V, F, scheme, wavelet, max_levels)


def wavelet_synthesis(multiresolution):
    """Synthesis: ``(V, F)`` of a :class:`Multiresolution`."""
    return multiresolution.synthesize()


def wavelet_compress(V, F, keep_fraction=0.1, scheme="midpoint", wavelet="lifted"):
    """Analysis, thresholding to the largest ``keep_fraction`` of the
    coefficients, synthesis: ``((V, F), errors)``."""
    return Multiresolution(V, F, scheme, wavelet).compress(keep_fraction)


__all__ = [
    "MeshkitError", "InvalidMeshError", "InvalidOptionError", "TopologyError", "DegenerateError",
    "SolverError", "NotConvergedError", "MeshIOError", "MeshFileNotFoundError",
    "read", "read_attributes", "write", "write_mesh", "shape", "info", "info_file",
    "clean", "edges", "boundary_loops", "connected_components",
    "cotan_laplacian", "uniform_laplacian", "adjacency_matrix", "gradient", "divergence", "mass_matrix",
    "lumped_mass", "intrinsic_delaunay_laplacian", "vertex_normals", "face_normals", "face_areas",
    "gaussian_curvature", "mean_curvature", "principal_curvature", "shape_index_histogram",
    "HeatSolver", "heat_distance", "FastMarchingSolver", "fmm_distance", "exact_distance", "dijkstra",
    "trace_path", "farthest_point_sampling",
    "PARAMETERIZATION_METHODS", "parameterize", "parameterize_cut", "remesh",
    "eigenpairs", "Harmonics", "spectral_filter", "spectral_compress", "heat_kernel_signature",
    "subdivide", "loop_subdivide", "Multiresolution", "wavelet_analysis", "wavelet_synthesis",
    "wavelet_compress",
]
