"""Exits 0 when two EXR files hold the same pixels bit for bit (size, channel names, and every
channel's values compared as their bit patterns, so -0 and NaNs count too); else prints the first
difference and exits 1. Run with Debian's /usr/bin/python3 (OpenImageIO, numpy)."""

import sys

import numpy
import OpenImageIO as oiio


def pixels(path):
    image = oiio.ImageInput.open(path)
    if image is None:
        sys.exit(f"{path}: cannot be read: {oiio.geterror()}")
    spec = image.spec()
    data = image.read_image(oiio.FLOAT)
    image.close()
    return spec, data


def main(first, second):
    spec_a, a = pixels(first)
    spec_b, b = pixels(second)
    shape_a = (spec_a.width, spec_a.height, list(spec_a.channelnames))
    shape_b = (spec_b.width, spec_b.height, list(spec_b.channelnames))
    if shape_a != shape_b:
        print(f"{second}: {shape_b}, {first}: {shape_a}")
        return 1
    bits_a, bits_b = a.view(numpy.uint32), b.view(numpy.uint32)
    differ = numpy.argwhere(bits_a != bits_b)
    if len(differ):
        y, x, c = differ[0]
        print(f"{second}: {len(differ)} values differ from {first}; first at x={x} y={y} "
              f"channel {spec_a.channelnames[c]}: {b[y, x, c]!r} against {a[y, x, c]!r}")
        return 1
    print(f"{second}: bit-identical to {first} ({spec_a.width}x{spec_a.height}, "
          f"{spec_a.nchannels} channels)")
    return 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:3]))
