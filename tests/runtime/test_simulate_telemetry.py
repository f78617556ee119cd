"""Live: each seed asset's simulated bridge (`python -m <package>.bridge --simulate`)
publishes every telemetry topic its descriptor declares, and a ground process that joins
late reads each one (tests/runtime/telemetry_ground.py) with the generated classes: every
topic arrives and decodes, headers name the asset and carry their config's serial, rated
topics come at about their rate, pictures have the declared size, MIME type and sensor and
are whole PNG or baseline JPEG files (checked here by an independent reader: PNG chunks,
CRCs and inflated size; every JPEG block Huffman-decoded to the end of the image), GPS fixes
are plausible. Domains 50-55; a helper's unit checks need no network."""
from __future__ import annotations

import base64
import json
import math
import struct
import subprocess
import sys
import zlib

import pytest

from tests.runtime.live import ROOT, SEEDS, BridgeProcess, env_for, python_dir
from tests.runtime.tables_of import tables

DOMAIN = 50
SECONDS = 25  # the ground side's bound; it stops once every topic has shown enough


# ---- an independent reader of the pictures' bytes ---------------------------------------------

def png_size(data: bytes) -> tuple[int, int, int]:
    """(width, height, channels) of a whole PNG: signature, every chunk's CRC, IHDR first and
    IEND last, the inflated IDAT exactly the size IHDR says with a valid filter per row."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n", data[:8]
    pos, kinds, idat, ihdr = 8, [], b"", None
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + length]
        (crc,) = struct.unpack(">I", data[pos + 8 + length:pos + 12 + length])
        assert zlib.crc32(kind + body) & 0xFFFFFFFF == crc, f"bad CRC in {kind!r}"
        kinds.append(kind)
        if kind == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    assert kinds[0] == b"IHDR" and kinds[-1] == b"IEND" and ihdr is not None, kinds
    width, height, depth, colour, _c, _f, interlace = ihdr
    channels = {0: 1, 2: 3, 4: 2, 6: 4}[colour]
    assert depth == 8 and interlace == 0
    raw = zlib.decompress(idat)
    stride = 1 + width * channels
    assert len(raw) == height * stride
    assert all(raw[r * stride] <= 4 for r in range(height))
    return width, height, channels


def jpeg_size(data: bytes) -> tuple[int, int, int]:
    """(width, height, components) of a whole baseline JPEG: its segments, then every block
    of every MCU Huffman-decoded (DC and AC) with its own tables, ending at EOI."""
    assert data[:2] == b"\xff\xd8"
    i, tables, frame, scan = 2, {}, None, None
    while scan is None:
        assert data[i] == 0xFF, f"no marker at {i}"
        marker = data[i + 1]
        (length,) = struct.unpack(">H", data[i + 2:i + 4])
        body = data[i + 4:i + 2 + length]
        assert marker not in (0xD9, 0xDD), "EOI or restart intervals before the scan"
        assert marker not in (0xC2, 0xC3, 0xC5, 0xC6, 0xC7, 0xC9, 0xCA, 0xCB, 0xCD, 0xCE, 0xCF), "not baseline"
        if marker in (0xC0, 0xC1):
            _p, h, w, n = struct.unpack(">BHHB", body[:6])
            frame = (w, h, [(body[6 + 3 * k], body[7 + 3 * k] >> 4, body[7 + 3 * k] & 15) for k in range(n)])
        elif marker == 0xC4:
            b = body
            while b:
                counts, k = b[1:17], 17
                codes, code = {}, 0
                for length_, count in enumerate(counts, start=1):
                    for _ in range(count):
                        codes[(length_, code)] = b[k]
                        code, k = code + 1, k + 1
                    code <<= 1
                tables[(b[0] >> 4, b[0] & 15)] = codes
                b = b[k:]
        elif marker == 0xDA:
            ns = body[0]
            scan = {body[1 + 2 * k]: (body[2 + 2 * k] >> 4, body[2 + 2 * k] & 15) for k in range(ns)}
        i += 2 + length
    assert frame is not None
    w, h, comps = frame
    # the entropy-coded data: unstuff FF00 up to the next marker, which must be EOI
    out, j = bytearray(), i
    while True:
        byte = data[j]
        if byte == 0xFF:
            if data[j + 1] == 0x00:
                out.append(0xFF)
                j += 2
                continue
            assert data[j + 1] == 0xD9 and j + 2 == len(data), f"marker {data[j + 1]:02X} at {j} of {len(data)}"
            break
        out.append(byte)
        j += 1
    bits = "".join(format(x, "08b") for x in out)
    pos = 0

    def decode(table) -> int:
        nonlocal pos
        code = 0
        for length_ in range(1, 17):
            code = code << 1 | (bits[pos] == "1")
            pos += 1
            if (length_, code) in table:
                return table[(length_, code)]
        raise AssertionError(f"no Huffman code at bit {pos}")

    hmax, vmax = max(c[1] for c in comps), max(c[2] for c in comps)
    mcus = math.ceil(w / (8 * hmax)) * math.ceil(h / (8 * vmax))
    for _ in range(mcus):
        for cid, hs, vs in comps:
            dc_t, ac_t = scan[cid]
            for _b in range(hs * vs):
                category = decode(tables[(0, dc_t)])  # DC: category, then that many bits
                pos += category  # (not `pos += decode(...)`: decode moves pos first)
                k = 1
                while k < 64:
                    rs = decode(tables[(1, ac_t)])
                    if rs == 0:
                        break  # end of block
                    k += (rs >> 4) + 1
                    pos += rs & 15
    rest = bits[pos:]
    assert len(rest) < 8 and set(rest) <= {"1"}, f"{len(rest)} bits left over"
    return w, h, len(comps)


def picture_size(mime: str, data: bytes) -> tuple[int, int, int]:
    return {"image/png": png_size, "image/jpeg": jpeg_size}[mime](data)


def octets(value) -> bytes:
    return base64.b64decode(value["base64"]) if isinstance(value, dict) else bytes(value)


def test_the_independent_reader_refuses_damaged_pictures():
    from rapid_runtime import images
    for mime in ("image/png", "image/jpeg"):
        good = images.synthetic(mime, 100, 60, heading=1.0, frame=3)
        assert picture_size(mime, good) == (100, 60, 3)
        assert images.describe(good) == images.ImageInfo(mime, 100, 60, 3)
        for bad in (good[:-40] + good[-2:], good[:len(good) // 2]):
            with pytest.raises((AssertionError, IndexError, zlib.error, struct.error)):
                picture_size(mime, bad)
    assert picture_size("image/jpeg", images.synthetic("image/jpeg", 17, 9, grey=True)) == (17, 9, 1)
    assert picture_size("image/png", images.synthetic("image/png", 17, 9, grey=True)) == (17, 9, 1)


# ---- live ---------------------------------------------------------------------------------------

def read(asset: str, domain: int) -> dict:
    pydir, package = python_dir(asset), SEEDS[asset]
    bridge = BridgeProcess(pydir, package, domain)
    try:
        bridge.wait_ready()
        res = subprocess.run([sys.executable, "-m", "tests.runtime.telemetry_ground", str(pydir), package, str(domain),
                              str(SECONDS)], cwd=ROOT, env=env_for(pydir, package), capture_output=True, text=True,
                             timeout=120)
    finally:
        err = bridge.stop()
    assert res.returncode == 0, res.stderr[-3000:] + err[-2000:]
    got = json.loads(res.stdout)
    got["bridge_log"] = err
    return got


@pytest.mark.parametrize("asset", sorted(SEEDS))
def test_every_declared_telemetry_topic_arrives_and_decodes(asset):
    got = read(asset, DOMAIN + sorted(SEEDS).index(asset))
    topics, name = got["topics"], got["asset"]
    assert "not sent" not in got["bridge_log"], got["bridge_log"][-2000:]
    missing = [t for t, g in topics.items() if not g["at"]]
    assert not missing, f"nothing on {missing}"
    entries = tables(asset).telemetry
    for t in entries:
        config = t["topics"].get("config")
        serial = topics[config]["first"]["hdr"]["serial"] if config else None
        for role, topic in t["topics"].items():
            g = topics[topic]
            for s in (g["first"], g["last"]):
                assert s["hdr"]["assetName"] == name and s["hdr"]["srcName"], (topic, s["hdr"])
                if serial is not None:
                    assert s["hdr"]["serial"] == serial, (topic, s["hdr"], serial)
            if t.get("rate") and role != "config" and len(g["at"]) >= 3:
                hz = (len(g["at"]) - 1) / (g["at"][-1] - g["at"][0])
                assert 0.5 * t["rate"] <= hz <= 1.5 * t["rate"], (topic, hz, t["rate"])
        if t["kind"] == "image":
            mime = t.get("mime") or "image/jpeg"
            for role in ("state", "sample"):
                for s in (topics[t["topics"][role]]["first"], topics[t["topics"][role]]["last"]):
                    meta = s["meta"]
                    assert (meta["width"], meta["height"]) == (t["width"], t["height"]), (role, meta)
                    assert (meta["sensorName"], meta["sensorType"]) == (t["sensor"], t["sensor_type"])
            for s in (topics[t["topics"]["sample"]]["first"], topics[t["topics"]["sample"]]["last"]):
                assert s["mimeType"] == mime
                w, h, channels = picture_size(mime, octets(s["data"]))
                assert (w, h) == (t["width"], t["height"])
                assert channels == (1 if "mono" in (t.get("sensor_type") or "") else 3)
        if t["kind"] == "custom" and "GpsSample" in t["types"].get("sample", ""):
            fix = topics[t["topics"]["sample"]]["last"]
            assert -90 <= fix["latitude"] <= 90 and -180 <= fix["longitude"] <= 180
            assert (fix["latitude"], fix["longitude"]) != (0, 0) and fix["numSatellites"] >= 4
            assert fix["fixType"] != "GPS_FIX_NONE" and 0 < fix["hdop"] < 5
            assert topics[t["topics"]["config"]]["first"]["datum"] == "WGS84"
    for a in got["asked"]:  # picture commands (K10's PanCam) answered OK, pictures seen above
        assert a["acks"][-1][:2] == ["ACK_COMPLETED", "ACK_COMPLETED_OK"], a
    if asset == "k10":
        assert {a["command"] for a in got["asked"]} == {"PanCam/takePicture", "PanCam/takePanorama"}
