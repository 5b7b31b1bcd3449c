/* Time-temperature superposition (tts.h): shifts of isotherms cut from a
 * known master curve at known offsets, the WLF fit on exact WLF data, and
 * the choice between E' alone and E' with E''. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "vl_test_util.h"

#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tts.h"

/* A Havriliak-Negami master curve (independent of any viscolube code):
 * E = Einf + (E0 - Einf)/(1 + (i w tau)^a)^b, DMA convention E'' > 0. */
static double complex hn(double w) {
  const double e0 = 2e6, einf = 2e9, tau = 2.5e-3, a = 0.6, b = 0.35;
  return einf + (e0 - einf) / cpow(1.0 + cpow(I * w * tau, a), b);
}

typedef struct {
  double x[32], y1[32], y2[32];
  vl_tts_isotherm iso;
} isotherm_buf;

/* An isotherm sampled at 0.1..100 Hz (13 points) whose master-curve
 * position is shifted by log10 aT; noise: relative Gaussian-like (sum of
 * uniforms) of amplitude rel on both curves; e2_flat replaces E'' by a
 * temperature-independent curve (a secondary relaxation that does not
 * superpose). */
static void make_isotherm(isotherm_buf *b, double t_c, double log_at, double rel, int e2_flat,
                          unsigned *seed) {
  for (int k = 0; k < 13; k++) {
    double w = 2.0 * M_PI * pow(10.0, -1.0 + 0.25 * k);
    double complex e = hn(w * pow(10.0, log_at));
    double n1 = 0.0, n2 = 0.0;
    for (int j = 0; j < 12; j++) {
      *seed = *seed * 1103515245u + 12345u;
      n1 += (double)(*seed >> 8) / 16777216.0 - 0.5;
      *seed = *seed * 1103515245u + 12345u;
      n2 += (double)(*seed >> 8) / 16777216.0 - 0.5;
    }
    b->x[k] = log10(w);
    b->y1[k] = log10(creal(e) * (1.0 + rel * n1));
    b->y2[k] = e2_flat ? log10(1e8 * (1.0 + 0.3 * pow(log10(w) - 1.0, 2.0)))
                       : log10(cimag(e) * (1.0 + rel * n2));
  }
  b->iso = (vl_tts_isotherm){t_c, 13, b->x, b->y1, b->y2};
}

/* An isotherm as a DMA sweep exports it: 10 frequencies 0.1..100 Hz (3 per
 * decade), 0.5 % noise, and an instrument artefact in the phase: tan delta
 * raised by art (f / 100 Hz)^0.7 at every temperature (pyvisco's glassy
 * isotherms all end at tan delta 0.044 at 100 Hz). */
static void make_sweep(isotherm_buf *b, double t_c, double log_at, double art, unsigned *seed) {
  for (int k = 0; k < 10; k++) {
    double f = pow(10.0, -1.0 + k / 3.0), w = 2.0 * M_PI * f;
    double complex e = hn(w * pow(10.0, log_at));
    double n1 = 0.0, n2 = 0.0;
    for (int j = 0; j < 12; j++) {
      *seed = *seed * 1103515245u + 12345u;
      n1 += (double)(*seed >> 8) / 16777216.0 - 0.5;
      *seed = *seed * 1103515245u + 12345u;
      n2 += (double)(*seed >> 8) / 16777216.0 - 0.5;
    }
    b->x[k] = log10(w);
    b->y1[k] = log10(creal(e) * (1.0 + 0.005 * n1));
    b->y2[k] = log10((cimag(e) + art * pow(f / 100.0, 0.7) * creal(e)) * (1.0 + 0.005 * n2));
  }
  b->iso = (vl_tts_isotherm){t_c, 10, b->x, b->y1, b->y2};
}

/* Sweeps through the glass transition 7.5 K apart (steps of 0.7 to 3.3
 * decades of a 3-decade window, as pyvisco's), with and without the phase
 * artefact, which adds a temperature-independent E'' that does not
 * superpose: every step within 0.05 decade of the truth (measured 0.030,
 * the bridged coldest step without the artefact; the 5 to 12.5 C step
 * with it 0.002, 0.025 when E'' weighed as much as E'), except that with
 * the artefact the coldest step (3.3 decades, E' flat, E'' spoilt) cannot
 * be found, and must then be flagged as a bound (no_join), not passed
 * off as a shift. */
static void test_phase_artefact(void **state) {
  (void)state;
  const double c1 = 17.44 * 51.6 / 71.6, c2 = 71.6;
  for (int with = 0; with < 2; with++) {
    isotherm_buf buf[9];
    vl_tts_isotherm iso[9];
    double t[9], exact[9], lat[9], worst = 0.0;
    unsigned seed = 11;
    for (int k = 0; k < 9; k++) {
      t[k] = -10.0 + 7.5 * k;
      exact[k] = -c1 * (t[k] - 20.0) / (c2 + t[k] - 20.0);
      make_sweep(&buf[k], t[k], exact[k], with ? 0.03 : 0.0, &seed);
      iso[k] = buf[k].iso;
    }
    vl_tts_pair_info info[8];
    vl_error err;
    assert_int_equal(vl_tts_chain_info(9, iso, 4, lat, info, &err), VL_OK);
    for (int k = 0; k + 1 < 9; k++) {
      double e = fabs((lat[k + 1] - lat[k]) - (exact[k + 1] - exact[k]));
      fprintf(stderr, "artefact %d: %5.1f..%5.1f C step %.3f (exact %.3f) loss weight %.3g%s%s\n",
              with, t[k], t[k + 1], lat[k + 1] - lat[k], exact[k + 1] - exact[k],
              info[k].loss_weight, info[k].bridged ? " bridged" : "",
              info[k].no_join ? " no join" : "");
      if (info[k].no_join || info[k].at_limit) {
        assert_true(with && k == 0);
        continue;
      }
      worst = fmax(worst, e);
      assert_true(e < 0.05);
    }
    fprintf(stderr, "artefact %d: worst step error %.3f decades\n", with, worst);
  }
}

/* Sweeps 3 points per decade offset by 1.60 to 1.74 decades (around 5
 * point spacings, 5/3 decade), 0.5 % noise: each pair shift within 0.03
 * decade of its offset, E' alone and with E'' (measured 0.004). The
 * interval mismatch through cubic interpolants (tts.c) was made for
 * pyvisco's real isotherms, where three neighbouring steps locked at
 * exactly 5/3 decades (test_tts_pyvisco); these smooth synthetic sweeps
 * did not lock with the point-set mean either (0.004, and 0.02 at 2-3 %
 * noise): this checks that the new comparison is as accurate. */
static void test_no_grid_lock(void **state) {
  (void)state;
  unsigned seed = 17;
  double worst = 0.0;
  for (int i = 0; i <= 7; i++) {
    double off = 1.60 + 0.02 * i, d;
    isotherm_buf a, b;
    make_sweep(&a, 0.0, 1.0, 0.0, &seed);
    make_sweep(&b, 5.0, 1.0 - off, 0.0, &seed);
    vl_error err;
    for (int w = 0; w < 2; w++) {
      assert_int_equal(vl_tts_pair_shift(&a.iso, &b.iso, (double)w, &d, NULL, &err), VL_OK);
      worst = fmax(worst, fabs(d + off));
    }
  }
  fprintf(stderr, "offsets near 5 point spacings: worst shift error %.4f decades\n", worst);
  assert_true(worst < 0.03);
}

/* Exact curves: the shift between two cuts of the same master curve is
 * their offset, to the accuracy of piecewise-linear interpolation between
 * points 0.25 decade apart (0.005 decade: the interpolant's error in log E
 * is ~1e-3 decade over slopes of ~0.3, read both ways). */
static void test_pair_exact(void **state) {
  (void)state;
  unsigned seed = 1;
  isotherm_buf a, b;
  const double offsets[][2] = {{2.0, 0.5}, {0.0, -1.3}, {-3.0, -4.7}, {5.0, 3.0}, {-6.0, -6.4}};
  for (size_t i = 0; i < sizeof offsets / sizeof *offsets; i++) {
    make_isotherm(&a, 10.0, offsets[i][0], 0.0, 0, &seed);
    make_isotherm(&b, 15.0, offsets[i][1], 0.0, 0, &seed);
    double want = offsets[i][1] - offsets[i][0], d, r;
    vl_error err;
    for (int w = 0; w < 2; w++) {
      assert_int_equal(vl_tts_pair_shift(&a.iso, &b.iso, (double)w, &d, &r, &err), VL_OK);
      if (fabs(d - want) > 0.005)
        fail_msg("pair %zu, loss weight %d: shift %.4f, want %.4f", i, w, d, want);
    }
  }
}

/* The chain over 21 noisy isotherms (1 % noise, as the shipped synthetic
 * data) at WLF shifts C1 12.57, C2 71.6 K about 20 C: every chained shift
 * within 0.05 decade of the exact one (measured ~0.02: each pair is
 * determined to ~0.005 decade and errors add along the chain), and the WLF
 * fit recovers C1 within 2 % and C2 within 2 K. */
static void test_chain_and_wlf(void **state) {
  (void)state;
  const double c1 = 17.44 * 51.6 / 71.6, c2 = 71.6;
  isotherm_buf buf[21];
  vl_tts_isotherm iso[21];
  double t[21], exact[21], lat[21];
  unsigned seed = 7;
  for (int k = 0; k < 21; k++) {
    t[k] = 5.0 * k;
    exact[k] = -c1 * (t[k] - 20.0) / (c2 + t[k] - 20.0);
    make_isotherm(&buf[k], t[k], exact[k], 0.01, 0, &seed);
    iso[k] = buf[k].iso;
  }
  vl_error err;
  assert_int_equal(vl_tts_chain(21, iso, 4, lat, NULL, &err), VL_OK);
  double worst = 0.0;
  for (int k = 0; k < 21; k++)
    worst = fmax(worst, fabs(lat[k] - exact[k]));
  fprintf(stderr, "chain of 21 noisy isotherms: worst shift error %.4f decades\n", worst);
  assert_true(worst < 0.05);
  double f1, f2, rms;
  assert_int_equal(vl_wlf_fit(21, t, lat, 20.0, &f1, &f2, &rms, &err), VL_OK);
  fprintf(stderr, "WLF fit: C1 %.4f (%.4f), C2 %.3f K (%.3f), rms %.4f\n", f1, c1, f2, c2, rms);
  assert_true(fabs(f1 / c1 - 1.0) < 0.02 && fabs(f2 - c2) < 2.0 && rms < 0.05);
}

/* E'' that does not superpose (a flat secondary relaxation) would pin every
 * shift to 0; E' alone must then decide, and still find the offset. */
static void test_nonsuperposing_loss(void **state) {
  (void)state;
  unsigned seed = 3;
  isotherm_buf a, b, c;
  make_isotherm(&a, 0.0, 4.0, 0.0, 1, &seed);
  make_isotherm(&b, 5.0, 3.0, 0.0, 1, &seed);
  make_isotherm(&c, 10.0, 2.2, 0.0, 1, &seed);
  vl_tts_isotherm iso[3] = {a.iso, b.iso, c.iso};
  double lat[3];
  vl_error err;
  assert_int_equal(vl_tts_chain(3, iso, 1, lat, NULL, &err), VL_OK);
  if (fabs(lat[0] - 1.0) > 0.01 || fabs(lat[2] + 0.8) > 0.01)
    fail_msg("shifts %.4f %.4f %.4f, want 1, 0, -0.8", lat[0], lat[1], lat[2]);
  /* with E'' forced in, the shift is visibly wrong: the case the policy avoids */
  double d;
  assert_int_equal(vl_tts_pair_shift(&a.iso, &b.iso, 1.0, &d, NULL, &err), VL_OK);
  assert_true(fabs(d + 1.0) > 0.1);
}

/* Offsets of most of a window (thin overlaps) and beyond it (gaps up to a
 * decade), deep in the glass where log E' is flat (offsets 6 to 9: the
 * isotherm sits 1e6 to 1e9 times above the loss peak): the chain bridges
 * them (vl_tts_chain_info) and finds the offset within 0.005 decade on
 * exact curves, in both directions; beyond a gap of a decade the pair is
 * flagged (at_limit, or no_join when the best bridge still fits badly).
 * Before bridging, the overlap constraint held such shifts at a
 * quarter-window overlap (2.25 decades here). */
static void test_bridged_pairs(void **state) {
  (void)state;
  unsigned seed = 5;
  const double steps[] = {2.6, 2.83, 2.95, 3.4, 3.9, 4.4};
  for (size_t i = 0; i < sizeof steps / sizeof *steps; i++) {
    isotherm_buf a, b;
    make_isotherm(&a, 0.0, 9.0, 0.0, 0, &seed);
    make_isotherm(&b, 5.0, 9.0 - steps[i], 0.0, 0, &seed);
    vl_tts_isotherm iso[2] = {a.iso, b.iso};
    double lat[2];
    vl_tts_pair_info info;
    vl_error err;
    for (size_t ref = 0; ref < 2; ref++) {
      assert_int_equal(vl_tts_chain_info(2, iso, ref, lat, &info, &err), VL_OK);
      double d = lat[1] - lat[0];
      fprintf(stderr, "offset %.2f: shift %.4f, overlap %.3f, bridged %d, at limit %d\n", -steps[i],
              d, info.overlap_decades, info.bridged, info.at_limit);
      assert_true(fabs(info.shift - d) < 1e-12);
      if (steps[i] > 3.0 + 1.0) { /* beyond a gap of a decade: flagged either way */
        fprintf(stderr, "  no join %d\n", info.no_join);
        assert_true((info.bridged && info.at_limit) || info.no_join);
        continue;
      }
      assert_true(info.bridged && !info.at_limit && !info.no_join);
      assert_true(info.loss_used);
      if (steps[i] < 4.0 && fabs(d + steps[i]) > 0.005)
        fail_msg("offset %.2f: shift %.4f", -steps[i], d);
    }
  }
  /* a pair with ample overlap is not bridged */
  isotherm_buf a, b;
  make_isotherm(&a, 0.0, 3.0, 0.0, 0, &seed);
  make_isotherm(&b, 5.0, 2.0, 0.0, 0, &seed);
  vl_tts_isotherm iso[2] = {a.iso, b.iso};
  double lat[2];
  vl_tts_pair_info info;
  vl_error err;
  assert_int_equal(vl_tts_chain_info(2, iso, 0, lat, &info, &err), VL_OK);
  assert_false(info.bridged);
  assert_true(fabs(info.overlap_decades - 2.0) < 0.01);
}

/* WLF on exact WLF shifts: the constants come back (1e-6: golden-section
 * refinement in log C2 to ~1e-9), also about a reference temperature that
 * is not one of the data points, and with a point at Tref itself. */
static void test_wlf_exact(void **state) {
  (void)state;
  const double c1 = 8.86, c2 = 101.6, tref = 25.0;
  double t[9], y[9], f1, f2, rms;
  for (int k = 0; k < 9; k++) {
    t[k] = -20.0 + 12.5 * k;
    y[k] = -c1 * (t[k] - tref) / (c2 + t[k] - tref);
  }
  vl_error err;
  assert_int_equal(vl_wlf_fit(9, t, y, tref, &f1, &f2, &rms, &err), VL_OK);
  assert_true(fabs(f1 - c1) < 1e-6 * c1 && fabs(f2 - c2) < 1e-6 * c2 && rms < 1e-9);
  assert_int_equal(vl_wlf_fit(9, t, y, tref, &f1, &f2, NULL, &err), VL_OK);
}

static void test_refusals(void **state) {
  (void)state;
  double t[3] = {0, 10, 20}, up[3] = {-1, 0, 1}, f1, f2;
  vl_error err;
  assert_int_equal(vl_wlf_fit(2, t, up, 10.0, &f1, &f2, NULL, &err), VL_EINPUT);
  assert_int_equal(vl_wlf_fit(3, t, up, 10.0, &f1, &f2, NULL, &err), VL_EINPUT);
  assert_non_null(strstr(err.msg, "do not decrease"));
  double bad[3] = {1, NAN, -1};
  assert_int_equal(vl_wlf_fit(3, t, bad, 10.0, &f1, &f2, NULL, &err), VL_EINPUT);

  /* windows that cannot overlap by a quarter */
  double xa[2] = {0, 1}, ya[2] = {6, 7}, xb[2] = {5, 6};
  vl_tts_isotherm a = {0.0, 2, xa, ya, ya}, b = {10.0, 2, xb, ya, ya}, one = {5.0, 1, xa, ya, ya};
  double d;
  assert_int_equal(vl_tts_pair_shift(&a, &one, 0.0, &d, NULL, &err), VL_EINPUT);
  assert_non_null(strstr(err.msg, "5 C"));
  assert_int_equal(vl_tts_pair_shift(&a, &b, 0.0, &d, NULL, &err), VL_OK); /* may overlap at d=-5 */
  assert_true(fabs(d + 5.0) < 0.76);
  assert_int_equal(vl_tts_chain(0, &a, 0, &d, NULL, &err), VL_EINPUT);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_pair_exact),          cmocka_unit_test(test_chain_and_wlf),
      cmocka_unit_test(test_nonsuperposing_loss), cmocka_unit_test(test_bridged_pairs),
      cmocka_unit_test(test_wlf_exact),           cmocka_unit_test(test_refusals),
      cmocka_unit_test(test_phase_artefact),      cmocka_unit_test(test_no_grid_lock),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
