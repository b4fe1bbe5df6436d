"""Images the FILMBACK_blender extension names, written beside the exported file.

Texture and world descriptions are gathered while Blender's exporter walks the scene, but its own
texture files are written only when the walk ends (`GlTF2Exporter.finalize_images`), under names
of its choosing. So the extension's images are only *referred* to during the walk: `refer` records
the dict (and key) that will hold the image's URI, and `write`, called from the exporter's last
hook, picks file names that clash neither with Blender's files nor with each other, writes the
files and fills the URIs in.

How an image reaches the file, as Cycles 3.4 reads it (intern/cycles/blender/shader.cpp: packed
and generated images are read from Blender's memory, others from their file):
* a file on disk is copied byte for byte (or named where it lies when it already is beside the
  exported file and Blender's exporter wrote nothing there); a file lying where Blender's exporter
  writes is read when it is referred to, before the exporter can write its own texture over it;
* a packed image is written as its packed bytes (the original file), unless it has unsaved edits;
* a generated image, or a packed one with unsaved edits, is saved from its pixels: PNG, or
  OpenEXR (32-bit float) when the image is float.
"""

import os
import re
import shutil
import urllib.parse

import bpy

# Extensions of the formats Blender packs or saves, for packed images whose path has none.
FORMAT_EXTENSIONS = {"PNG": ".png", "JPEG": ".jpg", "OPEN_EXR": ".exr",
                     "OPEN_EXR_MULTILAYER": ".exr", "HDR": ".hdr", "TIFF": ".tif",
                     "TARGA": ".tga", "TARGA_RAW": ".tga", "BMP": ".bmp", "WEBP": ".webp"}

# The scene-linear colour space of Blender 3.4's OCIO config: what float pixels hold.
LINEAR = "Linear"

# Bound on the "-N" suffixes tried for one name (one per image of the export would do).
MAX_SUFFIX = 100000


def source_path(image):
    return os.path.abspath(bpy.path.abspath(image.filepath, library=image.library))


def problem(image):
    """Why `image` cannot be written beside the export, or None when it can."""
    if image.source == "GENERATED" or image.packed_file is not None:
        return None
    if image.source != "FILE":
        return f"is a {image.source} image (only single files, packed and generated images " \
               f"are carried)"
    if not os.path.isfile(source_path(image)):
        return f"has no file at '{source_path(image)}'"
    return None


def _saved_from_pixels(image):
    return image.source == "GENERATED" or (image.packed_file is not None and image.is_dirty)


def _wanted_name(image):
    if _saved_from_pixels(image):
        stem = os.path.splitext(image.name)[0] if image.source != "GENERATED" else image.name
        return stem + (".exr" if image.is_float else ".png")
    name = bpy.path.basename(image.filepath) or image.name
    if not os.path.splitext(name)[1]:
        name += FORMAT_EXTENSIONS.get(image.file_format, ".png")
    return name


def safe_name(name):
    """A plain file name: no folders, no leading dot, only letters, digits, '.', '_' and '-'
    (so that the URI is the name itself and resolves inside the export's folder)."""
    name = re.sub(r"[^A-Za-z0-9._-]", "_", os.path.basename(name)).lstrip(".")
    return name or "image.png"


def file_colorspace(image):
    """The colour space of the file the image is written as: its own, except that float pixels
    saved to OpenEXR are scene-linear whatever the image's setting."""
    if _saved_from_pixels(image) and image.is_float:
        return LINEAR
    return image.colorspace_settings.name


def file_alpha_mode(image):
    """How the written file holds alpha: the image's setting, except that float pixels saved to
    OpenEXR are Blender's premultiplied float buffer (OpenEXR's own convention too)."""
    if _saved_from_pixels(image) and image.is_float:
        return "PREMUL"
    return image.alpha_mode


class ImageFiles:
    def __init__(self, output_folders):
        """`output_folders`: where Blender's exporter writes files (the exported file's folder
        and its texture folder)."""
        self._output_folders = {os.path.abspath(f) for f in output_folders}
        self._entries = {}  # image pointer -> [image, [(dict, key), ...]]
        self._snapshots = {}  # image pointer -> the bytes of its file, read before Blender writes

    def refer(self, image, holder, key):
        """`holder[key]` will be the URI (relative to the exported file) of `image`, one that
        `problem` accepts, once the export ends."""
        pointer = image.as_pointer()
        entry = self._entries.setdefault(pointer, [image, []])
        entry[1].append((holder, key))
        if pointer not in self._snapshots and not _saved_from_pixels(image) and \
                image.packed_file is None and \
                os.path.dirname(source_path(image)) in self._output_folders:
            # Blender's exporter may write its own texture over a file lying where it writes
            # (same name, other content: a combined metallic-roughness image): keep the original.
            with open(source_path(image), "rb") as f:
                self._snapshots[pointer] = f.read()

    def write(self, folder, taken_paths):
        """Writes every referred image into `folder` (the exported file's) under a name that is
        none of `taken_paths` (absolute paths of files Blender's exporter wrote) nor another
        image's, and sets the URIs. Returns the names written."""
        folder = os.path.abspath(folder)
        taken = {os.path.normcase(os.path.abspath(p)) for p in taken_paths}
        names = {}
        # Files already beside the export keep their place and name: nothing else may take it.
        for pointer, (image, _) in self._entries.items():
            if not _saved_from_pixels(image) and image.packed_file is None:
                path = source_path(image)
                name = os.path.basename(path)
                if os.path.dirname(path) == folder and safe_name(name) == name and \
                        os.path.normcase(path) not in taken:
                    names[pointer] = name
                    taken.add(os.path.normcase(path))
        for pointer, (image, _) in self._entries.items():
            if pointer not in names:
                names[pointer] = self._unique(folder, safe_name(_wanted_name(image)), taken)
        for pointer, (image, holders) in self._entries.items():
            name = names[pointer]
            destination = os.path.join(folder, name)
            snapshot = self._snapshots.get(pointer)
            if snapshot is not None and source_path(image) != destination:
                with open(destination, "wb") as f:
                    f.write(snapshot)
            elif snapshot is None:
                _write_image(image, destination)
            for holder, key in holders:
                holder[key] = urllib.parse.quote(name)
        return sorted(names.values())

    @staticmethod
    def _unique(folder, name, taken):
        stem, extension = os.path.splitext(name)
        for n in range(MAX_SUFFIX):
            candidate = name if n == 0 else f"{stem}-{n}{extension}"
            path = os.path.normcase(os.path.join(folder, candidate))
            if path not in taken:
                taken.add(path)
                return candidate
        raise ValueError(f"no free file name for image '{name}' in {folder}")


def _write_image(image, destination):
    if _saved_from_pixels(image):
        _save_pixels(image, destination)
    elif image.packed_file is not None:
        with open(destination, "wb") as f:
            f.write(image.packed_file.data)
    elif os.path.abspath(source_path(image)) != os.path.abspath(destination):
        shutil.copyfile(source_path(image), destination)


def _save_pixels(image, destination):
    """Saves the image's pixels through a temporary copy (the user's image keeps its source and
    path): byte images as 8-bit PNG, float images as 32-bit OpenEXR, both lossless."""
    import numpy as np

    width, height = image.size
    pixels = np.empty(width * height * 4, dtype=np.float32)
    image.pixels.foreach_get(pixels)
    copy = bpy.data.images.new("filmback_export_copy", width, height, alpha=True,
                               float_buffer=image.is_float)
    try:
        if image.is_float:
            # Float pixels are scene-linear in Blender; saving converts them to the copy's colour
            # space, which Blender resets to sRGB on saving unless it is a data space.
            copy.colorspace_settings.name = "Non-Color"
        copy.pixels.foreach_set(pixels)
        copy.filepath_raw = destination
        copy.file_format = "OPEN_EXR" if image.is_float else "PNG"
        copy.save()
    finally:
        bpy.data.images.remove(copy)
