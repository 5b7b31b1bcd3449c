#!/usr/bin/env python3
"""Derives the shipped fluid glycerol-water-85 (materials/0007_glycerol_water.sql).

Viscosity of 85 wt% glycerol in water from N.-S. Cheng, "Formula for the
viscosity of a glycerol-water mixture", Ind. Eng. Chem. Res. 47 (2008)
3285-3288, T in Celsius, viscosities in mPa s:

  glycerol  mu_g  = 12100 exp((-1233 + T) T / (9900 + 70 T))
  water     mu_w  = 1.790 exp((-1230 - T) T / (36100 + 360 T))
  a = 0.705 - 0.0017 T,   b = (4.9 + 0.036 T) a^2.5
  alpha = 1 - Cm + a b Cm (1 - Cm) / (a Cm + b (1 - Cm))   (Cm: glycerol mass fraction)
  mu = mu_w^alpha mu_g^(1 - alpha)

The stored viscosity is Cheng's value at 20 C rounded to four digits; the
Vogel law log10 eta = A + B / (T - C) (T, C in kelvin) is anchored there as
the other shipped laws are (A follows from B, C and the stored point) and
B, C are a least-squares fit in log10 eta to Cheng's values at 0, 10, ...,
100 C. For a fixed C the best B is linear least squares; C is found by a
scan and a golden-section search. The printed deviations are those of the
law with B and C rounded to 0.1 K, as stored, relative to Cheng's values.

Usage: python3 scripts/fit_glycerol_water.py   (standard library only)
"""

import math

CM = 0.85  # glycerol mass fraction
TREF_C = 20.0
KELVIN = 273.15
TEMPS_C = [10.0 * k for k in range(11)]

# Segur & Oberstar, Ind. Eng. Chem. 43 (1951) 2117, 85 wt% at 0-40 C
# (mPa s), as reproduced in the Dow glycerine tables
SEGUR_85 = {0.0: 540.0, 10.0: 223.0, 20.0: 109.0, 30.0: 58.0, 40.0: 33.5}


def cheng_mpa_s(cm, t):
    """Cheng (2008) viscosity of a glycerol-water mixture, mPa s, at t Celsius."""
    mu_g = 12100.0 * math.exp((-1233.0 + t) * t / (9900.0 + 70.0 * t))
    mu_w = 1.790 * math.exp((-1230.0 - t) * t / (36100.0 + 360.0 * t))
    a = 0.705 - 0.0017 * t
    b = (4.9 + 0.036 * t) * a**2.5
    alpha = 1.0 - cm + a * b * cm * (1.0 - cm) / (a * cm + b * (1.0 - cm))
    return mu_w**alpha * mu_g ** (1.0 - alpha)


def vogel(eta_ref, b_k, c_k, t):
    """Vogel law anchored at eta_ref at TREF_C."""
    tk, rk = t + KELVIN, TREF_C + KELVIN
    return eta_ref * 10.0 ** (b_k / (tk - c_k) - b_k / (rk - c_k))


def best_b(eta_ref, c_k, data):
    """Least-squares B in log10 eta for a fixed C, and its sum of squares."""
    sxy = sxx = 0.0
    rk = TREF_C + KELVIN
    for t, eta in data:
        x = 1.0 / (t + KELVIN - c_k) - 1.0 / (rk - c_k)
        y = math.log10(eta / eta_ref)
        sxy += x * y
        sxx += x * x
    b_k = sxy / sxx
    ss = sum((math.log10(vogel(eta_ref, b_k, c_k, t) / eta)) ** 2 for t, eta in data)
    return b_k, ss


def fit(eta_ref, data):
    """B, C (K) minimising the log10 residuals: scan C, then golden section."""
    grid = [0.5 * k for k in range(0, 500)]  # C from 0 to 249.5 K, below 0 C
    c0 = min(grid, key=lambda c: best_b(eta_ref, c, data)[1])
    lo, hi = max(0.0, c0 - 0.5), c0 + 0.5
    g = (math.sqrt(5.0) - 1.0) / 2.0
    for _ in range(100):
        m1, m2 = hi - g * (hi - lo), lo + g * (hi - lo)
        if best_b(eta_ref, m1, data)[1] < best_b(eta_ref, m2, data)[1]:
            hi = m2
        else:
            lo = m1
    c_k = 0.5 * (lo + hi)
    return best_b(eta_ref, c_k, data)[0], c_k


def main():
    data = [(t, cheng_mpa_s(CM, t)) for t in TEMPS_C]
    eta_ref = float("%.4g" % cheng_mpa_s(CM, TREF_C))  # mPa s, as stored (Pa s / 1000)
    b_k, c_k = fit(eta_ref, data)
    b_r, c_r = round(b_k, 1), round(c_k, 1)
    print("Cheng (2008), %g wt%% glycerol:" % (100 * CM))
    ss, worst, worst_t = 0.0, 0.0, None
    for t, eta in data:
        law = vogel(eta_ref, b_r, c_r, t)
        r = (law - eta) / eta
        ss += r * r
        if abs(r) > abs(worst):
            worst, worst_t = r, t
        print("  %5.1f C  Cheng %9.4f mPa s  law %9.4f  %+6.2f %%" % (t, eta, law, 100 * r))
    print("stored: %.4g Pa s at %g C (Cheng %.6g mPa s)" % (eta_ref / 1000, TREF_C,
                                                          cheng_mpa_s(CM, TREF_C)))
    print("fit: B %.4f K, C %.4f K -> stored B %.1f K, C %.1f K" % (b_k, c_k, b_r, c_r))
    print("law against Cheng: rms %.2f %%, largest %+.2f %% at %g C"
          % (100 * math.sqrt(ss / len(data)), 100 * worst, worst_t))
    print("Cheng against Segur & Oberstar (85 wt%):")
    for t, eta in SEGUR_85.items():
        c = cheng_mpa_s(CM, t)
        print("  %5.1f C  Segur %6.1f  Cheng %7.2f  %+5.2f %%" % (t, eta, c, 100 * (c - eta) / eta))


if __name__ == "__main__":
    main()
