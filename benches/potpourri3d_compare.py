#!/usr/bin/env python3
"""Heat-method geodesic distances: Veneer against potpourri3d (geometry-central's heat
method) on the same meshes, side by side in one run.

    pip install potpourri3d
    cargo build --release
    python3 benches/potpourri3d_compare.py [--veneer target/release/veneer] [--runs 5]

Each mesh is a Veneer primitive written out as OBJ by `veneer mesh --write`, so both
tools read the same file. Factorisation ("set-up") and one solve are timed separately;
each figure is the median over the runs. Peak memory is the largest resident size
of the process: `veneer geodesic`, and a fresh Python process that loads the mesh and
runs potpourri3d (this script, called with `--theirs`). The last column is the mean
relative difference between the two fields (vertices farther than 10% of the largest
distance).
"""

import argparse
import json
import os
import sys
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np
import potpourri3d as pp3d

MESHES = ["torus:160", "genus2:60", "sphere:128"]
SUMMARY_TIMES = ("set-up", "solve")


def veneer_run(veneer, obj, csv, method="heat"):
    """Runs `veneer geodesic` once from vertex 0 and returns (set-up ms, solve ms, peak MB)."""
    process = subprocess.Popen(
        [veneer, "geodesic", obj, "--sources", "0", "--method", method, "-o", csv],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
    )
    stderr = process.stderr.read()
    _, status, usage = os.wait4(process.pid, 0)
    process.returncode = os.waitstatus_to_exitcode(status)
    if process.returncode != 0:
        raise SystemExit(f"veneer geodesic failed: {stderr}")
    summary = stderr.strip().splitlines()[-1]
    times = {}
    for part in summary.split(";")[-1].split(","):
        label, value = part.strip().rsplit(" ", 2)[0], part.strip().split(" ")[-2]
        times[label] = float(value)
    # ru_maxrss is in kB on Linux.
    return (*(times[label] for label in SUMMARY_TIMES), usage.ru_maxrss / 1024)


def primitive_obj(veneer, folder, name):
    """Writes the primitive `name` (welded) as an OBJ file in `folder`; returns its path."""
    obj = str(Path(folder) / (name.replace(":", "_") + ".obj"))
    subprocess.run([veneer, "mesh", name, "--weld", "1e-6", "--write", obj], check=True, capture_output=True)
    return obj


def relative_differences(ours, theirs):
    """|ours - theirs| / theirs over the vertices farther than 10% of the largest distance."""
    far = theirs > 0.1 * theirs.max()
    return np.abs(ours[far] - theirs[far]) / theirs[far]


def theirs(vertices, faces):
    """potpourri3d: (set-up ms, solve ms, field)."""
    started = time.perf_counter()
    solver = pp3d.MeshHeatMethodDistanceSolver(vertices, faces)
    factored = time.perf_counter()
    field = solver.compute_distance(0)
    solved = time.perf_counter()
    return (factored - started) * 1e3, (solved - factored) * 1e3, field


def theirs_in_a_process(obj, runs, field_path):
    """Runs potpourri3d `runs` times in a fresh process: ([(set-up ms, solve ms)], peak MB);
    the last field is saved to `field_path`."""
    process = subprocess.Popen(
        [sys.executable, __file__, "--theirs", obj, "--runs", str(runs), "--field", field_path],
        stdout=subprocess.PIPE,
        text=True,
    )
    output = process.stdout.read()
    _, status, usage = os.wait4(process.pid, 0)
    if os.waitstatus_to_exitcode(status) != 0:
        raise SystemExit("the potpourri3d process failed")
    return json.loads(output), usage.ru_maxrss / 1024


def run_theirs(obj, runs, field_path):
    """The `--theirs` mode: times potpourri3d on `obj`, prints the times as JSON."""
    vertices, faces = pp3d.read_mesh(obj)
    results = [theirs(vertices, faces) for _ in range(runs)]
    np.save(field_path, results[-1][2])
    print(json.dumps([(setup, solve) for setup, solve, _ in results]))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--veneer", default="target/release/veneer")
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--meshes", nargs="+", default=MESHES, help="primitives to compare (default: %(default)s)")
    parser.add_argument("--theirs", help=argparse.SUPPRESS)
    parser.add_argument("--field", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.theirs:
        run_theirs(args.theirs, args.runs, args.field)
        return
    header = f"{'mesh':<12}{'triangles':>10}{'set-up ours':>13}{'theirs':>9}{'ratio':>7}{'solve ours':>12}{'theirs':>9}{'ratio':>7}{'peak MB ours':>14}{'theirs':>8}{'field diff':>12}"
    print(header)
    print("-" * len(header))
    with tempfile.TemporaryDirectory() as folder:
        for name in args.meshes:
            obj = primitive_obj(args.veneer, folder, name)
            csv = str(Path(folder) / "field.csv")
            faces = pp3d.read_mesh(obj)[1]
            ours = [veneer_run(args.veneer, obj, csv) for _ in range(args.runs)]
            field_path = str(Path(folder) / "theirs.npy")
            their_runs, their_peak = theirs_in_a_process(obj, args.runs, field_path)
            our_setup = statistics.median(o[0] for o in ours)
            our_solve = statistics.median(o[1] for o in ours)
            their_setup = statistics.median(t[0] for t in their_runs)
            their_solve = statistics.median(t[1] for t in their_runs)
            our_field = np.loadtxt(csv)
            their_field = np.load(field_path)
            difference = np.mean(relative_differences(our_field, their_field))
            print(
                f"{name:<12}{len(faces):>10}{our_setup:>11.1f}ms{their_setup:>7.1f}ms{our_setup / their_setup:>7.2f}"
                f"{our_solve:>10.1f}ms{their_solve:>7.1f}ms{our_solve / their_solve:>7.2f}"
                f"{ours[-1][2]:>14.0f}{their_peak:>8.0f}{difference:>11.2%}"
            )
    print(f"(median of {args.runs} runs each; ratio = ours / theirs)")


if __name__ == "__main__":
    main()
