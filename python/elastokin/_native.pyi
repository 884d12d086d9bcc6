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
MAX_VARIANTS: int
VERSION: str

_Column = Union[numpy.typing.NDArray[numpy.float64], List[Union[str, float, None]]]
_Columns = List[Tuple[str, _Column]]
_VariantEdits = Tuple[str, List[Tuple[str, str]]]

def analyses() -> List[str]: ...
def parameter(name: str) -> str: ...

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
    def batch(
        self,
        variants: Union[str, Sequence[Union[str, Tuple[Optional[str], Sequence[Tuple[str, str]]]]]],
        threads: Optional[int] = None,
    ) -> List[Dict[str, Any]]: ...
