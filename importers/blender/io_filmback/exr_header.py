"""The string attributes of an OpenEXR file's header, read without an image library (Blender's
Python has none): what the render engine copies into the Render Result's metadata, such as
filmback's Cryptomatte manifests (docs/blender.md, "Cryptomatte").

The header (OpenEXR's file layout, "Header"): the magic number 20000630 and a version field, then
attributes, each a null-terminated name, a null-terminated type name, a 4-byte little-endian size
and that many bytes of value, ended by an empty name. A `string` value is its bytes, unterminated.
"""

import struct

EXR_MAGIC = 20000630
# OpenEXR caps attribute and type names at 255 bytes; a header past this is not one filmback wrote.
MOST_HEADER_BYTES = 16 * 1024 * 1024


def string_attributes(path):
    """{name: value} of the file's `string` attributes (the first part's, for a multi-part file).
    Raises ValueError for a file that is not an OpenEXR image or whose header is cut short."""
    with open(path, "rb") as f:
        data = f.read(MOST_HEADER_BYTES)
    if len(data) < 8 or struct.unpack_from("<i", data, 0)[0] != EXR_MAGIC:
        raise ValueError(f"{path}: not an OpenEXR file")
    strings = {}
    at = 8
    while True:
        name, at = _null_terminated(data, at, path)
        if not name:
            return strings
        kind, at = _null_terminated(data, at, path)
        if at + 4 > len(data):
            raise ValueError(f"{path}: header cut short in attribute '{name}'")
        size = struct.unpack_from("<i", data, at)[0]
        at += 4
        if size < 0 or at + size > len(data):
            raise ValueError(f"{path}: attribute '{name}' claims {size} bytes past the header")
        if kind == "string":
            strings[name] = data[at:at + size].decode("utf-8", errors="replace")
        at += size


def _null_terminated(data, at, path):
    end = data.find(b"\0", at)
    if end < 0:
        raise ValueError(f"{path}: header cut short")
    return data[at:end].decode("utf-8", errors="replace"), end + 1
