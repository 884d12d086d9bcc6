"""A small design study: toe against wheel travel for five heights of the inner tie-rod point of the shipped
MacPherson, and the bump steer each gives at design.

    pip install ./python            # once, from the repository root
    python examples/python/tie_rod_study.py [--plot toe.png]

Without matplotlib it prints the table; with it (``pip install matplotlib``) ``--plot`` also draws toe against
travel, one line per variant. Every number comes from the library the ``elastokin`` command runs: the same
variants as lines of a variants file give the same bump steer through ``elastokin batch``.
"""

import argparse
import copy
from pathlib import Path

import elastokin

EXAMPLES = Path(__file__).resolve().parents[1]
# Inner tie-rod point moved up and down along z (m): the classic bump-steer knob.
SHIFTS = (-0.010, -0.005, 0.0, 0.005, 0.010)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plot", metavar="PNG", help="draw toe against travel into this file (needs matplotlib)")
    args = parser.parse_args()

    base = elastokin.load(EXAMPLES / "macpherson.json")
    hardpoint = base.to_dict()["suspension"]["macpherson"]["hardpoints"]["tie_rod_inner"]
    curves = {}
    edits = []
    for dz in SHIFTS:
        doc = copy.deepcopy(base.to_dict())
        doc["suspension"]["macpherson"]["hardpoints"]["tie_rod_inner"][2] = hardpoint[2] + dz
        name = f"tie rod {dz * 1000:+.0f} mm"
        travel = elastokin.load(doc, origin=name).run("parallel-travel", steps=32)
        curves[name] = (travel.columns["travel_m"], travel.columns["toe_deg"])
        edits.append({"name": name, "/suspension/macpherson/hardpoints/tie_rod_inner/2": hardpoint[2] + dz})

    # The same variants as a batch: bump steer at design, deg per metre of travel.
    rows = elastokin.batch(base, edits)
    print(f"{'variant':>16}  {'bump steer (deg/m)':>18}  {'toe at +80 mm (deg)':>19}")
    for row in rows:
        travel_m, toe_deg = curves[row["variant"]]
        print(f"{row['variant']:>16}  {row['bump_steer_deg_per_m']:18.4f}  {toe_deg[-1]:19.4f}")

    if args.plot:
        try:
            import matplotlib

            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
        except ImportError:
            raise SystemExit("--plot needs matplotlib: pip install matplotlib")
        fig, ax = plt.subplots(figsize=(6, 4))
        for name, (travel_m, toe_deg) in curves.items():
            ax.plot(travel_m * 1000.0, toe_deg, label=name)
        ax.set_xlabel("wheel travel [mm], bump +")
        ax.set_ylabel("toe [deg], toe-in +")
        ax.legend()
        ax.grid(True)
        fig.tight_layout()
        fig.savefig(args.plot, dpi=120)
        print(f"wrote {args.plot}")


if __name__ == "__main__":
    main()
