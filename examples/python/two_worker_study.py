"""A design study on two workers: bump steer, camber gain and wheel rate of the shipped MacPherson over a grid
of inner tie-rod heights and lower-arm bushing rates, run on Ray or Dask and kept as Parquet.

    pip install ./python ray pyarrow           # or "dask[distributed]" instead of ray
    python examples/python/two_worker_study.py --engine ray --workers 2 --out target/study

It writes the grid as a variants file (``OUT/variants.txt``) and the results as ``OUT/study.parquet``. The
command runs the same variants file in one process:

    cargo run -- batch examples/macpherson.json target/study/variants.txt --out target/study/command

and ``--compare target/study/command/batch.csv`` checks that every figure of the study is the command's, to
the digits batch.csv prints (it exits with 1 naming the first that is not). ``--plot PNG`` draws bump steer
against the tie-rod height, one line per bushing rate (needs matplotlib).
"""

import argparse
import csv
import math
import sys
from pathlib import Path

import elastokin

EXAMPLES = Path(__file__).resolve().parents[1]
TIE_ROD_Z = "/suspension/macpherson/hardpoints/tie_rod_inner/2"
ARM_RADIAL = "/suspension/macpherson/lower_arm_mounts/bushing/radial"


def grid(model: elastokin.Model) -> dict:
    """The variant table: 11 inner tie-rod heights (±10 mm) × 5 lower-arm bushing radial rates (1–16 kN/mm)."""
    z0 = model.to_dict()["suspension"]["macpherson"]["hardpoints"]["tie_rod_inner"][2]
    heights = [round(z0 + 0.002 * k, 6) for k in range(-5, 6)]
    rates = [1.0e6 * 2.0**k for k in range(5)]
    cells = [(z, k) for k in rates for z in heights]
    return {
        "name": [f"tie rod {1000 * (z - z0):+.0f} mm, arm bushing {k / 1e6:.0f} kN/mm" for z, k in cells],
        TIE_ROD_Z: [z for z, _ in cells],
        ARM_RADIAL: [k for _, k in cells],
    }


def printed(v: float) -> float:
    """A value as batch.csv prints it: 12 significant digits."""
    return float(f"{v:.11e}")


def compare(study: elastokin.Study, batch_csv: Path) -> int:
    """0 when every row of the study is the command's row, else 1 after naming the first that differs."""
    with open(batch_csv, newline="") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    if len(rows) != len(study):
        print(f"{batch_csv}: {len(rows)} rows, the study {len(study)}", file=sys.stderr)
        return 1
    for k, row in enumerate(rows):
        if row["variant"] != study.columns["variant"][k]:
            print(f"row {k + 1}: '{row['variant']}' against '{study.columns['variant'][k]}'", file=sys.stderr)
            return 1
        for figure in elastokin.BATCH_FIGURES:
            mine, theirs = float(study.columns[figure][k]), row[figure]
            same = (math.isnan(mine) and theirs == "") or (theirs != "" and printed(mine) == float(theirs))
            if not same:
                print(f"row {k + 1} ({row['variant']}): {figure} {mine!r} against {theirs}", file=sys.stderr)
                return 1
    print(f"all {len(rows)} variants: the study's figures are the command's ({batch_csv})")
    return 0


def plot(study: elastokin.Study, path: str) -> None:
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        raise SystemExit("--plot needs matplotlib: pip install matplotlib")
    fig, ax = plt.subplots(figsize=(6, 4))
    for rate in sorted(set(study.columns[ARM_RADIAL])):
        pick = study.columns[ARM_RADIAL] == rate
        ax.plot(study.columns[TIE_ROD_Z][pick] * 1000.0, study.columns["bump_steer_deg_per_m"][pick],
                marker="o", label=f"arm bushing {rate / 1e6:.0f} kN/mm")
    ax.set_xlabel("inner tie-rod height z [mm]")
    ax.set_ylabel("bump steer at design [deg/m]")
    ax.legend()
    ax.grid(True)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    print(f"wrote {path}")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--engine", choices=elastokin.ENGINES, default="ray")
    parser.add_argument("--workers", type=int, default=2, help="CPUs of the local Ray or Dask cluster")
    parser.add_argument("--out", type=Path, default=Path("target/study"), help="where the files go")
    parser.add_argument("--compare", type=Path, metavar="BATCH_CSV", help="the command's batch.csv of OUT/variants.txt")
    parser.add_argument("--plot", metavar="PNG", help="draw bump steer against tie-rod height (needs matplotlib)")
    args = parser.parse_args()

    model = elastokin.load(EXAMPLES / "macpherson.json")
    table = grid(model)
    args.out.mkdir(parents=True, exist_ok=True)
    lines = [f"{n}: {TIE_ROD_Z}={z!r}; {ARM_RADIAL}={k!r}" for n, z, k in zip(*table.values())]
    (args.out / "variants.txt").write_text("\n".join(lines) + "\n")

    study = elastokin.study(model, table, engine=args.engine, workers=args.workers, parquet=args.out / "study.parquet")
    bump = study.columns["bump_steer_deg_per_m"]
    print(f"{len(study)} variants on {args.engine} with {args.workers} workers; wrote {args.out / 'study.parquet'}")
    print(f"bump steer from {bump.min():.2f} to {bump.max():.2f} deg/m")
    flattest = min(range(len(study)), key=lambda k: abs(bump[k]))
    print(f"flattest: {study.columns['variant'][flattest]}, {bump[flattest]:+.3f} deg/m")
    if args.plot:
        plot(study, args.plot)
    return compare(study, args.compare) if args.compare else 0


if __name__ == "__main__":
    sys.exit(main())
