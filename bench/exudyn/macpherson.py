#!/usr/bin/env python3
"""The shipped MacPherson corner in Exudyn, on elastokin's vertical-force sweep.

Reads a suspension in elastokin's general form (the output of `elastokin expand MODEL`), builds its left
corner as elastokin's `Rig::Free` does (the wheel free on its spring, the tie rod's inner end on the
chassis) out of Exudyn's rigid bodies, joints and connectors, pushes the contact patch up from the first to
the last load of `--load-range` with Exudyn's `SolveStatic`, and writes one CSV row per load step: the load,
the wheel centre, toe and camber (as elastokin's `Wheel::attitude` defines them) and the time `SolveStatic`
took for the whole sweep (the median of `--repeat` runs). See `bench/exudyn/README.md` for how each part maps
and where the two codes' laws differ.

    cargo run -q -- expand examples/generic/macpherson.json | python3 bench/exudyn/macpherson.py - \
        --contact-patch -0.04 1.1 -0.326 --load-range 2071.4316122700156 6214.294836810047 --steps 100

Only what the sweep needs is mapped; anything else in the model (a curve, a stop, another joint kind, a
bushed tie rod) is refused by name rather than left out. Needs Exudyn (`pip install exudyn`).
"""

import argparse
import json
import math
import statistics
import sys
import time

import numpy as np

import exudyn as exu
from exudyn.utilities import ObjectGround, MarkerBodyPosition, LoadForceVector, SensorBody, RigidBodyInertia

# The spin axis of a corner that does not give one (elastokin's `corner.spin_axis` default).
DEFAULT_SPIN_AXIS = (0.0, 1.0, 0.0)

# A rigid body needs a mass and an inertia to be assembled; the static equilibrium does not depend on them
# (no gravity, no motion), so any small positive values do.
MASS = 1.0
INERTIA = 1e-2


class Refused(Exception):
    """A part of the model this mapping does not build."""


def unit(v):
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


def orthonormal_complement(h):
    """The first of two unit vectors across `h`, chosen as elastokin's `orthonormal_complement` does (so
    that a bushing without `y_axis` has the same frame in both codes)."""
    if abs(h[0]) < 0.6:
        helper = np.array([1.0, 0.0, 0.0])
    elif abs(h[1]) < 0.6:
        helper = np.array([0.0, 1.0, 0.0])
    else:
        helper = np.array([0.0, 0.0, 1.0])
    return unit(np.cross(h, helper))


def skew(v):
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


def rotation_log(r):
    """The rotation vector of the rotation matrix `r` (|θ| < π: a rubber bushing never twists further)."""
    cos = max(-1.0, min(1.0, 0.5 * (np.trace(r) - 1.0)))
    angle = math.acos(cos)
    w = 0.5 * np.array([r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1]])
    if angle < 1e-8:
        return w
    return w * angle / math.sin(angle)


def left_jacobian_inverse(theta):
    """J_l(θ)⁻¹ = I − ½θ̃ + (1/a² − (1 + cos a)/(2a sin a)) θ̃²: maps a left rotation increment to the change
    of the rotation vector."""
    a = np.linalg.norm(theta)
    t = skew(theta)
    if a < 1e-6:
        c = 1.0 / 12.0 + a * a / 720.0
    else:
        c = 1.0 / (a * a) - (1.0 + math.cos(a)) / (2.0 * a * math.sin(a))
    return np.eye(3) - 0.5 * t + c * (t @ t)


def tait_bryan_xyz_matrix(rot):
    """R = Rx(φ0) Ry(φ1) Rz(φ2): the relative rotation Exudyn's connector hands its user function."""
    c0, s0 = math.cos(rot[0]), math.sin(rot[0])
    c1, s1 = math.cos(rot[1]), math.sin(rot[1])
    c2, s2 = math.cos(rot[2]), math.sin(rot[2])
    return np.array(
        [
            [c1 * c2, -c1 * s2, s1],
            [s0 * s1 * c2 + c0 * s2, -s0 * s1 * s2 + c0 * c2, -s0 * c1],
            [-c0 * s1 * c2 + s0 * s2, c0 * s1 * s2 + s0 * c2, c0 * c1],
        ]
    )


class Model:
    """The general form's points, bodies and parts, resolved for the left corner."""

    def __init__(self, general):
        self.general = general
        self.hardpoints = {k: np.asarray(v, dtype=float) for k, v in general["hardpoints"].items()}

    def point(self, p):
        if isinstance(p, str):
            if p not in self.hardpoints:
                raise Refused(f"no hardpoint named '{p}'")
            return self.hardpoints[p]
        return np.asarray(p, dtype=float)

    def direction(self, axis):
        if isinstance(axis, list) and len(axis) == 2 and all(isinstance(a, (str, list)) for a in axis):
            return unit(self.point(axis[1]) - self.point(axis[0]))
        return unit(axis)


def check_keys(what, item, allowed):
    extra = sorted(set(item) - set(allowed))
    if extra:
        raise Refused(f"{what}: this mapping does not build {', '.join(extra)}")


class Corner:
    """The corner in an Exudyn system: bodies, joints, bushings, springs, the tie rod and the patch force."""

    def __init__(self, general, contact_patch, load_range, bushing_law):
        self.model = Model(general)
        self.load_from, self.load_to = load_range
        self.bushing_law = bushing_law
        self.sc = exu.SystemContainer()
        self.mbs = self.sc.AddSystem()
        mbs = self.mbs
        self.ground = mbs.AddObject(ObjectGround(referencePosition=[0.0, 0.0, 0.0]))
        self.bodies = {"chassis": (self.ground, np.zeros(3))}
        check_keys(
            "the model",
            general,
            ["hardpoints", "bodies", "joints", "bushings", "springs", "corner"],
        )
        for b in general["bodies"]:
            check_keys(f"body '{b['name']}'", b, ["name", "at"])
            at = self.model.point(b["at"])
            body = mbs.CreateRigidBody(
                name=b["name"],
                referencePosition=list(at),
                referenceRotationMatrix=np.eye(3),
                inertia=RigidBodyInertia(mass=MASS, inertiaTensor=INERTIA * np.eye(3)),
                gravity=[0.0, 0.0, 0.0],
                nodeType=exu.NodeType.RotationEulerParameters,
            )
            self.bodies[b["name"]] = (body, at)
        for j in general.get("joints", []):
            self.add_joint(j)
        for b in general.get("bushings", []):
            self.add_bushing(b)
        for s in general.get("springs", []):
            self.add_spring(s)
        self.add_tie_rod(general["corner"])
        self.add_patch_force(general["corner"], np.asarray(contact_patch, dtype=float))

    def body(self, name):
        if name not in self.bodies:
            raise Refused(f"no body named '{name}'")
        return self.bodies[name]

    def local(self, name, point):
        """The body's number and `point` (global, at design) relative to its reference point; bodies are
        not turned at design (elastokin: "axes global at design")."""
        body, at = self.body(name)
        return body, list(np.asarray(point, dtype=float) - at)

    def between(self, first, at, second, to):
        """A connector's bodies and positions: `at` on the first body, `to` on the second (global, at
        design), as the `itemNumbers`, `localPosition0` and `localPosition1` of Exudyn's `Create…`."""
        b0, p0 = self.local(first, at)
        b1, p1 = self.local(second, to)
        return {"itemNumbers": [b0, b1], "localPosition0": p0, "localPosition1": p1}

    def add_joint(self, j):
        kind = j["kind"]
        first, second = j["bodies"]
        if kind == "spherical":
            check_keys(f"joint '{j['name']}'", j, ["name", "kind", "bodies", "at"])
            self.mbs.CreateSphericalJoint(
                name=j["name"],
                itemNumbers=[self.body(first)[0], self.body(second)[0]],
                position=list(self.model.point(j["at"])),
                constrainedAxes=[1, 1, 1],
            )
        elif kind == "translational":
            # All but the slide along the axis: Exudyn's generic joint with its x axis along `axis`, the
            # two translations across it and the three rotations locked.
            check_keys(f"joint '{j['name']}'", j, ["name", "kind", "bodies", "at", "axis"])
            x = self.model.direction(j["axis"])
            y = orthonormal_complement(x)
            axes = np.column_stack([x, y, np.cross(x, y)])
            self.mbs.CreateGenericJoint(
                name=j["name"],
                itemNumbers=[self.body(first)[0], self.body(second)[0]],
                position=list(self.model.point(j["at"])),
                rotationMatrixAxes=axes,
                constrainedAxes=[0, 1, 1, 1, 1, 1],
                useGlobalFrame=True,
            )
        elif kind == "distance":
            check_keys(f"joint '{j['name']}'", j, ["name", "kind", "bodies", "at", "to"])
            self.distance(j["name"], first, self.model.point(j["at"]), second, self.model.point(j["to"]))
        else:
            raise Refused(f"joint '{j['name']}': kind '{kind}' is not mapped")

    def distance(self, name, first, at, second, to):
        self.mbs.CreateDistanceConstraint(
            name=name,
            **self.between(first, at, second, to),
            distance=float(np.linalg.norm(np.asarray(to) - np.asarray(at))),
        )

    def add_bushing(self, b):
        name = b["name"]
        check_keys(
            f"bushing '{name}'",
            b,
            ["name", "bodies", "at", "axis", "y_axis", "radial", "axial", "torsion", "conical",
             "translation", "rotation", "law"],
        )
        if b.get("law", "energy") != "energy":
            raise Refused(f"bushing '{name}': law '{b['law']}' is not mapped (only the default, energy)")
        if "translation" in b:
            kt, kr = [float(k) for k in b["translation"]], [float(k) for k in b["rotation"]]
        else:
            rates = [b[k] for k in ("radial", "axial", "torsion", "conical")]
            if not all(isinstance(r, (int, float)) for r in rates):
                raise Refused(f"bushing '{name}': only linear rates are mapped, not curves")
            radial, axial, torsion, conical = (float(r) for r in rates)
            kt, kr = [axial, radial, radial], [torsion, conical, conical]
        # The bushing frame, as elastokin's `bushing_frame`: x along the axis, y towards `y_axis` (or
        # elastokin's default across x), z completing it.
        x = self.model.direction(b["axis"]) if "axis" in b else np.array([1.0, 0.0, 0.0])
        if "y_axis" in b:
            h = self.model.direction(b["y_axis"])
            y = unit(h - x * x.dot(h))
        else:
            y = orthonormal_complement(x)
        frame = np.column_stack([x, y, np.cross(x, y)])
        first, second = b["bodies"]
        # elastokin's frame rides on the first body and the force acts at the second body's point; Exudyn's
        # connector measures in marker 0's frame and applies its force at each marker's own point. The two
        # agree when the first body is the chassis (every bushing of the shipped MacPherson): refuse the
        # others rather than build a slightly different law.
        if first != "chassis":
            raise Refused(f"bushing '{name}': only bushings whose first body is the chassis are mapped")
        at = self.model.point(b["at"])
        stiffness = np.diag(kt + kr)
        kwargs = {}
        if self.bushing_law == "energy":
            kwargs["springForceTorqueUserFunction"] = energy_law(np.array(kt), np.array(kr))
        # Not intrinsic (the default law): the force in marker 0's frame (the chassis's, as elastokin's)
        # at each marker's point, the moment from the Tait-Bryan angles of the relative rotation. Intrinsic:
        # both from the SE(3) logarithm, in the frame halfway between the markers, through the point halfway.
        self.mbs.CreateRigidBodySpringDamper(
            name=name,
            **self.between(first, at, second, at),
            stiffness=stiffness,
            damping=np.zeros((6, 6)),
            rotationMatrixJoint=frame,
            useGlobalFrame=True,
            useIntrinsicFormulation=self.bushing_law == "intrinsic",
            **kwargs,
        )

    def add_spring(self, s):
        name = s["name"]
        check_keys(f"spring '{name}'", s, ["name", "bodies", "from", "to", "rate", "design_force", "free_length"])
        if "rate" not in s:
            raise Refused(f"spring '{name}': only a rate is mapped, not a curve")
        start, end = self.model.point(s["from"]), self.model.point(s["to"])
        design_length = float(np.linalg.norm(end - start))
        rate = float(s["rate"])
        # elastokin's push F = design_force + rate·(design length − length), compression positive, is a
        # linear spring whose free length is the design length plus design_force / rate; Exudyn's spring
        # force rate·(length − reference length) with that reference length is the same force.
        if "design_force" in s:
            free_length = design_length + float(s["design_force"]) / rate
        else:
            free_length = float(s["free_length"])
        first, second = s["bodies"]
        self.mbs.CreateSpringDamper(
            name=name,
            **self.between(first, start, second, end),
            referenceLength=free_length,
            stiffness=rate,
            damping=0.0,
        )

    def add_tie_rod(self, corner):
        tie_rod = corner.get("tie_rod")
        if tie_rod is None:
            return
        if tie_rod.get("connection", "ideal") != "ideal":
            raise Refused("tie rod: only the ideal connection (a distance link) is mapped")
        # Rig::Free: the inner end on the chassis, the outer on the upright.
        inner, outer = self.model.point(tie_rod["inner"]), self.model.point(tie_rod["outer"])
        self.distance("tie rod", "chassis", inner, corner["upright"], outer)

    def add_patch_force(self, corner, patch):
        upright = corner["upright"]
        self.upright, _ = self.body(upright)
        wheel_centre = self.model.point(corner["wheel_centre"])
        _, self.wheel_centre_local = self.local(upright, wheel_centre)
        self.spin_axis = unit(corner.get("spin_axis", DEFAULT_SPIN_AXIS))
        _, patch_local = self.local(upright, patch)
        marker = self.mbs.AddMarker(MarkerBodyPosition(bodyNumber=self.upright, localPosition=patch_local))
        # The force keeps its global direction (+z) as the upright turns, as elastokin's PointForce. Its size
        # follows the load time t ∈ [0, 1] of a static solve between the two loads of `self.ramp`.
        self.ramp = [self.load_from, self.load_to]
        ramp = self.ramp

        def vertical_force(mbs, t, load_vector):
            return [0.0, 0.0, ramp[0] + (ramp[1] - ramp[0]) * t]

        self.mbs.AddLoad(LoadForceVector(markerNumber=marker, loadVector=[0.0, 0.0, 1.0], bodyFixed=False,
                                         loadVectorUserFunction=vertical_force))
        self.position_sensor = self.mbs.AddSensor(
            SensorBody(bodyNumber=self.upright, localPosition=self.wheel_centre_local, storeInternal=True,
                       writeToFile=False, outputVariableType=exu.OutputVariableType.Position))
        self.rotation_sensor = self.mbs.AddSensor(
            SensorBody(bodyNumber=self.upright, storeInternal=True, writeToFile=False,
                       outputVariableType=exu.OutputVariableType.RotationMatrix))
        self.mbs.Assemble()


def energy_law(kt, kr):
    """elastokin's bushing law as the connector's user function: the force K_T δ in the chassis frame (as
    the built-in connector), and the moment J_l(θ)⁻ᵀ K_R θ of the rotation vector θ = log R, the
    derivative of ½θᵀK_Rθ, instead of the built-in K_R φ of the Tait-Bryan angles φ."""

    def force_torque(mbs, t, item, displacement, rotation, velocity, angular_velocity, stiffness, damping,
                     rot_j0, rot_j1, offset):
        theta = rotation_log(tait_bryan_xyz_matrix(rotation))
        moment = left_jacobian_inverse(theta).T @ (kr * theta)
        force = kt * np.asarray(displacement)
        return [force[0], force[1], force[2], moment[0], moment[1], moment[2]]

    return force_torque


def settings(steps, tolerance, newton="full"):
    s = exu.SimulationSettings()
    s.solution.file.write = False
    s.solution.sensors.writePeriod = 0.5 / steps  # every load step is stored
    s.staticSolver.verboseMode = 0
    s.staticSolver.stepInformation = 0
    s.staticSolver.numberOfLoadSteps = steps
    s.staticSolver.loadStepStart = 0.0
    s.staticSolver.loadStepDuration = 1.0
    # The load follows the user function of the load time; no factor on top of it.
    s.staticSolver.useLoadFactor = False
    s.staticSolver.adaptiveStep = True
    s.staticSolver.newton.relativeTolerance = tolerance[0]
    s.staticSolver.newton.absoluteTolerance = tolerance[1]
    s.staticSolver.newton.maxIterations = 30
    # Full Newton (Exudyn's default for statics) factorizes in every iteration; modified Newton keeps the
    # factorization while the residual contracts fast enough.
    s.staticSolver.newton.useModifiedNewton = newton == "modified"
    s.show.computationTime = False
    s.show.statistics = False
    return s


def attitude(rotation, spin_axis_local, wheel_centre):
    """elastokin's `Wheel::attitude` on the left: a = A s' (outward spin axis), toe = atan2(aₓ, a_y),
    camber = atan2(−a_z, √(aₓ² + a_y²))."""
    a = rotation @ spin_axis_local
    return wheel_centre, math.atan2(a[0], a[1]), math.atan2(-a[2], math.hypot(a[0], a[1]))


def sweep(corner, steps, repeat, tolerance, newton):
    """The equilibrium at the first load (not timed), then `repeat` timed `SolveStatic` runs of `steps`
    equal load steps to the last load from it; returns the rows of the last run, every run's time and the
    last run's Newton iterations and Jacobians."""
    mbs = corner.mbs
    ramp = corner.ramp
    # From the design pose to the first load in a few steps, starting at the middle of the range (the design
    # wheel load of elastokin's sweep, under which the design pose is nearly in equilibrium).
    ramp[0], ramp[1] = 0.5 * (corner.load_from + corner.load_to), corner.load_from
    if not mbs.SolveStatic(settings(20, tolerance)):
        raise RuntimeError("SolveStatic found no equilibrium at the first load")
    mbs.systemData.SetODE2Coordinates(mbs.systemData.GetODE2Coordinates(), configuration=exu.ConfigurationType.Initial)
    mbs.systemData.SetAECoordinates(mbs.systemData.GetAECoordinates(), configuration=exu.ConfigurationType.Initial)
    ramp[0], ramp[1] = corner.load_from, corner.load_to
    s = settings(steps, tolerance, newton)
    times = []
    for _ in range(repeat):
        # Each run starts again from the initial coordinates, the equilibrium at the first load.
        t0 = time.perf_counter()
        ok = mbs.SolveStatic(s)
        times.append(time.perf_counter() - t0)
        if not ok:
            raise RuntimeError("SolveStatic did not converge")
    iterations = mbs.sys["staticSolver"].it
    positions = mbs.GetSensorStoredData(corner.position_sensor)
    rotations = mbs.GetSensorStoredData(corner.rotation_sensor)
    if len(positions) != steps + 1:
        # A step Exudyn had to cut would add rows between the equal steps the comparison expects.
        raise RuntimeError(f"expected {steps + 1} stored load steps, got {len(positions)}")
    rows = []
    for p, r in zip(positions, rotations):
        load = corner.load_from + (corner.load_to - corner.load_from) * p[0]
        # The upright is not turned at design: its local spin axis is the global one.
        centre, toe, camber = attitude(np.asarray(r[1:10]).reshape(3, 3), corner.spin_axis, p[1:4])
        rows.append((load, centre[0], centre[1], centre[2], toe, camber))
    return rows, times, (iterations.newtonStepsCount, iterations.newtonJacobiCount)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("model", help="the model in the general form (`elastokin expand MODEL`), or - for stdin")
    parser.add_argument("--contact-patch", nargs=3, type=float, required=True, metavar=("X", "Y", "Z"),
                        help="the contact patch at design (m), where the vertical force acts on the upright")
    parser.add_argument("--load-range", nargs=2, type=float, required=True, metavar=("FROM", "TO"),
                        help="the vertical force (N) at the equilibrium the sweep starts from and at its end")
    parser.add_argument("--steps", type=int, default=100, help="equal load steps of the timed sweep")
    parser.add_argument("--repeat", type=int, default=5, help="timed runs; the median is reported")
    parser.add_argument("--relative-tolerance", type=float, default=1e-9,
                        help="Newton's relative residual tolerance (elastokin's force tolerance)")
    parser.add_argument("--absolute-tolerance", type=float, default=1e-10,
                        help="Newton's absolute residual tolerance (elastokin's constraint tolerance)")
    parser.add_argument("--bushing-law", choices=["tait-bryan", "intrinsic", "energy"], default="tait-bryan",
                        help="tait-bryan: Exudyn's connector, not intrinsic (C++); intrinsic: its intrinsic "
                             "formulation (C++); energy: elastokin's law as a Python user function of the "
                             "connector (slow; for validation, not for timing)")
    parser.add_argument("--newton", choices=["full", "modified"], default="full",
                        help="full: a Jacobian in every iteration (Exudyn's default for SolveStatic); modified: "
                             "the Jacobian kept while the residual contracts")
    parser.add_argument("--csv", help="write the curve here (default: stdout)")
    args = parser.parse_args(argv)
    if args.steps < 1 or args.repeat < 1:
        parser.error("--steps and --repeat must be at least 1")
    text = sys.stdin.read() if args.model == "-" else open(args.model, encoding="utf-8").read()
    document = json.loads(text)
    suspension = document.get("suspension", document)
    if "general" not in suspension:
        parser.error("the model must be in the general form: run `elastokin expand MODEL` first")
    try:
        corner = Corner(suspension["general"], args.contact_patch, args.load_range, args.bushing_law)
    except Refused as e:
        print(f"refused: {e}", file=sys.stderr)
        return 2
    tolerance = (args.relative_tolerance, args.absolute_tolerance)
    rows, times, (iterations, jacobians) = sweep(corner, args.steps, args.repeat, tolerance, args.newton)
    median = statistics.median(times)
    out = open(args.csv, "w", encoding="utf-8", newline="") if args.csv else sys.stdout
    command = " ".join(["python3", "bench/exudyn/macpherson.py"] + argv)
    out.write(f"# Exudyn {exu.__version__}, Python {sys.version.split()[0]}, {time.strftime('%Y-%m-%d')}\n")
    out.write(f"# command: {command}\n")
    out.write(f"# model: {document.get('name', 'unnamed')!r} in the general form (`elastokin expand MODEL`)\n")
    out.write(f"# SolveStatic of {args.steps} load steps, {args.newton} Newton: {iterations} iterations, "
              f"{jacobians} Jacobians; {args.repeat} runs (s): " + " ".join(f"{t:.6g}" for t in times) + "\n")
    out.write("load_n,wheel_centre_x_m,wheel_centre_y_m,wheel_centre_z_m,toe_rad,camber_rad,solve_static_s\n")
    for row in rows:
        out.write(",".join(repr(float(v)) for v in row) + f",{median!r}\n")
    if out is not sys.stdout:
        out.close()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
