#!/usr/bin/env python3
"""Checks USD exports with the USD library itself (the `usd-core` package, which `.ci/run`
installs into target/python): each stage opens, has one mesh bound to one material whose
surface is a UsdPreviewSurface and whose MaterialX surface (`outputs:mtlx:surface`) is a
MaterialX node, every texture file resolves (inside a `.usdz` package or beside a
`.usda`), and USD's own validators report nothing — but that the MaterialX nodes' ids are
not in this build's shader registry (`usd-core` is built without MaterialX support).

    PYTHONPATH=target/python python3 tests/usd/check.py FILE.usda|FILE.usdz...

A `.usdz` must also read as a zip (its central directory too) with stored entries, the
layer first, each file 64-byte aligned.

Prints one line per file (`FILE: ok, N texture files, M points`) and exits with 1 if any fails.
"""

import sys
import zipfile

from pxr import Ar, Usd, UsdGeom, UsdShade, UsdValidation


def package_problems(path):
    """What a zip reader finds wrong with a `.usdz`: it must read as a zip whose entries
    are stored uncompressed, the layer first, each file's data 64-byte aligned."""
    try:
        with zipfile.ZipFile(path) as package:
            if package.testzip() is not None:
                return ["an entry's CRC does not match"]
            entries = package.infolist()
            found = []
            if not entries or not entries[0].filename.endswith((".usda", ".usdc", ".usd")):
                found.append("the first entry is not a USD layer")
            with open(path, "rb") as raw:
                data = raw.read()
            for entry in entries:
                if entry.compress_type != zipfile.ZIP_STORED:
                    found.append(f"{entry.filename} is compressed")
                offset = entry.header_offset
                name_length = int.from_bytes(data[offset + 26 : offset + 28], "little")
                extra_length = int.from_bytes(data[offset + 28 : offset + 30], "little")
                if (offset + 30 + name_length + extra_length) % 64 != 0:
                    found.append(f"{entry.filename} is not 64-byte aligned")
            return found
    except zipfile.BadZipFile as error:
        return [f"not a zip: {error}"]


def problems(path):
    """What is wrong with the stage at `path`, and a summary when nothing is."""
    if path.endswith(".usdz"):
        found = package_problems(path)
        if found:
            return found, ""
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
    textures = set()
    for prim in stage.Traverse():
        shader = UsdShade.Shader(prim)
        file = shader.GetInput("file") if shader else None
        if file:
            asset = file.Get()
            textures.add(asset.path)
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
    return found, f"{len(textures)} texture files, {points} points"


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
