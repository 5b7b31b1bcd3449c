/* Time-temperature superposition of real isotherms against pyvisco's
 * (tests/data/pyvisco, BSD-3, licence and attribution beside it).
 *
 * Two references ship with the fixture, and only one is for these data:
 *   - answers/time_user_raw__shift_factors.csv: pyvisco's own
 *     superposition of exactly these numbers (time_user_raw.csv holds
 *     freq_user_raw.csv's E' with t = 1/f), reference 3 C;
 *   - freq_user_master.csv with answers/freq_user_master__shift_factors.csv:
 *     a master curve pyvisco's examples give as a user's input, NOT built
 *     from freq_user_raw.csv: its loss peak is 874 MPa where no raw point
 *     exceeds 540 MPa, its rubbery E' reaches 89 MPa where the raw data
 *     stop at 257 MPa; the raw isotherms shifted by its own factors miss it
 *     by a factor ~2 to 40 (test_master_is_another_curve).
 * So the master curve is judged against pyvisco's superposition of the
 * same data: both sets of shifted points against one smooth curve through
 * pyvisco's (a local linear fit in log-log, test_same_master). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "vl_test_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tts.h"
#include "viscolube/dma.h"

#define MAXROWS 512

/* A numeric CSV table after its two header lines (names, units). */
typedef struct {
  size_t n, ncol;
  double v[MAXROWS][5];
} table;

static void read_table(const char *file, size_t ncol, table *t) {
  char path[4096];
  snprintf(path, sizeof path, "%s/%s", vl_test_source_path("tests/data/pyvisco"), file);
  FILE *f = fopen(path, "r");
  if (!f) fail_msg("pyvisco fixture missing: %s", path);
  char line[512];
  t->n = 0, t->ncol = ncol;
  for (int skip = 0; skip < 2 && fgets(line, sizeof line, f); skip++) {
  }
  while (t->n < MAXROWS && fgets(line, sizeof line, f)) {
    char *p = line, *end;
    size_t c = 0;
    for (; c < ncol; c++, p = end + (*end == ',')) {
      t->v[t->n][c] = strtod(p, &end);
      if (end == p) break;
    }
    if (c == ncol) t->n++;
  }
  fclose(f);
  assert_true(t->n > 0);
}

/* The raw data imported with the reference at isotherm `set` (its mean
 * temperature, so that no WLF interpolation enters the shifts). */
static void import_raw(size_t set, vl_measured *m) {
  table raw;
  read_table("freq_user_raw.csv", 5, &raw);
  double s = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < raw.n; i++)
    if ((size_t)raw.v[i][4] == set) s += raw.v[i][3], n++;
  vl_dma_options o = vl_dma_options_default();
  o.tref_c = s / (double)n;
  char path[4096];
  snprintf(path, sizeof path, "%s/freq_user_raw.csv", vl_test_source_path("tests/data/pyvisco"));
  vl_error err;
  if (vl_measured_read_file(path, &o, m, &err) != VL_OK) fail_msg("%s", err.msg);
  assert_int_equal(m->n_isotherms, 21);
}

/* pyvisco's log aT at the isotherm of mean temperature t (its table gives
 * nominal temperatures: the nearest). */
static double their_shift(const table *sf, double t) {
  size_t best = 0;
  for (size_t i = 1; i < sf->n; i++)
    if (fabs(sf->v[i][0] - t) < fabs(sf->v[best][0] - t)) best = i;
  return sf->v[best][1];
}

/* ln E' and ln E'' at reduced log10 f of a curve given by points (x, y1,
 * y2): a local linear fit with Gaussian weights of width h decades. */
static void smooth_at(size_t n, const double *x, const double *y1, const double *y2, double h,
                      double xq, double *f1, double *f2) {
  double sw = 0, sx = 0, sxx = 0, s1 = 0, s2 = 0, sx1 = 0, sx2 = 0;
  for (size_t i = 0; i < n; i++) {
    double u = (x[i] - xq) / h, w = exp(-0.5 * u * u), d = x[i] - xq;
    sw += w, sx += w * d, sxx += w * d * d;
    s1 += w * y1[i], s2 += w * y2[i], sx1 += w * d * y1[i], sx2 += w * d * y2[i];
  }
  double det = sw * sxx - sx * sx;
  *f1 = (sxx * s1 - sx * sx1) / det;
  *f2 = (sxx * s2 - sx * sx2) / det;
}

/* rms of ln(E / E_ref) over the points of m placed at reduced log10 f
 * x[i], E_ref from the smooth curve through (xr, ln E'r, ln E''r), for
 * points within [lo, hi]. */
static void rms_against(const vl_measured *m, const double *x, size_t nr, const double *xr,
                        const double *r1, const double *r2, double lo, double hi, double *e1,
                        double *e2) {
  double s1 = 0, s2 = 0;
  size_t n = 0;
  for (size_t i = 0; i < m->n; i++) {
    if (x[i] < lo || x[i] > hi) continue;
    double f1, f2;
    smooth_at(nr, xr, r1, r2, 0.15, x[i], &f1, &f2);
    s1 += pow(log(m->storage_pa[i]) - f1, 2.0);
    s2 += pow(log(m->loss_pa[i]) - f2, 2.0);
    n++;
  }
  *e1 = sqrt(s1 / (double)n);
  *e2 = sqrt(s2 / (double)n);
}

/* How each pair was shifted (vl_tts_chain_info on the imported points,
 * reference as in the import): printed, and the one pair whose windows
 * overlap too little (-20 to -12 C: the step of 2.3 decades leaves 0.7 of
 * a 3-decade window, below the quarter needed) must be flagged as a bound
 * (no_join), not passed off as a measured shift. */
static void check_pairs(const vl_measured *m, size_t ref) {
  static double lw[MAXROWS], y1[MAXROWS], y2[MAXROWS], lat[32];
  vl_tts_isotherm iso[32];
  vl_tts_pair_info info[32];
  size_t k = 0;
  for (size_t g = 0; g < m->n_isotherms; g++) {
    size_t k0 = k;
    for (size_t i = 0; i < m->n; i++)
      if (m->isotherm[i] == g)
        lw[k] = log10(m->omega_rad_s[i]), y1[k] = log10(m->storage_pa[i]),
        y2[k] = log10(m->loss_pa[i]), k++;
    iso[g] = (vl_tts_isotherm){m->iso_temperature_c[g], k - k0, lw + k0, y1 + k0, y2 + k0};
  }
  vl_error err;
  assert_int_equal(vl_tts_chain_info(m->n_isotherms, iso, ref, lat, info, &err), VL_OK);
  size_t flagged = 0;
  for (size_t g = 0; g + 1 < m->n_isotherms; g++) {
    fprintf(stderr,
            "pair %5.1f..%5.1f: shift %6.3f rms %.4f overlap %5.2f loss weight %.3g%s%s%s\n",
            m->iso_temperature_c[g], m->iso_temperature_c[g + 1], info[g].shift, info[g].rms,
            info[g].overlap_decades, info[g].loss_weight, info[g].bridged ? " bridged" : "",
            info[g].at_limit ? " at limit" : "", info[g].no_join ? " no join (a bound)" : "");
    if (info[g].overlap_decades < 0.25 * 3.0 + 0.01 && !info[g].bridged) {
      assert_true(info[g].no_join);
      flagged++;
    }
  }
  assert_int_equal(flagged, 1);
  assert_non_null(strstr(m->notes, "is only a bound"));
}

/* Our shifts against pyvisco's for the same numbers, step by step, and
 * both master curves against one smooth curve through pyvisco's (rms of
 * ln E over our shifted points). Tolerances, measured values in brackets:
 *   - steps from 2.5 C up, where E' rises through the transition and both
 *     methods see it: each within 0.1 decade (0.055; before the
 *     interval mismatch and E'' weighting 0.18, with two steps locked at
 *     exactly 5/3 decades: 5 point spacings);
 *   - glassy steps below, where E' changes by 1-2 % per decade: 0.35
 *     (0.28; before: 0.79, E'' pulled the first step to 0.1 decade where
 *     E' alone and pyvisco say 0.8-0.9);
 *   - the master curve: E' within 0.04 in ln (0.027; before 0.057; pyvisco's
 *     own points 0.010 from the smoothed curve); E'' within 0.25 (0.20;
 *     pyvisco's own 0.16: glassy E'' does not superpose under either set of
 *     shifts, so no shift can bring it to 3 %). */
static void test_same_master(void **state) {
  (void)state;
  vl_measured m;
  import_raw(7, &m); /* pyvisco's reference, "3 C" */
  table sf;
  read_table("answers/time_user_raw__shift_factors.csv", 2, &sf);
  static double xo[MAXROWS], xp[MAXROWS], l1[MAXROWS], l2[MAXROWS];
  double lo = INFINITY, hi = -INFINITY;
  for (size_t i = 0; i < m.n; i++) {
    size_t g = m.isotherm[i];
    double lf = log10(m.omega_rad_s[i] / (2.0 * M_PI));
    xo[i] = lf + m.iso_log10_a_t[g];
    xp[i] = lf + their_shift(&sf, m.iso_temperature_c[g]);
    l1[i] = log(m.storage_pa[i]), l2[i] = log(m.loss_pa[i]);
    lo = fmin(lo, xp[i]), hi = fmax(hi, xp[i]);
  }
  fprintf(stderr, "   T (C)   step ours  pyvisco   log aT ours  pyvisco\n");
  double worst_glass = 0.0, worst_warm = 0.0;
  for (size_t g = 0; g < m.n_isotherms; g++) {
    double t = m.iso_temperature_c[g], a = their_shift(&sf, t);
    double so = g ? m.iso_log10_a_t[g - 1] - m.iso_log10_a_t[g] : NAN;
    double sp = g ? their_shift(&sf, m.iso_temperature_c[g - 1]) - a : NAN;
    fprintf(stderr, "%8.2f  %8.3f %8.3f   %8.3f %8.3f\n", t, so, sp, m.iso_log10_a_t[g], a);
    if (!g) continue;
    if (m.iso_temperature_c[g - 1] < 2.0)
      worst_glass = fmax(worst_glass, fabs(so - sp));
    else
      worst_warm = fmax(worst_warm, fabs(so - sp));
  }
  check_pairs(&m, 7);
  double o1, o2, p1, p2;
  rms_against(&m, xo, m.n, xp, l1, l2, lo, hi, &o1, &o2);
  rms_against(&m, xp, m.n, xp, l1, l2, lo, hi, &p1, &p2);
  fprintf(stderr,
          "steps vs pyvisco: worst glassy %.3f, from 2.5 C up %.3f decades; against pyvisco's "
          "superposition (smoothed): ours E' %.4f E'' %.4f rms ln; pyvisco's own points E' %.4f "
          "E'' %.4f\n",
          worst_glass, worst_warm, o1, o2, p1, p2);
  assert_true(worst_warm < 0.1 && worst_glass < 0.35);
  assert_true(o1 < 0.04 && o2 < 0.25);
  vl_measured_free(&m);
}

/* freq_user_master.csv is not these data's master curve: shifted by the
 * factors that come with it, the raw points miss it by far more than any
 * shift error could explain. */
static void test_master_is_another_curve(void **state) {
  (void)state;
  vl_measured m;
  import_raw(6, &m); /* that master's reference, "-5 C" */
  table sf, mc;
  read_table("answers/freq_user_master__shift_factors.csv", 2, &sf);
  read_table("freq_user_master.csv", 3, &mc);
  static double xr[MAXROWS], r1[MAXROWS], r2[MAXROWS], xo[MAXROWS], xp[MAXROWS];
  for (size_t i = 0; i < mc.n; i++)
    xr[i] = log10(mc.v[i][0]), r1[i] = log(mc.v[i][1] * 1e6), r2[i] = log(mc.v[i][2] * 1e6);
  for (size_t i = 0; i < m.n; i++) {
    size_t g = m.isotherm[i];
    double lf = log10(m.omega_rad_s[i] / (2.0 * M_PI));
    xo[i] = lf + m.iso_log10_a_t[g];
    xp[i] = lf + their_shift(&sf, m.iso_temperature_c[g]);
  }
  double o1, o2, p1, p2;
  rms_against(&m, xo, mc.n, xr, r1, r2, xr[0], xr[mc.n - 1], &o1, &o2);
  rms_against(&m, xp, mc.n, xr, r1, r2, xr[0], xr[mc.n - 1], &p1, &p2);
  fprintf(stderr,
          "against freq_user_master.csv: ours E' %.4f E'' %.4f rms ln; the raw points at its "
          "own shifts E' %.4f E'' %.4f\n",
          o1, o2, p1, p2);
  /* a factor e and more (measured: 14 in E', 11 in E'' at its own shifts) */
  assert_true(p1 > 1.0 && p2 > 1.0 && o1 > 1.0 && o2 > 1.0);
  double peak_raw = 0.0, peak_master = 0.0;
  for (size_t i = 0; i < m.n; i++)
    peak_raw = fmax(peak_raw, m.loss_pa[i]);
  for (size_t i = 0; i < mc.n; i++)
    peak_master = fmax(peak_master, mc.v[i][2] * 1e6);
  fprintf(stderr, "loss peak: raw %.4g Pa, that master %.4g Pa\n", peak_raw, peak_master);
  assert_true(peak_raw < 0.7 * peak_master); /* no horizontal shift raises E'' */
  vl_measured_free(&m);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_same_master),
      cmocka_unit_test(test_master_is_another_curve),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
