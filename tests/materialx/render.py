#!/usr/bin/env python3
"""Renders one output of a MaterialX document with MaterialX's own GLSL shader generator and
GLSL renderer (the MaterialX Python package that `.ci/run` installs into target/python), over
a flat rectangle, so that the picture can be compared with the project's own flat renderer.

    PYTHONPATH=target/python python3 tests/materialx/render.py \
        DOC.mtlx OUTPUT_NAME X0,Z0,X1,Z1,Y SIZE OUT.png [domain-uv]

OUTPUT_NAME names a top-level `<output>` of the document, or a nodegraph's output written as
`graph/output`; its type must be color3 or float.

The picture follows the flat renderer's contract: pixel (i, j), counted from the top-left
(i = column, j = row), shows the output at object-space position

    (X0 + (X1 - X0) * (i + 0.5) / SIZE,  Y,  Z0 + (Z1 - Z0) * (j + 0.5) / SIZE)

with normal (0, 1, 0) and texcoord (0, 0) -- or, with `domain-uv`, the texcoord that puts
Veneer's uv at the point's place in the rectangle (u = (i + 0.5) / SIZE across, v =
(j + 0.5) / SIZE down, so texcoord (u, 1 - v), MaterialX counting v up), as Veneer's flat
view gives materials that read bitmaps or buffers; each channel is written as
round(255 * clamp(v, 0, 1)) with no colour-space conversion, as an 8-bit RGB PNG (a float
output goes to all three channels). It is drawn as a two-triangle quad at y = Y (a
temporary OBJ file) seen by an orthographic camera looking down -Y with -Z up, into a
32-bit float framebuffer (so nothing is quantised or sRGB-encoded before this script rounds;
MaterialX only sRGB-encodes into its 8-bit framebuffers), and no colour management system is
given to the generator, so no colour-space transform is emitted.

Custom `<nodedef>`s whose `<implementation target="genglsl" file="...">` files sit beside the
document are found: the document's folder is registered as a source-code search path (next to
the standard libraries').

Rendering needs an X display with GLX (Mesa's llvmpipe does on a machine without a GPU):
when DISPLAY is not set the script starts its own `Xvfb` on a free display and stops it at
exit. Exits with 1 and a message on stderr on any failure (the document does not read or is
invalid, the output is missing or of another type, shader generation fails, the GLSL does not
compile: the compiler log is printed).
"""

import atexit
import ctypes
import os
import shutil
import signal
import struct
import subprocess
import sys
import tempfile
import zlib

import MaterialX as mx

import documents


def fail(message):
    print(f"render.py: {message}", file=sys.stderr)
    sys.exit(1)


def start_xvfb():
    """Starts Xvfb on a free display (chosen by Xvfb itself through -displayfd) and points
    DISPLAY at it; it is stopped when the script exits."""
    xvfb = shutil.which("Xvfb")
    if not xvfb:
        fail("DISPLAY is not set and Xvfb is not installed")
    os.environ.setdefault("XDG_RUNTIME_DIR", tempfile.gettempdir())
    read_end, write_end = os.pipe()
    process = subprocess.Popen(
        [xvfb, "-displayfd", str(write_end), "-screen", "0", "64x64x24", "-nolisten", "tcp"],
        pass_fds=(write_end,),
        stdin=subprocess.DEVNULL,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        start_new_session=True,
    )
    os.close(write_end)

    def stop():
        if process.poll() is None:
            process.send_signal(signal.SIGTERM)
            try:
                process.wait(timeout=5)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()

    atexit.register(stop)
    number = b""
    with os.fdopen(read_end, "rb") as reader:
        while not number.endswith(b"\n"):
            chunk = reader.read(1)
            if not chunk:
                break
            number += chunk
    number = number.strip()
    if not number.isdigit():
        stop()
        log = process.stderr.read().decode(errors="replace") if process.stderr else ""
        fail(f"Xvfb did not start:\n{log}")
    os.environ["DISPLAY"] = f":{number.decode()}"


def write_png(path, size, rows):
    """Writes an 8-bit RGB PNG; rows: SIZE byte strings of 3 * SIZE bytes, top row first."""
    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    raw = b"".join(b"\x00" + row for row in rows)
    with open(path, "wb") as out:
        out.write(b"\x89PNG\r\n\x1a\n")
        out.write(chunk(b"IHDR", struct.pack(">IIBBBBB", size, size, 8, 2, 0, 0, 0)))
        out.write(chunk(b"IDAT", zlib.compress(raw, 9)))
        out.write(chunk(b"IEND", b""))


def parse_arguments(argv):
    if len(argv) not in (6, 7) or (len(argv) == 7 and argv[6] != "domain-uv"):
        fail("usage: render.py DOC.mtlx OUTPUT_NAME X0,Z0,X1,Z1,Y SIZE OUT.png [domain-uv]")
    _, document_path, output_name, rectangle, size, png_path = argv[:6]
    try:
        x0, z0, x1, z1, y = (float(value) for value in rectangle.split(","))
    except ValueError:
        fail(f"rectangle {rectangle!r} is not X0,Z0,X1,Z1,Y")
    if x0 == x1 or z0 == z1:
        fail(f"rectangle {rectangle!r} is empty")
    try:
        size = int(size)
    except ValueError:
        size = 0
    if size < 1:
        fail(f"size {argv[4]!r} is not a positive integer")
    return document_path, output_name, (x0, z0, x1, z1, y), size, png_path, len(argv) == 7


def find_output(document, name):
    if "/" in name:
        graph_name, _, output_name = name.partition("/")
        graph = document.getNodeGraph(graph_name)
        output = graph.getOutput(output_name) if graph else None
    else:
        output = document.getOutput(name)
    if output is None:
        fail(f"no output {name!r} in the document")
    if output.getType() not in ("color3", "float"):
        fail(f"output {name!r} is of type {output.getType()}, not color3 or float")
    return output


def check_images(document, document_path):
    """Fails unless every image file the document names loads with the renderer's loader
    (which reads PNG, JPEG, HDR and the like, not OpenEXR): MaterialX's renderer would
    otherwise draw black where it failed and go on."""
    import MaterialX.PyMaterialXRender as mx_render

    loader = mx_render.StbImageLoader.create()
    folder = os.path.dirname(os.path.abspath(document_path))
    for element in document.traverseTree():
        if (element.isA(mx.Input) and element.getType() == "filename"
                and element.getParent().isA(mx.Node) and element.getValueString()):
            path = os.path.join(folder, element.getValueString())
            if loader.loadImage(mx.FilePath(path)) is None:
                fail(f"{path}: MaterialX's image loader here cannot read it "
                     f"(it reads {', '.join(sorted(loader.supportedExtensions()))})")


def generate(document_path, output_name):
    import MaterialX.PyMaterialXGenGlsl as mx_glsl
    import MaterialX.PyMaterialXGenShader as mx_gen

    standard, search = documents.libraries()
    document, problem = documents.read_validated(document_path, standard)
    if problem:
        fail(f"{document_path}: {problem}")
    output = find_output(document, output_name)
    check_images(document, document_path)

    generator = mx_glsl.GlslShaderGenerator.create()
    context = mx_gen.GenContext(generator)
    context.registerSourceCodeSearchPath(search)
    context.registerSourceCodeSearchPath(
        mx.FilePath(os.path.dirname(os.path.abspath(document_path))))
    options = context.getOptions()
    options.hwSrgbEncodeOutput = False
    # OpenGL puts an image's first (top) row at t = 0; MaterialX's texture coordinates put
    # the image's bottom there, so the generated code flips t, as MaterialXView has it do.
    options.fileTextureVerticalFlip = True
    options.targetColorSpaceOverride = ""
    try:
        return generator.generate("render", output, context)
    except Exception as error:
        fail(f"shader generation for {output_name!r} failed: {error}")


def render(shader, rectangle, size, domain_uv, folder, work):
    import MaterialX.PyMaterialXRender as mx_render
    import MaterialX.PyMaterialXRenderGlsl as mx_renderglsl

    x0, z0, x1, z1, y = rectangle
    obj_path = os.path.join(work, "quad.obj")
    with open(obj_path, "w") as obj:
        obj.write(
            f"v {x0!r} {y!r} {z0!r}\nv {x1!r} {y!r} {z0!r}\n"
            f"v {x1!r} {y!r} {z1!r}\nv {x0!r} {y!r} {z1!r}\n"
            "vt 0 1\nvt 1 1\nvt 1 0\nvt 0 0\nvn 0 1 0\n"
            + ("f 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n" if domain_uv else
               "f 1/4/1 2/4/1 3/4/1\nf 1/4/1 3/4/1 4/4/1\n"))

    renderer = mx_renderglsl.GlslRenderer.create(size, size, mx_render.BaseType.FLOAT)
    try:
        renderer.initialize()
    except Exception as error:
        fail(f"OpenGL initialisation failed (DISPLAY={os.environ.get('DISPLAY')}): {error}")
    images = mx_renderglsl.GLTextureHandler.create(mx_render.StbImageLoader.create())
    # Image files named relative to the document are found beside it.
    images.setSearchPath(mx.FileSearchPath(folder))
    renderer.setImageHandler(images)
    renderer.setLightHandler(mx_render.LightHandler.create())
    geometry = renderer.getGeometryHandler()
    geometry.clearGeometry()
    if not geometry.loadGeometry(mx.FilePath(obj_path), False):
        fail("the quad geometry does not load")

    # Camera above the quad's centre looking down -Y, with -Z up (so +X is to the right
    # and +Z downward in the picture); the orthographic window is the rectangle itself,
    # so pixel centres fall on the contract's sample points.
    cx, cz = (x0 + x1) / 2, (z0 + z1) / 2
    hx, hz = (x1 - x0) / 2, (z1 - z0) / 2
    camera = mx_render.Camera.create()
    camera.setWorldMatrix(mx.Matrix44.IDENTITY)
    camera.setViewMatrix(mx_render.Camera.createViewMatrix(
        mx.Vector3(cx, y + 1.0, cz), mx.Vector3(cx, y, cz), mx.Vector3(0.0, 0.0, -1.0)))
    # The view maps world x - cx to view x and world z - cz to -(view y); a reversed
    # rectangle (X1 < X0 or Z1 < Z0) gives a mirrored window, which is what it asks for.
    camera.setProjectionMatrix(mx_render.Camera.createOrthographicMatrix(
        -hx, hx, -hz, hz, 0.5, 1.5))
    camera.setViewportSize(mx.Vector2(size, size))
    renderer.setCamera(camera)

    try:
        renderer.createProgram(shader)
    except Exception as error:
        fail(f"the generated GLSL does not compile:\n{error}")
    try:
        renderer.validateInputs()
        renderer.render()
        image = renderer.captureImage(None)
    except Exception as error:
        fail(f"rendering failed:\n{error}")

    width, height, channels = image.getWidth(), image.getHeight(), image.getChannelCount()
    if (width, height) != (size, size) or image.getBaseType() != mx_render.BaseType.FLOAT:
        fail("the captured image is not the float image asked for")
    data = ctypes.string_at(image.getResourceBuffer(), width * height * channels * 4)
    values = struct.unpack(f"{width * height * channels}f", data)
    rows = []
    # OpenGL reads rows bottom-up: the last row read is the picture's top row.
    for row in range(height - 1, -1, -1):
        line = bytearray()
        for column in range(width):
            base = (row * width + column) * channels
            for channel in range(3):
                value = values[base + channel]
                if value != value:  # NaN
                    value = 0.0
                # Half away from zero, like Rust's f32::round (Python's round() is to even).
                line.append(int(255.0 * min(max(value, 0.0), 1.0) + 0.5))
        rows.append(bytes(line))
    return rows


def main():
    document_path, output_name, rectangle, size, png_path, domain_uv = parse_arguments(sys.argv)
    shader = generate(document_path, output_name)
    if not os.environ.get("DISPLAY"):
        start_xvfb()
    work = tempfile.mkdtemp(prefix="mxrender")
    try:
        folder = os.path.dirname(os.path.abspath(document_path))
        rows = render(shader, rectangle, size, domain_uv, folder, work)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    write_png(png_path, size, rows)


if __name__ == "__main__":
    main()
