"""What a design study costs, measured: the figures of docs/scale-out.md.

    pip install ./python ray "dask[distributed]" pyarrow
    python bench/study/cost.py [--variants 4000] [--repeat 5] > cost.md

Prints a Markdown report. Every time is the median of ``--repeat`` runs, all in this one run, on this
machine; the variants are a grid of inner tie-rod heights and lower-arm bushing rates of the shipped
MacPherson, each judged as ``elastokin batch`` judges it (parallel travel ±20 mm, 8 steps, corrected mode).
"""

import argparse
import os
import platform
import statistics
import tempfile
import time
from pathlib import Path

import elastokin
from elastokin._study import Study

ROOT = Path(__file__).resolve().parents[2]
TIE_ROD_Z = "/suspension/macpherson/hardpoints/tie_rod_inner/2"
ARM_RADIAL = "/suspension/macpherson/lower_arm_mounts/bushing/radial"


def table(count: int) -> dict:
    """``count`` variants: tie-rod heights within ±10 mm × arm bushing rates 1–16 kN/mm, cycled."""
    return {
        "name": [f"v{k}" for k in range(count)],
        TIE_ROD_Z: [-0.069 + 0.02 * ((k * 0.618034) % 1.0) for k in range(count)],
        ARM_RADIAL: [1.0e6 * 2.0 ** (k % 5) for k in range(count)],
    }


def median_time(run, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        run()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--variants", type=int, default=4000, help="variants per timed study")
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    v, repeat = args.variants, args.repeat
    model = elastokin.load(ROOT / "examples" / "macpherson.json")
    variants = table(v)
    edits = elastokin.read_variants(model, variants)

    print("# What a design study costs\n")
    print(f"elastokin {elastokin._native.VERSION}, Python {platform.python_version()}, {os.cpu_count()} CPUs, "
          f"{v} variants, median of {repeat} runs, {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}\n")

    # The solver's cost: one batch on one thread and on every core, no engine.
    one = median_time(lambda: model._native.batch(edits, threads=1), repeat) / v
    every = median_time(lambda: model._native.batch(edits), repeat) / v
    print("| what | per variant |")
    print("|---|---|")
    print(f"| batch, one thread | {one * 1e6:.0f} µs |")
    print(f"| batch, {os.cpu_count()} threads | {every * 1e6:.0f} µs |")

    # The driver's own cost: reading the table and building the results (no solve), on 25× the variants.
    big = table(25 * v)
    read = median_time(lambda: elastokin.read_variants(model, big), repeat) / (25 * v)
    rows = model._native.batch(edits[:200], threads=1)
    # 200 rows solved, told apart in the last digits so that Parquet stores 25·v different figures.
    figures = elastokin.BATCH_FIGURES
    many_rows = [
        dict(rows[k % 200], variant_number=k + 1, **{f: rows[k % 200][f] * (1.0 + 1e-9 * k) for f in figures})
        for k in range(25 * v)
    ]
    big_edits = elastokin.read_variants(model, big)
    build = median_time(lambda: Study(many_rows, big_edits, {}), repeat) / (25 * v)
    print(f"| driver: read and check the table | {read * 1e6:.1f} µs |")
    print(f"| driver: gather the rows into a table | {build * 1e6:.1f} µs |")

    # On each engine, two workers; startup timed apart from the studies.
    import ray
    from distributed import Client, LocalCluster

    start = time.perf_counter()
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    ray_start = time.perf_counter() - start
    elastokin.study(model, variants, engine="ray")  # workers warmed (each imports elastokin once)
    on_ray = median_time(lambda: elastokin.study(model, variants, engine="ray"), repeat) / v
    small_tasks = median_time(lambda: elastokin.study(model, variants, engine="ray", chunks=v // 10), repeat) / v
    # The same number of variants as a grid written in parts by the tasks: nothing per variant on the driver.
    grid = elastokin.Grid({TIE_ROD_Z: [-0.079 + 0.02 * k / (v // 5) for k in range(v // 5)],
                           ARM_RADIAL: [1.0e6 * 2.0**k for k in range(5)]})

    def in_parts(engine):
        with tempfile.TemporaryDirectory() as d:
            elastokin.study_parts(model, grid, d, engine=engine, workers=2, part_size=v // 8)

    ray_parts = median_time(lambda: in_parts("ray"), repeat) / v
    ray.shutdown()
    local_parts = median_time(lambda: in_parts("local"), repeat) / v
    start = time.perf_counter()
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            Client(cluster):
        dask_start = time.perf_counter() - start
        elastokin.study(model, variants, engine="dask")
        on_dask = median_time(lambda: elastokin.study(model, variants, engine="dask"), repeat) / v
        dask_small = median_time(lambda: elastokin.study(model, variants, engine="dask", chunks=v // 10), repeat) / v
    local = median_time(lambda: elastokin.study(model, variants, engine="local", workers=2), repeat) / v
    print(f"| study, local, 2 threads | {local * 1e6:.0f} µs |")
    print(f"| study, Ray, 2 workers, 8 tasks | {on_ray * 1e6:.0f} µs |")
    print(f"| study, Ray, 2 workers, tasks of 10 variants | {small_tasks * 1e6:.0f} µs |")
    print(f"| study, Dask, 2 workers, 8 tasks | {on_dask * 1e6:.0f} µs |")
    print(f"| study, Dask, 2 workers, tasks of 10 variants | {dask_small * 1e6:.0f} µs |")
    print(f"| study_parts of a grid, local, 2 threads, 8 parts | {local_parts * 1e6:.0f} µs |")
    print(f"| study_parts of a grid, Ray, 2 workers, 8 parts | {ray_parts * 1e6:.0f} µs |")
    print(f"\nStartup: local Ray {ray_start:.2f} s, Dask LocalCluster {dask_start:.2f} s.")
    per_task_ray = (small_tasks - on_ray) * v / (v // 10 - 8)
    per_task_dask = (dask_small - on_dask) * v / (v // 10 - 8)
    print(f"Cost of a task (from the two task sizes, 2 workers): Ray {per_task_ray * 1e3:.2f} ms, "
          f"Dask {per_task_dask * 1e3:.2f} ms of wall time.\n")

    # Storage: the table of 25× the variants as Parquet, its size and a query over it.
    study = Study(many_rows, big_edits, {"variants": str(25 * v)})
    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "study.parquet"
        write = median_time(lambda: study.to_parquet(path), repeat)
        size = path.stat().st_size
        import pyarrow.compute as pc
        import pyarrow.dataset as ds

        def query():
            data = ds.dataset(path)
            return data.to_table(columns=["variant", "bump_steer_deg_per_m"],
                                 filter=pc.abs(ds.field("bump_steer_deg_per_m")) < 30.0)

        found = query().num_rows
        scan = median_time(query, repeat)
    n = 25 * v
    print("| Parquet (pyarrow defaults, snappy) | |")
    print("|---|---|")
    print(f"| rows | {n} |")
    print(f"| bytes per row | {size / n:.1f} |")
    print(f"| write, per row | {write / n * 1e6:.2f} µs |")
    print(f"| query \\|bump steer\\| < 30 deg/m ({found} rows), per row scanned | {scan / n * 1e9:.0f} ns |")


if __name__ == "__main__":
    main()
