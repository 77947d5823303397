#!/usr/bin/env python3
"""Exact geodesic distances: Veneer's window propagation against pygeodesic (Kirsanov's
implementation of Mitchell, Mount and Papadimitriou's exact algorithm) on the same
meshes, side by side in one run.

    pip install pygeodesic potpourri3d
    cargo build --release
    python3 benches/pygeodesic_compare.py [--veneer target/release/veneer] [--runs 3]
        [--baseline OTHER_VENEER] [--meshes torus:160 ...]

Each mesh is a Veneer primitive written out as OBJ by `veneer mesh --write`. Veneer is
timed end to end per process (its solve figure: the propagation alone); pygeodesic in
this process, from building its mesh to the distances. `--baseline` times another
Veneer build in the same run, e.g. the exact method as it was before the window queue
and shadow work (`git worktree add /tmp/before d629972 && cargo build --release
--no-default-features --bin veneer` there).

The differences are relative, over the vertices farther than 10% of the largest
distance, signed: both methods report lengths of real paths, so where one is longer
the other found a shorter path, and the longer one missed it (`ours longer` is our
error, `theirs longer` pygeodesic's). The error of both includes reading the OBJ's
decimal positions (Veneer reads them as 32-bit floats).
"""

import argparse
import statistics
import tempfile
import time
from pathlib import Path

import numpy as np
import potpourri3d as pp3d
import pygeodesic.geodesic as geodesic

from potpourri3d_compare import primitive_obj, veneer_run

# A clean torus, a marching-tetrahedra surface with slivers, and a sphere with pole fans.
MESHES = ["torus:160", "genus2:40", "sphere:64"]


def theirs(vertices, faces):
    """pygeodesic from vertex 0: (ms, field)."""
    started = time.perf_counter()
    algorithm = geodesic.PyGeodesicAlgorithmExact(vertices, faces)
    field, _ = algorithm.geodesicDistances(np.array([0]), None)
    return (time.perf_counter() - started) * 1e3, field


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--veneer", default="target/release/veneer")
    parser.add_argument("--baseline", help="another veneer binary to time in the same run")
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--meshes", nargs="+", default=MESHES, help="primitives to compare (default: %(default)s)")
    args = parser.parse_args()
    header = (
        f"{'mesh':<12}{'triangles':>10}{'ours':>10}{'baseline':>10}{'ratio':>7}{'theirs':>10}{'ratio':>7}"
        f"{'mean diff':>11}{'ours longer':>13}{'theirs longer':>15}"
    )
    print(header)
    print("-" * len(header))
    with tempfile.TemporaryDirectory() as folder:
        for name in args.meshes:
            obj = primitive_obj(args.veneer, folder, name)
            csv = str(Path(folder) / "field.csv")
            vertices, faces = pp3d.read_mesh(obj)
            ours = statistics.median(veneer_run(args.veneer, obj, csv, "exact")[1] for _ in range(args.runs))
            our_field = np.loadtxt(csv)
            baseline = "-"
            baseline_ratio = "-"
            if args.baseline:
                other_csv = str(Path(folder) / "baseline.csv")
                runs = [veneer_run(args.baseline, obj, other_csv, "exact")[1] for _ in range(args.runs)]
                baseline = f"{statistics.median(runs):.0f}ms"
                baseline_ratio = f"{ours / statistics.median(runs):.2f}"
            their_runs = [theirs(vertices, faces) for _ in range(args.runs)]
            their_time = statistics.median(t[0] for t in their_runs)
            their_field = their_runs[-1][1]
            far = their_field > 0.1 * their_field.max()
            signed = (our_field[far] - their_field[far]) / their_field[far]
            print(
                f"{name:<12}{len(faces):>10}{ours:>8.0f}ms{baseline:>10}{baseline_ratio:>7}"
                f"{their_time:>8.0f}ms{ours / their_time:>7.2f}"
                f"{np.abs(signed).mean():>11.1e}{max(signed.max(), 0):>13.1e}{max(-signed.min(), 0):>15.1e}"
            )
    print(f"(median of {args.runs} runs each; ratio = ours / baseline, ours / theirs)")


if __name__ == "__main__":
    main()
