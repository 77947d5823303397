#!/usr/bin/env python3
"""Exact geodesic distances: Veneer's window propagation against pygeodesic (Kirsanov's
implementation of Mitchell, Mount and Papadimitriou's exact algorithm) on the same
meshes, side by side in one run.

    pip install pygeodesic potpourri3d
    cargo build --release
    python3 benches/pygeodesic_compare.py [--veneer target/release/veneer] [--runs 3]

Each mesh is a Veneer primitive written out as OBJ by `veneer mesh --write`. Veneer is
timed end to end per process (its solve figure: the propagation alone); pygeodesic in
this process, from building its mesh to the distances. The error columns are the mean
and largest relative difference between the two fields over the vertices farther than
10% of the largest distance: MMP is exact, so this is Veneer's error (and the rounding
of both).
"""

import argparse
import statistics
import tempfile
import time
from pathlib import Path

import numpy as np
import potpourri3d as pp3d
import pygeodesic.geodesic as geodesic

from potpourri3d_compare import primitive_obj, relative_differences, veneer_run

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
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--meshes", nargs="+", default=MESHES, help="primitives to compare (default: %(default)s)")
    args = parser.parse_args()
    header = f"{'mesh':<12}{'triangles':>10}{'ours':>11}{'theirs':>11}{'ratio':>7}{'mean error':>12}{'max error':>11}"
    print(header)
    print("-" * len(header))
    with tempfile.TemporaryDirectory() as folder:
        for name in args.meshes:
            obj = primitive_obj(args.veneer, folder, name)
            csv = str(Path(folder) / "field.csv")
            vertices, faces = pp3d.read_mesh(obj)
            ours = statistics.median(veneer_run(args.veneer, obj, csv, "exact")[1] for _ in range(args.runs))
            their_runs = [theirs(vertices, faces) for _ in range(args.runs)]
            their_time = statistics.median(t[0] for t in their_runs)
            our_field = np.loadtxt(csv)
            their_field = their_runs[-1][1]
            errors = relative_differences(our_field, their_field)
            print(
                f"{name:<12}{len(faces):>10}{ours:>9.0f}ms{their_time:>9.0f}ms{ours / their_time:>7.2f}"
                f"{errors.mean():>12.2e}{errors.max():>11.2e}"
            )
    print(f"(median of {args.runs} runs each; ratio = ours / theirs)")


if __name__ == "__main__":
    main()
