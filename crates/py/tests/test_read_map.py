"""stiction.read_map: an instrument file as a NumPy array with its metadata, the map the command
line reads (`stiction topography FILE --channel ... --json`)."""
import numpy as np
import pytest

import stiction
from conftest import ROOT

NID = ROOT / "data" / "topography-formats" / "nid-1.nid"


def test_read_map_gives_the_channel_in_metres_with_its_metadata(cli_json):
    heights, meta = stiction.read_map(NID, channel="Scan backward (Z-Axis)")
    assert heights.shape == (256, 256) and heights.dtype == np.float64
    assert meta["nx"] == 256 and meta["ny"] == 256 and meta["unit"] == "m"
    assert meta["pixel_size_x_m"] == pytest.approx(20e-6 / 256, rel=1e-12)
    assert meta["channel"]["index"] == 5 and meta["channel"]["chosen"] == "given"
    assert len(meta["channels"]) == 8 and meta["missing_pixels"] == 0
    # The same channel by index; the command line reads the same grid and pixel size.
    again, _ = stiction.read_map(NID, channel=5)
    assert np.array_equal(heights, again)
    e = cli_json("topography", NID, "--channel", "5")
    assert e["read"]["channel"]["index"] == 5 and e["read"]["missing_pixels"] == meta["missing_pixels"]


def test_read_map_names_a_missing_channel():
    with pytest.raises(stiction.StictionError, match="no channel 9"):
        stiction.read_map(NID, channel=9)


def test_topography_reads_an_instrument_file_as_the_command_line_does(cli_json):
    """stiction.topography(path, channel=...) gives the command line's statistics of the same
    file and channel (plane levelling; the same heights in metres and pixel sizes), to 1e-12."""
    r = stiction.topography(NID, channel=5)
    e = cli_json("topography", NID, "--channel", "5")
    assert r.summit_count == e["summit_count"] > 0
    for key in ["rms_height_m", "rms_slope", "summit_density_per_m2", "summit_radius_mean_m"]:
        assert getattr(r, key) == pytest.approx(e[key], rel=1e-12), key
    assert r.read["channel"]["name"] == "Scan backward (Z-Axis)"
    # A channel of the file by name is the same map.
    assert stiction.topography(NID, channel="Scan backward (Z-Axis)").rms_height_m == r.rms_height_m


def test_topography_refuses_a_channel_for_an_array_and_a_second_pixel_size_for_a_file():
    with pytest.raises(stiction.StictionError, match="channel"):
        stiction.topography(np.zeros((8, 8)), pixel_size="1 um", height_unit="nm", channel=1)
    with pytest.raises(stiction.StictionError, match="pixel_size_y"):
        stiction.topography(NID, pixel_size_y="1 um")


@pytest.mark.parametrize("kwargs, argument", [
    ({"channel": ""}, "channel"),
    ({"format": "tiff2"}, "format"),
    ({"height_unit": "furlong"}, "height_unit"),
    ({"pixel_size": "3 kg"}, "pixel_size"),
])
def test_read_map_names_a_bad_argument(kwargs, argument):
    """A bad argument is a StictionError naming it, as everywhere else in the package."""
    with pytest.raises(stiction.StictionError, match=f"^{argument}="):
        stiction.read_map(NID, **kwargs)
