/* Validation: a long ellipsoid tends to the line contact in its central
 * strip (issue 35; docs/POINT_CONTACT.md section 6). An ellipsoid
 * elongated across the sliding direction (Ry >> Rx) presses, near y = 0,
 * like a cylinder of radius Rx carrying the strip's load per unit length
 * w = \int p(x, 0) dx. The ellipsoid is solved by the point contact (its
 * row of cells next to y = 0 is the strip), the cylinder by the line
 * contact (include/viscolube/contact.h: an independent code, with its own
 * closed-form memory kernel and its own grid) at the same speed and w.
 *
 * Both on the model rubber (E0 3.6 MPa, Einf/E0 = 10, tau 0.1 s,
 * nu 0.5), Rx = 1 cm, W = 10 N; De = v0 tau / a, a the relaxed Hertz
 * ellipse's semi-axis along x, b across (b/a = 4.50 at Ry/Rx = 10, 8.88 at
 * 30). Compared: the strip's half-width (from its second moment,
 * a = 2 sqrt(\int p x^2 / \int p) for Hertz's p0 sqrt(1 - x^2/a^2)), its
 * peak pressure (elastic) and its pressure centroid (viscoelastic).
 *
 * The strip is not the cylinder exactly at a finite length. Elastic, the
 * difference is Hertz's (Johnson, Contact Mechanics, 4.2): the curvature
 * along the minor axis, 1/(2 Rx) = p0 (E(e) - (1 - e^2) K(e))/(Er a e^2),
 * gives p0 = c Er a/(2 Rx) with c = e^2/(E - (1 - e^2) K), against the
 * cylinder's Er a/(2 R): at the same w = pi a p0/2 the strip is narrower
 * by 1/sqrt(c) and its peak higher by sqrt(c) (c = 1.0135 at Ry/Rx = 30:
 * -0.67 % and +0.67 %; 1.0379 at 10: -1.84 % and +1.88 %). Viscoelastic,
 * the memory reaches De a upstream; while that is short against the
 * ellipse's length b the strip's rubber deforms as a cylinder's, and the
 * strip's centroid is the cylinder's up to the same finite-length order.
 * Measured (the solves of this file and a scratch copy of
 * bench/ball_long_ellipsoid; 8 to 16 cells across a at Ry/Rx = 30, 12 at
 * 10, 8 and 10 at 60 and 120), strip's centroid / cylinder's - 1:
 *
 *   De 0.3: -0.72, -0.72, -0.45, -0.53, -0.36 % on 8, 10, 12, 14, 16 cells
 *           at Ry/Rx = 30; -0.6 % at 60 and 120: falls with the cells
 *           (not steadily: the inlet's edge crosses the cells differently
 *           on each grid), not with the length. Numerical.
 *   De 1:   -1.24, -1.02, -1.10, -1.17, -1.14 % on the same cells at 30;
 *           -2.8 % at 10, -0.5 to -0.7 % at 60, -0.2 to -0.45 % at 120:
 *           falls with the length, not with the cells. Physical.
 *   De 3:   -5.0 % at 30 (4.9-5.3 on every grid), -11 % at 10: the memory
 *           (3 a) reaches a third of the way along the ellipse; not
 *           asserted (docs/POINT_CONTACT.md section 6: up to 40 % beyond).
 *
 * The line contact's numbers move by less than 1e-5 between 512, 1024 and
 * 2048 cells (measured): its own error is negligible here. Cost: about
 * 3.2 s (the ellipsoid of Ry/Rx = 30 on 12 cells across a: 3248 cells). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
/* cmocka.h needs the four above first (own block: not re-sorted) */
#include <cmocka.h>

#include "vl_test_util.h"

#include <gsl/gsl_sf_ellint.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rheology_internal.h"
#include "viscolube/contact.h"
#include "viscolube/point_contact.h"

#define E0 3.6e6
#define NU 0.5
#define TAU 0.1
#define RADIUS_X 0.01
#define LOAD 10.0
#define LINE_CELLS 1024

/* The domain around the relaxed Hertz ellipse (its semi-axes times these):
 * the viscoelastic contact shrinks and moves upstream inside it; each run
 * checks that no pressure reaches the domain's edge. */
#define MARGIN_X 1.15
#define MARGIN_Y 1.05

/* The runs: (Ry/Rx, cells across a), each at the speeds below. */
enum { RUN_30_COARSE, RUN_30, RUN_10, N_RUNS };
static const double run_ratio[N_RUNS] = {30.0, 30.0, 10.0};
static const double run_across[N_RUNS] = {8.0, 12.0, 12.0};
enum { N_DE = 3 };
static const double de_list[N_DE] = {0.0, 0.3, 1.0}; /* 0: relaxed (elastic) */

/* The moments of a pressure on one line: load per length, centroid,
 * half-width from the second moment about the centroid, peak. */
typedef struct {
  double w, xc, half, peak;
} strip_moments;

typedef struct {
  double a, b, c; /* Hertz ellipse (m) and its finite-length factor */
  size_t cells;   /* of the point contact's half */
  strip_moments strip[N_DE], line[N_DE];
  double line_hertz_half; /* closed-form half-width of the cylinder at the strip's w */
} long_run;

static long_run runs[N_RUNS];

static strip_moments moments(size_t n, const double *x, const double *p, const double *w) {
  strip_moments m = {0};
  for (size_t i = 0; i < n; i++) {
    m.w += p[i] * w[i];
    m.xc += p[i] * x[i] * w[i];
    m.peak = fmax(m.peak, p[i]);
  }
  m.xc /= m.w;
  double m2 = 0.0;
  for (size_t i = 0; i < n; i++)
    m2 += p[i] * (x[i] - m.xc) * (x[i] - m.xc) * w[i];
  m.half = 2.0 * sqrt(m2 / m.w);
  return m;
}

/* c = e^2/(E(e) - (1 - e^2) K(e)) for the ellipse of semi-axes a < b. */
static double finite_length_factor(double a, double b) {
  double k2 = (a / b) * (a / b), e = sqrt(1.0 - k2);
  double K = gsl_sf_ellint_Kcomp(e, GSL_PREC_DOUBLE), E = gsl_sf_ellint_Ecomp(e, GSL_PREC_DOUBLE);
  return e * e / (E - k2 * K);
}

/* The strip of the solved point contact: the cells next to y = 0 (their
 * centres at h/2: Hertz's pressure there differs from y = 0 by
 * (h/2b)^2/2 < 2e-5). Fails the test when a cell on the domain's edge
 * carries pressure. */
static strip_moments point_strip(const vl_point_contact *c) {
  size_t n = vl_point_contact_cells(c);
  double *buf = malloc(3 * n * sizeof *buf);
  assert_non_null(buf);
  vl_fields2d f = {buf, buf + n, buf + 2 * n, NULL, NULL};
  vl_point_contact_fields(c, &f);
  size_t ny = 0;
  while (ny < n && f.x_m[ny] == f.x_m[0])
    ny++;
  size_t nx = n / ny;
  double h = f.x_m[ny] - f.x_m[0];
  double *x = malloc(3 * nx * sizeof *x), *p = x + nx, *w = x + 2 * nx;
  assert_non_null(x);
  for (size_t i = 0; i < nx; i++) {
    x[i] = f.x_m[i * ny], p[i] = f.p_c_pa[i * ny], w[i] = h;
    assert_true(f.p_c_pa[i * ny + ny - 1] == 0.0);
  }
  for (size_t j = 0; j < ny; j++)
    assert_true(f.p_c_pa[j] == 0.0 && f.p_c_pa[(nx - 1) * ny + j] == 0.0);
  strip_moments m = moments(nx, x, p, w);
  free(x);
  free(buf);
  return m;
}

/* The cylinder of radius Rx carrying w (N/m) at v0, solved by the line
 * contact on LINE_CELLS cells over [-1.5, 1.5] of its Hertz half-width. */
static strip_moments line_strip(const vl_prony *rubber, double w, double v0) {
  vl_contact_config lc;
  vl_contact_config_defaults(&lc);
  lc.rubber = *rubber, lc.radius_m = RADIUS_X, lc.load_n_per_m = w;
  lc.grid = LINE_CELLS, lc.x_min_a0 = -1.5, lc.x_max_a0 = 1.5;
  vl_contact *line = NULL;
  vl_error err;
  if (vl_contact_create(&lc, &line, &err) != VL_OK) fail_msg("line contact: %s", err.msg);
  vl_point pt;
  if (vl_contact_solve(line, v0, &pt, &err) != VL_OK) fail_msg("line contact: %s", err.msg);
  assert_true(pt.converged);
  size_t m = vl_contact_grid(line);
  double *b = malloc(7 * m * sizeof *b);
  assert_non_null(b);
  vl_fields f = {m, b, b + m, b + 2 * m, b + 3 * m, b + 4 * m, b + 5 * m, b + 6 * m};
  vl_contact_fields(line, &f);
  strip_moments s = moments(m, f.x_m, f.p_c_pa, f.width_m);
  assert_true(fabs(s.xc - pt.x_centroid_m) <= 1e-9 * s.half); /* the same centroid */
  free(b);
  vl_contact_free(line);
  return s;
}

/* Solves every run at every speed (once, for all the tests below). */
static int solve_runs(void **state) {
  (void)state;
  vl_prony rubber = vl_prony_single(E0, 10.0, TAU, NU);
  double er0 = E0 / (1.0 - NU * NU);
  for (size_t r = 0; r < N_RUNS; r++) {
    long_run *run = &runs[r];
    vl_point_contact_config cfg;
    vl_point_contact_config_defaults(&cfg);
    cfg.rubber = rubber;
    cfg.radius_x_m = RADIUS_X, cfg.radius_y_m = run_ratio[r] * RADIUS_X, cfg.load_n = LOAD;
    if (vl_hertz_ellipse(cfg.radius_x_m, cfg.radius_y_m, LOAD, er0, &run->a, &run->b, NULL) !=
        VL_OK)
      return -1;
    run->c = finite_length_factor(run->a, run->b);
    vl_point_contact *c = NULL;
    vl_error err;
    if (vl_point_contact_create(&cfg, &c, &err) != VL_OK) return -1;
    double a0 = vl_point_contact_a0(c);
    vl_point_contact_free(c);
    cfg.cells_per_a0 = run_across[r] * a0 / run->a;
    cfg.x_half_a0 = MARGIN_X * run->a / a0, cfg.y_max_a0 = MARGIN_Y * run->b / a0;
    if (vl_point_contact_create(&cfg, &c, &err) != VL_OK) {
      fprintf(stderr, "create: %s\n", err.msg);
      return -1;
    }
    run->cells = vl_point_contact_cells(c);
    for (size_t k = 0; k < N_DE; k++) {
      double v0 = de_list[k] * run->a / TAU;
      vl_point pt;
      if (vl_point_contact_solve(c, v0, &pt, &err) != VL_OK || !pt.converged ||
          !(pt.load_error < 1e-9)) {
        fprintf(stderr, "Ry/Rx %g, De %g: %s\n", run_ratio[r], de_list[k], err.msg);
        vl_point_contact_free(c);
        return -1;
      }
      run->strip[k] = point_strip(c);
      run->line[k] = line_strip(&rubber, run->strip[k].w, v0);
    }
    vl_point_contact_free(c);
    double w0 = run->strip[0].w;
    run->line_hertz_half = sqrt(4.0 * w0 * RADIUS_X / (M_PI * er0));
    printf("Ry/Rx %3.0f (b/a %.2f), %2.0f cells across a (%zu cells), c = %.5f\n", run_ratio[r],
           run->b / run->a, run_across[r], run->cells, run->c);
    for (size_t k = 0; k < N_DE; k++) {
      const strip_moments *s = &run->strip[k], *l = &run->line[k];
      printf("  De %.1f: strip w %.1f N/m, centroid %+.5f a, half-width %.5f a, peak %.4g Pa | "
             "cylinder centroid %+.5f a, half-width %.5f a, peak %.4g Pa\n",
             de_list[k], s->w, s->xc / run->a, s->half / run->a, s->peak, l->xc / run->a,
             l->half / run->a, l->peak);
    }
  }
  return 0;
}

/* Relaxed (elastic): the strip's half-width and peak within 1 % of the
 * cylinder's at the same load per length (Ry/Rx = 30, 12 cells across a;
 * measured -0.74 and +0.70 %), and their departure from the cylinder the
 * finite length of Hertz's ellipse (1/sqrt(c) and sqrt(c)) to within
 * 0.1 % on 12 cells (measured 0.07 and 0.02 % at 30, 0.06 and 0.02 % at
 * 10), the rest numerical: it falls from 8 to 12 cells (0.14 -> 0.07 %
 * and 0.05 -> 0.02 %, order 1.7-2.1; 0.04 % at 16) and is asserted to. The
 * cylinder against its own closed form sqrt(4 w R/(pi Er0)): 1e-3. */
static void test_relaxed_strip(void **state) {
  (void)state;
  double dev_half[N_RUNS], dev_peak[N_RUNS];
  for (size_t r = 0; r < N_RUNS; r++) {
    const long_run *run = &runs[r];
    const strip_moments *s = &run->strip[0], *l = &run->line[0];
    double half = s->half / l->half, peak = s->peak / l->peak;
    dev_half[r] = half * sqrt(run->c) - 1.0, dev_peak[r] = peak / sqrt(run->c) - 1.0;
    printf("Ry/Rx %3.0f, %2.0f cells: strip/cylinder half-width %+.3f %%, peak %+.3f %%; "
           "Hertz's ellipse: %+.3f %%, %+.3f %%; departure %+.3f %%, %+.3f %%; cylinder "
           "against its closed form %+.4f %%\n",
           run_ratio[r], run_across[r], 100.0 * (half - 1.0), 100.0 * (peak - 1.0),
           100.0 * (1.0 / sqrt(run->c) - 1.0), 100.0 * (sqrt(run->c) - 1.0), 100.0 * dev_half[r],
           100.0 * dev_peak[r], 100.0 * (l->half / run->line_hertz_half - 1.0));
    assert_true(fabs(l->half / run->line_hertz_half - 1.0) < 1e-3);
    assert_true(fabs(s->xc) < 1e-9 * run->a && fabs(l->xc) < 1e-9 * run->a); /* symmetric */
    if (r != RUN_30_COARSE) {
      assert_true(fabs(dev_half[r]) < 1e-3);
      assert_true(fabs(dev_peak[r]) < 1e-3);
    }
  }
  const long_run *run = &runs[RUN_30];
  assert_true(fabs(run->strip[0].half / run->line[0].half - 1.0) < 0.01);
  assert_true(fabs(run->strip[0].peak / run->line[0].peak - 1.0) < 0.01);
  assert_true(fabs(dev_half[RUN_30]) < fabs(dev_half[RUN_30_COARSE]));
  assert_true(fabs(dev_peak[RUN_30]) < fabs(dev_peak[RUN_30_COARSE]));
}

/* Viscoelastic: the strip's pressure centroid against the cylinder's at
 * De = 0.3 and 1 (the memory 0.3 a and a against b = 8.9 a), Ry/Rx = 30,
 * on 8 and 12 cells across a. Tolerances from the measurements of the
 * header: at De 0.3 within 1 % (the numerical scatter, 0.36-0.72 % on 8-16
 * cells), at De 1 within 1.5 % (1.02-1.24 % on 8-16 cells: the finite
 * length, as the elastic strip's 0.67 %, and the scatter). That the
 * difference at De 1 is the finite length and not the cells: it changes
 * by less than 0.3 % between 8 and 12 cells (measured 0.14 %), and at
 * Ry/Rx = 10 (12 cells) it is more than twice as large (measured 2.78 %
 * against 1.10 %). */
static void test_viscoelastic_centroid(void **state) {
  (void)state;
  const double tol[N_DE] = {0.0, 0.01, 0.015};
  double d[N_RUNS][N_DE];
  for (size_t r = 0; r < N_RUNS; r++)
    for (size_t k = 1; k < N_DE; k++) {
      d[r][k] = runs[r].strip[k].xc / runs[r].line[k].xc - 1.0;
      printf("Ry/Rx %3.0f, %2.0f cells, De %.1f: centroid strip/cylinder %+.3f %%\n", run_ratio[r],
             run_across[r], de_list[k], 100.0 * d[r][k]);
      assert_true(runs[r].strip[k].xc < 0.0 && runs[r].line[k].xc < 0.0); /* inlet side */
    }
  for (size_t k = 1; k < N_DE; k++) {
    assert_true(fabs(d[RUN_30][k]) < tol[k]);
    assert_true(fabs(d[RUN_30_COARSE][k]) < tol[k]);
  }
  assert_true(fabs(d[RUN_30][2] - d[RUN_30_COARSE][2]) < 3e-3);
  assert_true(fabs(d[RUN_10][2]) > 2.0 * fabs(d[RUN_30][2]));
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_relaxed_strip),
      cmocka_unit_test(test_viscoelastic_centroid),
  };
  return cmocka_run_group_tests(tests, solve_runs, NULL);
}
