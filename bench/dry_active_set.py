#!/usr/bin/env python3
"""Independent reference for the dry smooth point (issue 30): a numpy/LAPACK
active-set solver of the discrete problem that bench/dry_point dumps.

  dry_active_set.py DIR [--repeats R]

DIR holds `dry_point --dump DIR`: per speed k the influence matrix M (gap_i =
h0 + xi_i^2/2 + sum_j M_ij P_j, cells of widths wc on nodes xi, in a0) and
viscolube's pressure P and mu_Rc. Unknowns P >= 0 and h0; hard contact P_i >= 0,
gap_i >= 0, P_i gap_i = 0; load sum_i wc_i P_i = pi/2 (docs/MODEL.md sections
3, 4, 6). Primal-dual active set: solve [M_AA 1; wc_A 0] [P_A; h0] =
[-xi_A^2/2; pi/2] with P = 0 elsewhere, then A = {P > 0} + {gap < 0}, until A
repeats. Each speed starts from the previous speed's set (the first from the
Hertz width |xi| < 1), as viscolube continues from the previous point.

Prints the median over R repeats of the time per speed, for all speeds solved
in sequence (matrices already in memory: loading, the interpreter and numpy's
import are not timed), then the largest difference from viscolube's solution:
of P (relative to max P) and of mu_Rc (relative).
"""
import sys
import time

import numpy as np


def solve(M, xi, wc, active):
    n = len(xi)
    for it in range(1, 4 * n):
        a = np.flatnonzero(active)
        m = len(a)
        K = np.empty((m + 1, m + 1))
        K[:m, :m] = M[np.ix_(a, a)]
        K[:m, m] = 1.0
        K[m, :m] = wc[a]
        K[m, m] = 0.0
        sol = np.linalg.solve(K, np.concatenate((-0.5 * xi[a] ** 2, [0.5 * np.pi])))
        P = np.zeros(n)
        P[a] = sol[:m]
        gap = sol[m] + 0.5 * xi**2 + M[:, a] @ sol[:m]
        new = (P > 0.0) | (~active & (gap < 0.0))
        if np.array_equal(new, active):
            return P, sol[m], it
        active = new
    raise RuntimeError("active set did not settle")


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    d = sys.argv[1]
    repeats = int(sys.argv[sys.argv.index("--repeats") + 1]) if "--repeats" in sys.argv else 9
    n, fac = open(f"{d}/grid.txt").read().split()
    n, fac = int(n), float(fac)
    xi, wc = np.fromfile(f"{d}/xi.bin"), np.fromfile(f"{d}/wc.bin")
    pts = np.loadtxt(f"{d}/points.txt", ndmin=2)
    Ms = [np.fromfile(f"{d}/M{k}.bin").reshape(n, n) for k in range(len(pts))]
    times, cpu = [], []
    for _ in range(repeats):
        t0, c0 = time.perf_counter(), time.process_time()
        active, out = np.abs(xi) < 1.0, []
        for M in Ms:
            P, h0, its = solve(M, xi, wc, active)
            active = P > 0.0
            out.append((P, h0, its))
        times.append((time.perf_counter() - t0) / len(Ms))
        cpu.append((time.process_time() - c0) / len(Ms))
    dp = dmu = 0.0
    for k, (P, h0, its) in enumerate(out):
        Pv = np.fromfile(f"{d}/P{k}.bin")
        mu, mu_v = -fac * np.sum(P * xi * wc), pts[k, 3]
        dp = max(dp, np.max(np.abs(P - Pv)) / np.max(np.abs(Pv)))
        dmu = max(dmu, abs(mu - mu_v) / abs(mu_v))
    print(f"numpy_ms_per_point {1e3 * np.median(times):.4f} (median of {repeats}; "
          f"min {1e3 * min(times):.4f}, max {1e3 * max(times):.4f}; "
          f"CPU time {1e3 * np.median(cpu):.4f}; "
          f"{sum(o[2] for o in out)} LAPACK solves for {len(Ms)} speeds)")
    print(f"numpy_vs_viscolube max |dP|/max P {dp:.2e}, max |d mu_Rc|/mu_Rc {dmu:.2e}")


if __name__ == "__main__":
    main()
