#!/usr/bin/python3
"""moraine: PNG files are valid, non-empty images.

    check_png.py FILE.png [FILE.png ...] [--min-colors N]

For each file: the PNG signature; every chunk whole with a correct CRC; IHDR
first, with a width and a height above zero and a valid bit depth and colour
type; PLTE for a palette image; the IDAT data decompresses (zlib) to exactly
the size the header announces, every scanline with a known filter; IEND last.
A non-interlaced image is then unfiltered and must hold at least N distinct
pixel values (default 2), so a blank image fails. Only the standard library
is needed."""

import struct
import sys
import zlib

SIGNATURE = b"\x89PNG\r\n\x1a\n"

# colour type: (channels, allowed bit depths)
COLOUR_TYPES = {0: (1, (1, 2, 4, 8, 16)), 2: (3, (8, 16)), 3: (1, (1, 2, 4, 8)), 4: (2, (8, 16)), 6: (4, (8, 16))}

# Adam7 passes: (x start, y start, x step, y step)
ADAM7 = ((0, 0, 8, 8), (4, 0, 8, 8), (0, 4, 4, 8), (2, 0, 4, 4), (0, 2, 2, 4), (1, 0, 2, 2), (0, 1, 1, 2))


class PngError(Exception):
    pass


def chunks(data):
    """[(type, payload)] after checking the signature and every CRC"""
    if not data.startswith(SIGNATURE):
        raise PngError("no PNG signature")
    pos, out = len(SIGNATURE), []
    while pos < len(data):
        if pos + 8 > len(data):
            raise PngError(f"chunk header cut short at byte {pos}")
        length, ctype = struct.unpack(">I4s", data[pos:pos + 8])
        end = pos + 8 + length + 4
        if end > len(data):
            raise PngError(f"chunk {ctype!r} cut short (file truncated)")
        payload = data[pos + 8:pos + 8 + length]
        (crc,) = struct.unpack(">I", data[pos + 8 + length:end])
        if zlib.crc32(ctype + payload) & 0xFFFFFFFF != crc:
            raise PngError(f"chunk {ctype!r} has a wrong CRC")
        out.append((ctype, payload))
        pos = end
        if ctype == b"IEND":
            break
    if not out or out[-1][0] != b"IEND":
        raise PngError("no IEND chunk (file truncated)")
    return out


def header(parts):
    if parts[0][0] != b"IHDR" or len(parts[0][1]) != 13:
        raise PngError("the first chunk is not a 13-byte IHDR")
    w, h, depth, colour, comp, filt, interlace = struct.unpack(">IIBBBBB", parts[0][1])
    if w == 0 or h == 0:
        raise PngError(f"empty image: {w} x {h}")
    if colour not in COLOUR_TYPES or depth not in COLOUR_TYPES[colour][1]:
        raise PngError(f"invalid colour type {colour} with bit depth {depth}")
    if comp != 0 or filt != 0 or interlace not in (0, 1):
        raise PngError(f"unknown compression {comp}, filter method {filt} or interlace {interlace}")
    return w, h, depth, colour, interlace


def row_bytes(width, depth, channels):
    return (width * channels * depth + 7) // 8


def expected_size(w, h, depth, channels, interlace):
    if not interlace:
        return h * (1 + row_bytes(w, depth, channels))
    total = 0
    for x0, y0, dx, dy in ADAM7:
        pw, ph = (w - x0 + dx - 1) // dx, (h - y0 + dy - 1) // dy
        if pw > 0 and ph > 0:
            total += ph * (1 + row_bytes(pw, depth, channels))
    return total


def paeth(a, b, c):
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    if pa <= pb and pa <= pc:
        return a
    return b if pb <= pc else c


def unfilter_row(ftype, cur, prev, bpp):
    """one scanline back to its bytes (PNG specification, section 9)"""
    n = len(cur)
    out = bytearray(cur)
    if ftype == 0:
        return out
    if ftype == 2:
        return bytearray((x + p) & 0xFF for x, p in zip(cur, prev))
    for i in range(n):
        a = out[i - bpp] if i >= bpp else 0
        if ftype == 1:
            out[i] = (out[i] + a) & 0xFF
        elif ftype == 3:
            out[i] = (out[i] + ((a + prev[i]) >> 1)) & 0xFF
        else:
            c = prev[i - bpp] if i >= bpp else 0
            out[i] = (out[i] + paeth(a, prev[i], c)) & 0xFF
    return out


def check_filters(raw, w, h, depth, channels):
    stride = row_bytes(w, depth, channels)
    for y in range(h):
        if raw[y * (stride + 1)] > 4:
            raise PngError(f"scanline {y} has unknown filter type {raw[y * (stride + 1)]}")


def distinct_pixels(raw, w, h, depth, channels, limit):
    """how many distinct pixel values the image holds, up to `limit`: the
    scan stops there, since unfiltering in Python is slow"""
    stride = row_bytes(w, depth, channels)
    bpp = max(1, channels * depth // 8)
    prev = bytearray(stride)
    seen = set()
    for y in range(h):
        start = y * (stride + 1)
        cur = unfilter_row(raw[start], raw[start + 1:start + 1 + stride], prev, bpp)
        if depth < 8:
            seen.update(cur)  # packed pixels: distinct bytes tell a blank image from another
        else:
            seen.update(bytes(cur[i:i + bpp]) for i in range(0, stride, bpp))
        if len(seen) >= limit:
            break
        prev = cur
    return len(seen)


def check_file(path, min_colors):
    with open(path, "rb") as f:
        data = f.read()
    if not data:
        raise PngError("empty file")
    parts = chunks(data)
    w, h, depth, colour, interlace = header(parts)
    types = [t for t, _ in parts]
    if colour == 3 and b"PLTE" not in types:
        raise PngError("a palette image without PLTE")
    idat = [i for i, t in enumerate(types) if t == b"IDAT"]
    if not idat:
        raise PngError("no IDAT chunk")
    if idat != list(range(idat[0], idat[-1] + 1)):
        raise PngError("IDAT chunks are not consecutive")
    try:
        raw = zlib.decompress(b"".join(parts[i][1] for i in idat))
    except zlib.error as e:
        raise PngError(f"image data does not decompress: {e}")
    channels = COLOUR_TYPES[colour][0]
    want = expected_size(w, h, depth, channels, interlace)
    if len(raw) != want:
        raise PngError(f"image data holds {len(raw)} bytes, the header announces {want}")
    colours = None
    if not interlace:
        check_filters(raw, w, h, depth, channels)
        colours = distinct_pixels(raw, w, h, depth, channels, max(min_colors, 2))
        if colours < min_colors:
            raise PngError(f"only {colours} distinct pixel value(s): a blank image")
    return w, h, colours


def main(argv):
    min_colors, files, args = 2, [], list(argv[1:])
    while args:
        a = args.pop(0)
        if a == "--min-colors" and args:
            min_colors = int(args.pop(0))
        else:
            files.append(a)
    if not files:
        print("usage: check_png.py FILE.png [FILE.png ...] [--min-colors N]", file=sys.stderr)
        return 2
    passed = failed = 0
    for path in files:
        try:
            w, h, colours = check_file(path, min_colors)
            passed += 1
            print(f"{path}: {w} x {h}" + (f", at least {colours} distinct pixel values" if colours else ""))
        except (OSError, PngError) as e:
            failed += 1
            print(f"FAIL: {path}: {e}", file=sys.stderr)
    print(f"check_png: {passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
