#!/usr/bin/env python3
"""mpmath references of the Greenwood-Williamson tests (crates/contact/tests/analytic_gw.rs and the
end-to-end tests/models.rs): LN_F_REFERENCE, G_REFERENCE, GW_DMT_REFERENCE and the plain-GW
constants, computed independently of the Rust code.

Definitions (paper eq. 5, 6, 8, 9; module docs of crates/contact/src/gw.rs):
  F_n(h) = 1/sqrt(2 pi) int_h^inf (y - h)^n exp(-y^2/2) dy
         = Gamma(n+1)/sqrt(2 pi) exp(-h^2/4) U(n + 1/2, h)     (U: Whittaker's parabolic cylinder)
  G_n(h) = F_n(h) / phi(h) = Gamma(n+1) exp(h^2/4) D_{-n-1}(h)   (D_nu = U(-nu - 1/2, .))
  N* = F_0(h), A* = pi F_1(h), L*(h) = F_3/2(h) - (2 pi/theta) F_0(h)   (theta = inf: plain GW)
  GW+DMT pull-off: dL*/dh = 0 at h_m (dF_n/dh = -n F_{n-1}, so -(3/2) F_1/2 + (2 pi/theta) phi = 0),
  L*_min = L*(h_m); zero load: L*(h0) = 0 on the stable branch h0 < h_m.
F_n is cross-checked against mpmath quadrature of the integral (h < 15) and F_0 against erfc.

Run (mpmath; the CI only checks the committed values):
  python3 crates/contact/tools/gw_reference.py          # print the tables
  python3 crates/contact/tools/gw_reference.py --check  # compare with the values committed in the tests
"""
import os
import re
import sys

import mpmath as mp

mp.mp.dps = 40
HERE = os.path.dirname(os.path.abspath(__file__))
TEST = os.path.join(HERE, "..", "tests", "analytic_gw.rs")


def ln_f(n, h):
    n, h = mp.mpf(n), mp.mpf(h)
    return mp.loggamma(n + 1) - mp.log(mp.sqrt(2 * mp.pi)) - h * h / 4 + mp.log(mp.pcfu(n + mp.mpf(1) / 2, h))


def f(n, h):
    return mp.exp(ln_f(n, h))


def g(n, h):
    n, h = mp.mpf(n), mp.mpf(h)
    return mp.gamma(n + 1) * mp.exp(h * h / 4) * mp.pcfd(-n - 1, h)


def phi(h):
    return mp.exp(-h * h / 2) / mp.sqrt(2 * mp.pi)


def cross_check():
    for n in [0, 0.5, 1, 1.5, 3.7]:
        for h in [-3.5, -0.7, 0, 1, 2.5, 8, 14]:
            h = mp.mpf(h)
            q = phi(h) * mp.quad(lambda t: t**n * mp.exp(-h * t - t * t / 2), [0, 1, 5, 20, mp.inf])
            assert abs(q / f(n, h) - 1) < mp.mpf(10) ** -25, (n, h, q, f(n, h))
            assert abs(g(n, h) * phi(h) / f(n, h) - 1) < mp.mpf(10) ** -30, (n, h)
    for h in [-10, 0, 3, 50, 190]:
        h = mp.mpf(h)
        assert abs(f(0, h) / (mp.erfc(h / mp.sqrt(2)) / 2) - 1) < mp.mpf(10) ** -30, h


def l_star(theta, h):
    adhesive = 0 if theta is None else 2 * mp.pi / theta * f(0, h)
    return f(1.5, h) - adhesive


def gw_dmt(theta):
    """(h_m, log10|L*_min|, h0, log10 N*(0), log10 A*(0)) for GW+DMT at theta."""
    theta = mp.mpf(theta)
    # dL*/dh = -(3/2) F_1/2 + (2 pi / theta) phi = 0, in logs: ln(3/2) + ln F_1/2 = ln(2 pi/theta) + ln phi
    slope = lambda h: mp.log(mp.mpf(3) / 2) + ln_f(0.5, h) - (mp.log(2 * mp.pi / theta) - h * h / 2 - mp.log(mp.sqrt(2 * mp.pi)))
    h_m = mp.findroot(slope, guess(theta, 0))
    l_min = l_star(theta, h_m)
    # L* = 0: F_3/2 = (2 pi/theta) F_0, in logs
    zero = lambda h: ln_f(1.5, h) - mp.log(2 * mp.pi / theta) - ln_f(0, h)
    h0 = mp.findroot(zero, guess(theta, 1))
    assert h0 < h_m
    ln10 = mp.log(10)
    return (h_m, mp.log(-l_min) / ln10, h0, ln_f(0, h0) / ln10, (mp.log(mp.pi) + ln_f(1, h0)) / ln10)


def guess(theta, which):
    """Starting points for findroot: a coarse scan for the sign change."""
    fn = [
        lambda h: mp.log(mp.mpf(3) / 2) + ln_f(0.5, h) - (mp.log(2 * mp.pi / theta) - h * h / 2 - mp.log(mp.sqrt(2 * mp.pi))),
        lambda h: ln_f(1.5, h) - mp.log(2 * mp.pi / theta) - ln_f(0, h),
    ][which]
    grid = [mp.mpf(-10) + mp.mpf(k) / 4 for k in range(0, 4 * 220)]
    prev = fn(grid[0])
    for a, b in zip(grid, grid[1:]):
        cur = fn(b)
        if (prev < 0) != (cur < 0):
            return (a, b)
        prev = cur
    raise ValueError("no sign change")


def plain_gw(load):
    return mp.findroot(lambda h: mp.log(f(1.5, h)) - mp.log(load), (-5, 10), solver="anderson")


def points(name, k):
    """The first k columns (the arguments) of each row of a committed table: the points are the
    test's choice, the values are what this script regenerates."""
    return [tuple(mp.mpf(float(x)) for x in row[:k]) for row in committed(name)]  # the f64 the test passes


def tables():
    out = {}
    out["LN_F_REFERENCE"] = [(n, h, ln_f(n, h)) for n, h in points("LN_F_REFERENCE", 2)]
    out["G_REFERENCE"] = [(n, h, g(n, h)) for n, h in points("G_REFERENCE", 2)]
    out["GW_DMT_REFERENCE"] = [(t,) + gw_dmt(t) for (t,) in points("GW_DMT_REFERENCE", 1)]
    h1 = plain_gw(mp.mpf("0.001"))
    ln10 = mp.log(10)
    out["plain GW"] = [
        ("h(L* = 0.001)", h1),
        ("log10 N*(0.001)", ln_f(0, h1) / ln10),
        ("log10 A*(0.001)", (mp.log(mp.pi) + ln_f(1, h1)) / ln10),
        ("h(L* = 0.5)", plain_gw(mp.mpf("0.5"))),
        ("ln F_0(190)", ln_f(0, 190)),
    ]
    return out


def committed(name):
    """The rows of a `const NAME: &[(...)] = &[...];` table in the test file, as lists of strings."""
    text = open(TEST).read()
    body = text[text.index("const %s" % name):]
    body = body[body.index("= &[") + 4: body.index("];")]
    rows = re.findall(r"\(([^()]*)\)", body)
    return [[x.strip() for x in r.split(",") if x.strip()] for r in rows]


def check(out):
    worst = mp.mpf(0)
    for name in ["LN_F_REFERENCE", "G_REFERENCE", "GW_DMT_REFERENCE"]:
        rows = committed(name)
        assert len(rows) == len(out[name]), name
        for row, ref in zip(rows, out[name]):
            for s, v in zip(row, ref):
                v = mp.mpf(v)
                err = abs(mp.mpf(s) - v) / max(abs(v), 1)
                worst = max(worst, err)
                if err > mp.mpf(10) ** -15:
                    print("MISMATCH %s: committed %s, mpmath %s" % (name, s, mp.nstr(v, 25)))
        print("%s: %d rows checked" % (name, len(rows)))
    text = open(TEST).read()
    for what, v in out["plain GW"]:
        s = mp.nstr(v, 17, strip_zeros=False)
        found = any(abs(mp.mpf(m) - v) <= mp.mpf(10) ** -17 * max(abs(v), 1) for m in re.findall(r"-?\d+\.\d{12,}", text))
        print("%s = %s: %s in %s" % (what, mp.nstr(v, 22), "found" if found else "NOT FOUND", os.path.basename(TEST)))
        if not found:
            worst = max(worst, mp.mpf(1))
    print("worst relative difference to the committed values: %s" % mp.nstr(worst, 3))
    return worst <= mp.mpf(10) ** -15


def main():
    print("# mpmath %s, %d digits" % (mp.__version__, mp.mp.dps))
    cross_check()
    out = tables()
    if "--check" in sys.argv:
        sys.exit(0 if check(out) else 1)
    for name, rows in out.items():
        print("%s:" % name)
        for r in rows:
            print("    (" + ", ".join(mp.nstr(x, 25) if isinstance(x, mp.mpf) else str(x) for x in r) + "),")


if __name__ == "__main__":
    main()
