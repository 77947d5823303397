#!/usr/bin/env python3
"""Checks USD exports with the USD library itself (the `usd-core` package, which `.ci/run`
installs into target/python): each stage opens, has one mesh bound to one material whose
surface is a UsdPreviewSurface and whose MaterialX surface (`outputs:mtlx:surface`) is a
MaterialX node, every texture file resolves (inside a `.usdz` package or beside a
`.usda`), and USD's own validators report nothing — but that the MaterialX nodes' ids are
not in this build's shader registry (`usd-core` is built without MaterialX support).

    PYTHONPATH=target/python python3 tests/usd/check.py FILE.usda|FILE.usdz...

Prints one line per file (`FILE: ok, N textures, M points`) and exits with 1 if any fails.
"""

import sys

from pxr import Ar, Usd, UsdGeom, UsdShade, UsdValidation


def problems(path):
    """What is wrong with the stage at `path`, and a summary when nothing is."""
    stage = Usd.Stage.Open(path)
    meshes = [prim for prim in stage.Traverse() if prim.IsA(UsdGeom.Mesh)]
    if len(meshes) != 1:
        return [f"{len(meshes)} meshes"], ""
    mesh = UsdGeom.Mesh(meshes[0])
    material, _ = UsdShade.MaterialBindingAPI(meshes[0]).ComputeBoundMaterial()
    if not material:
        return ["no material bound to the mesh"], ""
    found = []
    preview = material.ComputeSurfaceSource()[0]
    if not preview or preview.GetIdAttr().Get() != "UsdPreviewSurface":
        found.append("the surface is not a UsdPreviewSurface")
    materialx = material.ComputeSurfaceSource("mtlx")[0]
    if not materialx or not str(materialx.GetIdAttr().Get()).startswith("ND_"):
        found.append("no MaterialX surface")
    textures = 0
    for prim in stage.Traverse():
        shader = UsdShade.Shader(prim)
        file = shader.GetInput("file") if shader else None
        if file:
            asset = file.Get()
            textures += 1
            if not asset.resolvedPath or not Ar.GetResolver().OpenAsset(Ar.ResolvedPath(asset.resolvedPath)):
                found.append(f"{prim.GetPath()}: {asset.path} does not resolve")
    registry = UsdValidation.ValidationRegistry()
    context = UsdValidation.ValidationContext(registry.GetOrLoadAllValidators())
    for error in context.Validate(stage):
        text = error.GetErrorAsString()
        if "MissingShaderIdInRegistry" in text and "shaderId 'ND_" in text:
            continue
        found.append(text)
    points = len(mesh.GetPointsAttr().Get())
    return found, f"{textures} textures, {points} points"


def main():
    failed = False
    for path in sys.argv[1:]:
        found, summary = problems(path)
        if found:
            failed = True
            print(f"{path}: " + "; ".join(found))
        else:
            print(f"{path}: ok, {summary}")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
