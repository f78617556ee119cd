"""The image and extension-type telemetry helpers (TelemetryPublisher.image, .image_state,
.custom), the synthetic pictures and the simulator's plausible values, without a network:
K10's generated classes, a node that records what would be written (each sample encoded
and decoded as on the wire)."""
from __future__ import annotations

import importlib
import sys

import pytest

from rapid_runtime import images
from rapid_runtime import messages as M
from rapid_runtime.bridge import TelemetryPublisher
from rapid_runtime.configs import Serials
from rapid_runtime.telemetry import TelemetryError, typed_values
from tests.runtime.live import SEEDS, python_dir
from tests.runtime.tables_of import tables


@pytest.fixture(scope="module")
def rapid():
    path = str(python_dir("k10"))
    sys.path.insert(0, path)
    try:
        return importlib.import_module(f"{SEEDS['k10']}.rapid")
    finally:
        sys.path.remove(path)


class Node:
    def __init__(self) -> None:
        self.written: list[tuple[str, object]] = []

    def writer(self, topic, cls, keep_last=None):
        node = self

        class Writer:
            def write(self, sample):
                assert isinstance(sample, cls)
                node.written.append((topic, cls.deserialize(sample.serialize())))
        return Writer()


class FakeBridge:
    def __init__(self, rapid) -> None:
        self.tables, self.rapid, self.name = tables("k10"), rapid, "K10Red"
        self.serials, self.node = Serials(1_700_000_000), Node()


@pytest.fixture
def tel(rapid):
    return TelemetryPublisher(FakeBridge(rapid))


def test_image_takes_size_and_type_from_the_pictures_header(tel):
    png = images.synthetic("image/png", 64, 48)
    tel.image(png, index=2, state=True)  # HazCamFront, declared image/png 640x480
    (st_topic, state), (topic, sample) = tel.b.node.written
    assert (st_topic, topic) == ("rapid_imagesensor_state-hazCam", "rapid_imagesensor_sample-hazCam")
    assert sample.mimeType == "image/png" and bytes(sample.data) == png
    assert (sample.meta.width, sample.meta.height) == (64, 48) == (state.meta.width, state.meta.height)
    assert (sample.meta.sensorName, sample.meta.sensorType) == ("HazCamFront", "stereo-left")
    assert sample.meta.offset.rot == pytest.approx(M.IDENTITY)
    assert sample.hdr.assetName == "K10Red" and sample.hdr.serial == 1_700_000_000


def test_image_without_a_known_header_uses_the_arguments_then_the_declaration(tel):
    tel.image(b"\x00" * 100, index=0)
    _t, s = tel.b.node.written[-1]
    assert (s.mimeType, s.meta.width, s.meta.height, s.meta.sensorName) == ("image/jpeg", 1360, 1024, "PanCamLeft")
    tel.image(b"\x00" * 100, mime="image/x-raw8", width=10, height=10, index=0,
              extras={"IMG_H_FOV": ("RAPID_FLOAT", 0.8), "gain": 2})
    _t, s = tel.b.node.written[-1]
    assert (s.mimeType, s.meta.width) == ("image/x-raw8", 10)
    assert [(e.key, M.union_value(e.value)) for e in s.meta.extras] == [
        ("IMG_H_FOV", ("RAPID_FLOAT", pytest.approx(0.8))), ("gain", ("RAPID_INT", 2))]


def test_image_refuses_what_contradicts_the_picture_or_does_not_fit(tel):
    jpeg = images.synthetic("image/jpeg", 32, 16)
    with pytest.raises(TelemetryError, match="mime 'image/png'"):
        tel.image(jpeg, mime="image/png")
    with pytest.raises(TelemetryError, match="width 33"):
        tel.image(jpeg, width=33)
    with pytest.raises(TelemetryError, match="holds 1048576"):
        tel.image(b"\x00" * (1048576 + 1))
    with pytest.raises(LookupError):
        tel.image(jpeg, index=3)  # K10 declares three cameras
    assert tel.b.node.written == []


def test_image_state_alone(tel):
    tel.image_state(index=1)
    topic, s = tel.b.node.written[-1]
    assert topic == "rapid_imagesensor_state-panCamRight"
    assert (s.meta.sensorName, s.meta.width, s.meta.height) == ("PanCamRight", 1360, 1024)


def test_custom_config_serial_and_samples(tel):
    b = tel.b
    first = tel.custom({"receiverModel": "NovAtel", "datum": "WGS84", "antennaOffset": [0, 0, 1.2]}, role="config")
    again = tel.custom({"receiverModel": "NovAtel", "datum": "WGS84", "antennaOffset": [0, 0, 1.2]}, role="config")
    assert first == again == 1_700_000_000 and len(b.node.written) == 1  # unchanged: not written again
    changed = tel.custom({"receiverModel": "NovAtel", "datum": "NAD83", "antennaOffset": [0, 0, 1.2]}, role="config")
    assert changed > first and len(b.node.written) == 2
    assert b.node.written[-1][0] == "rapid_ext_arc_gps_config" and b.node.written[-1][1].hdr.serial == changed
    assert tel.custom({"latitude": 47.1, "longitude": -119.3, "fixType": "GPS_FIX_RTK", "numSatellites": 11}) == changed
    topic, fix = b.node.written[-1]
    assert topic == "rapid_ext_arc_gps_sample" and fix.hdr.serial == changed and fix.hdr.assetName == "K10Red"
    assert (fix.latitude, fix.fixType.name, fix.numSatellites, fix.altitude) == (47.1, "GPS_FIX_RTK", 11, 0.0)


def test_custom_takes_an_instance_and_fills_its_header(tel, rapid):
    arc = importlib.import_module(f"{rapid.__name__}.ext.arc")
    mine = arc.GpsSample(latitude=1.0)
    tel.custom(mine)
    _t, s = tel.b.node.written[-1]
    assert s.latitude == 1.0 and s.hdr.assetName == "K10Red"
    assert mine.hdr.assetName == ""  # the caller's instance is left as it was


@pytest.mark.parametrize("values, why", [
    ({"speed": 1.0}, "no member speed"),
    ({"numSatellites": 2.5}, "an integer"),
    ({"numSatellites": 1 << 40}, "outside"),
    ({"fixType": "GPS_FIX_4D"}, "not one of GPS_FIX_NONE"),
    ({"latitude": "north"}, "a number"),
])
def test_custom_refuses_values_that_do_not_fit(tel, values, why):
    with pytest.raises(TelemetryError, match=why):
        tel.custom(values)
    with pytest.raises(TelemetryError, match="no state"):
        tel.custom({}, role="state")
    with pytest.raises(TelemetryError, match="36 bytes, at most 32"):
        tel.custom({"datum": "x" * 36}, role="config")


def test_typed_values():
    assert typed_values({"a": True, "b": 3, "c": 1 << 40, "d": 0.5, "e": "x", "f": (1, 2, 3),
                         "g": ("RAPID_FLOAT", 2)}) == [
        ("a", "RAPID_BOOL", True), ("b", "RAPID_INT", 3), ("c", "RAPID_LONGLONG", 1 << 40),
        ("d", "RAPID_DOUBLE", 0.5), ("e", "RAPID_STRING", "x"), ("f", "RAPID_VEC3d", [1.0, 2.0, 3.0]),
        ("g", "RAPID_FLOAT", 2.0)]
    with pytest.raises(TelemetryError):
        typed_values({"x": object()})
    with pytest.raises(TelemetryError):
        typed_values({"x": ("RAPID_VEC3d", [1, 2])})


def test_plausible_values_follow_the_body(rapid):
    from rapid_runtime.simulate import SITE, Here, plausible
    arc = importlib.import_module(f"{rapid.__name__}.ext.arc")
    home = plausible(arc.GpsSample, Here([0.0, 0.0, 0.0], 0.0, 0.0, "K10Red"))
    away = plausible(arc.GpsSample, Here([111.32, 0.0, 0.0], 0.0, 0.5, "K10Red"))
    assert (home.latitude, home.longitude, home.altitude) == pytest.approx(SITE)
    assert away.latitude - home.latitude == pytest.approx(0.001) and away.longitude == home.longitude
    assert home.fixType.name == "GPS_FIX_3D" and home.numSatellites == 9 and home.hdop == pytest.approx(0.9)
    cfg = plausible(arc.GpsConfig, Here([0.0, 0.0, 0.0], 0.0, 0.0, "K10Red"))
    assert cfg.datum == "WGS84" and len(cfg.antennaOffset) == 3
    for name in dir(rapid):  # every RAPID message encodes as filled (bounds kept)
        cls = getattr(rapid, name)
        if isinstance(cls, type) and issubclass(cls, M.IdlStruct):
            value = plausible(cls, Here([1.0, 2.0, 0.0], 0.1, 0.2, "K" * 40))
            assert cls.deserialize(value.serialize()) is not None


@pytest.mark.parametrize("mime", sorted(images.ENCODERS))
def test_synthetic_pictures_say_what_they_are(mime):
    data = images.synthetic(mime, 37, 21, heading=0.5, frame=9)
    info = images.describe(data)
    assert info is not None and (info.width, info.height) == (37, 21)
    assert images.ENCODERS[info.mime] == images.ENCODERS[mime] or {info.mime, mime} <= {
        "image/x-portable-pixmap", "image/x-portable-anymap"}
    assert images.synthetic(mime, 37, 21, heading=0.5, frame=9) == data  # the same scene, the same bytes
    assert images.synthetic(mime, 37, 21, heading=0.5, frame=10) != data  # the frame counter shows


def test_synthetic_refuses_what_it_cannot_paint():
    with pytest.raises(images.ImageError, match="image/tiff"):
        images.synthetic("image/tiff", 10, 10)
    with pytest.raises(images.ImageError):
        images.synthetic("image/png", 0, 10)
    assert images.describe(b"not a picture") is None and images.describe(b"\xff\xd8\xff") is None
