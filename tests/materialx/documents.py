"""What the MaterialX test scripts share: a document read and validated against MaterialX's
standard data libraries (the Python package `.ci/run` installs into target/python)."""

import MaterialX as mx


def libraries():
    """The standard data libraries, loaded once per call, and their search path."""
    search = mx.getDefaultDataSearchPath()
    loaded = mx.createDocument()
    mx.loadLibraries(mx.getDefaultDataLibraryFolders(), search, loaded)
    return loaded, search


def read_validated(path, standard):
    """The document at `path` with the `standard` libraries imported, or why not: returns
    (document, None) or (None, message)."""
    document = mx.createDocument()
    try:
        mx.readFromXmlFile(document, path)
    except Exception as error:  # MaterialX raises its own classes, not mx.Exception
        return None, f"does not read: {error}"
    document.importLibrary(standard)
    valid, message = document.validate()
    if not valid:
        return None, f"invalid: {message}"
    return document, None
