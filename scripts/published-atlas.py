#!/usr/bin/env python3
"""The atlas of published MEMS static friction experiments (docs/published.md).

For every scenario in scenarios/published/: `stiction study` over its uncertain inputs (fixed seed,
SAMPLES samples) gives the predictive distribution of the adhesion-aware coefficient mu_e,a (eq. 10
slope) and of F_a0, with first-order Sobol indices; `stiction run` at the nominal inputs gives the
lab's own reduction (the number the publication reports) beside it. Writes
data/published-friction/atlas.csv (one row per experiment), the table and the honesty checks into
docs/published.md (between the `atlas` markers) and the figures' data for
`cargo run --release -p stiction-plot --example published_atlas`, which it runs (the figures
docs/figures/published-*.png, .svg, .csv).

Usage: scripts/published-atlas.py [--check] [--bin PATH]
  --check  recompute and fail (exit 1) when a row differs from data/published-friction/atlas.csv
"""
import csv, io, json, math, os, random, shutil, subprocess, sys, tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SAMPLES, SEED = 64, 1
BIN = os.path.join(ROOT, "target/release/stiction")
ATLAS = os.path.join(ROOT, "data/published-friction/atlas.csv")
DOC = os.path.join(ROOT, "docs/published.md")
ORDER = ["tas2000-paper", "lim1990-poly", "lim1990-nitride", "cornell-comb-sidewall", "leiden-tribometer",
         "vacuum-flats-1992", "pentanol-sidewall"]
COLUMNS = ["experiment", "quantity", "measured", "measured_uncertainty", "predicted_p05", "predicted_median",
           "predicted_p95", "covered", "interval_width", "deciding_inputs", "mu_ea_p05", "mu_ea_median", "mu_ea_p95",
           "lab_reduction", "lab_number_nominal", "load_per_area_pa", "adhesion_ratio"]


def sh(args):
    r = subprocess.run([BIN] + args, capture_output=True, text=True, cwd=ROOT)
    if r.returncode != 0:
        sys.exit(f"stiction {' '.join(args)}: {r.stderr.strip()}")
    return json.loads(r.stdout)


def percentiles(values):
    """5 %, median, 95 % by linear interpolation between order statistics (Hyndman-Fan type 7, as the
    study's summary)."""
    v = sorted(values)
    def q(p):
        h = p * (len(v) - 1)
        lo = math.floor(h)
        return v[lo] + (h - lo) * (v[min(lo + 1, len(v) - 1)] - v[lo])
    return q(0.05), q(0.5), q(0.95)


def lab_numbers(path, tmp):
    """The lab's own number for every sample of the study: the study's log gives each sample's draws
    (and its surface seed is seed + i); `stiction run` with those values set gives the lab's
    reduction. Each run's mu_e,a must equal the study's for that sample (the same device)."""
    log = open(os.path.join(tmp, "samples.log")).read().splitlines()
    header = json.loads(log[0].lstrip("# ").split("\t")[0])
    params = [name for name, _unit in header["parameters"]]
    out = []
    for line in log[1:]:
        cells = line.split("\t")[0].split(",")
        i = int(cells[0])
        draws = [float(x) for x in cells[9:9 + len(params)]]
        sets = []
        for name, x in zip(params, draws):
            sets += ["--set", f"{name}={x!r}"]
        sets += ["--set", f"surface.seed={SEED + i}"]
        r = sh(["run", path, "--json"] + sets)
        mu_log = float(cells[1]) if cells[1] else None
        if mu_log is not None and abs((r.get("mu_apparent") or 0.0) - mu_log) > 1e-9 * abs(mu_log):
            sys.exit(f"{path} sample {i}: run gives mu_e,a {r.get('mu_apparent')}, the study {mu_log}")
        c = (r.get("lab_coefficient") or {}).get("coefficient")
        if c is not None:
            out.append(c)
    return out


def g(x):
    """Four significant digits, the table's and the CSV's precision (what a row test compares)."""
    return "" if x is None else f"{x:.4g}"


def row(name):
    path = f"scenarios/published/{name}.json"
    scen = json.load(open(os.path.join(ROOT, path)))
    ref = scen["reference"]
    tmp = tempfile.mkdtemp(prefix="atlas-")
    try:
        study = sh(["study", path, "--samples", str(SAMPLES), "--seed", str(SEED), "--json", "--quiet", "--threads", "1",
                    "--out", tmp, "--force"])
        run = sh(["run", path, "--json"])
        lab_kind = (run.get("lab_coefficient") or {}).get("kind", "eq10")
        lab = lab_numbers(path, tmp) if lab_kind != "eq10" else None
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    force = "mu_apparent" not in ref
    key = "apparent_adhesion_force_n" if force else "mu_apparent"
    dist = dict(study[key])
    if lab is not None and not force:
        dist["p05"], dist["median"], dist["p95"] = percentiles(lab)
    if force:
        measured = float(ref["apparent_adhesion_force"].split()[0]) * 1e-9  # "75 nN"
        unc = None
    else:
        measured, unc = ref["mu_apparent"], ref.get("mu_apparent_uncertainty")
    lo, hi = (measured - (unc or 0.0), measured + (unc or 0.0))
    covered = dist["p05"] <= hi and lo <= dist["p95"]
    sens = study.get("sensitivity") or {}
    idx = "fa0_first_order" if force else "mu_first_order"
    ranked = sorted(((i[idx] or 0.0, i["input"]) for i in sens.get("inputs", []) if i["input"] != "1 - sum"), reverse=True)
    deciding = "; ".join(f"{n} {s:.2f}" for s, n in ranked[:2] if s > 0) or "none above 0"
    lab = run.get("lab_coefficient") or {"kind": "eq10", "coefficient": run.get("mu_apparent")}
    pts = [p for p in run["points"] if p.get("in_contact") and p.get("load_n")]
    area = scen["surface"]["apparent_length"], scen["surface"]["apparent_width"]
    um = lambda t: float(t.split()[0]) * 1e-6
    load = sum(p["load_n"] for p in pts) / max(len(pts), 1)
    fa0 = run.get("apparent_adhesion_force_n")
    return {
        "experiment": name, "quantity": "F_a0 (N)" if force else "mu",
        "measured": g(measured), "measured_uncertainty": g(unc),
        "predicted_p05": g(dist["p05"]), "predicted_median": g(dist["median"]), "predicted_p95": g(dist["p95"]),
        "covered": "yes" if covered else "no", "interval_width": g(dist["p95"] - dist["p05"]),
        "deciding_inputs": deciding, "mu_ea_p05": g(study["mu_apparent"]["p05"]),
        "mu_ea_median": g(study["mu_apparent"]["median"]), "mu_ea_p95": g(study["mu_apparent"]["p95"]),
        "lab_reduction": lab.get("kind", "eq10"), "lab_number_nominal": g(lab.get("coefficient")),
        "load_per_area_pa": g(load / (um(area[0]) * um(area[1]))),
        "adhesion_ratio": g(fa0 / load if fa0 is not None and load > 0 else None),
    }


def spearman(x, y):
    def ranks(v):
        order = sorted(range(len(v)), key=lambda i: v[i])
        r = [0.0] * len(v)
        i = 0
        while i < len(v):
            j = i
            while j + 1 < len(v) and v[order[j + 1]] == v[order[i]]:
                j += 1
            for k in range(i, j + 1):
                r[order[k]] = (i + j) / 2.0
            i = j + 1
        return r
    rx, ry = ranks(x), ranks(y)
    mx, my = sum(rx) / len(rx), sum(ry) / len(ry)
    sxy = sum((a - mx) * (b - my) for a, b in zip(rx, ry))
    sx = math.sqrt(sum((a - mx) ** 2 for a in rx)); sy = math.sqrt(sum((b - my) ** 2 for b in ry))
    return sxy / (sx * sy) if sx > 0 and sy > 0 else float("nan")


def honesty(rows):
    mu = [r for r in rows if r["quantity"] == "mu"]
    pred = [float(r["predicted_median"]) for r in mu]
    meas = [float(r["measured"]) for r in mu]
    rho = spearman(pred, meas)
    rng = random.Random(20260101)
    boots = []
    for _ in range(2000):
        pick = [rng.randrange(len(mu)) for _ in mu]
        v = spearman([pred[i] for i in pick], [meas[i] for i in pick])
        if not math.isnan(v):
            boots.append(v)
    boots.sort()
    lo, hi = boots[int(0.025 * len(boots))], boots[int(0.975 * len(boots)) - 1]
    widths = [float(r["interval_width"]) for r in mu]
    span = max(meas) - min(meas)
    return rho, lo, hi, len(mu), widths, span


def table(rows, check):
    rho, lo, hi, n, widths, span = check
    out = io.StringIO()
    out.write("| experiment | quantity (lab's reduction) | measured | predicted median [5 %, 95 %] | covered | width | deciding inputs (first-order Sobol of mu_e,a or F_a0) | adhesion-aware mu_e,a median [5 %, 95 %] | lab's number at nominal inputs |\n")
    out.write("|---|---|---|---|---|---|---|---|---|\n")
    for r in rows:
        m = r["measured"] + (f" +/- {r['measured_uncertainty']}" if r["measured_uncertainty"] else " (no uncertainty stated)")
        out.write(f"| {r['experiment']} | {r['quantity']} ({r['lab_reduction']}) | {m} | {r['predicted_median']} [{r['predicted_p05']}, {r['predicted_p95']}] | "
                  f"{r['covered']} | {r['interval_width']} | {r['deciding_inputs']} | {r['mu_ea_median']} [{r['mu_ea_p05']}, {r['mu_ea_p95']}] | {r['lab_number_nominal']} |\n")
    out.write(f"\nSpearman rank correlation of the predicted medians against the measured values over the {n} friction "
              f"coefficients: rho = {rho:.2f}, 95 % bootstrap interval over the experiments [{lo:.2f}, {hi:.2f}] "
              f"(2000 resamples, seed 20260101). Interval widths {min(widths):.2f} to {max(widths):.2f}, against a "
              f"spread of the measured values of {span:.2f}.\n")
    return out.getvalue()


def main():
    global BIN
    args = sys.argv[1:]
    if "--bin" in args:
        BIN = args[args.index("--bin") + 1]
    rows = [row(n) for n in ORDER]
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=COLUMNS, lineterminator="\n")
    w.writeheader()
    w.writerows(rows)
    text = buf.getvalue()
    if "--check" in args:
        old = open(ATLAS).read()
        if old != text:
            for a, b in zip(old.splitlines(), text.splitlines()):
                if a != b:
                    print(f"row changed:\n  was {a}\n  now {b}")
            sys.exit(1)
        print("atlas rows unchanged")
        return
    open(ATLAS, "w").write(text)
    doc = open(DOC).read()
    b, e = "<!-- atlas: begin -->\n", "<!-- atlas: end -->"
    i, j = doc.index(b) + len(b), doc.index(e)
    open(DOC, "w").write(doc[:i] + table(rows, honesty(rows)) + doc[j:])
    # The figures, drawn by the project's plot crate from the CSV just written.
    subprocess.run(["cargo", "run", "--quiet", "--release", "-p", "stiction-plot", "--example", "published_atlas", "--",
                    ATLAS, os.path.join(ROOT, "docs/figures")], cwd=ROOT, check=True)
    print(text)


if __name__ == "__main__":
    main()
