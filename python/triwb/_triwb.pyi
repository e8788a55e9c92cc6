"""Type stubs of the native module (``triwb._triwb``); ``help()`` shows the docstrings."""

from os import PathLike
from typing import Any, Iterator, Literal, Optional, Sequence, TypedDict, Union

import numpy as np
import numpy.typing as npt

__version__: str

ArrayLike = npt.ArrayLike
FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]
PathOrName = Union[str, "PathLike[str]"]

class WorkbenchError(Exception):
    """A job failed; the message is the command line's."""

class UsageError(ValueError):
    """A bad name, value or array (the command line exits 2 for these)."""

class MeshData:
    """A mesh as arrays: ``V, F = mesh`` unpacks like libigl's pair."""

    V: FloatArray
    F: IntArray
    normals: Optional[FloatArray]
    shape: Optional[FloatArray]
    colors: Optional[FloatArray]
    creases: IntArray
    name: str
    notes: list[str]
    def __iter__(self) -> Iterator[npt.NDArray[Any]]: ...

class Tessellation(TypedDict):
    V: FloatArray
    F: IntArray
    normals: FloatArray
    K: FloatArray
    H: FloatArray
    k1: FloatArray
    k2: FloatArray
    d1: FloatArray
    d2: FloatArray
    patch: IntArray
    welds: int
    singular_samples: int
    collapsed_faces: int

class Estimate(TypedDict):
    normals: FloatArray
    shape: FloatArray
    k1: FloatArray
    k2: FloatArray
    d1: FloatArray
    d2: FloatArray
    K: FloatArray
    H: FloatArray
    missing: int
    crease_vertices: int
    notes: list[str]

class CurveBatch(TypedDict):
    alpha: FloatArray
    points: FloatArray
    kappa: FloatArray
    curvature_variation: FloatArray
    fallback: npt.NDArray[np.bool_]
    converged: npt.NDArray[np.bool_]
    iterations: IntArray
    reports: Optional[list[dict[str, Any]]]

class Fit:
    """A finished fit: nets, report, G1 and tessellations, in the input's coordinates."""

    @property
    def nets(self) -> FloatArray:
        """(patches, points per patch, 3)."""
    @property
    def layout(self) -> dict[str, Any]: ...
    @property
    def report(self) -> dict[str, Any]:
        """The command line's ``fit --report`` JSON, as a dict."""
    @property
    def report_json(self) -> str: ...
    @property
    def V(self) -> FloatArray: ...
    @property
    def F(self) -> IntArray: ...
    @property
    def face_source(self) -> Optional[IntArray]: ...
    @property
    def vertex_source(self) -> Optional[IntArray]: ...
    @property
    def edges(self) -> IntArray: ...
    @property
    def edge_curves(self) -> FloatArray:
        """(edges, 4, 3) cubic Bézier points."""
    @property
    def alphas(self) -> FloatArray: ...
    @property
    def fallback_faces(self) -> list[dict[str, Any]]: ...
    log: list[str]
    job_seconds: float
    def tessellate(self, segments: int = 4) -> Tessellation: ...
    def g1(self, samples: Optional[int] = None) -> dict[str, Any]: ...
    def to_mesh(
        self, path: PathOrName, segments: int = 4, up: Literal["z", "y"] = "z"
    ) -> PathLike[str]: ...

def read_mesh(path: PathOrName) -> MeshData: ...
def write_mesh(
    path: PathOrName,
    V: ArrayLike,
    F: ArrayLike,
    *,
    normals: Optional[ArrayLike] = None,
    colors: Optional[ArrayLike] = None,
    K: Optional[ArrayLike] = None,
    H: Optional[ArrayLike] = None,
    shape: Optional[ArrayLike] = None,
    ascii: bool = False,
    double: bool = False,
    up: Literal["z", "y"] = "z",
) -> PathLike[str]: ...
def ring(resolution: Optional[int] = None) -> MeshData: ...
def sphere(resolution: Optional[int] = None) -> MeshData: ...
def capsule(resolution: Optional[int] = None) -> MeshData: ...
def octa() -> MeshData: ...
def datasets() -> list[str]: ...
def estimate(
    V: ArrayLike,
    F: ArrayLike,
    method: str = "hybrid",
    normals: Optional[ArrayLike] = None,
    *,
    crease_angle: Optional[float] = None,
    no_creases: bool = False,
    threads: Optional[int] = None,
) -> Estimate: ...
def fit(
    V: Union[ArrayLike, PathOrName],
    F: Optional[ArrayLike] = None,
    *,
    normals: Optional[ArrayLike] = None,
    shape: Optional[ArrayLike] = None,
    creases: Optional[ArrayLike] = None,
    resolution: Optional[int] = None,
    scheme: str = "shirman-sequin",
    curves: str = "chord",
    solver: str = "exact-penalty",
    dbhs_pick: Optional[str] = None,
    tweak_t: float = 0.5858,
    four_ninths: bool = False,
    tangents: Literal["star", "per-edge"] = "star",
    heightfield: Optional[bool] = None,
    interior: Literal["default", "thin-plate", "membrane"] = "default",
    estimate: str = "hybrid",
    replace_normals: bool = False,
    crease_angle: Optional[float] = None,
    no_creases: bool = False,
    g1_samples: int = 9,
    segments: int = 4,
    patches_out: Optional[PathOrName] = None,
    mesh_out: Optional[PathOrName] = None,
    up: Literal["z", "y"] = "z",
    label: Optional[str] = None,
    threads: Optional[int] = None,
    **params: float,
) -> Fit: ...
def curve(
    t0: Sequence[float],
    t1: Sequence[float],
    k0: float,
    k1: float,
    method: str = "optimized",
    *,
    solver: str = "exact-penalty",
    dbhs_pick: Optional[str] = None,
    tweak_t: float = 0.5858,
    four_ninths: bool = False,
) -> dict[str, Any]: ...
def curves(
    problems: ArrayLike,
    method: str = "optimized",
    *,
    solver: str = "exact-penalty",
    dbhs_pick: Optional[str] = None,
    tweak_t: float = 0.5858,
    four_ninths: bool = False,
) -> CurveBatch: ...
def schemes() -> list[dict[str, Any]]: ...
def curve_methods() -> list[dict[str, Any]]: ...
def solvers() -> list[dict[str, Any]]: ...
def estimators() -> list[dict[str, Any]]: ...
def sweep_manifest(grid: dict[str, Any]) -> dict[str, Any]: ...
def sweep_task(grid: dict[str, Any], id: str) -> dict[str, Any]: ...
def sweep_merge(manifest: dict[str, Any], results: list[dict[str, Any]]) -> list[dict[str, Any]]: ...
