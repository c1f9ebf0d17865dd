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
