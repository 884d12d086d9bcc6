"""Scenes built in Python, body by body, against numbers from elsewhere: the Rust example that builds the
same scene (run with `cargo run`, its printed table parsed), closed forms of mechanics (those of the
repository's tests/closed_form.rs and tests/common.rs), and equilibrium itself (the forces and moments on
a body sum to zero). Each tolerance carries, in a comment, the error the test measured.
"""

import doctest
import math
import subprocess
import threading
from pathlib import Path

import numpy
import pytest

import elastokin

ROOT = Path(__file__).resolve().parents[2]

# Tolerances of the closed-form comparisons: the default relative force residual of 1e-9 would leave
# ~1e-9 rad in an angle; these leave round-off only (as tests/common.rs's `tight`).
TIGHT = dict(force_tolerance=1e-11, constraint_tolerance=1e-12)


# --- The swing arm of examples/swing_arm.rs --------------------------------------------------------------

PIVOT = [0.0, 0.55, 0.0]
WHEEL_CENTRE = [-0.45, 0.80, -0.02]
SEAT_ARM = [-0.30, 0.62, 0.0]
SEAT_CHASSIS = [-0.30, 0.62, 0.30]


def swing_arm():
    """The scene of examples/swing_arm.rs, part for part and in its order (the order fixes the sums)."""
    scene = elastokin.Scene()
    scene.body("swing arm", at=[(p + w) / 2.0 for p, w in zip(PIVOT, WHEEL_CENTRE)])
    # Local x along the pivot axis (lateral), y = z × x = −x global, z up: the example's frame.
    scene.bushing(
        "pivot bushing",
        bodies=("chassis", "swing arm"),
        at=PIVOT,
        axis=[0, 1, 0],
        y_axis=[-1, 0, 0],
        radial=5e6,
        axial=1e6,
        torsion=math.degrees(10.0),
        conical=math.degrees(100.0),
    )
    scene.spring(
        "spring", bodies=("chassis", "swing arm"), from_=SEAT_CHASSIS, to=SEAT_ARM, rate=60e3, design_force=3000.0
    )
    scene.force("wheel force", body="swing arm", at=WHEEL_CENTRE, force=[0, 0, 1500.0], constant=[0, 0, 2000.0])
    return scene


@pytest.fixture(scope="module")
def example_table():
    """The rows the Rust example prints: (Fz, dz, paper dz, iterations, spring, bushing, pitch) as text."""
    done = subprocess.run(
        ["cargo", "run", "-q", "--example", "swing_arm"], cwd=ROOT, capture_output=True, text=True, check=True
    )
    rows = []
    for line in done.stdout.splitlines():
        cells = line.split()
        if len(cells) == 7 and cells[0].lstrip("-").isdigit():
            rows.append(cells)
    assert len(rows) == 21, done.stdout
    return rows


def test_swing_arm_gives_the_rust_example_s_table(example_table):
    scene = swing_arm()
    corrected = scene.sweep(-1.0, 1.0, 20, mode="corrected")
    paper = scene.sweep(-1.0, 1.0, 20, mode="paper")
    assert corrected.complete and paper.complete and len(corrected) == len(paper) == 21
    z = corrected.point("swing arm", WHEEL_CENTRE)[:, 2] - WHEEL_CENTRE[2]
    zp = paper.point("swing arm", WHEEL_CENTRE)[:, 2] - WHEEL_CENTRE[2]
    spring = corrected.element("spring")["force"]
    bushing = corrected.element("pivot bushing")["force"]
    pitch = numpy.degrees(corrected.rotation("swing arm")[:, 1])
    for k, row in enumerate(example_table):
        norm = lambda v: math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])  # noqa: E731 (nalgebra's order)
        ours = [
            f"{2000.0 + 1500.0 * corrected.t[k]:.0f}",
            f"{z[k] * 1e3:.4f}",
            f"{zp[k] * 1e3:.4f}",
            f"{corrected.iterations[k]}",
            f"{norm(spring[k]):.1f}",
            f"{norm(bushing[k]):.1f}",
            f"{pitch[k]:.4f}",
        ]
        # Every printed digit: the same library calls on the same scene give the same numbers.
        assert ours == row, (k, ours, row)
    # The paper's recurrence drifts from the exact path and the corrected walk does not: the table's two
    # columns differ, so the comparison above tells the modes apart.
    assert abs(z[-1] - zp[-1]) > 1e-5


def test_forces_and_moments_on_the_swing_arm_balance():
    """Conservation: on the arm, the bushing's and the spring's forces and the wheel force sum to zero, and
    so do their moments about the origin, at every corrected step."""
    sweep = swing_arm().sweep(-1.0, 1.0, 20)
    t = sweep.t[:, None]
    applied = numpy.array([0, 0, 2000.0]) + t * numpy.array([0, 0, 1500.0])
    bushing, spring = sweep.element("pivot bushing"), sweep.element("spring")
    at_bushing = sweep.point("swing arm", PIVOT)
    at_seat = sweep.point("swing arm", SEAT_ARM)
    at_wheel = sweep.point("swing arm", WHEEL_CENTRE)
    force = bushing["force"] + spring["force"] + applied
    moment = (
        bushing["torque"]
        + numpy.cross(at_bushing, bushing["force"])
        + spring["torque"]
        + numpy.cross(at_seat, spring["force"])
        + numpy.cross(at_wheel, applied)
    )
    assert numpy.abs(force).max() < 1e-6  # measured 1.4e-7 N of 5e3 N (the solver's tolerance: 5e-6 N)
    assert numpy.abs(moment).max() < 1e-6  # measured 7.7e-8 N·m
    # Step by step, the imbalance is within the force residual the solver reports.
    assert (numpy.abs(force).max(axis=1) <= sweep.force_residual * (1 + 1e-9)).all()


# --- Closed forms ---------------------------------------------------------------------------------------


def test_slider_on_a_spring_moves_by_force_over_rate_and_its_guide_takes_the_rest():
    """A slider on a translational guide along x, a spring along the guide: x = Fx / k exactly; the guide
    carries the force across it and the moment of the offset force about its point."""
    k, origin = 2.5e4, numpy.array([0.1, 0.2, 0.3])
    offset = numpy.array([0.05, -0.04, 0.12])  # where the force acts, from the slider's point
    f = numpy.array([400.0, -150.0, 900.0])
    scene = elastokin.Scene()
    scene.body("slider", at=origin)
    scene.joint("guide", "translational", bodies=("chassis", "slider"), at=origin, axis=[1, 0, 0])
    scene.spring(
        "spring", bodies=("chassis", "slider"), from_=origin + [0.4, 0, 0], to=origin, rate=k, free_length=0.4
    )
    scene.force("push", body="slider", at=origin + offset, force=f)
    sweep = scene.sweep(0.0, 1.0, 5, **TIGHT)
    t = sweep.t[:, None]
    expected = origin + t * numpy.array([f[0] / k, 0, 0])
    assert numpy.abs(sweep.position("slider") - expected).max() < 1e-15  # measured 5.6e-17 m
    assert numpy.abs(sweep.rotation("slider")).max() < 1e-15  # measured 0 rad
    force, torque = sweep.reaction("guide")
    assert numpy.abs(force - t * -f * [0, 1, 1]).max() < 1e-12  # measured 1.4e-14 N
    assert numpy.abs(torque + t * numpy.cross(offset, f)).max() < 1e-12  # measured 1.6e-14 N·m
    spring = sweep.element("spring")
    assert numpy.abs(spring["deflection"][:, 0] + t[:, 0] * f[0] / k).max() < 1e-15  # measured 5.2e-17 m
    # One equilibrium alone, from the design pose, is the sweep's last.
    one = scene.solve(1.0, **TIGHT)
    assert len(one) == 1 and one.t[0] == 1.0
    assert numpy.abs(one.position("slider")[0] - expected[-1]).max() < 1e-15  # measured 0 m


def test_bump_stop_takes_over_past_its_clearance():
    """A slider like the one above, with a bump stop beside its spring: free over the clearance c, then
    the stop's rate adds to the spring's, x = c + (F − k c) / (k + k_stop)."""
    k, k_stop, c, f = 2e4, 1e5, 0.02, 1000.0
    origin = numpy.array([0.0, 0.4, 0.2])
    seat = origin + [0.3, 0, 0]
    scene = elastokin.Scene()
    scene.body("slider", at=origin)
    scene.joint("guide", "translational", bodies=("chassis", "slider"), at=origin, axis=[1, 0, 0])
    scene.spring("spring", bodies=("chassis", "slider"), from_=seat, to=origin, rate=k, free_length=0.3)
    # A straight curve: the force past contact is k_stop times the travel past contact.
    scene.stop("bump stop", "bump", bodies=("chassis", "slider"), from_=seat, to=origin, clearance=c,
               curve=[[0, 0], [0.01, k_stop * 0.01]])
    scene.force("push", body="slider", at=origin, force=[f, 0, 0])
    sweep = scene.sweep(0.0, 1.0, 10, **TIGHT)
    load = sweep.t * f
    x = numpy.where(load <= k * c, load / k, c + (load - k * c) / (k + k_stop))
    assert x[-1] - c > 0.004  # the stop is well in contact at the end
    assert numpy.abs(sweep.position("slider")[:, 0] - origin[0] - x).max() < 1e-15  # measured 3.5e-17 m
    stop = sweep.element("bump stop")
    assert stop["kind"] == "stop"
    # Its deflection is the travel past contact: minus the gap left before it.
    assert numpy.abs(stop["deflection"][:, 0] - (x - c)).max() < 1e-15  # measured 5.6e-17 m
    contact = k_stop * numpy.maximum(x - c, 0)
    assert numpy.abs(stop["force"][:, 0] + contact).max() < 1e-10  # measured 3.8e-12 N of 500 N


# The lever of tests/common.rs: pivot at the origin about +y, tip at (A, 0, 0), spring seat on the lever
# at (B, 0, 0), chassis seat at (0, 0, H), free at design, a downward tip force F at t = 1.
A, B, H, K_SPRING, F_TIP = 0.5, 0.3, 0.2, 20_000.0, 500.0


def lever_angle(f):
    """tests/common.rs: the moment balance a f cos φ = k (L − L₀) b h cos φ / L gives L = L₀ / (1 − a f /
    (k b h)) and sin φ = (L² − b² − h²) / (2 b h)."""
    l0 = math.hypot(B, H)
    length = l0 / (1.0 - A * f / (K_SPRING * B * H))
    return math.asin((length * length - B * B - H * H) / (2.0 * B * H))


def pivot_reaction(phi, f):
    """The pivot's reaction on the lever: minus the tip force and the spring's force on the lever."""
    p = B * numpy.array([math.cos(phi), 0.0, -math.sin(phi)])
    g = numpy.array([0.0, 0.0, H])
    length = numpy.linalg.norm(p - g)
    push = K_SPRING * (math.hypot(B, H) - length)
    return -(numpy.array([0.0, 0.0, -f]) + push * (p - g) / length)


def revolute(scene):
    scene.joint("pivot", "revolute", bodies=("chassis", "lever"), at=[0, 0, 0], axis=[0, 1, 0])


def ball_and_parallel_axes(scene):
    scene.joint("pivot ball", "spherical", bodies=("chassis", "lever"), at=[0, 0, 0])
    scene.joint("pivot axis", "parallel_axes", bodies=("chassis", "lever"), axis=[0, 1, 0])


def cylinder_and_plane(scene):
    scene.joint("pivot shaft", "cylindrical", bodies=("lever", "chassis"), at=[0, 0, 0], axis=[0, 1, 0])
    scene.joint("pivot collar", "in_plane", bodies=("lever", "chassis"), at=[0, 0, 0], axis=[0, 1, 0])


def line_plane_and_perpendiculars(scene):
    scene.joint("pivot line", "in_line", bodies=("lever", "chassis"), at=[0, 0, 0], axis=[0, 1, 0])
    scene.joint("pivot plane", "in_plane", bodies=("lever", "chassis"), at=[0, 0, 0], axis=[0, 1, 0])
    scene.joint("keeps x", "perpendicular", bodies=("chassis", "lever"), axis=[0, 1, 0], axis_j=[1, 0, 0])
    scene.joint("keeps z", "perpendicular", bodies=("chassis", "lever"), axis=[0, 1, 0], axis_j=[0, 0, 1])


@pytest.mark.parametrize(
    "pivot", [revolute, ball_and_parallel_axes, cylinder_and_plane, line_plane_and_perpendiculars]
)
def test_lever_reaches_the_closed_form_angle_and_pivot_reaction(pivot):
    """Each pivot is a hinge about y built from other joint kinds; the tip load hangs on a second body welded
    to the lever by a fixed joint."""
    scene = elastokin.Scene()
    scene.body("lever", at=[0.25, 0, 0])
    scene.body("tip", at=[A, 0, 0])
    pivot(scene)
    scene.joint("weld", "fixed", bodies=("lever", "tip"), at=[A, 0, 0])
    scene.spring("spring", bodies=("chassis", "lever"), from_=[0, 0, H], to=[B, 0, 0], rate=K_SPRING,
                 free_length=math.hypot(B, H))
    scene.force("tip load", body="tip", at=[A, 0, 0], force=[0, 0, -F_TIP])
    sweep = scene.sweep(0.0, 1.0, 10, **TIGHT)
    assert sweep.complete
    phi = numpy.array([lever_angle(F_TIP * t) for t in sweep.t])
    assert phi[-1] > math.radians(35)  # a large angle: the closed form's nonlinearity matters
    rotation = sweep.rotation("lever")
    assert numpy.abs(rotation[:, 1] - phi).max() < 1e-10  # measured 4.8e-12 rad (4.4e-16 for the revolute)
    assert numpy.abs(rotation[:, [0, 2]]).max() < 1e-15  # measured 0 rad
    assert numpy.abs(sweep.rotation("tip") - rotation).max() < 1e-15  # measured 5.6e-17 rad: welded
    # The pivot's joints together carry the closed-form reaction (each joint's point is the origin). A
    # joint written (lever, chassis) reports what acts on the chassis: minus what acts on the lever.
    total = numpy.zeros((len(sweep), 3))
    for joint in sweep.joints:
        if joint == "weld":
            continue
        force, _ = sweep.reaction(joint)
        total += -force if joint in ("pivot shaft", "pivot collar", "pivot line", "pivot plane") else force
    expected = numpy.array([pivot_reaction(p, F_TIP * t) for p, t in zip(phi, sweep.t)])
    assert numpy.abs(total - expected).max() < 1e-7  # measured 1.0e-8 N of ~1e3 N (1.1e-12 for the revolute)
    # The weld carries the whole tip load.
    weld, _ = sweep.reaction("weld")
    assert numpy.abs(weld - sweep.t[:, None] * [0, 0, F_TIP]).max() < 1e-15  # measured 0 N


def test_bushing_deflects_and_twists_in_the_frame_its_axes_give():
    """tests/closed_form.rs: a force at the centre of a bushing deflects it by E K⁻¹ Eᵀ F, and a torque
    about a principal axis twists it by M / K however large. The frame E is the model file's: x along
    `axis`, y towards `y_axis` made perpendicular, z = x × y."""
    axis, hint = numpy.array([0.3, 0.8, -0.2]), numpy.array([0.1, 0.2, 1.0])
    x = axis / numpy.linalg.norm(axis)
    y = hint - x * (x @ hint)
    y /= numpy.linalg.norm(y)
    frame = numpy.column_stack([x, y, numpy.cross(x, y)])
    kt, kr = numpy.array([2e6, 5e5, 8e6]), numpy.array([500.0, 800.0, 1500.0])
    centre = numpy.array([0.1, 0.7, -0.2])
    f = numpy.array([300.0, -1200.0, 4000.0])
    scene = elastokin.Scene()
    scene.body("knuckle", at=centre)
    scene.bushing("mount", bodies=("chassis", "knuckle"), at=centre, axis=axis, y_axis=hint,
                  translation=list(kt), rotation=list(kr))
    scene.force("force", body="knuckle", at=centre, force=f)
    scene.torque("twist", body="knuckle", torque=0.9 * kr[0] * x)
    sweep = scene.sweep(0.0, 1.0, 6, **TIGHT)
    t = sweep.t[:, None]
    deflection = frame @ ((frame.T @ f) / kt)
    assert numpy.abs(sweep.position("knuckle") - centre - t * deflection).max() < 1e-15  # measured 5.0e-17 m
    # 0.9 rad about the frame's x axis at t = 1.
    assert numpy.abs(sweep.rotation("knuckle") - t * 0.9 * x).max() < 1e-14  # measured 3.9e-16 rad
    mount = sweep.element("mount")
    assert numpy.abs(mount["force"] + t * f).max() < 1e-8  # measured 1.4e-10 N of 4.2e3 N
    assert numpy.abs(mount["deflection"] - t * (frame.T @ deflection)).max() < 1e-15  # measured 4.4e-17 m


def test_bushing_preload_pushes_the_body_to_where_the_rates_balance_it():
    """A bushing's preload acts on its second body at zero deflection: with nothing else on the body, it
    comes to rest where the rates balance the preload, δ = P / K along each axis and θ = M / K about x
    (a principal axis, so any rotation law gives it)."""
    kt, kr = numpy.array([1e5, 2e5, 4e5]), numpy.array([100.0, 300.0, 300.0])
    preload_force, preload_torque = numpy.array([100.0, -50.0, 200.0]), numpy.array([2.0, 0.0, 0.0])
    centre = numpy.array([0.3, -0.2, 0.5])
    for law in ("energy", "linear", "tait_bryan_xyz"):
        scene = elastokin.Scene()
        scene.body("hub", at=centre)
        # The frame is the global axes: x by default, y given (without it, y is any direction across x).
        scene.bushing("mount", bodies=("chassis", "hub"), at=centre, y_axis=[0, 1, 0], translation=kt,
                      rotation=kr, law=law, preload_force=preload_force, preload_torque=preload_torque)
        rest = scene.solve(0.0, **TIGHT)
        assert numpy.abs(rest.position("hub")[0] - centre - preload_force / kt).max() < 1e-15  # measured 5.5e-17 m
        assert numpy.abs(rest.rotation("hub")[0] - preload_torque / kr).max() < 1e-15  # measured 0 rad
        # At rest the bushing applies no force: the preload and the rates cancel.
        assert numpy.abs(rest.element("mount")["force"]).max() < 1e-9  # measured 2.2e-11 N of 200 N


def test_torsion_bushing_on_a_hinge_twists_by_torque_over_rate():
    """A lever on a revolute about y and a bushing whose axis is the hinge's: under a torque about y the
    twist is M / K_torsion exactly, here 1.2 rad; the hinge carries no moment about its axis."""
    torsion, torque = 250.0, 300.0
    scene = elastokin.Scene()
    scene.body("lever", at=[0.2, 0.1, 0.0])
    scene.joint("hinge", "revolute", bodies=("chassis", "lever"), at=[0, 0.1, 0], axis=[0, 1, 0])
    scene.bushing("torsion bar", bodies=("chassis", "lever"), at=[0, 0.1, 0], axis=[0, 1, 0], radial=1e7,
                  axial=1e7, torsion=torsion, conical=1e4)
    scene.torque("drive", body="lever", torque=[0, torque, 0])
    sweep = scene.sweep(0.0, 1.0, 12, **TIGHT)
    assert numpy.abs(sweep.rotation("lever")[:, 1] - sweep.t * torque / torsion).max() < 1e-12  # measured 1.4e-14 rad
    _, moment = sweep.reaction("hinge")
    assert numpy.abs(moment[:, 1]).max() < 1e-15  # measured 0 N·m


def test_distance_link_carries_the_load_along_itself():
    """A lever hinged at the origin about y and braced by a distance link from the chassis: no motion is
    left, so statics at design gives the link's force — along the link (a two-force member), its size from
    the moments about the hinge axis — and the hinge takes the rest of the load."""
    tip, brace, anchor = numpy.array([0.5, 0, 0]), numpy.array([0.4, 0, 0]), numpy.array([0.1, 0, 0.3])
    f = numpy.array([200.0, 50.0, -1000.0])
    scene = elastokin.Scene()
    scene.body("arm", at=[0.25, 0, 0])
    scene.joint("hinge", "revolute", bodies=("chassis", "arm"), at=[0, 0, 0], axis=[0, 1, 0])
    scene.joint("brace", "distance", bodies=("chassis", "arm"), at=anchor, to=brace)
    scene.force("load", body="arm", at=tip, force=f)
    sweep = scene.sweep(0.0, 1.0, 4, **TIGHT)
    t = sweep.t[:, None]
    e = (brace - anchor) / numpy.linalg.norm(brace - anchor)
    size = -numpy.cross(tip, f)[1] / numpy.cross(brace, e)[1]
    link, link_moment = sweep.reaction("brace")
    assert numpy.abs(link - t * size * e).max() < 1e-11  # measured 4.5e-13 N of 1.9e3 N
    assert numpy.abs(link_moment).max() < 1e-12  # measured 2.8e-14 N·m: ball joints at its ends carry none
    hinge, hinge_moment = sweep.reaction("hinge")
    assert numpy.abs(hinge + t * (f + size * e)).max() < 1e-11  # measured 4.0e-13 N
    moment = t * (numpy.cross(tip, f) + numpy.cross(brace, size * e))
    assert numpy.abs(hinge_moment + moment).max() < 1e-12  # measured 5.7e-14 N·m
    assert numpy.abs(sweep.position("arm") - [0.25, 0, 0]).max() < 1e-15  # measured 1.4e-16 m: nothing moves


# tests/closed_form.rs's slider-crank: a crank of radius R_CRANK on a revolute about +y at the origin, a
# rod of length L_ROD (spherical at the crank pin, universal at the slider), a slider on a translational
# guide along x against a return spring to a chassis seat at (XG, 0, 0), compressed 20 mm at design, and a
# torque M_CRANK about +y on the crank. At crank angle θ the slider is at x(θ) = R cos θ + √(L² − R² sin² θ).
R_CRANK, L_ROD, K_RETURN, M_CRANK, THETA0, XG = 0.1, 0.3, 5e4, 150.0, 0.6, 0.7


def slider_x(th):
    return R_CRANK * math.cos(th) + math.sqrt(L_ROD**2 - (R_CRANK * math.sin(th)) ** 2)


def slider_dx(th):
    return -R_CRANK * math.sin(th) - R_CRANK**2 * math.sin(th) * math.cos(th) / math.sqrt(
        L_ROD**2 - (R_CRANK * math.sin(th)) ** 2
    )


SLIDER_FREE = (XG - slider_x(THETA0)) + 0.02
CRANK_PIN = R_CRANK * numpy.array([math.cos(THETA0), 0, -math.sin(THETA0)])


def spring_on_slider(th):
    """The return spring's push on the slider along x at crank angle θ (it pushes the slider back)."""
    return -K_RETURN * (SLIDER_FREE - (XG - slider_x(th)))


def slider_crank():
    b = numpy.array([slider_x(THETA0), 0, 0])
    scene = elastokin.Scene()
    scene.body("crank", at=CRANK_PIN / 2)
    scene.body("rod", at=(CRANK_PIN + b) / 2)
    scene.body("slider", at=b)
    scene.joint("crank bearing", "revolute", bodies=("chassis", "crank"), at=[0, 0, 0], axis=[0, 1, 0])
    scene.joint("crank pin", "spherical", bodies=("crank", "rod"), at=CRANK_PIN)
    scene.joint("wrist pin", "universal", bodies=("rod", "slider"), at=b, axis=[0, 1, 0], axis_j=[0, 0, 1])
    scene.joint("slideway", "translational", bodies=("chassis", "slider"), at=b, axis=[1, 0, 0])
    scene.spring("return spring", bodies=("slider", "chassis"), from_=b, to=[XG, 0, 0], rate=K_RETURN,
                 free_length=SLIDER_FREE)
    scene.torque("crank torque", body="crank", torque=[0, M_CRANK, 0])
    return scene


def test_slider_crank_matches_virtual_work():
    """Virtual work, M + F_x dx/dθ = 0, solved for θ by bisection, gives the crank angle; the rod is a
    two-force member, so the bearing's reaction on the crank is along it, its size from the slider's
    x-balance."""
    sweep = slider_crank().sweep(0.0, 1.0, 8, **TIGHT)

    def g(th):
        return M_CRANK + spring_on_slider(th) * slider_dx(th)

    lo, hi = -0.9, 1.5
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if math.copysign(1, g(lo)) == math.copysign(1, g(mid)):
            lo = mid
        else:
            hi = mid
    theta = 0.5 * (lo + hi)
    got = THETA0 + sweep.rotation("crank")[-1, 1]
    assert abs(got - theta) < 1e-14  # measured 6.7e-16 rad
    assert abs(theta - THETA0) > 0.3
    assert abs(sweep.position("slider")[-1, 0] - slider_x(theta)) < 1e-14  # measured 1.1e-16 m
    a = R_CRANK * numpy.array([math.cos(theta), 0, -math.sin(theta)])
    e_ab = (numpy.array([slider_x(theta), 0, 0]) - a) / L_ROD
    expected = e_ab * (-spring_on_slider(theta) / e_ab[0])
    force, _ = sweep.reaction("crank bearing")
    assert numpy.linalg.norm(force[-1] - expected) < 1e-13 * numpy.linalg.norm(expected)  # measured 3.1e-15 rel.


def test_joint_reactions_and_element_forces_on_each_body_balance():
    """Conservation on the slider-crank, body by body and step by step: the forces on each body sum to zero,
    and the moments on the crank about the origin. A joint's reaction is reported on its second body; on its
    first body it acts with the opposite sign (and the spring reports its force on the chassis)."""
    sweep = slider_crank().sweep(0.0, 1.0, 8)
    bearing, bearing_moment = sweep.reaction("crank bearing")
    pin, pin_moment = sweep.reaction("crank pin")
    wrist, _ = sweep.reaction("wrist pin")
    slideway, _ = sweep.reaction("slideway")
    spring = sweep.element("return spring")
    assert numpy.abs(bearing - pin).max() < 1e-12  # the crank; measured 0 N
    assert numpy.abs(pin - wrist).max() < 1e-12  # the rod; measured 0 N
    assert numpy.abs(wrist + slideway - spring["force"]).max() < 1e-10  # the slider; measured 1.4e-12 N
    torque = sweep.t[:, None] * [0, M_CRANK, 0]
    at_pin = sweep.point("crank", CRANK_PIN)
    crank = bearing_moment + torque - numpy.cross(at_pin, pin) - pin_moment
    assert numpy.abs(crank).max() < 1e-7  # measured 2.2e-9 N·m of 150 N·m
    # A ball joint carries no moment.
    assert numpy.abs(pin_moment).max() < 1e-12  # measured 1.4e-14 N·m


# Two bars (springs of rate K_BAR, free at design) from the chassis at (±A_BAR, 0, 0) to an apex on a
# vertical guide at height H_BAR, pressed down: the von Mises truss. At apex height z each bar is
# L(z) = √(a² + z²) long and pushes with k (L₀ − L), so the load that holds the apex there is
# F(z) = 2 k z (L₀ / L − 1). It peaks where L³ = L₀ a², at z*, and F(z*) = F_max.
A_BAR, H_BAR, K_BAR = 0.3, 0.05, 1e5


def truss_load(z):
    l0 = math.hypot(A_BAR, H_BAR)
    return 2 * K_BAR * z * (l0 / numpy.hypot(A_BAR, z) - 1)


def truss_peak():
    """(z*, F_max)."""
    length = (math.hypot(A_BAR, H_BAR) * A_BAR * A_BAR) ** (1 / 3)
    z_star = math.sqrt(length * length - A_BAR * A_BAR)
    return z_star, truss_load(z_star)


def truss(press):
    scene = elastokin.Scene()
    scene.body("apex", at=[0, 0, H_BAR])
    scene.joint("guide", "translational", bodies=("chassis", "apex"), at=[0, 0, H_BAR], axis=[0, 0, 1])
    for side in (-1, 1):
        scene.spring(f"bar {side}", bodies=("chassis", "apex"), from_=[side * A_BAR, 0, 0], to=[0, 0, H_BAR],
                     rate=K_BAR, design_force=0.0)
    scene.force("press", body="apex", at=[0, 0, H_BAR], force=[0, 0, -press])
    return scene


def test_a_snap_through_stops_at_its_limit_point_and_says_so():
    """Ramped to F_max / 0.77 the truss's path folds at t = 0.77: the sweep stops there and says so, its
    last row the equilibrium at the limit point."""
    z_star, f_max = truss_peak()
    t_star = 0.77
    scene = truss(f_max / t_star)
    for mode in ("corrected", "paper"):
        sweep = scene.sweep(0.0, 1.0, 20, mode=mode)
        assert not sweep.complete and sweep.arc_length_from is None and len(sweep) < 21
        # Located to 1e-6 of the range (the library's LIMIT_POINT_TOLERANCE), on the near side.
        assert 0 <= t_star - sweep.limit < 1e-6  # measured 3.1e-7
        assert sweep.t[-1] == sweep.limit and sweep.t[-2] < sweep.limit
        # Near a fold the height goes as the square root of the load left: 3e-7 of it leaves 1.5e-5 m.
        assert abs(sweep.position("apex")[-1, 2] - z_star) < 1e-4  # measured 1.5e-5 m
        assert "stopped at the limit point" in repr(sweep)
    done = scene.sweep(0.0, 0.7, 7)
    assert done.complete and done.limit is None and done.arc_length_from is None


def test_a_snap_through_followed_by_arc_length_stays_on_the_closed_form_path():
    """Through the fold by arc length: every row, before and past the limit point, is an equilibrium of the
    closed form, F(z) = t · F_ramp, while the apex passes below z* and the load falls after the peak."""
    z_star, f_max = truss_peak()
    press = f_max / 0.77
    sweep = truss(press).sweep(0.0, 1.0, 20, through_limits=True, **TIGHT)
    first = sweep.arc_length_from
    assert first is not None and 0 < first < len(sweep) and abs(sweep.limit - 0.77) < 1e-6
    z = sweep.position("apex")[:, 2]
    assert numpy.abs(truss_load(z) - sweep.t * press).max() < 1e-7  # measured 3.5e-9 N of 68 N
    # Past the peak the apex goes below z* and the load it holds falls, through zero (the bars level) until
    # the path leaves the range.
    assert z[first:].min() < 0 < z_star < z[first - 1] and sweep.t[first:].max() < 0.77
    assert sweep.complete and not 0.0 <= sweep.t[-1] <= 1.0
    assert "through the limit point" in repr(sweep)


def test_sweeps_in_threads_give_the_serial_numbers():
    """The solver runs without the GIL: sweeps of one scene in several threads give what one thread gives."""
    scene = swing_arm()
    serial = scene.sweep(-1.0, 1.0, 20).position("swing arm")
    results = [None] * 4

    def run(k):
        results[k] = scene.sweep(-1.0, 1.0, 20).position("swing arm")

    threads = [threading.Thread(target=run, args=(k,)) for k in range(4)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    for r in results:
        assert numpy.array_equal(r, serial)


# --- Errors ---------------------------------------------------------------------------------------------


def test_a_part_on_an_unknown_body_is_refused_naming_both():
    scene = elastokin.Scene()
    scene.body("upright", at=[0, 0.7, 0])
    with pytest.raises(elastokin.ModelError, match=r"'ball joint': there is no body 'uprigth'.*'upright'"):
        scene.joint("ball joint", "spherical", bodies=("chassis", "uprigth"), at=[0, 0.7, 0])
    with pytest.raises(elastokin.ModelError, match="'load': there is no body 'hub'"):
        scene.force("load", body="hub", at=[0, 0, 0], force=[0, 0, 1])
    with pytest.raises(elastokin.ModelError, match="'load': a load on the ground .* moves nothing"):
        scene.force("load", body="chassis", at=[0, 0, 0], force=[0, 0, 1])
    # Nothing was added by the refused calls.
    assert scene.joints == [] and scene.elements == []


def test_a_name_used_twice_is_refused():
    scene = elastokin.Scene()
    scene.body("arm", at=[0, 0, 0])
    with pytest.raises(elastokin.ModelError, match="the name 'arm' is used twice"):
        scene.body("arm", at=[1, 0, 0])
    with pytest.raises(elastokin.ModelError, match="the name 'arm' is used twice"):
        scene.joint("arm", "spherical", bodies=("chassis", "arm"), at=[0, 0, 0])
    with pytest.raises(elastokin.ModelError, match="body 'chassis': .* name the fixed ground: give the body another"):
        scene.body("chassis", at=[0, 0, 0])


def test_a_kind_word_the_library_does_not_know_is_a_value_error_listing_the_words():
    scene = elastokin.Scene()
    scene.body("arm", at=[0, 0, 0])
    with pytest.raises(ValueError, match="joint kind 'hinge': give one of 'spherical', 'revolute'.*'parallel_axes'"):
        scene.joint("pivot", "hinge", bodies=("chassis", "arm"), at=[0, 0, 0], axis=[0, 1, 0])
    with pytest.raises(ValueError, match="joint kind 'point_driver'"):
        scene.joint("drive", "point_driver", bodies=("chassis", "arm"), at=[0, 0, 0], axis=[0, 0, 1])
    with pytest.raises(ValueError, match="rotation law 'chrono': give one of 'energy', 'linear', 'tait_bryan_xyz'"):
        scene.bushing("mount", bodies=("chassis", "arm"), at=[0, 0, 0], radial=1e6, axial=1e6, torsion=1e2,
                      conical=1e3, law="chrono")
    with pytest.raises(ValueError, match="stop kind 'jounce': give one of 'bump', 'rebound'"):
        scene.stop("stop", "jounce", bodies=("chassis", "arm"), from_=[0, 0, 1], to=[0, 0, 0], clearance=0.01,
                   curve=[[0, 0], [0.01, 100]])
    scene.joint("pivot", "revolute", bodies=("chassis", "arm"), at=[0, 0, 0], axis=[0, 1, 0])
    with pytest.raises(ValueError, match="mode 'exact': give 'corrected' or 'paper'"):
        scene.sweep(0, 1, 4, mode="exact")
    with pytest.raises(ValueError, match="steps must be a whole number of at least 1"):
        scene.sweep(0, 1, 0)
    with pytest.raises(ValueError, match="'pivot 2': at must be three numbers"):
        scene.joint("pivot 2", "revolute", bodies=("chassis", "arm"), at=[0, 0], axis=[0, 1, 0])


def test_not_finite_inputs_are_refused_by_name():
    scene = elastokin.Scene()
    with pytest.raises(elastokin.ModelError, match="'arm': reference point 'at' is not finite"):
        scene.body("arm", at=[0, math.nan, 0])
    scene.body("arm", at=[0, 0, 0])
    with pytest.raises(elastokin.ModelError, match="'pivot': axis is not finite"):
        scene.joint("pivot", "revolute", bodies=("chassis", "arm"), at=[0, 0, 0], axis=[0, math.inf, 0])
    with pytest.raises(elastokin.ModelError, match="'push': force is not finite"):
        scene.force("push", body="arm", at=[0, 0, 0], force=[math.nan, 0, 0])
    with pytest.raises(elastokin.ModelError, match=r"spring \(spring\)\.rate must be a rate in N/m"):
        scene.spring("spring", bodies=("chassis", "arm"), from_=[0, 0, 1], to=[0, 0, 0], rate=math.nan,
                     design_force=0.0)
    with pytest.raises(ValueError, match="start must be a finite load parameter"):
        scene.sweep(math.nan, 1.0, 4)
    with pytest.raises(ValueError, match="t must be a finite load parameter"):
        scene.solve(math.inf)


def test_bad_geometry_and_rates_are_refused_naming_the_part_and_the_fix():
    scene = elastokin.Scene()
    scene.body("arm", at=[0, 0, 0])
    with pytest.raises(elastokin.ModelError, match="'pivot': axis has zero length: give a non-zero direction"):
        scene.joint("pivot", "revolute", bodies=("chassis", "arm"), at=[0, 0, 0], axis=[0, 0, 0])
    with pytest.raises(elastokin.ModelError, match="a revolute joint needs 'axis': add it"):
        scene.joint("pivot", "revolute", bodies=("chassis", "arm"), at=[0, 0, 0])
    with pytest.raises(elastokin.ModelError, match="'to' means nothing to a spherical joint: remove it"):
        scene.joint("ball", "spherical", bodies=("chassis", "arm"), at=[0, 0, 0], to=[1, 0, 0])
    with pytest.raises(elastokin.ModelError, match=r"bushing \(mount\).translation y must be a rate in N/m"):
        scene.bushing("mount", bodies=("chassis", "arm"), at=[0, 0, 0], radial=0.0, axial=1e6, torsion=1e2,
                      conical=1e3)
    with pytest.raises(elastokin.ModelError, match="a cylindrical bushing needs all four rates"):
        scene.bushing("mount", bodies=("chassis", "arm"), at=[0, 0, 0], radial=1e6, axial=1e6)
    # Named as the rates' errors name it, by the model file's shared reading of a bushing entry.
    with pytest.raises(elastokin.ModelError, match=r"'bushing \(mount\)': y_axis is parallel to the bushing's axis"):
        scene.bushing("mount", bodies=("chassis", "arm"), at=[0, 0, 0], axis=[0, 1, 0], y_axis=[0, 2, 0],
                      radial=1e6, axial=1e6, torsion=1e2, conical=1e3)
    with pytest.raises(elastokin.ModelError, match="give either design_force"):
        scene.spring("spring", bodies=("chassis", "arm"), from_=[0, 0, 1], to=[0, 0, 0], rate=1e4)
    assert scene.joints == [] and scene.elements == []


def test_a_scene_the_solver_cannot_hold_says_which_body_is_free():
    scene = elastokin.Scene()
    scene.body("loose", at=[0, 0, 0])
    # Held by nothing at all: refused as built.
    with pytest.raises(elastokin.ModelError, match="body 'loose' is held by nothing"):
        scene.sweep(0, 1, 2)
    # On a ball joint alone it is free to turn: the solver finds the motion and names the body.
    scene.joint("ball", "spherical", bodies=("chassis", "loose"), at=[0, 0, 0])
    with pytest.raises(elastokin.AnalysisError, match="'loose' is free to move \\(rotation"):
        scene.sweep(0, 1, 2)
    with pytest.raises(elastokin.AnalysisError, match="'loose' is free to move"):
        scene.solve(0.5)


def test_results_name_what_they_have():
    sweep = swing_arm().sweep(0.0, 1.0, 2)
    assert sweep.bodies == ["swing arm"] and sweep.joints == []
    assert sweep.elements == {"pivot bushing": "bushing", "spring": "spring", "wheel force": "force"}
    with pytest.raises(KeyError, match="there is no body 'arm': the scene's are 'swing arm'"):
        sweep.position("arm")
    with pytest.raises(KeyError, match="there is no joint 'pivot'"):
        sweep.reaction("pivot")
    with pytest.raises(KeyError, match="there is no element 'damper'.*'pivot bushing', 'spring' or 'wheel force'"):
        sweep.element("damper")
    # The ground does not move.
    assert numpy.array_equal(sweep.point("chassis", [1, 2, 3]), numpy.tile([1.0, 2, 3], (3, 1)))


def test_the_module_s_example_runs_as_written():
    """elastokin.scene's docstring: a slider on a 20 kN/m spring pushed by 100 N moves 5 mm."""
    import elastokin.scene

    result = doctest.testmod(elastokin.scene)
    assert result.attempted >= 8 and result.failed == 0


def test_adding_a_part_while_another_thread_sweeps_says_the_scene_is_being_swept():
    """Adding a part to a scene that another thread was sweeping raised PyO3's "Already borrowed". It now
    says, in the scene's words, that the scene is being swept. The part tried names a body the scene does
    not have, so that when it is not refused for the sweep it is refused for that (a ModelError) and the
    scene being swept never changes."""
    scene = elastokin.Scene()
    scene.body("slider", at=[0, 0, 0])
    scene.joint("guide", "translational", bodies=("chassis", "slider"), at=[0, 0, 0], axis=[1, 0, 0])
    scene.spring("spring", bodies=("chassis", "slider"), from_=[0.4, 0, 0], to=[0, 0, 0], rate=2.5e4,
                 free_length=0.4)
    scene.force("push", body="slider", at=[0, 0, 0], force=[400, 0, 0])
    done = threading.Event()
    swept = []

    def sweep():
        try:
            swept.append(scene.sweep(0.0, 1.0, 20000))
        finally:
            done.set()

    worker = threading.Thread(target=sweep)
    worker.start()
    refusals, unknown_body, other = [], 0, []
    while not done.is_set():
        try:
            scene.joint("probe", "spherical", bodies=("chassis", "nobody"), at=[0, 0, 0])
        except RuntimeError as e:
            refusals.append(str(e))
        except elastokin.ModelError:
            unknown_body += 1
        except Exception as e:  # noqa: BLE001 — any other failure is the bug this test is about
            other.append(repr(e))
    worker.join()
    assert not other, other[:3]
    assert refusals, f"no part was tried while the sweep held the scene ({unknown_body} tried outside it)"
    expected = "'probe' cannot be added while the scene is being swept on another thread"
    assert all(r.startswith(expected) for r in refusals), refusals[:3]
    assert len(swept) == 1 and len(swept[0].t) == 20001
    scene.body("after", at=[2, 0, 0])
    assert "after" in scene.bodies


# --- Field elements -----------------------------------------------------------------------------------------


def test_a_field_of_the_bushing_s_rates_gives_the_bushing_s_sweep():
    """The swing arm's pivot bushing written as a field: its frame's diagonal (axial along x, radial across;
    torsion about x, conical across) gives the same sweep, and a coupled term moves it."""

    def with_field(couple):
        scene = elastokin.Scene()
        scene.body("swing arm", at=[(p + w) / 2.0 for p, w in zip(PIVOT, WHEEL_CENTRE)])
        k = numpy.diag([1e6, 5e6, 5e6, math.degrees(10.0), math.degrees(100.0), math.degrees(100.0)])
        k[1, 5] = k[5, 1] = couple * math.sqrt(k[1, 1] * k[5, 5])
        scene.field("pivot bushing", bodies=("chassis", "swing arm"), at=PIVOT, axis=[0, 1, 0], y_axis=[-1, 0, 0],
                    stiffness=k)
        scene.spring(
            "spring", bodies=("chassis", "swing arm"), from_=SEAT_CHASSIS, to=SEAT_ARM, rate=60e3, design_force=3000.0
        )
        scene.force("wheel force", body="swing arm", at=WHEEL_CENTRE, force=[0, 0, 1500.0], constant=[0, 0, 2000.0])
        return scene.sweep(-1.0, 1.0, 20)

    bushing = swing_arm().sweep(-1.0, 1.0, 20)
    field = with_field(0.0)
    z = lambda s: s.point("swing arm", WHEEL_CENTRE)[:, 2]
    # The same elements in the same order: measured 0.
    assert numpy.abs(z(field) - z(bushing)).max() <= 1e-15
    coupled = with_field(0.3)
    assert numpy.abs(z(coupled) - z(bushing)).max() > 1e-6
    with pytest.raises(elastokin.ModelError, match="not symmetric"):
        scene = elastokin.Scene()
        scene.body("b", at=[0, 0, 0])
        k = numpy.eye(6)
        k[0, 1] = 1.0
        scene.field("f", bodies=("chassis", "b"), at=[0, 0, 0], stiffness=k)


def test_a_beam_bends_as_a_cantilever_and_a_bad_section_is_refused_by_name():
    """A steel bar from the chassis to a body, loaded at its end: the end drops P·L³/3EI (the bar along x,
    the load down z, bending about the section's y axis): a beam from the ground is the linear cantilever."""
    length, e, g, iy = 0.5, 210e9, 80e9, 1e-8
    scene = elastokin.Scene()
    scene.body("tip", at=[length, 0.0, 0.0])
    section = {"youngs_modulus": e, "shear_modulus": g, "area": 1e-4, "iy": iy, "iz": 2 * iy, "j": 3 * iy}
    scene.beam("bar", bodies=("chassis", "tip"), from_=[0, 0, 0], to=[length, 0, 0], y_axis=[0, 1, 0],
               section=section)
    load = 10.0
    scene.force("end load", body="tip", at=[length, 0, 0], force=[0, 0, -load])
    sweep = scene.sweep(0.0, 1.0, 4)
    drop = -sweep.point("tip", [length, 0, 0])[-1, 2]
    closed_form = load * length**3 / (3 * e * iy)
    # Measured 1.1e-16.
    assert abs(drop / closed_form - 1) < 1e-14
    bad = dict(section, j=-1.0)
    with pytest.raises(elastokin.ModelError, match="torsion constant J must be a positive number"):
        scene = elastokin.Scene()
        scene.body("tip", at=[length, 0.0, 0.0])
        scene.beam("bar", bodies=("chassis", "tip"), from_=[0, 0, 0], to=[length, 0, 0], y_axis=[0, 1, 0],
                   section=bad)
    with pytest.raises(ValueError, match="section area must be a number, got '1e-4'"):
        elastokin.Scene().beam("bar", bodies=("chassis", "tip"), from_=[0, 0, 0], to=[1, 0, 0], y_axis=[0, 1, 0],
                               section=dict(section, area="1e-4"))
    with pytest.raises(ValueError, match="section shear_centre must be two numbers"):
        elastokin.Scene().beam("bar", bodies=("chassis", "tip"), from_=[0, 0, 0], to=[1, 0, 0], y_axis=[0, 1, 0],
                               section=dict(section, shear_centre=0.01))
    with pytest.raises(ValueError, match="section needs iy"):
        elastokin.Scene().beam("bar", bodies=("chassis", "tip"), from_=[0, 0, 0], to=[1, 0, 0], y_axis=[0, 1, 0],
                               section={k: v for k, v in section.items() if k != "iy"})
