"""The exceptions meshkit raises. Every one derives from :class:`MeshkitError`
and carries the text of the Rust error that caused it."""


class MeshkitError(Exception):
    """Base class of every meshkit error."""


class InvalidMeshError(MeshkitError, ValueError):
    """The arrays do not make a mesh: wrong shape or dtype, an index out of
    range or negative, a NaN or infinite coordinate, a triangle repeating a
    vertex, no faces where faces are needed."""


class InvalidOptionError(MeshkitError, ValueError):
    """An argument is out of its range: an unknown method name, k = 0, a
    source vertex that does not exist, an attribute of the wrong length."""


class TopologyError(MeshkitError):
    """The operation needs another topology: an oriented manifold, a disk,
    subdivision connectivity, a start point connected to a source."""


class DegenerateError(MeshkitError):
    """The geometry is too degenerate for the operation (zero-area faces
    where the method cannot handle them)."""


class SolverError(MeshkitError):
    """A sparse or dense factorization failed."""


class NotConvergedError(SolverError):
    """An iterative solver missed its tolerance or reached its work bound."""


class MeshIOError(MeshkitError, OSError):
    """Reading or writing a mesh file failed (syntax, truncation, unknown
    format, values a 32-bit format cannot hold, operating system errors)."""


class MeshFileNotFoundError(MeshIOError, FileNotFoundError):
    """The mesh file does not exist."""


__all__ = [
    "MeshkitError",
    "InvalidMeshError",
    "InvalidOptionError",
    "TopologyError",
    "DegenerateError",
    "SolverError",
    "NotConvergedError",
    "MeshIOError",
    "MeshFileNotFoundError",
]
