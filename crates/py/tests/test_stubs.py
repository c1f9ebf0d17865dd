"""The type stubs (stiction/__init__.pyi) against the installed module: every public name, every
signature (mypy's stubtest), and mypy accepting typed use and refusing a wrong type."""

import subprocess
import sys
import textwrap

import pytest


def _mypy(*args):
    pytest.importorskip("mypy")
    return subprocess.run([sys.executable, "-m", *args], capture_output=True, text=True)


def test_stubs_cover_every_public_name_with_its_signature():
    p = _mypy("mypy.stubtest", "stiction")
    assert p.returncode == 0, p.stdout + p.stderr


def test_mypy_checks_a_script_against_the_stubs(tmp_path):
    good = tmp_path / "good.py"
    good.write_text(textwrap.dedent('''
        import numpy as np
        import stiction
        r = stiction.run({"format_version": 1})
        mu: float = r.mu_apparent
        g = stiction.gw(2.0, np.array([0.5, 1.0]))
        s = stiction.Scenario.load("scenarios/tas2000.json")
        s.set("surface.summit_sd", "50 nm")
        t = stiction.topography(np.zeros((4, 4)), pixel_size="1 um", scenario=s)
        b = stiction.bem(scenario="scenarios/tas2000-height-map.json", pressure="5 MPa")
        gen = stiction.bem(pressure=5e6, grid=16, hurst=0.8, seed=2, rh=np.array([0.3, 0.6]), temperature="25 C")
        h = stiction.humidity(s, rh=[0.2, 0.5], progress=lambda done, total: None)
        share: float = h.columns["capillary_share"][1]
        c = stiction.contact("scenarios/tas2000-height-map.json", "3 uN", model="bem")
    '''))
    p = _mypy("mypy", "--strict", "--no-incremental", "--cache-dir", str(tmp_path / "cache"), str(good))
    assert p.returncode == 0, p.stdout + p.stderr
    bad = tmp_path / "bad.py"
    bad.write_text(
        "import stiction\nstiction.gw('two', 0.5)\nstiction.Scenario.load(3)\n"
        "stiction.humidity('s.json', rh={'a': 1})\nstiction.bem(grid='16')\n"
    )
    p = _mypy("mypy", "--no-incremental", "--cache-dir", str(tmp_path / "cache"), str(bad))
    assert p.returncode == 1 and 'Argument 1 to "gw"' in p.stdout and 'Argument 1 to "load"' in p.stdout, p.stdout
    assert 'Argument "rh" to "humidity"' in p.stdout and 'Argument "grid" to "bem"' in p.stdout, p.stdout
