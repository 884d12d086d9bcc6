"""Type stubs of the compiled part of elastokin (the Rust extension); use the package ``elastokin``."""

from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy
import numpy.typing

class Error(Exception):
    """Every error elastokin raises."""

class ModelError(Error):
    """A model file, model dict or variant edit that cannot be read as a suspension model."""

class AnalysisError(Error):
    """An analysis that failed on the model: the solver's reason."""

COMPLIANCE_ROWS: List[str]
COMPLIANCE_COLUMNS: List[str]
BATCH_HALF_RANGE: float
BATCH_STEPS: int
BATCH_FIGURES: List[str]
MAX_VARIANTS: int
VERSION: str

_Column = Union[numpy.typing.NDArray[numpy.float64], List[Union[str, float, None]]]
_Columns = List[Tuple[str, _Column]]
_VariantEdits = Tuple[str, List[Tuple[str, str]]]

def analyses() -> List[str]: ...
def parameter(name: str) -> str: ...
def shard_blocks(count: int, chunks: int) -> List[Tuple[int, int]]: ...
def compare(
    designs: List[Any],
    analysis: Optional[str] = None,
    range: Optional[Tuple[float, float]] = None,
    steps: int = 32,
) -> Dict[str, Any]: ...

class Model:
    @staticmethod
    def read(path: str) -> Model: ...
    @staticmethod
    def from_json(text: str, origin: str) -> Model: ...
    @property
    def name(self) -> str: ...
    def to_json(self) -> str: ...
    def document(self) -> Tuple[str, str]: ...
    def read_variants(self, variants: Union[str, Sequence[Union[str, _VariantEdits]]]) -> List[_VariantEdits]: ...
    def run(
        self,
        name: str,
        range: Optional[Tuple[float, float]] = None,
        steps: int = 32,
        mode: str = "corrected",
        wheel: str = "held",
        load_point: str = "contact_patch",
        compliance: bool = False,
        through_limits: bool = False,
        arc_step: Optional[float] = None,
    ) -> Tuple[str, _Columns, Optional[_Columns]]: ...
    def suite(
        self,
        analyses: Optional[Sequence[str]] = None,
        range: Optional[Tuple[float, float]] = None,
        steps: int = 32,
        mode: str = "corrected",
        wheel: str = "held",
        load_point: str = "contact_patch",
        compliance: bool = False,
        through_limits: bool = False,
        arc_step: Optional[float] = None,
    ) -> str: ...
    def compliance(self) -> numpy.typing.NDArray[numpy.float64]: ...
    def hardpoint_parameters(self) -> List[str]: ...
    def live(
        self,
        analyses: Optional[Sequence[str]] = None,
        steps: int = 32,
        targets: Optional[str] = None,
        directory: str = ".",
        port: int = 0,
        bind: str = "127.0.0.1",
        frame_ancestors: Sequence[str] = ...,
    ) -> LiveServer: ...
    def tune(self, targets: str, directory: str = ".") -> Dict[str, Any]: ...
    def tolerance(self, tolerances: str, monte_carlo: Optional[int] = None, seed: int = 1) -> Dict[str, Any]: ...
    def tolerance_samples(self, tolerances: str, n: int, seed: int = 1) -> Dict[str, Any]: ...
    def sensitivities(
        self,
        parameters: List[str],
        analysis: str = "parallel-travel",
        range: Optional[Tuple[float, float]] = None,
        steps: int = 32,
        figures_only: bool = False,
    ) -> Dict[str, Any]: ...
    def batch(
        self,
        variants: Union[str, Sequence[Union[str, Tuple[Optional[str], Sequence[Tuple[str, str]]]]]],
        threads: Optional[int] = None,
        analyses: Optional[Sequence[str]] = None,
    ) -> List[Dict[str, Any]]: ...

class LiveServer:
    @property
    def address(self) -> str: ...
    @property
    def port(self) -> int: ...
    @property
    def serving(self) -> bool: ...
    def stop(self) -> bool: ...

_Vector3 = Tuple[float, float, float]
_Stiffness = Union[float, List[Tuple[float, float]]]
_Rows = numpy.typing.NDArray[numpy.float64]

class Scene:
    def __init__(self) -> None: ...
    def body(self, name: str, at: _Vector3) -> str: ...
    def joint(
        self,
        name: str,
        kind: str,
        bodies: Tuple[str, str],
        at: Optional[_Vector3] = None,
        to: Optional[_Vector3] = None,
        axis: Optional[_Vector3] = None,
        axis_j: Optional[_Vector3] = None,
    ) -> None: ...
    def field(
        self,
        name: str,
        bodies: Tuple[str, str],
        at: _Vector3,
        stiffness: List[List[float]],
        axis: Optional[_Vector3] = None,
        y_axis: Optional[_Vector3] = None,
        preload_force: Optional[_Vector3] = None,
        preload_torque: Optional[_Vector3] = None,
    ) -> None: ...
    def beam(
        self,
        name: str,
        bodies: Tuple[str, str],
        from_: _Vector3,
        to: _Vector3,
        y_axis: _Vector3,
        youngs_modulus: float,
        shear_modulus: float,
        area: float,
        iy: float,
        iz: float,
        j: float,
        shear_areas: Optional[Tuple[float, float]] = None,
        shear_centre: Optional[Tuple[float, float]] = None,
    ) -> None: ...
    def bushing(
        self,
        name: str,
        bodies: Tuple[str, str],
        at: _Vector3,
        axis: Optional[_Vector3] = None,
        y_axis: Optional[_Vector3] = None,
        radial: Optional[_Stiffness] = None,
        axial: Optional[_Stiffness] = None,
        torsion: Optional[_Stiffness] = None,
        conical: Optional[_Stiffness] = None,
        translation: Optional[Sequence[_Stiffness]] = None,
        rotation: Optional[Sequence[_Stiffness]] = None,
        law: str = "energy",
        preload_force: Optional[_Vector3] = None,
        preload_torque: Optional[_Vector3] = None,
    ) -> None: ...
    def spring(
        self,
        name: str,
        bodies: Tuple[str, str],
        from_: _Vector3,
        to: _Vector3,
        rate: Optional[float] = None,
        curve: Optional[List[Tuple[float, float]]] = None,
        design_force: Optional[float] = None,
        free_length: Optional[float] = None,
        preload: Optional[float] = None,
    ) -> None: ...
    def stop(
        self,
        name: str,
        kind: str,
        bodies: Tuple[str, str],
        from_: _Vector3,
        to: _Vector3,
        clearance: float,
        curve: List[Tuple[float, float]],
    ) -> None: ...
    def force(
        self, name: str, body: str, at: _Vector3, force: _Vector3, constant: Optional[_Vector3] = None
    ) -> None: ...
    def torque(self, name: str, body: str, torque: _Vector3, constant: Optional[_Vector3] = None) -> None: ...
    @property
    def bodies(self) -> List[str]: ...
    @property
    def joints(self) -> List[str]: ...
    @property
    def elements(self) -> List[str]: ...
    def sweep(
        self,
        start: float,
        end: float,
        steps: int,
        mode: str = "corrected",
        through_limits: bool = False,
        arc_step: Optional[float] = None,
        force_tolerance: float = 1e-9,
        constraint_tolerance: float = 1e-10,
    ) -> SceneSweep: ...
    def solve(self, t: float, force_tolerance: float = 1e-9, constraint_tolerance: float = 1e-10) -> SceneSweep: ...

class SceneSweep:
    @property
    def mode(self) -> str: ...
    @property
    def t(self) -> numpy.typing.NDArray[numpy.float64]: ...
    @property
    def iterations(self) -> numpy.typing.NDArray[numpy.int64]: ...
    @property
    def force_residual(self) -> numpy.typing.NDArray[numpy.float64]: ...
    @property
    def constraint_residual(self) -> numpy.typing.NDArray[numpy.float64]: ...
    @property
    def limit(self) -> Optional[float]: ...
    @property
    def arc_length_from(self) -> Optional[int]: ...
    @property
    def complete(self) -> bool: ...
    @property
    def bodies(self) -> List[str]: ...
    @property
    def joints(self) -> List[str]: ...
    @property
    def elements(self) -> List[Tuple[str, str]]: ...
    def position(self, body: str) -> _Rows: ...
    def rotation(self, body: str) -> _Rows: ...
    def point(self, body: str, at: _Vector3) -> _Rows: ...
    def reaction(self, joint: str) -> Tuple[_Rows, _Rows]: ...
    def element(self, name: str) -> Dict[str, Any]: ...
    def __len__(self) -> int: ...
