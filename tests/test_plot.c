/* Figures (plot.h): the files are written and are what they claim to be
 * (PNG signature and IHDR size; SVG from its XML header to </svg>), each
 * holds the expected number of series, points that did not converge break
 * their lines and are drawn as hollow markers, bad input is refused without
 * leaving files, and `viscolube run --plot` and `compound show --plot`
 * write the documented figures.
 *
 * Series are counted in the SVG, independently of the report the library
 * returns: plot.h promises that series are the strokes of 2 px or more in
 * colours that are not greys (axes, grid and reference lines are grey,
 * black or thinner) and that a hollow marker is a path filled white (the
 * page background is a rect). The parser accepts both styles
 * cairo writes (style="stroke:rgb(...)" up to 1.16, attributes later). */
#define _POSIX_C_SOURCE 200809L

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "viscolube/plot.h"
#include "vl_test_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* ---- reading the files back --------------------------------------------- */

static int file_exists(const char *path) {
  struct stat st;
  return stat(path, &st) == 0 && st.st_size > 0;
}

/* PNG: the 8-byte signature, then the IHDR chunk (length 13) with width
 * and height big-endian (PNG specification, sections 5.2 and 11.2.2). */
static void check_png(const char *path, unsigned width, unsigned height) {
  FILE *f = fopen(path, "rb");
  if (!f) fail_msg("%s: missing", path);
  unsigned char h[24];
  assert_int_equal(fread(h, 1, sizeof h, f), sizeof h);
  fclose(f);
  assert_memory_equal(h, "\x89PNG\r\n\x1a\n", 8);
  assert_memory_equal(h + 8, "\0\0\0\x0dIHDR", 8);
  unsigned w = (unsigned)h[16] << 24 | (unsigned)h[17] << 16 | (unsigned)h[18] << 8 | h[19];
  unsigned hh = (unsigned)h[20] << 24 | (unsigned)h[21] << 16 | (unsigned)h[22] << 8 | h[23];
  assert_int_equal(w, width);
  assert_int_equal(hh, height);
}

/* SVG: an XML declaration or <svg first, </svg> last, and as many '<' as
 * '>' (no element cut short). Returns the text (caller frees). */
static char *read_svg(const char *path) {
  char *s = vl_test_read_file(path);
  assert_non_null(s);
  const char *p = s;
  while (*p == ' ' || *p == '\n' || *p == '\r' || *p == '\t')
    p++;
  assert_true(!strncmp(p, "<?xml", 5) || !strncmp(p, "<svg", 4));
  assert_non_null(strstr(s, "<svg"));
  const char *end = strstr(s, "</svg>");
  assert_non_null(end);
  for (const char *q = end + 6; *q; q++)
    assert_true(*q == ' ' || *q == '\n' || *q == '\r');
  size_t lt = 0, gt = 0;
  for (const char *q = s; *q; q++)
    lt += *q == '<', gt += *q == '>';
  assert_int_equal(lt, gt);
  return s;
}

/* Looks for `name` as a CSS property ("name:") or an attribute ("name=\"")
 * inside [a, b); returns a pointer just after it or NULL. */
static const char *find_prop(const char *a, const char *b, const char *name) {
  size_t n = strlen(name);
  for (const char *p = a; p + n < b; p++) {
    if (strncmp(p, name, n)) continue;
    if (p > a && (p[-1] == '-' || (p[-1] >= 'a' && p[-1] <= 'z'))) continue; /* stroke-width */
    if (p[n] == ':') return p + n + 1;
    if (p[n] == '=' && p[n + 1] == '"') return p + n + 2;
  }
  return NULL;
}

/* Parses "rgb(r%, g%, b%)" into percent values. */
static int parse_rgb(const char *p, double c[3]) {
  if (!p || strncmp(p, "rgb(", 4)) return 0;
  p += 4;
  for (int k = 0; k < 3; k++) {
    char *end;
    c[k] = strtod(p, &end);
    if (end == p) return 0;
    p = end;
    while (*p == '%' || *p == ',' || *p == ' ')
      p++;
  }
  return 1;
}

typedef struct {
  double rgb[3];
  size_t paths;
} color_count;

typedef struct {
  color_count series[64]; /* distinct series colours and their paths */
  size_t n_series;
  size_t white_fills; /* paths filled white */
} svg_stats;

static svg_stats svg_analyse(const char *svg) {
  svg_stats s = {0};
  for (const char *p = strstr(svg, "<path"); p; p = strstr(p + 5, "<path")) {
    const char *end = strchr(p, '>');
    assert_non_null(end);
    double c[3];
    const char *fill = find_prop(p, end, "fill");
    if (parse_rgb(fill, c) && c[0] > 99.9 && c[1] > 99.9 && c[2] > 99.9) s.white_fills++;
    if (fill && !strncmp(fill, "rgb(", 4)) continue; /* filled: a marker or the page */
    const char *stroke = find_prop(p, end, "stroke");
    const char *width = find_prop(p, end, "stroke-width");
    if (!parse_rgb(stroke, c) || !width || strtod(width, NULL) < 2.0) continue;
    if (fabs(c[0] - c[1]) < 0.5 && fabs(c[1] - c[2]) < 0.5) continue; /* grey or black */
    size_t k = 0;
    while (k < s.n_series &&
           (fabs(s.series[k].rgb[0] - c[0]) > 0.01 || fabs(s.series[k].rgb[1] - c[1]) > 0.01 ||
            fabs(s.series[k].rgb[2] - c[2]) > 0.01))
      k++;
    if (k == s.n_series) {
      assert_true(s.n_series < 64);
      memcpy(s.series[k].rgb, c, sizeof c);
      s.n_series++;
    }
    s.series[k].paths++;
  }
  return s;
}

static svg_stats svg_file_stats(const char *path) {
  char *svg = read_svg(path);
  svg_stats s = svg_analyse(svg);
  free(svg);
  return s;
}

static const char *path_in(const char *dir, const char *name) {
  static char buf[8][8400];
  static int k = 0;
  k = (k + 1) % 8;
  snprintf(buf[k], sizeof buf[k], "%s/%s", dir, name);
  return buf[k];
}

/* ---- data --------------------------------------------------------------- */

#define NPTS 25
static const vl_curve_meta META = {1e-3, 0.1, 1.6e-3, NULL, 0.0, NULL};

/* A Stribeck-like curve (values invented, shapes as in a wet sweep):
 * v0 log-spaced 1e-6 .. 1e2 m/s, every component non-zero. */
static void make_curve(vl_point *pts) {
  for (size_t i = 0; i < NPTS; i++) {
    vl_point *p = &pts[i];
    memset(p, 0, sizeof *p);
    double lx = -6.0 + 8.0 * (double)i / (NPTS - 1);
    p->v0_m_s = pow(10.0, lx);
    p->converged = true;
    p->mu_Rc = 0.05 * exp(-(lx + 3) * (lx + 3));
    p->mu_Sc = 0.03 / (1 + pow(10.0, lx + 1));
    p->mu_Rf = 0.002 * pow(10.0, 0.3 * (lx + 6));
    p->mu_Sf = 0.001 * pow(10.0, 0.3 * (lx + 6));
    p->mu = p->mu_Rc + p->mu_Sc + p->mu_Rf + p->mu_Sf;
    p->u_min_m = 3e-6 * (1.2 + pow(10.0, 0.5 * (lx + 1)));
    p->fluid_load_fraction = 1 / (1 + exp(-3 * (lx - 0.5)));
  }
}

/* ---- tests -------------------------------------------------------------- */

static void test_format_value(void **state) {
  (void)state;
  char b[64];
  vl_plot_format_value(b, sizeof b, 1e-7);
  assert_string_equal(b, "10⁻⁷");
  vl_plot_format_value(b, sizeof b, 3e-6);
  assert_string_equal(b, "3×10⁻⁶");
  vl_plot_format_value(b, sizeof b, 0.25);
  assert_string_equal(b, "0.25");
  vl_plot_format_value(b, sizeof b, 1500);
  assert_string_equal(b, "1500");
  vl_plot_format_value(b, sizeof b, 0.001);
  assert_string_equal(b, "0.001");
  vl_plot_format_value(b, sizeof b, 3.2e5);
  assert_string_equal(b, "3.2×10⁵");
  vl_plot_format_value(b, sizeof b, 9.9996e-5); /* rounds into the next decade */
  assert_string_equal(b, "10⁻⁴");
  vl_plot_format_value(b, sizeof b, 0);
  assert_string_equal(b, "0");
  vl_plot_format_value(b, sizeof b, -2.5e-5);
  assert_string_equal(b, "−2.5×10⁻⁵");
  vl_plot_format_value(b, sizeof b, -0.5);
  assert_string_equal(b, "−0.5");
  /* truncation keeps the string terminated */
  assert_int_equal(vl_plot_format_value(b, 4, 123456.0), 3);
  assert_int_equal(strlen(b), 3);
}

static void test_stribeck_files_and_series(void **state) {
  (void)state;
  const char *dir = vl_test_tmpdir();
  vl_point pts[NPTS];
  make_curve(pts);
  size_t marks[3] = {4, 12, 20};
  vl_plot_options opt;
  vl_plot_options_defaults(&opt);
  opt.title = "a # title with PLplot's escape character";
  vl_plot_report r;
  vl_error err = {{0}};
  assert_int_equal(vl_plot_stribeck(path_in(dir, "s"), NPTS, pts, &META, VL_SWEEP_V0_ETA, 3, marks,
                                    &opt, &r, &err),
                   VL_OK);
  assert_int_equal(r.files, 2);
  assert_int_equal(r.series, 5);
  assert_int_equal(r.failed_markers, 0);
  check_png(path_in(dir, "s.png"), 1000, 750);
  svg_stats s = svg_file_stats(path_in(dir, "s.svg"));
  assert_int_equal(s.n_series, 5);    /* mu and its four components */
  assert_int_equal(s.white_fills, 0); /* no hollow marker */
  assert_false(file_exists(path_in(dir, "s.png.tmp")));
  assert_false(file_exists(path_in(dir, "s.svg.tmp")));

  /* one format, another size */
  opt.formats = VL_PLOT_PNG;
  opt.width_px = 640;
  opt.height_px = 480;
  assert_int_equal(vl_plot_stribeck(path_in(dir, "small"), NPTS, pts, &META, VL_SWEEP_V0, 0, NULL,
                                    &opt, &r, &err),
                   VL_OK);
  assert_int_equal(r.files, 1);
  check_png(path_in(dir, "small.png"), 640, 480);
  assert_false(file_exists(path_in(dir, "small.svg")));

  /* a dry curve: no fluid components, so three series */
  for (size_t i = 0; i < NPTS; i++) {
    pts[i].mu -= pts[i].mu_Rf + pts[i].mu_Sf;
    pts[i].mu_Rf = pts[i].mu_Sf = 0;
  }
  vl_curve_meta dry = {0, 0.1, 1.6e-3, NULL, 0.0, NULL};
  assert_int_equal(vl_plot_stribeck(path_in(dir, "dry"), NPTS, pts, &dry, VL_SWEEP_DEBORAH, 0, NULL,
                                    NULL, &r, &err),
                   VL_OK);
  assert_int_equal(r.series, 3);
  assert_int_equal(svg_file_stats(path_in(dir, "dry.svg")).n_series, 3);

  /* dry and smooth: mu is mu_Rc alone, one series */
  for (size_t i = 0; i < NPTS; i++) {
    pts[i].mu = pts[i].mu_Rc;
    pts[i].mu_Sc = 0;
  }
  assert_int_equal(vl_plot_stribeck(path_in(dir, "rc"), NPTS, pts, &dry, VL_SWEEP_DEBORAH, 0, NULL,
                                    NULL, &r, &err),
                   VL_OK);
  assert_int_equal(r.series, 1);
  assert_int_equal(svg_file_stats(path_in(dir, "rc.svg")).n_series, 1);
}

/* Three points fail (one alone, two together), none at the ends: every
 * solid series is cut into three runs, and three hollow markers appear. */
static void test_failed_points_break_lines(void **state) {
  (void)state;
  const char *dir = vl_test_tmpdir();
  vl_point pts[NPTS];
  make_curve(pts);
  vl_plot_report r;
  vl_error err = {{0}};
  assert_int_equal(vl_plot_stribeck(path_in(dir, "ok"), NPTS, pts, &META, VL_SWEEP_V0_ETA, 0, NULL,
                                    NULL, &r, &err),
                   VL_OK);
  pts[6].converged = pts[15].converged = pts[16].converged = false;
  assert_int_equal(vl_plot_stribeck(path_in(dir, "bad"), NPTS, pts, &META, VL_SWEEP_V0_ETA, 0, NULL,
                                    NULL, &r, &err),
                   VL_OK);
  assert_int_equal(r.failed_markers, 3);
  svg_stats a = svg_file_stats(path_in(dir, "ok.svg"));
  svg_stats b = svg_file_stats(path_in(dir, "bad.svg"));
  assert_int_equal(b.n_series, a.n_series);
  /* three markers on the plot and one in the legend's "not converged" */
  assert_int_equal(b.white_fills, a.white_fills + 3 + 1);
  /* a solid series is one path plus its legend sample; cut, three plus one */
  size_t solid = 0;
  for (size_t k = 0; k < a.n_series; k++) {
    if (a.series[k].paths != 2) continue; /* dashed lines come in pieces */
    solid++;
    size_t j = 0;
    while (j < b.n_series && memcmp(b.series[j].rgb, a.series[k].rgb, sizeof a.series[k].rgb))
      j++;
    assert_true(j < b.n_series);
    assert_int_equal(b.series[j].paths, 4);
  }
  assert_true(solid >= 1);
}

static void test_separation(void **state) {
  (void)state;
  const char *dir = vl_test_tmpdir();
  vl_point pts[NPTS];
  make_curve(pts);
  pts[3].converged = false;
  vl_plot_options opt;
  vl_plot_options_defaults(&opt);
  opt.mark_half_load = true;
  size_t marks[2] = {3, 10}; /* the first on a failed point: skipped */
  vl_plot_report r;
  vl_error err = {{0}};
  assert_int_equal(vl_plot_separation(path_in(dir, "u"), NPTS, pts, &META, VL_SWEEP_V0_ETA, 3e-6, 2,
                                      marks, &opt, &r, &err),
                   VL_OK);
  assert_int_equal(r.series, 1);
  assert_int_equal(r.failed_markers, 1);
  check_png(path_in(dir, "u.png"), 1000, 750);
  svg_stats s = svg_file_stats(path_in(dir, "u.svg"));
  assert_int_equal(s.n_series, 1);
  assert_int_equal(s.white_fills, 1 + 1); /* on the plot and in the legend */
  /* smooth: u_min in um */
  assert_int_equal(vl_plot_separation(path_in(dir, "u2"), NPTS, pts, &META, VL_SWEEP_V0, 0, 0, NULL,
                                      NULL, &r, &err),
                   VL_OK);
}

/* Fields at three speeds, the middle one not converged. */
static void test_fields(void **state) {
  (void)state;
  const char *dir = vl_test_tmpdir();
  enum { N = 101 };
  static double buf[3][6][N];
  vl_fields f[3];
  const double a0 = 1.6e-3, p0 = 4e5, hrms = 3e-6;
  for (int j = 0; j < 3; j++) {
    f[j] = (vl_fields){N, buf[j][0], buf[j][1], buf[j][2], buf[j][3], buf[j][4], buf[j][5], NULL};
    for (int i = 0; i < N; i++) {
      double x = -3.0 + 4.6 * i / (N - 1);
      double hz = fabs(x) < 1 ? sqrt(1 - x * x) : 0;
      f[j].x_m[i] = x * a0;
      f[j].p_c_pa[i] = p0 * hz / (1 + j);
      f[j].p_f_pa[i] = p0 * hz * j * 0.3;
      f[j].u_m[i] = hrms * (1.2 + j + 50 * (fabs(x) > 1 ? x * x - 1 : 0));
      f[j].area_ratio[i] = 0.3 * hz;
      f[j].film_fraction[i] = 1;
    }
  }
  f[1].n = 0;
  const char *labels[3] = {"1: v₀η = 10⁻⁷ Pa m", "2: #2", NULL};
  vl_plot_scales sc = {a0, p0, hrms};
  vl_plot_report r;
  vl_error err = {{0}};
  static const vl_plot_field which[4] = {VL_PLOT_FIELD_PC, VL_PLOT_FIELD_PF, VL_PLOT_FIELD_U,
                                         VL_PLOT_FIELD_AREA};
  for (int q = 0; q < 4; q++) {
    char stem[32];
    snprintf(stem, sizeof stem, "f%d", q);
    assert_int_equal(
        vl_plot_fields(path_in(dir, stem), which[q], 3, f, labels, &sc, NULL, &r, &err), VL_OK);
    assert_int_equal(r.series, 2);
    assert_int_equal(r.failed_markers, 1);
    char name[40];
    snprintf(name, sizeof name, "%s.svg", stem);
    svg_stats s = svg_file_stats(path_in(dir, name));
    assert_int_equal(s.n_series, 2);
    assert_int_equal(s.white_fills, 1); /* the legend's hollow marker */
    snprintf(name, sizeof name, "%s.png", stem);
    check_png(path_in(dir, name), 1000, 750);
  }
}

/* Fields of a lubricated contact on a long inlet (-96 ... 1.6 a0) with the
 * pressure on [-1, 1] a0 (and a fluid tail to -3 a0 in one of them): the
 * x axis shows where the pressure is (>= 1e-3 of its peak), widened by
 * half its width, not the whole inlet; without any pressure, all of it. */
static void test_fields_window(void **state) {
  (void)state;
  const char *dir = vl_test_tmpdir();
  enum { N = 2001 };
  static double buf[2][6][N];
  vl_fields f[2];
  const double a0 = 1e-3, p0 = 1e6, hrms = 1e-6;
  for (int j = 0; j < 2; j++) {
    f[j] = (vl_fields){N, buf[j][0], buf[j][1], buf[j][2], buf[j][3], buf[j][4], buf[j][5], NULL};
    for (int i = 0; i < N; i++) {
      double x = -96.0 + 97.6 * i / (N - 1), hz = fabs(x) < 1 ? sqrt(1 - x * x) : 0;
      f[j].x_m[i] = x * a0;
      f[j].p_c_pa[i] = p0 * hz;
      f[j].p_f_pa[i] = j && x < -1 && x > -3 ? 0.01 * p0 : 0.0;
      f[j].u_m[i] = hrms * (2 + x * x);
      f[j].area_ratio[i] = 0.2 * hz;
      f[j].film_fraction[i] = 1;
    }
  }
  vl_plot_scales sc = {a0, p0, hrms};
  vl_plot_report r;
  vl_error err = {{0}};
  assert_int_equal(
      vl_plot_fields(path_in(dir, "w1"), VL_PLOT_FIELD_U, 1, f, NULL, &sc, NULL, &r, &err), VL_OK);
  /* pressure on [-1, 1] (nodes to +-0.99...): window about [-2, 2], cut at 1.6 */
  assert_true(r.x_lo <= -1.9 && r.x_lo >= -2.6);
  assert_true(r.x_hi >= 1.55 && r.x_hi <= 1.7);
  assert_int_equal(
      vl_plot_fields(path_in(dir, "w2"), VL_PLOT_FIELD_PF, 2, f, NULL, &sc, NULL, &r, &err), VL_OK);
  /* with the tail of set 2, pressure on [-3, 1]: window about [-5, 1.6] */
  assert_true(r.x_lo <= -4.9 && r.x_lo >= -5.6);
  for (int i = 0; i < N; i++)
    f[0].p_c_pa[i] = 0.0;
  assert_int_equal(
      vl_plot_fields(path_in(dir, "w3"), VL_PLOT_FIELD_U, 1, f, NULL, &sc, NULL, &r, &err), VL_OK);
  assert_true(r.x_lo <= -95.9 && r.x_hi >= 1.55); /* no pressure: all the data */
}

/* K curves on one axis, one with two failed points. */
static void test_compare(void **state) {
  (void)state;
  const char *dir = vl_test_tmpdir();
  enum { K = 5 };
  static vl_point pts[K][NPTS];
  vl_plot_curve c[K];
  static const char *const names[K] = {"unfilled", "filled", "c", "d", "e"};
  for (int k = 0; k < K; k++) {
    make_curve(pts[k]);
    for (size_t i = 0; i < NPTS; i++)
      pts[k][i].mu *= 1 + 0.2 * k;
    c[k] = (vl_plot_curve){names[k], NPTS, pts[k], META, 3e-6};
  }
  pts[2][8].converged = pts[2][9].converged = false;
  vl_plot_options opt;
  vl_plot_options_defaults(&opt);
  opt.mark_half_load = true;
  vl_plot_report r;
  vl_error err = {{0}};
  assert_int_equal(
      vl_plot_compare(path_in(dir, "cmp"), K, c, VL_SWEEP_V0_ETA, VL_PLOT_Y_MU, &opt, &r, &err),
      VL_OK);
  assert_int_equal(r.series, K);
  assert_int_equal(r.failed_markers, 2);
  svg_stats s = svg_file_stats(path_in(dir, "cmp.svg"));
  assert_int_equal(s.n_series, K);
  assert_int_equal(s.white_fills, 2 + 1);
  check_png(path_in(dir, "cmp.png"), 1000, 750);
  /* other quantities and axes */
  static const vl_plot_y ys[] = {VL_PLOT_Y_MU_ROLLING, VL_PLOT_Y_U_MIN, VL_PLOT_Y_FLUID_LOAD};
  for (size_t q = 0; q < 3; q++)
    assert_int_equal(
        vl_plot_compare(path_in(dir, "q"), 2, c, VL_SWEEP_DEBORAH, ys[q], NULL, &r, &err), VL_OK);
}

static void test_modulus_and_shifts(void **state) {
  (void)state;
  const char *dir = vl_test_tmpdir();
  enum { NM = 20, NF = 80 };
  double w[NM], e1[NM], e2[NM], fw[NF], f1[NF], f2[NF];
  /* a standard linear solid, E0 = 1 MPa, Einf = 10 MPa, tau = 0.01 s */
  for (int i = 0; i < NM + NF; i++) {
    double om =
        i < NM ? pow(10, -1 + 5.0 * i / (NM - 1)) : pow(10, -1.5 + 6.0 * (i - NM) / (NF - 1));
    double wt = om * 0.01, e0 = 1e6, ei = 1e7;
    double re = (e0 + ei * wt * wt) / (1 + wt * wt), im = (ei - e0) * wt / (1 + wt * wt);
    if (i < NM)
      w[i] = om, e1[i] = re * 1.02, e2[i] = im * 0.98;
    else
      fw[i - NM] = om, f1[i - NM] = re, f2[i - NM] = im;
  }
  vl_plot_modulus_data d = {NM, w, e1, e2, NF, fw, f1, f2, "measured", NULL};
  vl_plot_report r;
  vl_error err = {{0}};
  assert_int_equal(vl_plot_modulus(path_in(dir, "m"), &d, NULL, &r, &err), VL_OK);
  assert_int_equal(r.series, 6); /* E', E'', tan delta: measured and fitted */
  svg_stats s = svg_file_stats(path_in(dir, "m.svg"));
  assert_int_equal(s.n_series, 3); /* the fitted lines; measured are filled markers */
  check_png(path_in(dir, "m.png"), 1000, 750);
  d.n_fit = 0;
  assert_int_equal(vl_plot_modulus(path_in(dir, "m2"), &d, NULL, &r, &err), VL_OK);
  assert_int_equal(r.series, 3);
  assert_int_equal(svg_file_stats(path_in(dir, "m2.svg")).n_series, 0);

  double t[5] = {-20, 0, 20, 40, 60}, a[5];
  for (int i = 0; i < 5; i++)
    a[i] = -8.86 * (t[i] - 20) / (101.6 + t[i] - 20);
  assert_int_equal(vl_plot_shifts(path_in(dir, "wlf"), 5, t, a, 20, 8.86, 101.6, NULL, &r, &err),
                   VL_OK);
  assert_int_equal(r.series, 2);
  assert_int_equal(svg_file_stats(path_in(dir, "wlf.svg")).n_series, 1); /* the WLF line */
  assert_int_equal(vl_plot_shifts(path_in(dir, "nowlf"), 5, t, a, 20, NAN, NAN, NULL, &r, &err),
                   VL_OK);
  assert_int_equal(r.series, 1);
}

static void test_bad_input(void **state) {
  (void)state;
  const char *dir = vl_test_tmpdir();
  vl_point pts[NPTS];
  make_curve(pts);
  vl_error err = {{0}};
  vl_curve_meta no_eta = {0, 0.1, 1.6e-3, NULL, 0.0, NULL};
  assert_int_equal(
      vl_plot_stribeck(path_in(dir, "x"), 0, pts, &META, VL_SWEEP_V0, 0, NULL, NULL, NULL, &err),
      VL_EINPUT);
  assert_int_equal(vl_plot_stribeck(path_in(dir, "x"), NPTS, pts, &no_eta, VL_SWEEP_V0_ETA, 0, NULL,
                                    NULL, NULL, &err),
                   VL_EINPUT);
  assert_non_null(strstr(err.msg, "v0_eta"));
  size_t bad_mark = NPTS;
  assert_int_equal(vl_plot_stribeck(path_in(dir, "x"), NPTS, pts, &META, VL_SWEEP_V0, 1, &bad_mark,
                                    NULL, NULL, &err),
                   VL_EINPUT);
  vl_plot_options opt;
  vl_plot_options_defaults(&opt);
  opt.width_px = 20;
  assert_int_equal(
      vl_plot_stribeck(path_in(dir, "x"), NPTS, pts, &META, VL_SWEEP_V0, 0, NULL, &opt, NULL, &err),
      VL_EINPUT);
  assert_false(file_exists(path_in(dir, "x.png")));
  /* a directory that does not exist: an I/O error, nothing written */
  assert_int_equal(vl_plot_stribeck(path_in(dir, "no/such/dir/x"), NPTS, pts, &META, VL_SWEEP_V0, 0,
                                    NULL, NULL, NULL, &err),
                   VL_EIO);
  assert_non_null(strstr(err.msg, "no/such/dir/x.png"));
  vl_plot_modulus_data d = {
      1, (double[]){1.0}, (double[]){-1.0}, (double[]){1.0}, 0, NULL, NULL, NULL, NULL, NULL};
  assert_int_equal(vl_plot_modulus(path_in(dir, "m"), &d, NULL, NULL, &err), VL_EINPUT);
  vl_plot_scales sc = {0, 1, 0};
  vl_fields f = {0};
  assert_int_equal(
      vl_plot_fields(path_in(dir, "f"), VL_PLOT_FIELD_PC, 1, &f, NULL, &sc, NULL, NULL, &err),
      VL_EINPUT);
  assert_int_equal(vl_plot_shifts(path_in(dir, "s"), 1, (double[]){NAN}, (double[]){0}, 20, 1, 1,
                                  NULL, NULL, &err),
                   VL_EINPUT);
}

/* `viscolube run SCENE --plot` on a small wet scene (the fig05 materials,
 * a coarse grid, five speeds, fields at two of them). */
static void test_cli_run_plot(void **state) {
  (void)state;
  char dir[4096]; /* vl_test_cli reuses vl_test_tmpdir's buffer */
  snprintf(dir, sizeof dir, "%s", vl_test_tmpdir());
  char scene[4200], env[4200], args[9000], out_dir[4200];
  snprintf(scene, sizeof scene, "%s/wet.ini", dir);
  snprintf(out_dir, sizeof out_dir, "%s/out", dir);
  snprintf(env, sizeof env, "VISCOLUBE_DB=%s/m.db", dir);
  vl_test_write_file(scene, "[scene]\ntitle = small wet scene\n"
                            "[materials]\ncompound = model-rubber\nsurface = paper-3um\n"
                            "fluid = model-1e-4\n"
                            "[contact]\nradius_m = 0.01\nload_n_per_m = 1000\nsigma_s_pa = 1e6\n"
                            "[sweep]\nquantity = v0_eta\nfrom = 1e-8\nto = 1e-2\npoints = 5\n"
                            "fields_at = 1e-6, 1e-3\n"
                            "[effects]\nviscoelastic = on\nroughness = on\nfluid = on\n"
                            "solid_shear = on\nflow_factors = patir-cheng\n"
                            /* coarse cells for speed: a target they meet */
                            "[numerics]\ngrid = 64\ndomain_a0 = -3, 1.6\ntarget_error = 0.5\n");
  /* --quiet: the scene's model-validity warnings are not PLplot's output */
  snprintf(args, sizeof args, "--quiet run %s --out %s --plot", scene, out_dir);
  char *out = NULL, *errs = NULL;
  int rc = vl_test_cli(env, args, &out, &errs);
  if (rc != 0) fprintf(stderr, "stdout: %s\nstderr: %s\n", out, errs);
  assert_int_equal(rc, 0);
  assert_non_null(strstr(out, "plots (png, svg)"));
  assert_string_equal(errs, ""); /* PLplot printed nothing */
  free(out);
  free(errs);
  static const char *const figs[] = {"stribeck", "separation", "fields-pc", "fields-pf",
                                     "fields-u"};
  static const size_t series[] = {5, 1, 2, 2, 2};
  for (size_t k = 0; k < sizeof figs / sizeof figs[0]; k++) {
    char name[64];
    snprintf(name, sizeof name, "%s.png", figs[k]);
    check_png(path_in(out_dir, name), 1000, 750);
    snprintf(name, sizeof name, "%s.svg", figs[k]);
    svg_stats s = svg_file_stats(path_in(out_dir, name));
    assert_int_equal(s.n_series, series[k]);
  }
  /* --json: stdout stays one JSON array, figures written all the same */
  snprintf(args, sizeof args, "run %s --out %s/j --plot --json", scene, dir);
  rc = vl_test_cli(env, args, &out, NULL);
  assert_int_equal(rc, 0);
  assert_int_equal(out[0], '[');
  assert_null(strstr(out, "plots"));
  free(out);
  char jdir[4300];
  snprintf(jdir, sizeof jdir, "%s/j", dir);
  check_png(path_in(jdir, "stribeck.png"), 1000, 750);
}

/* `viscolube compound show NAME --plot --out DIR` on the shipped compounds:
 * a fitted one (isotherms: moduli and shifts) and the one-term model. */
static void test_cli_compound_plot(void **state) {
  (void)state;
  char dir[4096];
  snprintf(dir, sizeof dir, "%s", vl_test_tmpdir());
  char env[4200], args[9000], out_dir[4200];
  snprintf(env, sizeof env, "VISCOLUBE_DB=%s/m.db", dir);
  snprintf(out_dir, sizeof out_dir, "%s/filled", dir);
  snprintf(args, sizeof args, "compound show sbr-filled --plot --out %s", out_dir);
  char *out = NULL, *errs = NULL;
  int rc = vl_test_cli(env, args, &out, &errs);
  if (rc != 0) fprintf(stderr, "stdout: %s\nstderr: %s\n", out, errs);
  assert_int_equal(rc, 0);
  assert_non_null(strstr(out, "plots (png, svg)"));
  assert_string_equal(errs, "");
  free(out);
  free(errs);
  check_png(path_in(out_dir, "moduli.png"), 1000, 750);
  check_png(path_in(out_dir, "shifts.png"), 1000, 750);
  assert_int_equal(svg_file_stats(path_in(out_dir, "moduli.svg")).n_series, 3);
  assert_int_equal(svg_file_stats(path_in(out_dir, "shifts.svg")).n_series, 1);

  snprintf(out_dir, sizeof out_dir, "%s/model", dir);
  snprintf(args, sizeof args, "compound show model-rubber --plot --out %s --json", out_dir);
  rc = vl_test_cli(env, args, &out, NULL);
  assert_int_equal(rc, 0);
  assert_int_equal(out[0], '{');
  assert_null(strstr(out, "plots"));
  free(out);
  assert_int_equal(svg_file_stats(path_in(out_dir, "moduli.svg")).n_series, 3);
  assert_false(file_exists(path_in(out_dir, "shifts.svg"))); /* no isotherms */

  snprintf(args, sizeof args, "compound show model-rubber --out %s", out_dir);
  assert_int_not_equal(vl_test_cli(env, args, NULL, NULL), 0);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_format_value),
      cmocka_unit_test(test_stribeck_files_and_series),
      cmocka_unit_test(test_failed_points_break_lines),
      cmocka_unit_test(test_separation),
      cmocka_unit_test(test_fields),
      cmocka_unit_test(test_fields_window),
      cmocka_unit_test(test_compare),
      cmocka_unit_test(test_modulus_and_shifts),
      cmocka_unit_test(test_bad_input),
      cmocka_unit_test(test_cli_run_plot),
      cmocka_unit_test(test_cli_compound_plot),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
