#!/usr/bin/env python3
"""mpmath reference of the Maugis-Dugdale test (MD_REFERENCE in crates/contact/tests/analytic_single.rs),
computed independently of the Rust code in Maugis' original variables (Maugis 1992; Johnson &
Greenwood 1997): with m = c/a and s = sqrt(m^2 - 1),

  (lambda A^2/2) [s + (s^2 - 1) atan s] + (4 lambda^2 A / 3) [s atan s - m + 1] = 1   (MD-1)
  P_bar = A^3 - lambda A^2 [s + m^2 atan s]                                         (MD-2)
  Delta = A^2 - (4/3) lambda A s                                                    (MD-3)

For each lambda of the committed table: P_min = min over A of P_bar (golden-section search on A,
bracket narrowed to 1e-30), A(P_bar = 0) (findroot), P_bar(A = 1) and Delta(A = 1). MD-1 is solved
for m by bisection-safe findroot (its left side grows with m from -1 at m = 1). 40 digits.

Run (mpmath; the CI only checks the committed values):
  python3 crates/contact/tools/md_reference.py          # print the table
  python3 crates/contact/tools/md_reference.py --check  # compare with the values committed in the test
"""
import os
import re
import sys

import mpmath as mp

mp.mp.dps = 40
TEST = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "analytic_single.rs")


def md1(lam, a, m):
    s = mp.sqrt(m * m - 1)
    return lam * a * a / 2 * (s + (s * s - 1) * mp.atan(s)) + 4 * lam * lam * a / 3 * (s * mp.atan(s) - m + 1) - 1


def m_of(lam, a):
    hi = mp.mpf(2)
    while md1(lam, a, hi) < 0:
        hi *= 2
    return mp.findroot(lambda m: md1(lam, a, m), (mp.mpf(1), hi), solver="anderson")


def state(lam, a):
    m = m_of(lam, a)
    s = mp.sqrt(m * m - 1)
    p = a**3 - lam * a * a * (s + m * m * mp.atan(s))
    d = a * a - mp.mpf(4) / 3 * lam * a * s
    return p, d


def p_min(lam):
    # golden section on A in (0, 3]: P_bar(A) falls from its A -> 0 value to the minimum, then rises
    lo, hi = mp.mpf("1e-6"), mp.mpf(3)
    r = (mp.sqrt(5) - 1) / 2
    x1, x2 = hi - r * (hi - lo), lo + r * (hi - lo)
    f1, f2 = state(lam, x1)[0], state(lam, x2)[0]
    while hi - lo > mp.mpf(10) ** -30:
        if f1 < f2:
            hi, x2, f2 = x2, x1, f1
            x1 = hi - r * (hi - lo)
            f1 = state(lam, x1)[0]
        else:
            lo, x1, f1 = x1, x2, f2
            x2 = lo + r * (hi - lo)
            f2 = state(lam, x2)[0]
    return min(f1, f2)


def a_at_zero_load(lam):
    return mp.findroot(lambda a: state(lam, a)[0], (mp.mpf("1.0"), mp.mpf("2.5")), solver="anderson")


def committed():
    text = open(TEST).read()
    body = text[text.index("const MD_REFERENCE"):]
    body = body[body.index("= &[") + 4: body.index("];")]
    return [[x.strip() for x in r.split(",") if x.strip()] for r in re.findall(r"\(([^()]*)\)", body)]


def main():
    print("# mpmath %s, %d digits" % (mp.__version__, mp.mp.dps))
    rows = committed()
    worst = mp.mpf(0)
    for row in rows:
        lam = mp.mpf(float(row[0]))  # the f64 the test passes
        p1, d1 = state(lam, mp.mpf(1))
        ref = (lam, p_min(lam), a_at_zero_load(lam), p1, d1)
        print("    (" + ", ".join(mp.nstr(x, 20) for x in ref) + "),")
        for s, v in zip(row[1:], ref[1:]):
            err = abs(mp.mpf(s) - v) / max(abs(v), 1)
            worst = max(worst, err)
            if err > mp.mpf(10) ** -15:
                print("  MISMATCH: committed %s, mpmath %s" % (s, mp.nstr(v, 20)))
    print("MD_REFERENCE: %d rows; worst relative difference to the committed values %s" % (len(rows), mp.nstr(worst, 3)))
    if "--check" in sys.argv:
        sys.exit(0 if worst <= mp.mpf(10) ** -15 else 1)


if __name__ == "__main__":
    main()
