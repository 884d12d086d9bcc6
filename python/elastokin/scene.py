"""A multibody scene built in code, body by body, and its equilibria along a load path.

The engine level under the model files: rigid bodies, kinematic joints, rubber bushings, coil springs, bump
and rebound stops, and point forces and torques, solved quasi-statically by the Rust library. Every number
comes from the library; an entry means what the same entry of a model file's general form means
(``docs/model-file.md``). Points are global ``[x, y, z]`` in metres at design (ISO 8855: x forward, y left,
z up), axes are directions ``[x, y, z]``; ``"chassis"`` (or ``"ground"``) is the fixed ground.

>>> import elastokin
>>> scene = elastokin.Scene()
>>> scene.body("slider", at=[0.0, 0.0, 0.0])
'slider'
>>> scene.joint("slideway", "translational", bodies=("chassis", "slider"), at=[0, 0, 0], axis=[1, 0, 0])
'slideway'
>>> scene.spring("return spring", bodies=("chassis", "slider"), from_=[0.5, 0, 0], to=[0, 0, 0],
...              rate=2e4, design_force=0.0)
'return spring'
>>> scene.force("push", body="slider", at=[0, 0, 0], force=[100.0, 0, 0])
'push'
>>> sweep = scene.sweep(0.0, 1.0, 4)
>>> round(float(sweep.position("slider")[-1, 0]), 9)     # 100 N on 20 kN/m: 5 mm
0.005
"""

from __future__ import annotations

import contextlib
import math
import numbers
from typing import Any, Dict, Iterator, List, Optional, Sequence, Tuple, Union, cast

import numpy

from . import _native

_Vector = Union[Sequence[float], numpy.ndarray]
_Stiffness = Union[float, Sequence[Sequence[float]], numpy.ndarray]


def _vector(value: Any, what: str, item: str) -> Tuple[float, float, float]:
    """Three numbers, or a ValueError naming the argument (NaN passes: the library refuses it by name)."""
    try:
        array = numpy.asarray(value, dtype=float)
    except (TypeError, ValueError):
        array = None
    if array is None or array.shape != (3,):
        raise ValueError(f"'{item}': {what} must be three numbers [x, y, z], got {value!r}")
    return (float(array[0]), float(array[1]), float(array[2]))


def _optional_vector(value: Any, what: str, item: str) -> Optional[Tuple[float, float, float]]:
    return None if value is None else _vector(value, what, item)


def _curve(value: Any, what: str, item: str) -> List[Tuple[float, float]]:
    """A table of (x, y) points, or a ValueError naming the argument."""
    try:
        array = numpy.asarray(value, dtype=float)
    except (TypeError, ValueError):
        array = None
    if array is None or array.ndim != 2 or array.shape[1] != 2:
        raise ValueError(f"'{item}': {what} must be a table of (x, y) points, got {value!r}")
    return [(float(x), float(y)) for x, y in array]


def _stiffness(value: Any, what: str, item: str) -> Union[float, List[Tuple[float, float]], None]:
    """A rate (a number) or a curve (a table of (deflection, force) points)."""
    if value is None:
        return None
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        return float(value)
    return _curve(value, f"{what} (a rate, or a curve of (deflection, force) points)", item)


def _number(value: Any, what: str, item: str) -> Optional[float]:
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ValueError(f"'{item}': {what} must be a number, got {value!r}")
    return float(value)


def _name(name: Any, what: str) -> str:
    if not isinstance(name, str) or not name:
        raise ValueError(f"a {what}'s name must be a non-empty string, got {name!r}")
    return name


def _bodies(value: Any, item: str) -> Tuple[str, str]:
    if isinstance(value, str) or not isinstance(value, Sequence) or len(value) != 2:
        raise ValueError(f"'{item}': bodies must be two body names (first, second), got {value!r}")
    first, second = value
    if not (isinstance(first, str) and isinstance(second, str)):
        raise ValueError(f"'{item}': bodies must be two body names (first, second), got {value!r}")
    return first, second


def _path(start: Any, end: Any, steps: Any) -> Tuple[float, float, int]:
    for what, v in (("start", start), ("end", end)):
        if isinstance(v, bool) or not isinstance(v, numbers.Real) or not math.isfinite(float(v)):
            raise ValueError(f"{what} must be a finite load parameter, got {v!r}")
    if isinstance(steps, bool) or not isinstance(steps, numbers.Integral) or steps < 1:
        raise ValueError(f"steps must be a whole number of at least 1, got {steps!r}")
    return float(start), float(end), int(steps)


@contextlib.contextmanager
def _not_while_swept(name: str) -> Iterator[None]:
    """Says in the scene's words what PyO3 says as "Already borrowed": another thread is sweeping this scene
    (a sweep holds it, the GIL released, until its last row), so a part cannot be added to it now."""
    try:
        yield
    except RuntimeError as e:
        if "already borrowed" not in str(e).lower() or "mutably" in str(e).lower():
            raise
        raise RuntimeError(
            f"'{name}' cannot be added while the scene is being swept on another thread: add parts before the "
            "sweep starts or after it ends"
        ) from None


@contextlib.contextmanager
def _not_while_built() -> Iterator[None]:
    """Says in the scene's words what PyO3 says as "Already mutably borrowed": another thread is adding a
    part to this scene, so it cannot be swept at that instant."""
    try:
        yield
    except RuntimeError as e:
        if "already mutably borrowed" not in str(e).lower():
            raise
        raise RuntimeError(
            "the scene is having a part added on another thread: sweep it once its parts are added"
        ) from None


class Scene:
    """A multibody scene: bodies, joints, bushings, springs, stops and loads, added one at a time.

    Each method adds one part and gives back its name; names are unique across bodies, joints and elements.
    Raises ModelError for a part the library refuses (an unknown body, a name used twice, a zero axis, a
    rate out of range, a NaN coordinate: the message names the part and says what to give), ValueError for
    an argument that is not what the method takes (a kind word it does not know, a point that is not three
    numbers). Its sweeps release the GIL, so other threads run while one sweeps; a part added to a scene
    that another thread is sweeping is refused with a RuntimeError saying so (add parts before or after).
    """

    __slots__ = ("_native",)

    def __init__(self) -> None:
        self._native = _native.Scene()

    def body(self, name: str, at: _Vector) -> str:
        """Adds a rigid body whose reference point is ``at`` at design (its axes are global at design);
        results give its motion there. ``"chassis"`` and ``"ground"`` are the ground's names, not a body's."""
        name = _name(name, "body")
        with _not_while_swept(name):
            return self._native.body(name, _vector(at, "at", name))

    def joint(
        self,
        name: str,
        kind: str,
        *,
        bodies: Tuple[str, str],
        at: Optional[_Vector] = None,
        to: Optional[_Vector] = None,
        axis: Optional[_Vector] = None,
        axis_j: Optional[_Vector] = None,
    ) -> str:
        """Adds a kinematic joint between ``bodies`` (first, second); its reaction is the one on the second.

        ``kind`` and the keys each kind takes are the model file's (``docs/model-file.md``, "joints"):
        ``spherical`` (at), ``revolute``, ``cylindrical``, ``translational`` (at, axis), ``universal`` (at,
        axis of the first body, axis_j of the second, perpendicular), ``fixed`` (at), ``distance`` (at on
        the first body, to on the second), ``in_plane`` (at, axis the normal, optional to), ``in_line`` (at,
        axis, optional to), ``perpendicular`` (axis, axis_j), ``parallel_axes`` (axis). A key the kind needs
        and lacks, or one it does not use, is a ModelError."""
        name = _name(name, "joint")
        if not isinstance(kind, str):
            raise ValueError(f"'{name}': kind must be a joint kind's name, got {kind!r}")
        with _not_while_swept(name):
            self._native.joint(
                name,
                kind,
                _bodies(bodies, name),
                at=_optional_vector(at, "at", name),
                to=_optional_vector(to, "to", name),
                axis=_optional_vector(axis, "axis", name),
                axis_j=_optional_vector(axis_j, "axis_j", name),
            )
        return name

    def bushing(
        self,
        name: str,
        *,
        bodies: Tuple[str, str],
        at: _Vector,
        axis: Optional[_Vector] = None,
        y_axis: Optional[_Vector] = None,
        radial: Optional[_Stiffness] = None,
        axial: Optional[_Stiffness] = None,
        torsion: Optional[_Stiffness] = None,
        conical: Optional[_Stiffness] = None,
        translation: Optional[Sequence[_Stiffness]] = None,
        rotation: Optional[Sequence[_Stiffness]] = None,
        law: str = "energy",
        preload_force: Optional[_Vector] = None,
        preload_torque: Optional[_Vector] = None,
    ) -> str:
        """Adds a rubber bushing between ``bodies`` centred at ``at``, as a model file's bushing entry.

        Its frame moves with the first body: x along ``axis`` (default global x), y towards ``y_axis`` made
        perpendicular (default any), z completing a right-handed frame. Give either the four rates of a
        cylindrical bushing — ``radial`` and ``axial`` (N/m), ``torsion`` and ``conical`` (N·m/rad), x its
        axis — or ``translation`` and ``rotation``, three each along and about x, y, z. Each rate may instead
        be a measured curve, a table of (deflection, force) points through (0, 0) (m and N, or rad and N·m).
        ``law`` is how the moment follows the twist: "energy" (default), "linear" or "tait_bryan_xyz".
        ``preload_force`` (N) and ``preload_torque`` (N·m), in the bushing frame, act on the second body at
        zero deflection. Reports give the force and moment on the second body."""
        name = _name(name, "bushing")

        def three(value: Any, what: str) -> Optional[List[Any]]:
            if value is None:
                return None
            if isinstance(value, (str, numbers.Real)) or len(value) != 3:
                raise ValueError(f"'{name}': {what} must be three rates or curves (x, y, z), got {value!r}")
            return [_stiffness(v, f"{what}[{k}]", name) for k, v in enumerate(value)]

        if not isinstance(law, str):
            raise ValueError(f"'{name}': law must be a rotation law's name, got {law!r}")
        with _not_while_swept(name):
            self._native.bushing(
                name,
                _bodies(bodies, name),
                _vector(at, "at", name),
                axis=_optional_vector(axis, "axis", name),
                y_axis=_optional_vector(y_axis, "y_axis", name),
                radial=_stiffness(radial, "radial", name),
                axial=_stiffness(axial, "axial", name),
                torsion=_stiffness(torsion, "torsion", name),
                conical=_stiffness(conical, "conical", name),
                translation=three(translation, "translation"),
                rotation=three(rotation, "rotation"),
                law=law,
                preload_force=_optional_vector(preload_force, "preload_force", name),
                preload_torque=_optional_vector(preload_torque, "preload_torque", name),
            )
        return name

    def field(
        self,
        name: str,
        *,
        bodies: Tuple[str, str],
        at: _Vector,
        stiffness: Any,
        axis: Optional[_Vector] = None,
        y_axis: Optional[_Vector] = None,
        preload_force: Optional[_Vector] = None,
        preload_torque: Optional[_Vector] = None,
    ) -> str:
        """Adds a field element between ``bodies`` at ``at``, as a model file's field entry: ``stiffness`` is a
        6×6 matrix (six rows of six, or a numpy array) over the deflection along x, y, z (m) and the rotation
        about them (rad) in its frame — N/m, N/rad, N·m/m, N·m/rad — symmetric and positive semi-definite, the
        coupled terms of a data sheet allowed (a diagonal one is the bushing of those rates). Its frame is a
        bushing's: x along ``axis``, y towards ``y_axis``, moving with the first body. ``preload_force`` (N)
        and ``preload_torque`` (N·m), in its frame, act on the second body at zero deflection."""
        name = _name(name, "field")
        matrix = numpy.asarray(stiffness, dtype=float)
        if matrix.shape != (6, 6):
            raise ValueError(f"'{name}': stiffness must be 6×6 (six rows of six), got shape {matrix.shape}")
        with _not_while_swept(name):
            self._native.field(
                name,
                _bodies(bodies, name),
                _vector(at, "at", name),
                [[float(v) for v in row] for row in matrix],
                axis=_optional_vector(axis, "axis", name),
                y_axis=_optional_vector(y_axis, "y_axis", name),
                preload_force=_optional_vector(preload_force, "preload_force", name),
                preload_torque=_optional_vector(preload_torque, "preload_torque", name),
            )
        return name

    def beam(
        self,
        name: str,
        *,
        bodies: Tuple[str, str],
        from_: _Vector,
        to: _Vector,
        y_axis: _Vector,
        section: Dict[str, Any],
    ) -> str:
        """Adds a straight elastic beam from ``from_`` on the first body to ``to`` on the second, as a model
        file's beam entry of one segment: ``section`` is a model file's section (``youngs_modulus``,
        ``shear_modulus`` in Pa, ``area`` in m², ``iy``, ``iz``, ``j`` in m⁴, and optionally ``shear_areas``
        ``[A_y, A_z]`` and ``shear_centre`` ``[e_y, e_z]``), its y axis leaning towards ``y_axis``. Large rigid
        motion, small strain: split a member that bends far into beams with bodies between them."""
        name = _name(name, "beam")
        known = {"youngs_modulus", "shear_modulus", "area", "iy", "iz", "j", "shear_areas", "shear_centre"}
        unknown = sorted(set(section) - known)
        if unknown:
            raise ValueError(f"'{name}': section has no {', '.join(unknown)}: give {', '.join(sorted(known))}")
        missing = sorted({"youngs_modulus", "shear_modulus", "area", "iy", "iz", "j"} - set(section))
        if missing:
            raise ValueError(f"'{name}': section needs {', '.join(missing)} (SI: Pa, m², m⁴)")

        def number(key: str, value: Any) -> float:
            # A value present (None is no number here): `_number` refuses it by name, or gives a float.
            if value is None:
                raise ValueError(f"'{name}': section {key} must be a number, got None")
            return cast(float, _number(value, f"section {key}", name))

        def pair(key: str) -> Optional[Tuple[float, float]]:
            value = section.get(key)
            if value is None:
                return None
            if isinstance(value, (str, bytes)) or not isinstance(value, Sequence) or len(value) != 2:
                raise ValueError(f"'{name}': section {key} must be two numbers, got {value!r}")
            return (number(key, value[0]), number(key, value[1]))

        with _not_while_swept(name):
            self._native.beam(
                name,
                _bodies(bodies, name),
                _vector(from_, "from_", name),
                _vector(to, "to", name),
                _vector(y_axis, "y_axis", name),
                youngs_modulus=number("youngs_modulus", section["youngs_modulus"]),
                shear_modulus=number("shear_modulus", section["shear_modulus"]),
                area=number("area", section["area"]),
                iy=number("iy", section["iy"]),
                iz=number("iz", section["iz"]),
                j=number("j", section["j"]),
                shear_areas=pair("shear_areas"),
                shear_centre=pair("shear_centre"),
            )
        return name

    def spring(
        self,
        name: str,
        *,
        bodies: Tuple[str, str],
        from_: _Vector,
        to: _Vector,
        rate: Optional[float] = None,
        curve: Optional[Sequence[Sequence[float]]] = None,
        design_force: Optional[float] = None,
        free_length: Optional[float] = None,
        preload: Optional[float] = None,
    ) -> str:
        """Adds a coil spring pushing its seats apart, ``from_`` on the first body and ``to`` on the second,
        as a model file's spring entry. Either a ``rate`` (N/m) or a ``curve``, the data sheet's push force
        (N) against compression from the free length (m) from (0, 0); either its push at design,
        ``design_force`` (N), or its ``free_length`` (m), with an optional constant ``preload`` (N) added
        then. Reports give the force on the second body and the deflection (length − free length, 0, 0)."""
        name = _name(name, "spring")
        with _not_while_swept(name):
            self._native.spring(
                name,
                _bodies(bodies, name),
                _vector(from_, "from_", name),
                _vector(to, "to", name),
                rate=_number(rate, "rate", name),
                curve=None if curve is None else _curve(curve, "curve", name),
                design_force=_number(design_force, "design_force", name),
                free_length=_number(free_length, "free_length", name),
                preload=_number(preload, "preload", name),
            )
        return name

    def stop(
        self,
        name: str,
        kind: str,
        *,
        bodies: Tuple[str, str],
        from_: _Vector,
        to: _Vector,
        clearance: float,
        curve: Sequence[Sequence[float]],
    ) -> str:
        """Adds a one-sided stop along the line from ``from_`` on the first body to ``to`` on the second,
        as a model file's stop entry: a "bump" stop acts once the points have come ``clearance`` (m) closer
        than at design, pushing them apart, a "rebound" stop once they have moved ``clearance`` further
        apart; ``curve`` is its force (N) against the travel past contact (m), from (0, 0). Reports give
        the force on the second body and the travel past contact as the deflection's x."""
        name = _name(name, "stop")
        if not isinstance(kind, str):
            raise ValueError(f"'{name}': kind must be 'bump' or 'rebound', got {kind!r}")
        if clearance is None:
            raise ValueError(f"'{name}': clearance must be a number (m), got None")
        clearance_value = _number(clearance, "clearance", name)
        assert clearance_value is not None  # None was refused above
        with _not_while_swept(name):
            self._native.stop(
                name,
                kind,
                _bodies(bodies, name),
                _vector(from_, "from_", name),
                _vector(to, "to", name),
                clearance_value,
                _curve(curve, "curve", name),
            )
        return name

    def force(
        self,
        name: str,
        *,
        body: str,
        at: _Vector,
        force: _Vector,
        constant: Optional[_Vector] = None,
    ) -> str:
        """Adds a force at the point ``at`` of ``body`` (the point moves with the body), fixed in direction
        in global axes: ``constant + t · force`` (N) at load parameter ``t``."""
        name = _name(name, "force")
        if not isinstance(body, str):
            raise ValueError(f"'{name}': body must be a body name, got {body!r}")
        with _not_while_swept(name):
            self._native.force(
                name,
                body,
                _vector(at, "at", name),
                _vector(force, "force", name),
                constant=_optional_vector(constant, "constant", name),
            )
        return name

    def torque(self, name: str, *, body: str, torque: _Vector, constant: Optional[_Vector] = None) -> str:
        """Adds a moment on ``body``, fixed in direction in global axes: ``constant + t · torque`` (N·m) at
        load parameter ``t``."""
        name = _name(name, "torque")
        if not isinstance(body, str):
            raise ValueError(f"'{name}': body must be a body name, got {body!r}")
        with _not_while_swept(name):
            self._native.torque(
                name,
                body,
                _vector(torque, "torque", name),
                constant=_optional_vector(constant, "constant", name),
            )
        return name

    @property
    def bodies(self) -> List[str]:
        """The bodies' names, in the order they were added."""
        return list(self._native.bodies)

    @property
    def joints(self) -> List[str]:
        """The joints' names, in the order they were added."""
        return list(self._native.joints)

    @property
    def elements(self) -> List[str]:
        """The bushings', springs', stops' and loads' names, in the order they were added."""
        return list(self._native.elements)

    def sweep(
        self,
        start: float,
        end: float,
        steps: int,
        *,
        mode: str = "corrected",
        through_limits: bool = False,
        arc_step: Optional[float] = None,
        force_tolerance: float = 1e-9,
        constraint_tolerance: float = 1e-10,
    ) -> "SceneSweep":
        """Walks the load parameter ``t`` from ``start`` to ``end`` in ``steps`` equal steps, from the
        equilibrium at ``start`` found from the design pose, as the K&C analyses walk theirs.

        ``mode`` "corrected": a predictor and Newton iterations to the exact equilibrium at every step;
        "paper": the paper's linear recurrence, no iterations. A path that meets a limit point (a load the
        scene cannot carry, where it snaps through or gives way) stops there, its last row the equilibrium
        at the limit point, and says so: :attr:`SceneSweep.limit` is its load parameter and
        :attr:`SceneSweep.complete` is False. With ``through_limits`` it goes on through the limit point by
        arc length instead (exact equilibria, the load parameter falling and rising again as the path
        turns), the first arc-length step changing the load by ``arc_step`` (default: one load step),
        until it leaves the range. ``force_tolerance`` is relative to the largest force in the scene,
        ``constraint_tolerance`` in m and rad.

        Raises ModelError for a scene the library refuses as built (a body held by nothing),
        AnalysisError when the solver finds no equilibrium or a motion nothing resists (naming the body)."""
        start, end, steps = _path(start, end, steps)
        if mode not in ("corrected", "paper"):
            raise ValueError(f"mode '{mode}': give 'corrected' or 'paper'")
        with _not_while_built():
            native = self._native.sweep(
                start,
                end,
                steps,
                mode=mode,
                through_limits=bool(through_limits),
                arc_step=_number(arc_step, "arc_step", "sweep"),
                force_tolerance=float(force_tolerance),
                constraint_tolerance=float(constraint_tolerance),
            )
        return SceneSweep(native)

    def solve(
        self, t: float, *, force_tolerance: float = 1e-9, constraint_tolerance: float = 1e-10
    ) -> "SceneSweep":
        """The equilibrium at load parameter ``t``, by Newton's method from the design pose, as a sweep of
        one step. A load far from design may need the path to it: use :meth:`sweep` then."""
        if isinstance(t, bool) or not isinstance(t, numbers.Real) or not numpy.isfinite(t):
            raise ValueError(f"t must be a finite load parameter, got {t!r}")
        with _not_while_built():
            native = self._native.solve(
                float(t), force_tolerance=float(force_tolerance), constraint_tolerance=float(constraint_tolerance)
            )
        return SceneSweep(native)

    def __repr__(self) -> str:
        return (
            f"<elastokin.Scene: {len(self.bodies)} bodies, {len(self.joints)} joints, "
            f"{len(self.elements)} elements>"
        )


class SceneSweep:
    """The equilibria of a scene along a load path, one row per step, as numpy arrays.

    Positions in m, rotations as rotation vectors (axis times angle, rad, global), forces in N, moments in
    N·m, all in global axes. Results refer to the scene as it was swept; parts added to the scene later are
    not in it. Unknown names raise KeyError listing the names there are.
    """

    __slots__ = ("_native",)

    def __init__(self, native: "_native.SceneSweep") -> None:
        self._native = native

    @property
    def mode(self) -> str:
        """"corrected" or "paper"."""
        return self._native.mode

    @property
    def t(self) -> numpy.ndarray:
        """The load parameter at each step."""
        return self._native.t

    @property
    def iterations(self) -> numpy.ndarray:
        """Newton iterations at each step (0 in paper mode)."""
        return self._native.iterations

    @property
    def force_residual(self) -> numpy.ndarray:
        """The force residual left at each step (N and N·m)."""
        return self._native.force_residual

    @property
    def constraint_residual(self) -> numpy.ndarray:
        """The constraint residual left at each step (m and rad)."""
        return self._native.constraint_residual

    @property
    def limit(self) -> Optional[float]:
        """The load parameter of the limit point the path met (to 1e-6 of the range), None when it met
        none. Without ``through_limits`` the rows stop there, the last one the equilibrium at it."""
        return self._native.limit

    @property
    def arc_length_from(self) -> Optional[int]:
        """With ``through_limits``, the index of the first row walked by arc length past the limit point
        (the rows before it are the sweep's own steps); None when the path went through none."""
        return self._native.arc_length_from

    @property
    def complete(self) -> bool:
        """Whether the path covered its range: it met no limit point, or went on through it by arc length
        until it left the range."""
        return self._native.complete

    @property
    def bodies(self) -> List[str]:
        """The bodies' names."""
        return list(self._native.bodies)

    @property
    def joints(self) -> List[str]:
        """The joints' names."""
        return list(self._native.joints)

    @property
    def elements(self) -> Dict[str, str]:
        """Each element's name and kind ("bushing", "spring", "stop", "force", "torque")."""
        return dict(self._native.elements)

    def position(self, body: str) -> numpy.ndarray:
        """Where the body's reference point is at each step: (steps, 3), m."""
        return self._native.position(body)

    def rotation(self, body: str) -> numpy.ndarray:
        """The body's rotation from its design attitude at each step as a rotation vector: (steps, 3), rad."""
        return self._native.rotation(body)

    def point(self, body: str, at: _Vector) -> numpy.ndarray:
        """Where the point of ``body`` that is at ``at`` at design is at each step: (steps, 3), m."""
        return self._native.point(body, _vector(at, "at", body))

    def reaction(self, joint: str) -> Tuple[numpy.ndarray, numpy.ndarray]:
        """The joint's reaction on its second body at each step: ``(force, torque)``, each (steps, 3); the
        moment is about the joint's point (``at``; a distance link's second point). On a joint whose second
        body is the ground, the reaction on the ground."""
        return self._native.reaction(joint)

    def element(self, name: str) -> Dict[str, Any]:
        """The element's report at each step: ``force`` it applies to its second body (N) and ``torque``
        about its point there (N·m), ``deflection`` (m) and ``rotation`` (rad) in its frame, each (steps, 3);
        and its ``kind``. A spring's deflection is (length − free length, 0, 0), a stop's (travel past
        contact, 0, 0), negative before contact; a load reports its force or moment."""
        return dict(self._native.element(name))

    def __len__(self) -> int:
        return len(self._native)

    def __repr__(self) -> str:
        t = self.t
        span = f"t {t[0]:g} to {t[-1]:g}" if len(t) else "no steps"
        if self.limit is None:
            end = ""
        elif self.arc_length_from is None:
            end = f", stopped at the limit point t = {self.limit:g}"
        else:
            end = f", through the limit point t = {self.limit:g}"
        return f"<elastokin.SceneSweep {self.mode}: {len(t)} steps, {span}{end}>"
