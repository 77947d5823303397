#!/usr/bin/env python3
"""Checks MaterialX documents with the MaterialX library itself (its Python package, which
`.ci/run` installs into target/python): each file is read, validated against the
standard data libraries, and every renderable element in it is given to MaterialX's GLSL
shader generator, whose pixel and vertex stages are written beside the file as
`<file>.<element>.frag` and `.vert` for glslangValidator, and to its Metal generator, whose
pixel stage is written as `<file>.<element>.metal`.

    PYTHONPATH=target/python python3 tests/materialx/check.py FILE.mtlx...

Prints one line per file (`FILE: valid, 1 shader`) and exits with 1 if any file fails.
Compile the stages it writes with `glslangValidator FILE.mtlx.<element>.frag` (the tests
do); they are left beside the document.
"""

import sys

import MaterialX.PyMaterialXGenGlsl as glsl
import MaterialX.PyMaterialXGenMsl as msl
import MaterialX.PyMaterialXGenShader as shadergen

import documents


def main():
    standard, search = documents.libraries()
    failed = False
    for path in sys.argv[1:]:
        document, problem = documents.read_validated(path, standard)
        if problem:
            print(f"{path}: {problem}")
            failed = True
            continue
        elements = shadergen.findRenderableElements(document)
        targets = (
            (glsl.GlslShaderGenerator, ((shadergen.PIXEL_STAGE, "frag"), (shadergen.VERTEX_STAGE, "vert"))),
            (msl.MslShaderGenerator, ((shadergen.PIXEL_STAGE, "metal"),)),
        )
        for generator_class, stages in targets:
            generator = generator_class.create()
            context = shadergen.GenContext(generator)
            context.registerSourceCodeSearchPath(search)
            for element in elements:
                shader = generator.generate(element.getName(), element, context)
                for stage, extension in stages:
                    with open(f"{path}.{element.getName()}.{extension}", "w") as out:
                        out.write(shader.getSourceCode(stage))
        if not elements:
            print(f"{path}: nothing renderable")
            failed = True
            continue
        count = len(elements)
        print(f"{path}: valid, {count} shader{'' if count == 1 else 's'}")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
