#!/usr/bin/env python3
"""Behaviour snapshot of the `stiction` binary and the Python package: a manifest of sha256 per case.

Every case runs the release `stiction` binary (target/release/stiction, built by
`cargo build --release -p stiction-cli`) with a fixed command line: `--json` of every command on
every bundled scenario (scenarios/*.json) and the bundled example data (data/), with small sample
counts where a command is slow, and the files of `--out` folders (each file hashed; the manifest of
an output folder, which names the files, is hashed too). A case records the sha256 of stdout, the
exit status and the sha256 of stderr, so a refusal must stay the same refusal.

With --python PY (a Python interpreter with the `stiction` package installed), the Python
functions are called on the same inputs and their results hashed as canonical JSON.

    scripts/behaviour-snapshot.py --write scripts/behaviour-snapshot/manifest.txt [--python PY]
    scripts/behaviour-snapshot.py --check scripts/behaviour-snapshot/manifest.txt [--python PY]

--check lists each case whose hash differs, is missing or is new, and exits 1 when any does.
Absolute paths of the checkout and of the temporary folder are replaced before hashing, so a
manifest checks the same on any clone. The bundled manifest is the behaviour of the current main;
a change that means to alter an output re-records it in the same commit and says which cases
changed and why.
"""

import argparse
import hashlib
import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BIN = ROOT / "target" / "release" / "stiction"


def sha(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def scenarios():
    return sorted(p.relative_to(ROOT).as_posix() for p in (ROOT / "scenarios").glob("*.json"))


def cli_cases():
    """(name, argv, out-dir flag or None) for every case. The list is the contract: change it and
    record a new manifest on the unchanged code first."""
    cases = []
    add = lambda name, *argv, out=None: cases.append((name, list(argv), out))
    for s in scenarios():
        stem = Path(s).stem
        add(f"run/{stem}", "run", s, "--json")
        add(f"scenario/{stem}", "scenario", s)
        add(f"scenario-explain/{stem}", "scenario", s, "--explain", "--json")
        add(f"surface/{stem}", "surface", s, "--json")
        add(f"contact/{stem}", "contact", s, "--load", "2 uN", "--json")
        add(f"contact-sweep/{stem}", "contact", s, "--sweep", "0uN:4uN:5", "--json")
        add(f"actuator/{stem}", "actuator", s, "--json")
        add(f"actuator-clamp/{stem}", "actuator", s, "--array", "clamp", "--json")
        add(f"study/{stem}", "study", s, "--samples", "3", "--threads", "1", "--quiet", "--json")
        add(f"humidity/{stem}", "plot", "humidity", "--scenario", s, "--rh", "0.3,0.6", "--json")
    t = "scenarios/tas2000.json"
    add("run-humid/tas2000", "run", t, "--set", "environment.relative_humidity=0.35", "--json")
    add("run-out/tas2000", "run", t, "--json", out="--out")
    add("run-out/tas2000-fit-synthetic", "run", "scenarios/tas2000-fit-synthetic.json", out="--out")
    add("scenario/schema", "scenario", "--schema")
    add("scenario/domains", "scenario", "--domains")
    add("scenario-explain/own_device", "scenario", "tests/data/own_device.json", "--explain", "--json")
    add("run/own_device", "run", "tests/data/own_device.json", "--json")
    for theta, load in [("15", "0"), ("10", "-0.5"), ("10", "-0.01"), ("inf", "1"), ("30", "-100")]:
        add(f"gw/{theta}/{load}", "gw", "--theta", theta, f"--load-star={load}", "--json")
    disc = ["--radius", "0.5 um", "--work-of-adhesion", "0.1 J/m^2", "--compliance", "9.1e-12 1/Pa",
            "--shear-strength", "1.4 GPa"]
    for law in ["dmt", "jkr", "maugis-dugdale", "hertz"]:
        add(f"discrete/{law}", "discrete", "--contacts", "3", *disc, "--load", "2 uN", "--adhesion", law, "--json")
    add("discrete/target-slope", "discrete", "--contacts", "3", *disc, "--load", "2 uN", "--target-slope", "0.5",
        "--json")
    add("discrete/text", "discrete", "--contacts", "1", *disc, "--load", "1 uN")
    add("contact/flat", "contact", t, "--load", "2 uN", "--mode", "flat", "--json")
    add("contact/fixed", "contact", t, "--load", "2 uN", "--mode", "fixed", "--contacts", "3", "--json")
    add("contact/summits", "contact", t, "--load", "2 uN", "--summits", "--json")
    add("contact/bem", "contact", "scenarios/tas2000-height-map.json", "--model", "bem", "--load", "2 uN", "--json")
    g = "scenarios/gca-rauf2022.json"
    add("actuator/sweep", "actuator", g, "--sweep", "--sweep-steps", "20", "--json")
    add("actuator/validate", "actuator", g, "--validate", "data/gca-pullin-release/measured.csv", "--json")
    add("actuator/transients", "actuator", g, "--transients", "data/gca-transients/measured_times.csv", "--json")
    add("actuator/switches", "actuator", g, "--switches", "--json")
    add("actuator/switches-validate", "actuator", g, "--switches", "--validate", "data/gca-pullin-release/measured.csv",
        "--json")
    add("actuator/out", "actuator", g, "--sweep", "--sweep-steps", "20", "--json", out="--out")
    for fig in ["fig2", "fig3", "fig7"]:
        add(f"plot/{fig}", "plot", fig, out="--out.svg")
        add(f"plot/{fig}-scenario", "plot", fig, "--scenario", t, out="--out.svg")
    add("plot/actuator", "plot", "actuator", "--scenario", g, out="--out.svg")
    add("plot/humidity-out", "plot", "humidity", "--scenario", "scenarios/tas2000-humid.json", "--rh", "0.2,0.5",
        out="--out")
    add("study/out", "study", t, "--samples", "4", "--threads", "1", "--quiet", "--json", out="--out")
    add("study/pull-in", "study", t, "--samples", "3", "--threads", "1", "--quiet", "--calibration", "pull-in",
        "--json")
    add("study/fixed", "study", t, "--samples", "3", "--threads", "2", "--quiet", "--fixed-surface", "--json")
    add("study/rigid", "study", t, "--samples", "2", "--threads", "1", "--quiet", "--slip-path", "rigid-body",
        "--json")
    add("design/vary", "study", t, "--samples", "2", "--threads", "1", "--quiet", "--vary",
        "surface.summit_sd=20nm,40nm", "--json")
    add("design/vary-out", "study", t, "--samples", "2", "--threads", "1", "--quiet", "--vary",
        "surface.summit_sd=20nm,40nm", "--rank-by", "most-usable", "--json", out="--out")
    fs = "scenarios/tas2000-fit-synthetic.json"
    add("fit/synthetic", "fit", "--scenario", fs, "--surfaces", "3", "--draws", "200", "--json")
    add("fit/data", "fit", "data/measured-voltages-synthetic/voltages.csv", "--scenario", fs, "--models",
        "discrete-n3,gw-dmt", "--draws", "200", "--free", "s,R", "--json")
    add("fit/out", "fit", "--scenario", fs, "--models", "discrete-n1,discrete-n3", "--draws", "200", "--json",
        out="--out")
    add("bem/pressure", "bem", "--grid", "32", "--pressure", "1 MPa", "--json")
    add("bem/sweep", "bem", "--grid", "32", "--size", "20 um", "--rms-height", "50 nm", "--sweep", "1MPa:20MPa:3",
        "--json")
    add("bem/gap", "bem", "--grid", "32", "--size", "2 um", "--rms-height", "3 nm", "--gap-sweep", "20nm:1nm:4",
        "--gap-back", "--work-of-adhesion", "0.1 J/m^2", "--range", "1 nm", "--json")
    add("bem/rh", "bem", "--grid", "32", "--size", "1um", "--rms-height", "3nm", "--rh", "0.1:0.9:3",
        "--work-of-adhesion", "0.05 J/m^2", "--range", "1 nm", "--pressure", "1 MPa", "--json")
    add("bem/compare", "bem", "--grid", "32", "--pressure", "1 MPa", "--compare-asperity", "--json")
    add("bem/map", "bem", "--map", "data/topography-example/wall.gsf", "--pressure", "5 MPa", "--map-cells", "64",
        "--json")
    add("bem/scenario", "bem", "--scenario", "scenarios/tas2000-bem.json", "--json")
    add("bem/scenario-pressure", "bem", "--scenario", "scenarios/tas2000-bem.json", "--pressure", "5 MPa", "--json")
    add("bem/out", "bem", "--grid", "32", "--sweep", "1MPa:5MPa:2", out="--out")
    add("bem/hardness", "bem", "--grid", "32", "--size", "20 um", "--rms-height", "50 nm", "--e-star", "1 GPa",
        "--sweep", "1MPa:5MPa:2", "--hardness", "10 MPa", "--json")
    add("bem/non-periodic", "bem", "--grid", "32", "--boundary", "non-periodic", "--pressure", "1 MPa", "--json")
    add("bem/tilt", "bem", "--grid", "32", "--boundary", "non-periodic", "--tilt", "--pressure", "1 MPa", "--json")
    add("bem/err-tilt-periodic", "bem", "--grid", "32", "--tilt", "--pressure", "1 MPa", "--json")
    add("bem/hardness-adhesion", "bem", "--grid", "64", "--size", "100 um", "--rms-height", "0.24 um", "--e-star",
        "1 GPa", "--boundary", "non-periodic", "--hardness", "50 MPa", "--work-of-adhesion", "1", "--range",
        "100nm", "--sweep", "2MPa:20MPa:2", "--json")
    add("topography/wall", "topography", "data/topography-example/wall.gsf", "--json")
    add("topography/wall-scenario", "topography", "data/topography-example/wall.gsf", "--scenario", t, "--cutoff",
        "2 um", "--json")
    add("topography/wall-out", "topography", "data/topography-example/wall.gsf", out="--out")
    for f in sorted((ROOT / "data" / "topography-formats").iterdir()):
        if f.suffix != ".md":
            rel = f.relative_to(ROOT).as_posix()
            add(f"topography/{f.name}", "topography", rel, "--json")
            add(f"topography-channels/{f.name}", "topography", rel, "--channels")
    return cases


def run_cli(cases, tmp: Path):
    rows = []
    for name, argv, out in cases:
        extra = []
        target = None
        if out is not None:
            target = tmp / name.replace("/", "_")
            if target.exists():
                shutil.rmtree(target)
            if out == "--out.svg":
                target.mkdir(parents=True)
                extra = ["--out", str(target / "figure.svg")]
            else:
                extra = ["--out", str(target)]
        if argv[0] == "merge":
            pass
        p = subprocess.run([str(BIN), *argv, *extra], cwd=ROOT, capture_output=True, timeout=600)
        # Paths of the temporary folder and of the checkout are replaced, so the record does not
        # depend on where it ran (`scenario FILE` prints absolute file paths).
        stdout = p.stdout.replace(str(tmp).encode(), b"TMP").replace(str(ROOT).encode(), b"ROOT")
        stderr = p.stderr.replace(str(tmp).encode(), b"TMP").replace(str(ROOT).encode(), b"ROOT")
        rows.append((name, f"exit={p.returncode} stdout={sha(stdout)} stderr={sha(stderr)}"))
        if target is not None:
            for f in sorted(target.rglob("*")):
                if f.is_file():
                    data = f.read_bytes().replace(str(tmp).encode(), b"TMP").replace(str(ROOT).encode(), b"ROOT")
                    rows.append((f"{name}/{f.relative_to(target).as_posix()}", sha(data)))
    return rows


def merge_cases(tmp: Path):
    """Shards of a study and their merge (the folders are inputs, so this case runs its own study)."""
    rows = []
    base = tmp / "merge"
    if base.exists():
        shutil.rmtree(base)
    for k in range(2):
        subprocess.run([str(BIN), "study", "scenarios/tas2000.json", "--samples", "4", "--threads", "1", "--quiet",
                        "--shard", f"{k}/2", "--out", str(base / f"shard-{k}")], cwd=ROOT, capture_output=True,
                       check=True, timeout=600)
    for name, extra in [("merge/json", ["--json"]), ("merge/text", [])]:
        out = base / name.replace("/", "_")
        p = subprocess.run([str(BIN), "merge", str(base / "shard-0"), str(base / "shard-1"), "--out", str(out),
                            *extra], cwd=ROOT, capture_output=True, timeout=600)
        stdout = p.stdout.replace(str(tmp).encode(), b"TMP")
        stderr = p.stderr.replace(str(tmp).encode(), b"TMP")
        rows.append((name, f"exit={p.returncode} stdout={sha(stdout)} stderr={sha(stderr)}"))
        for f in sorted(out.rglob("*")):
            if f.is_file():
                rows.append((f"{name}/{f.relative_to(out).as_posix()}",
                             sha(f.read_bytes().replace(str(tmp).encode(), b"TMP"))))
    return rows


PY_CASES = r'''
import hashlib, json, sys
import numpy as np
import stiction

def canon(x):
    if hasattr(x, "to_dict"):
        x = x.to_dict()
    def conv(v):
        if isinstance(v, dict):
            return {k: conv(w) for k, w in v.items()}
        if isinstance(v, (list, tuple)):
            return [conv(w) for w in v]
        if isinstance(v, np.ndarray):
            return conv(v.tolist())
        if isinstance(v, (np.floating,)):
            return float(v)
        if isinstance(v, (np.integer,)):
            return int(v)
        if isinstance(v, float) and v != v:
            return "NaN"
        return v
    return json.dumps(conv(x), sort_keys=True, allow_nan=True).encode()

def case(name, f):
    try:
        out = b"ok " + canon(f())
    except Exception as e:  # the refusal and its message are part of the behaviour
        out = ("error " + type(e).__name__ + ": " + str(e)).encode()
    print(name, hashlib.sha256(out).hexdigest())

t = "scenarios/tas2000.json"
scen = sorted(__import__("glob").glob("scenarios/*.json"))
for s in scen:
    case("py/run/" + s, lambda s=s: stiction.run(s))
    case("py/contact/" + s, lambda s=s: stiction.contact(s, load="2 uN"))
case("py/run-scenario-object", lambda: stiction.run(stiction.Scenario(t)))
case("py/study", lambda: stiction.study(t, samples=3, threads=1))
case("py/study-fixed", lambda: stiction.study(t, samples=3, threads=2, fixed_surface=True))
case("py/gw", lambda: stiction.gw(15, [-1.0, 0.0, 1.0]))
case("py/gw-inf", lambda: stiction.gw(None, 1.0))
case("py/discrete", lambda: stiction.discrete(3, "0.5 um", "0.1 J/m^2", "9.1e-12 1/Pa", "1.4 GPa", [1e-6, 2e-6]))
case("py/discrete-jkr", lambda: stiction.discrete(3, 0.5e-6, 0.1, 9.1e-12, 1.4e9, "2 uN", adhesion="jkr"))
case("py/asperity-md", lambda: stiction.asperity(0.5e-6, 0.1, 9.1e-12, 1.4e9, [1e-6], adhesion="maugis-dugdale"))
case("py/contact-sweep", lambda: stiction.contact(t, load=np.linspace(0, 4e-6, 5)))
case("py/contact-flat", lambda: stiction.contact(t, load="2 uN", mode="flat"))
case("py/contact-bem", lambda: stiction.contact("scenarios/tas2000-height-map.json", load="2 uN", model="bem"))
rng = np.random.default_rng(1)
h = rng.normal(0, 5e-9, (64, 64))
case("py/topography", lambda: stiction.topography(h, pixel_size="50 nm", height_unit="m"))
case("py/bem-generated", lambda: stiction.bem(pressure="1 MPa", grid=32))
case("py/bem-map", lambda: stiction.bem(h, pressure=[1e6, 2e6], pixel_size="50 nm", height_unit="m", e_star="100 GPa"))
case("py/humidity", lambda: stiction.humidity(t, rh=[0.3, 0.6]))
case("py/humidity-text", lambda: stiction.humidity(t, rh="0.2:0.6:2"))
case("py/fit", lambda: stiction.fit("data/measured-voltages-synthetic/voltages.csv", "scenarios/tas2000-fit-synthetic.json", models="discrete-n3,gw-dmt", draws=200))
# refusals
case("py/err/topography-unit", lambda: stiction.topography(h, pixel_size="50 nm"))
case("py/err/bem-grid", lambda: stiction.bem(np.zeros((2, 5000)), pressure=1e6, pixel_size=1e-8))
case("py/err/discrete-law", lambda: stiction.discrete(3, 0.5e-6, 0.1, 9.1e-12, 1.4e9, 1e-6, adhesion="nope"))
case("py/err/study-samples", lambda: stiction.study(t, samples=0))
case("py/err/rh", lambda: stiction.humidity(t, rh=[1.5]))
'''


def run_python(py: str):
    p = subprocess.run([py, "-c", PY_CASES], cwd=ROOT, capture_output=True, timeout=900)
    if p.returncode != 0:
        sys.exit(f"the Python cases failed:\n{p.stderr.decode()[-2000:]}")
    return [tuple(line.split(" ", 1)) for line in p.stdout.decode().splitlines() if line.strip()]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    g = ap.add_mutually_exclusive_group(required=True)
    g.add_argument("--write", metavar="MANIFEST")
    g.add_argument("--check", metavar="MANIFEST")
    ap.add_argument("--python", metavar="PY", help="a Python with the stiction package installed")
    ap.add_argument("--only", metavar="PREFIX", help="only the cases whose name starts with PREFIX")
    a = ap.parse_args()
    if not BIN.exists():
        sys.exit(f"{BIN} is missing: cargo build --release -p stiction-cli")
    tmp = Path(tempfile.mkdtemp(prefix="stiction-snapshot-"))
    try:
        cases = [c for c in cli_cases() if not a.only or c[0].startswith(a.only)]
        rows = run_cli(cases, tmp)
        if not a.only or a.only.startswith("merge"):
            rows += merge_cases(tmp)
        if a.python:
            rows += [r for r in run_python(a.python) if not a.only or r[0].startswith(a.only)]
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    text = "".join(f"{n} {h}\n" for n, h in rows)
    if a.write:
        Path(a.write).parent.mkdir(parents=True, exist_ok=True)
        Path(a.write).write_text(text)
        print(f"{len(rows)} cases written to {a.write}")
        return 0
    recorded = dict(line.split(" ", 1) for line in Path(a.check).read_text().splitlines() if line.strip())
    now = dict(rows)
    diffs = []
    for n, h in now.items():
        if n not in recorded:
            if not a.only or n.startswith(a.only):
                diffs.append(f"new      {n}")
        elif recorded[n] != h:
            diffs.append(f"changed  {n}\n  was {recorded[n]}\n  now {h}")
    for n in recorded:
        if n not in now and (not a.only or n.startswith(a.only)) and (a.python or not n.startswith("py/")):
            diffs.append(f"missing  {n}")
    for d in diffs:
        print(d)
    print(f"{len(now)} cases checked, {len(diffs)} differences")
    return 1 if diffs else 0


if __name__ == "__main__":
    sys.exit(main())
