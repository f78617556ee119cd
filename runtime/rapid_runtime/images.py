"""Image bytes, with the standard library only: what a picture's own header says (format,
width, height), and small synthetic pictures for the simulator.

`describe(data)` reads PNG, JPEG, GIF, BMP and PNM headers. `synthetic(mime, width, height,
...)` paints a landscape (sky, sun, ground with rocks, seen from a heading; a frame counter
in the bottom-left corner) on a grid of 8x8-pixel blocks and encodes it as the MIME type
asks: PNG (zlib), baseline JPEG (one DC coefficient per block: the JPEG shows exactly the
block grid), BMP or PNM. Pictures are small (a 1360x1024 JPEG is about 30 KB), so they fit
ImageSensorSample.data (at most 1 MiB) with room to spare.
"""
from __future__ import annotations

import math
import struct
import zlib
from dataclasses import dataclass

BLOCK = 8  # pixels per block side (one JPEG block)


class ImageError(ValueError):
    """No synthetic picture for that MIME type, or a size that cannot be painted."""


@dataclass(frozen=True)
class ImageInfo:
    mime: str
    width: int
    height: int
    channels: int  # 1 grey, 3 colour (4 with alpha; 0 unknown)


# ---- reading a header ------------------------------------------------------------------------

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
_SOF = {0xC0, 0xC1, 0xC2, 0xC3, 0xC5, 0xC6, 0xC7, 0xC9, 0xCA, 0xCB, 0xCD, 0xCE, 0xCF}


def describe(data: bytes) -> ImageInfo | None:
    """The format and size the bytes' own header gives, or None when they are none of PNG,
    JPEG, GIF, BMP or PNM (raw pixels, another format, or a damaged header)."""
    data = bytes(data[:65536]) if not isinstance(data, bytes) else data
    try:
        if data.startswith(PNG_SIGNATURE) and data[12:16] == b"IHDR":
            w, h, _depth, colour = struct.unpack(">IIBB", data[16:26])
            return ImageInfo("image/png", w, h, {0: 1, 2: 3, 3: 3, 4: 2, 6: 4}.get(colour, 0))
        if data.startswith(b"\xff\xd8"):
            return _jpeg_info(data)
        if data[:6] in (b"GIF87a", b"GIF89a"):
            w, h = struct.unpack("<HH", data[6:10])
            return ImageInfo("image/gif", w, h, 3)
        if data.startswith(b"BM") and len(data) >= 26:
            w, h = struct.unpack("<ii", data[18:26])
            return ImageInfo("image/bmp", w, abs(h), 3)
        if data[:2] in (b"P5", b"P6"):
            fields = data[2:64].split()
            if len(fields) >= 3:
                return ImageInfo("image/x-portable-graymap" if data[1:2] == b"5" else "image/x-portable-pixmap",
                                 int(fields[0]), int(fields[1]), 1 if data[1:2] == b"5" else 3)
    except (struct.error, ValueError, IndexError):
        return None
    return None


def _jpeg_info(data: bytes) -> ImageInfo | None:
    i = 2
    while i + 4 <= len(data):
        if data[i] != 0xFF:
            return None
        marker = data[i + 1]
        if marker == 0xFF:  # fill byte
            i += 1
            continue
        if marker in (0xD8, 0x01) or 0xD0 <= marker <= 0xD7:
            i += 2
            continue
        length = struct.unpack(">H", data[i + 2:i + 4])[0]
        if marker in _SOF:
            _precision, h, w, n = struct.unpack(">BHHB", data[i + 4:i + 10])
            return ImageInfo("image/jpeg", w, h, n)
        if marker in (0xDA, 0xD9):  # scan or end before any frame header
            return None
        i += 2 + length
    return None


# ---- painting --------------------------------------------------------------------------------

def _noise(i: int, j: int) -> int:
    """A fixed pseudo-random 0..65535 per block (the same rock is seen again from the same heading)."""
    h = (i * 73856093) ^ (j * 19349663) ^ 0x5BD1E995
    h = (h ^ (h >> 13)) * 0x5BD1E995 & 0xFFFFFFFF
    return (h ^ (h >> 15)) & 0xFFFF


def scene(bw: int, bh: int, heading: float = 0.0, frame: int = 0) -> list[list[tuple[int, int, int]]]:
    """bh rows of bw RGB blocks: a landscape seen from `heading` (rad; the view pans as it
    turns, a full turn being four picture widths) and `frame` in binary, bottom left."""
    horizon = max(1, int(bh * 0.45))
    shift = int(round(heading / math.tau * bw * 4))
    sun_c, sun_r = int((0.7 * bw - heading / math.tau * bw * 4) % (bw * 4)), max(0, horizon // 3)
    sun_rad = max(1.0, bw / 24)
    rows = []
    for r in range(bh):
        row = []
        if r < horizon:  # sky: deep blue above, pale at the horizon
            t = r / horizon
            base = (int(70 + 110 * t), int(120 + 90 * t), int(200 + 40 * t))
            for c in range(bw):
                if math.hypot(c - sun_c, r - sun_r) <= sun_rad:
                    row.append((255, 244, 200))
                else:
                    row.append(base)
        else:  # ground: ochre, darker towards the viewer, scattered rocks
            t = (r - horizon) / max(1, bh - horizon)
            for c in range(bw):
                n = _noise(c + shift, r)
                shade = int(20 * (n & 0xFF) / 255) - 10
                g = (int(170 - 60 * t) + shade, int(120 - 45 * t) + shade, int(80 - 30 * t) + shade)
                if n >> 8 < max(2, int(12 * t)):  # rocks, more of them nearby
                    g = (g[0] // 2, g[1] // 2, g[2] // 2)
                row.append(g)
        rows.append(row)
    n = min(16, bw)
    for bit in range(n):  # the frame counter, its lowest n bits: white 1s, black 0s
        rows[bh - 1][bit] = (255, 255, 255) if frame >> (n - 1 - bit) & 1 else (0, 0, 0)
    return rows


def _grey(rgb: tuple[int, int, int]) -> int:
    r, g, b = rgb
    return max(0, min(255, int(0.299 * r + 0.587 * g + 0.114 * b + 0.5)))


# ---- encoders --------------------------------------------------------------------------------

def _expand_rows(blocks, width: int, height: int, grey: bool):
    """Pixel rows (bytes) of the block grid, each block BLOCK pixels square, cut to size."""
    px = 1 if grey else 3
    for r in range(height):
        if r % BLOCK == 0:
            line = b"".join((bytes((_grey(c),)) if grey else bytes(c)) * BLOCK for c in blocks[r // BLOCK])
            line = line[:width * px]
        yield line


def png(blocks, width: int, height: int, grey: bool = False) -> bytes:
    def chunk(kind: bytes, body: bytes) -> bytes:
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)
    raw = b"".join(b"\x00" + line for line in _expand_rows(blocks, width, height, grey))
    ihdr = struct.pack(">IIBBBBB", width, height, 8, 0 if grey else 2, 0, 0, 0)
    return PNG_SIGNATURE + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b"")


def bmp(blocks, width: int, height: int) -> bytes:
    stride = (width * 3 + 3) & ~3
    lines = [bytes(v for px in zip(line[2::3], line[1::3], line[0::3]) for v in px).ljust(stride, b"\x00")
             for line in _expand_rows(blocks, width, height, False)]
    body = b"".join(reversed(lines))  # bottom-up, BGR
    head = struct.pack("<2sIHHI", b"BM", 54 + len(body), 0, 0, 54)
    info = struct.pack("<IiiHHIIiiII", 40, width, height, 1, 24, 0, len(body), 2835, 2835, 0, 0)
    return head + info + body


def pnm(blocks, width: int, height: int, grey: bool) -> bytes:
    head = f"{'P5' if grey else 'P6'}\n{width} {height}\n255\n".encode()
    return head + b"".join(_expand_rows(blocks, width, height, grey))


# Baseline JPEG, one DC coefficient per 8x8 block and every AC coefficient zero: the
# standard DC luminance Huffman table (ITU T.81 Annex K.3) and an AC table with one code
# (end of block). A flat block of value v has DC = 8 (v - 128); with quantizer 8 that is v - 128.
_DC_BITS = (0, 1, 5, 1, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0)
_DC_VALUES = tuple(range(12))
_AC_BITS = (1,) + (0,) * 15
_AC_VALUES = (0x00,)
_DC_QUANT = 8


def _huffman_codes(bits, values) -> dict[int, str]:
    codes, code, k = {}, 0, 0
    for length, count in enumerate(bits, start=1):
        for _ in range(count):
            codes[values[k]] = format(code, f"0{length}b")
            code += 1
            k += 1
        code <<= 1
    return codes


_DC_CODES = _huffman_codes(_DC_BITS, _DC_VALUES)
_EOB = _huffman_codes(_AC_BITS, _AC_VALUES)[0x00]
# the bits of one block per DC difference (-2047..2047): category code, magnitude, EOB
_BLOCK_BITS: dict[int, str] = {}


def _block_bits(diff: int) -> str:
    bits = _BLOCK_BITS.get(diff)
    if bits is None:
        cat = abs(diff).bit_length()
        extra = "" if cat == 0 else format(diff if diff > 0 else diff + (1 << cat) - 1, f"0{cat}b")
        bits = _BLOCK_BITS[diff] = _DC_CODES[cat] + extra + _EOB
    return bits


def _segment(marker: int, body: bytes) -> bytes:
    return struct.pack(">BBH", 0xFF, marker, len(body) + 2) + body


def jpeg(blocks, width: int, height: int, grey: bool = False) -> bytes:
    if not 0 < width <= 65535 or not 0 < height <= 65535:
        raise ImageError(f"a JPEG is at most 65535 pixels a side, not {width}x{height}")
    ncomp = 1 if grey else 3
    ycc: dict[tuple, tuple] = {}  # colour -> quantized DC per component (few colours repeat a lot)

    def dcs(rgb):
        r, g, b = rgb
        if grey:
            return (max(-127, min(127, _grey(rgb) - 128)),)
        return (max(-127, min(127, int(round(0.299 * r + 0.587 * g + 0.114 * b)) - 128)),
                max(-127, min(127, int(round(-0.168736 * r - 0.331264 * g + 0.5 * b)))),
                max(-127, min(127, int(round(0.5 * r - 0.418688 * g - 0.081312 * b)))))
    bits: list[str] = []
    block_bits, pred = _block_bits, [0] * ncomp
    for row in blocks:
        for rgb in row:
            dc = ycc.get(rgb)
            if dc is None:
                dc = ycc[rgb] = dcs(rgb)
            for k in range(ncomp):  # one block per component per MCU (no subsampling)
                bits.append(block_bits(dc[k] - pred[k]))
                pred[k] = dc[k]
    stream = "".join(bits)
    stream += "1" * (-len(stream) % 8)  # pad with 1s
    scan = int(stream, 2).to_bytes(len(stream) // 8, "big") if stream else b""
    scan = scan.replace(b"\xff", b"\xff\x00")

    quant = bytes([_DC_QUANT] + [16] * 63)
    out = [b"\xff\xd8",
           _segment(0xE0, b"JFIF\x00\x01\x01\x00\x00\x01\x00\x01\x00\x00"),
           _segment(0xDB, b"\x00" + quant),
           _segment(0xC0, struct.pack(">BHHB", 8, height, width, ncomp)
                    + b"".join(bytes((k + 1, 0x11, 0)) for k in range(ncomp))),
           _segment(0xC4, b"\x00" + bytes(_DC_BITS) + bytes(_DC_VALUES)),
           _segment(0xC4, b"\x10" + bytes(_AC_BITS) + bytes(_AC_VALUES)),
           _segment(0xDA, bytes((ncomp,)) + b"".join(bytes((k + 1, 0x00)) for k in range(ncomp)) + b"\x00\x3f\x00"),
           scan, b"\xff\xd9"]
    return b"".join(out)


ENCODERS = {
    "image/png": "png", "image/jpeg": "jpeg", "image/jpg": "jpeg", "image/pjpeg": "jpeg",
    "image/bmp": "bmp", "image/x-bmp": "bmp", "image/x-ms-bmp": "bmp",
    "image/x-portable-graymap": "pgm", "image/x-portable-pixmap": "ppm", "image/x-portable-anymap": "ppm",
}


def can_paint(mime: str) -> bool:
    return mime.lower() in ENCODERS


def synthetic(mime: str, width: int, height: int, heading: float = 0.0, frame: int = 0,
              grey: bool = False) -> bytes:
    """A landscape of width x height pixels encoded as `mime` (ENCODERS); `grey` for a mono
    sensor. ImageError for another MIME type or a size below 1 pixel."""
    kind = ENCODERS.get(mime.lower())
    if kind is None:
        raise ImageError(f"no synthetic picture for MIME type {mime!r} (can paint: {', '.join(sorted(ENCODERS))})")
    if width < 1 or height < 1:
        raise ImageError(f"a picture of {width}x{height} pixels")
    blocks = scene(-(-width // BLOCK), -(-height // BLOCK), heading, frame)
    if kind == "png":
        return png(blocks, width, height, grey)
    if kind == "jpeg":
        return jpeg(blocks, width, height, grey)
    if kind == "bmp":
        return bmp(blocks, width, height)
    return pnm(blocks, width, height, kind == "pgm")  # the MIME type says which
