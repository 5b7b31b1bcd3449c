/* `viscolube surface flow-factors` and `surface add --topography`, run as a
 * separate program (vl_test_run). The flow-factor table of a shipped
 * surface is checked against the model's own identities (phi_s = x (1 -
 * phi_fp), no pressure flow below percolation, the Tripp limit), the CSV
 * against the JSON number for number, the smooth model against its
 * constants; the topography import against the rms of heights this test
 * generates and detrends itself. Every refusal: one line on stderr, exit
 * status, the database unchanged. */
#define _POSIX_C_SOURCE 200809L

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

#define PI 3.14159265358979323846
#define N_COLS 7

static const char *const cols[N_COLS] = {"u_over_hrms", "contact_fraction", "phi_p", "phi_s",
                                         "phi_fp",      "phi_fs",           "phi_f"};

/* ---- helpers ------------------------------------------------------------ */

/* Runs and requires success with nothing on stderr; returns stdout. */
static char *run_ok(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static char *run_ok(const char *fmt, ...) {
  char args[8192];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(args, sizeof args, fmt, ap);
  va_end(ap);
  char *out = NULL, *err = NULL;
  int rc = vl_test_run(&out, &err, "%s", args);
  if (rc != 0) fail_msg("`%s` exited %d: %s", args, rc, err ? err : "");
  if (!err || err[0]) fail_msg("`%s`: stderr: %s", args, err ? err : "(none)");
  free(err);
  return out;
}

static void create_db(void) { free(run_ok("surface list")); }

/* A flow-factor CSV: its '#' line, and rows x N_COLS numbers. */
typedef struct {
  char comment[512];
  size_t n;
  double *v; /* v[i * N_COLS + k] */
} table;

static table read_csv(const char *path) {
  table t = {0};
  char *text = vl_test_read_file(path);
  if (!text) fail_msg("%s: not written", path);
  char *save = NULL, *line = strtok_r(text, "\n", &save);
  assert_non_null(line);
  assert_true(line[0] == '#');
  snprintf(t.comment, sizeof t.comment, "%s", line);
  line = strtok_r(NULL, "\n", &save);
  assert_string_equal(line, "u_over_hrms,contact_fraction,phi_p,phi_s,phi_fp,phi_fs,phi_f");
  size_t cap = 0;
  while ((line = strtok_r(NULL, "\n", &save))) {
    if (t.n == cap) {
      cap = cap ? 2 * cap : 64;
      t.v = realloc(t.v, cap * N_COLS * sizeof *t.v);
      assert_non_null(t.v);
    }
    char *p = line;
    for (size_t k = 0; k < N_COLS; k++) {
      char *end;
      t.v[t.n * N_COLS + k] = strtod(p, &end);
      if (end == p) fail_msg("%s: row %zu, column %zu is not a number: %s", path, t.n + 1, k, line);
      p = end + (*end == ',');
    }
    if (*p) fail_msg("%s: row %zu has more than %d columns", path, t.n + 1, N_COLS);
    t.n++;
  }
  free(text);
  return t;
}

static double at(const table *t, size_t i, size_t k) { return t->v[i * N_COLS + k]; }

/* ---- flow factors ----------------------------------------------------- */

static void test_flow_factors_persson_emt(void **state) {
  (void)state;
  const char *dir = vl_test_scratch("ff", NULL);
  const char *csv = vl_test_scratch("ff/flow-factors.csv", NULL);
  /* from below the percolation point (x_p = 6.30e-4, docs/FLOW_FACTORS.md)
   * to the Tripp regime */
  char *out =
      run_ok("surface flow-factors paper-0.5um --u-range 1e-5,30 --points 120 --out %s", dir);
  assert_non_null(strstr(out, "surface paper-0.5um, model persson-emt: h_rms 5e-07 m, film "
                              "cut-off 1e-09 m, percolation at u/h_rms = 0.00063"));
  assert_non_null(strstr(out, " u_over_hrms contact_fraction        phi_p        phi_s"));
  free(out);
  table t = read_csv(csv);
  assert_int_equal(t.n, 120);
  assert_non_null(strstr(t.comment, "# flow factors of surface paper-0.5um, model persson-emt, "
                                    "h_rms 5e-07 m, film_cutoff_m 1e-09"));
  const char *pc = strstr(t.comment, "percolation_u_over_hrms ");
  assert_non_null(pc);
  double xp = strtod(pc + strlen("percolation_u_over_hrms "), NULL);
  assert_true(fabs(xp / 6.30e-4 - 1) < 0.01);
  assert_true(at(&t, 0, 0) == 1e-5 && at(&t, t.n - 1, 0) == 30.0);
  size_t below = 0;
  for (size_t i = 0; i < t.n; i++) {
    double x = at(&t, i, 0), a = at(&t, i, 1), p = at(&t, i, 2), s = at(&t, i, 3),
           fp = at(&t, i, 4), fs = at(&t, i, 5), f = at(&t, i, 6);
    if (i > 0) {
      /* log spaced, A/A0 falling with the separation */
      double r = log(x / at(&t, i - 1, 0)) / (log(30.0 / 1e-5) / 119.0);
      assert_true(fabs(r - 1) < 1e-9);
      assert_true(a < at(&t, i - 1, 1));
    }
    assert_true(a > 0 && a < 1 && fs >= 0 && f >= 0);
    /* the reciprocity identity on every row */
    double want = x * (1.0 - fp);
    if (fabs(s - want) > 1e-9 * fmax(fabs(s), 1e-300))
      fail_msg("row %zu (x %g): phi_s %.17g, x (1 - phi_fp) %.17g", i + 1, x, s, want);
    if (x < xp) {
      below++;
      assert_true(p == 0.0 && fp == 0.0); /* percolated: no pressure flow */
    } else if (x > 1.001 * xp) {
      assert_true(p > 0.0 && fp > 0.0);
    }
  }
  assert_true(below >= 20);
  /* x = 30: 1 - phi_p ~ 1.5/x^2 (Tripp), phi_f -> 1 */
  double p_end = at(&t, t.n - 1, 2);
  assert_true(p_end > 0.995 && p_end < 1.0);
  assert_true(fabs(at(&t, t.n - 1, 6) - 1.0) < 0.01);
  /* the documented value at x = 1 (docs/FLOW_FACTORS.md: phi_p 0.4258) */
  out = run_ok("surface flow-factors paper-0.5um --u-range 1,2 --points 2 --json");
  assert_true(fabs(vl_test_json_number(out, "phi_p", 0) - 0.4258) < 1e-3);
  assert_true(fabs(vl_test_json_number(out, "phi_s", 0) - 0.6087) < 1e-3);
  free(out);

  /* --json: the same numbers as the CSV, bit for bit (the table now comes
   * from the database cache) */
  out = run_ok("surface flow-factors paper-0.5um --u-range 1e-5,30 --points 120 --json");
  if (!vl_test_json_valid(out)) fail_msg("invalid JSON: %.300s", out);
  assert_non_null(strstr(out, "\"surface\": \"paper-0.5um\""));
  assert_non_null(strstr(out, "\"model\": \"persson-emt\""));
  assert_true(vl_test_json_number(out, "hrms_m", 0) == 5e-7);
  assert_true(vl_test_json_number(out, "film_cutoff_m", 0) == 1e-9);
  assert_true(vl_test_rel(vl_test_json_number(out, "percolation_u_over_hrms", 0), xp) < 1e-9);
  for (size_t i = 0; i < t.n; i++)
    for (size_t k = 0; k < N_COLS; k++) {
      double j = vl_test_json_number(out, cols[k], i);
      if (j != at(&t, i, k))
        fail_msg("row %zu %s: JSON %.17g, CSV %.17g", i + 1, cols[k], j, at(&t, i, k));
    }
  free(out);
  free(t.v);
}

static void test_flow_factors_other_models(void **state) {
  (void)state;
  const char *csv = vl_test_scratch("smooth/flow-factors.csv", NULL);
  char *out = run_ok("surface flow-factors paper-0.5um --model smooth --points 7 --out %s/smooth",
                     vl_test_dir);
  assert_non_null(strstr(out, "model smooth: h_rms 5e-07 m\n"));
  free(out);
  table t = read_csv(csv);
  assert_int_equal(t.n, 7);
  assert_non_null(strstr(t.comment, "model smooth, h_rms 5e-07 m, film_cutoff_m none"));
  const double smooth[5] = {1, 0, 1, 0, 1};
  for (size_t i = 0; i < t.n; i++)
    for (size_t k = 0; k < 5; k++)
      assert_true(at(&t, i, k + 2) == smooth[k]);
  /* A/A0 is the contact law's, whatever the flow model */
  out = run_ok("surface flow-factors paper-0.5um --points 7 --json");
  for (size_t i = 0; i < t.n; i++)
    assert_true(vl_test_json_number(out, "contact_fraction", i) == at(&t, i, 1));
  free(out);
  free(t.v);

  /* patir-cheng: no pressure flow below H = 0, i.e. u/sigma = 1/sqrt(2 pi) */
  out = run_ok("surface flow-factors paper-0.5um --model patir-cheng --u-range 0.1,10 --points 30 "
               "--json");
  if (!vl_test_json_valid(out)) fail_msg("invalid JSON: %.300s", out);
  assert_true(isnan(vl_test_json_number(out, "film_cutoff_m", 0)));
  double xp = vl_test_json_number(out, "percolation_u_over_hrms", 0);
  assert_true(fabs(xp - 1.0 / sqrt(2.0 * PI)) < 1e-12);
  for (int i = 0; i < 30; i++) {
    double x = vl_test_json_number(out, "u_over_hrms", i), p = vl_test_json_number(out, "phi_p", i);
    assert_true(x < xp ? p == 0.0 : p > 0.0);
  }
  free(out);
}

static void test_flow_factors_plot(void **state) {
  (void)state;
  /* --out DIR, as in every command: the table and the figure in it */
  char *out =
      run_ok("surface flow-factors paper-0.5um --points 40 --out %s/fig --plot", vl_test_dir);
  assert_non_null(strstr(out, "fig/flow-factors.png and "));
  free(out);
  const char *ext[3] = {"png", "svg", "csv"};
  for (int k = 0; k < 3; k++) {
    char name[48];
    snprintf(name, sizeof name, "fig/flow-factors.%s", ext[k]);
    char *bytes = vl_test_read_file(vl_test_scratch(name, NULL));
    if (!bytes) fail_msg("%s not written", name);
    assert_true(k == 0   ? !memcmp(bytes, "\x89PNG", 4)
                : k == 1 ? strstr(bytes, "</svg>") != NULL
                         : !strncmp(bytes, "# flow factors", 14));
    /* the figure names what it shows and of which surface (issue 32) */
    if (k == 1)
      assert_non_null(strstr(bytes, "<title>Flow factors — surface paper-0.5um (persson-emt)"
                                    "</title>"));
    free(bytes);
  }
  /* the file --out once named is refused, saying what changed */
  vl_test_expect_fail(2, "--out names a folder, as in every command (got 'x.csv'",
                      "flow-factors.csv", "surface flow-factors paper-0.5um --out x.csv");
  /* without --out: out/flow-factors-NAME/flow-factors.{png,svg} */
  char env[1400], args[1400];
  snprintf(env, sizeof env, "cd %s && env -u VISCOLUBE_DB", vl_test_dir);
  snprintf(args, sizeof args, "--db %s surface flow-factors paper-1um --model smooth --plot --json",
           vl_test_db);
  out = NULL;
  assert_int_equal(vl_test_cli(env, args, &out, NULL), 0);
  assert_true(vl_test_json_valid(out)); /* nothing else on stdout */
  free(out);
  assert_int_equal(
      access(vl_test_scratch("out/flow-factors-paper-1um/flow-factors.png", NULL), F_OK), 0);
  assert_int_equal(
      access(vl_test_scratch("out/flow-factors-paper-1um/flow-factors.svg", NULL), F_OK), 0);
  assert_int_not_equal(
      access(vl_test_scratch("out/flow-factors-paper-1um/flow-factors.csv", NULL), F_OK),
      0); /* the table only with --out */
}

static void test_flow_factors_refusals(void **state) {
  (void)state;
  const char *ff = "surface flow-factors paper-0.5um";
  /* the database and its tables of paper-0.5um (a cache a reading command
   * may store) exist before the refusals */
  free(run_ok("%s --points 2", ff));
  vl_test_expect_fail(2, "--model", "unknown flow-factor model 'emt'", "%s --model emt", ff);
  vl_test_expect_fail(2, "--u-range", "0 < MIN < MAX", "%s --u-range 1,0.5", ff);
  vl_test_expect_fail(2, "--u-range", "0 < MIN < MAX", "%s --u-range 0,1", ff);
  vl_test_expect_fail(2, "--u-range", "0 < MIN < MAX", "%s --u-range 1", ff);
  vl_test_expect_fail(2, "--u-range", "0 < MIN < MAX", "%s --u-range 1e-3,inf", ff);
  vl_test_expect_fail(2, "--u-range", "'a,b'", "%s --u-range a,b", ff);
  vl_test_expect_fail(2, "--points", "[2, 10000]", "%s --points 1", ff);
  vl_test_expect_fail(2, "--points", "[2, 10000]", "%s --points 10001", ff);
  vl_test_expect_fail(2, "--points", "[2, 10000]", "%s --points 2.5", ff);
  vl_test_expect_fail(2, "--points", "[2, 10000]", "%s --points many", ff);
  vl_test_expect_fail(2, "--film-cutoff", "(0, 1e-06]", "%s --film-cutoff 0", ff);
  vl_test_expect_fail(2, "--film-cutoff", "(0, 1e-06]", "%s --film-cutoff -1e-9", ff);
  vl_test_expect_fail(2, "--film-cutoff", "(0, 1e-06]", "%s --film-cutoff 2e-6", ff);
  vl_test_expect_fail(2, "--film-cutoff", "persson-emt only",
                      "%s --model smooth --film-cutoff 1e-9", ff);
  vl_test_expect_fail(2, "--film-cutoff", "persson-emt only",
                      "%s --model patir-cheng --film-cutoff 1e-9", ff);
  vl_test_expect_fail(2, "unknown option '--speed'", NULL, "%s --speed 1", ff);
  vl_test_expect_fail(2, "--points", "twice", "%s --points 5 --points 6", ff);
  vl_test_expect_fail(2, "missing NAME", NULL, "surface flow-factors --points 5");
  vl_test_expect_fail(2, "unknown verb 'flow-factors'", NULL, "compound flow-factors x");
  /* an unknown surface, with the closest names */
  vl_test_expect_fail(3, "no surface named 'paper-0.5'", "did you mean",
                      "surface flow-factors "
                      "paper-0.5");
  /* a folder that cannot be made (a file in the way): nothing on stdout */
  vl_test_scratch("afile", "x");
  vl_test_expect_fail(6, "afile/ff: cannot create the folder", NULL, "%s --out %s/afile/ff", ff,
                      vl_test_dir);
  char *out, *err;
  assert_int_equal(vl_test_run(&out, &err, "surface flow-factors --help"), 0);
  assert_non_null(strstr(out, "contact_fraction, phi_p, phi_s, phi_fp, phi_fs, phi_f"));
  free(out), free(err);
  assert_int_equal(vl_test_run(&out, &err, "surface --help"), 0);
  assert_non_null(strstr(out, "flow-factors NAME"));
  assert_non_null(strstr(out, "--topography FILE"));
  free(out), free(err);
}

/* ---- topography ----------------------------------------------------------- */

/* Deterministic phases (a 64-bit LCG), so the files are the same on every
 * run. */
static double phase(uint64_t *s) {
  *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
  return 2.0 * PI * (double)(*s >> 11) / 9007199254740992.0;
}

/* rms after removing the least-squares plane (ny > 1) or line (ny = 1):
 * on a regular grid the centred coordinates are orthogonal to each other
 * and to the constant, so each coefficient is one projection. */
static double detrended_rms(const double *h, size_t nx, size_t ny) {
  double mean = 0, sx = 0, sy = 0, xx = 0, yy = 0;
  double cx = 0.5 * (double)(nx - 1), cy = 0.5 * (double)(ny - 1);
  for (size_t i = 0; i < ny; i++)
    for (size_t j = 0; j < nx; j++) {
      double v = h[i * nx + j], x = (double)j - cx, y = (double)i - cy;
      mean += v;
      sx += v * x;
      sy += v * y;
      xx += x * x;
      yy += y * y;
    }
  mean /= (double)(nx * ny);
  double bx = sx / xx, by = ny > 1 ? sy / yy : 0, ss = 0;
  for (size_t i = 0; i < ny; i++)
    for (size_t j = 0; j < nx; j++) {
      double r = h[i * nx + j] - mean - bx * ((double)j - cx) - by * ((double)i - cy);
      ss += r * r;
    }
  return sqrt(ss / (double)(nx * ny));
}

/* A random profile of n points (1 um apart): cosines of wavenumbers k = 1
 * .. n/8 (well inside the band the import keeps) with a self-affine
 * amplitude rolled off below k = 8. Written as a line scan in um and nm
 * with '#' comment lines; returns its detrended rms in m. */
static double write_line_scan(const char *path, size_t n) {
  double *z = calloc(n, sizeof *z);
  assert_non_null(z);
  uint64_t s = 7;
  for (size_t k = 1; k <= n / 8; k++) {
    double a = pow(fmax((double)k, 8.0), -1.3), ph = phase(&s);
    for (size_t i = 0; i < n; i++)
      z[i] += a * cos(2.0 * PI * (double)(k * i) / (double)n + ph);
  }
  double scale = 50e-9 / detrended_rms(z, n, 1);
  FILE *f = fopen(path, "w");
  assert_non_null(f);
  fprintf(f, "# synthetic profile, 50 nm rms\n# instrument: none\nx [um], z [nm]\n");
  for (size_t i = 0; i < n; i++) {
    z[i] = 1e-9 * round(1e6 * z[i] * scale * 1e9) / 1e6; /* what the file holds */
    fprintf(f, "%zu, %.6f\n", i, z[i] * 1e9);
  }
  assert_int_equal(fclose(f), 0);
  double rms = detrended_rms(z, n, 1);
  free(z);
  return rms;
}

/* An n x n isotropic random map, pixel 20 nm: plane waves with |k| <= n/5
 * rolled off below |k| = 6, written in nm under SurfaceTopography's '#'
 * header lines. ragged: one row loses its last value. Returns the
 * detrended rms in m. */
static double write_map(const char *path, size_t n, int ragged) {
  double *h = calloc(n * n, sizeof *h);
  assert_non_null(h);
  uint64_t s = 11;
  int kmax = (int)n / 5;
  for (int kx = -kmax; kx <= kmax; kx++)
    for (int ky = 0; ky <= kmax; ky++) {
      double k = hypot(kx, ky);
      if ((ky == 0 && kx <= 0) || k > kmax) continue;
      double a = pow(fmax(k, 6.0), -1.8), ph = phase(&s);
      for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < n; j++)
          h[i * n + j] += a * cos(2.0 * PI * (double)(kx * (int)j + ky * (int)i) / (double)n + ph);
    }
  double scale = 5e-9 / detrended_rms(h, n, n);
  FILE *f = fopen(path, "w");
  assert_non_null(f);
  fprintf(f, "# Channel: synthetic\n# Width: %g µm\n# Height: %g µm\n# Value units: nm\n",
          (double)n * 0.02, (double)n * 0.02);
  for (size_t i = 0; i < n; i++) {
    size_t m = ragged && i == n / 2 ? n - 1 : n;
    for (size_t j = 0; j < m; j++) {
      h[i * n + j] = 1e-9 * round(1e6 * h[i * n + j] * scale * 1e9) / 1e6;
      fprintf(f, "%s%.6f", j ? "\t" : "", h[i * n + j] * 1e9);
    }
    fputc('\n', f);
  }
  assert_int_equal(fclose(f), 0);
  double rms = detrended_rms(h, n, n);
  free(h);
  return rms;
}

/* surface show NAME --json: h_rms within 5 % of rms; returns the JSON. */
static char *check_registered(const char *name, double rms) {
  char *out = run_ok("surface show %s --json", name);
  if (!vl_test_json_valid(out)) fail_msg("invalid JSON: %s", out);
  double h = vl_test_json_number(out, "hrms_m", 0);
  fprintf(stderr, "%s: h_rms %.4g m, topography rms %.4g m, ratio %.4f\n", name, h, rms, h / rms);
  assert_true(fabs(h / rms - 1.0) < 0.05);
  assert_non_null(strstr(out, "\"kind\": \"tabulated\""));
  return out;
}

static void test_topography_add(void **state) {
  (void)state;
  const char *line = vl_test_scratch("profile.txt", NULL);
  double rms_line = write_line_scan(line, 4096);
  char *out = run_ok("surface add scan --topography %s", line);
  assert_non_null(strstr(out, "added surface 'scan'"));
  assert_non_null(strstr(out, "line scan, 4096 points over 0.004096 m (dx 1e-06 m)"));
  assert_non_null(strstr(out, "x the rms height"));
  free(out);
  out = check_registered("scan", rms_line);
  /* the provenance is the description; the file is the source */
  assert_non_null(strstr(out, "\"description\": \"line scan 4096 points over 0.004096 m"));
  assert_non_null(strstr(out, "inverse Abel transform"));
  assert_non_null(strstr(out, "profile.txt\""));
  free(out);

  const char *map = vl_test_scratch("map.txt", NULL);
  double rms_map = write_map(map, 128, 0);
  out = run_ok("surface add afm-like --topography %s --description 'synthetic map'", map);
  assert_non_null(strstr(out, "height map, 128 x 128 px over 2.56e-06 x 2.56e-06 m (pixel 2e-08 x "
                              "2e-08 m)"));
  free(out);
  out = check_registered("afm-like", rms_map);
  assert_non_null(strstr(out, "\"description\": \"synthetic map; height map 128 x 128 px"));
  free(out);
  /* a long --description is kept whole, the provenance cut to fit */
  char desc[501];
  memset(desc, 'd', 500);
  desc[500] = '\0';
  free(run_ok("surface add long --topography %s --description %s", line, desc));
  out = run_ok("surface show %s --json", "long");
  const char *d = strstr(out, "\"description\": \"");
  assert_non_null(d);
  d += strlen("\"description\": \"");
  assert_true(!strncmp(d, desc, 500) && !strncmp(d + 500, "; line s", 8));
  assert_true(strchr(d, '"') - d == 511 && !strncmp(d + 508, "...\"", 4));
  free(out);
  /* `surface show` and `list` have them; flow factors work on them */
  out = run_ok("surface list");
  assert_non_null(strstr(out, "scan "));
  assert_non_null(strstr(out, "afm-like "));
  free(out);
  out = run_ok("surface flow-factors afm-like --points 10 --json");
  assert_true(vl_test_json_valid(out));
  free(out);
}

static void test_topography_refusals(void **state) {
  (void)state;
  create_db();
  char *before = run_ok("surface list");
  const char *ragged = vl_test_scratch("ragged.txt", NULL);
  write_map(ragged, 32, 1);
  vl_test_expect_fail(2, "ragged.txt:", NULL, "surface add r --topography %s", ragged);
  /* a tilted line: nothing left after detrending */
  char tilt[512] = "x [um], z [nm]\n";
  for (int i = 0; i < 18; i++)
    snprintf(tilt + strlen(tilt), sizeof tilt - strlen(tilt), "%d,%d\n", i, 3 * i + 5);
  vl_test_expect_fail(2, "tilt.txt", "flat", "surface add r --topography %s",
                      vl_test_scratch("tilt.txt", tilt));
  vl_test_expect_fail(6, "missing.txt", NULL, "surface add r --topography %s/missing.txt",
                      vl_test_dir);
  const char *line = vl_test_scratch("ok.txt", NULL);
  write_line_scan(line, 256);
  vl_test_expect_fail(2, "--topography", "--psd", "surface add r --topography %s --psd %s", line,
                      line);
  vl_test_expect_fail(2, "--hurst", "--topography", "surface add r --topography %s --hurst 0.8",
                      line);
  vl_test_expect_fail(4, "paper-1um", NULL, "surface add paper-1um --topography %s", line);
  char *after = run_ok("surface list");
  assert_string_equal(before, after);
  free(before);
  free(after);
}

/* The AFM map the project keeps (SurfaceTopography's matrix-3, 10 um,
 * 256 x 256): its rms from the file itself, against the stored h_rms. */
static void test_topography_real_afm(void **state) {
  (void)state;
  /* beside the source tree, or beside the directory of worktrees */
  char path[4200];
  char *text = NULL;
  const char *rel[2] = {"../shared/data/real/surfacetopography_matrix-3_afm.txt",
                        "../../shared/data/real/surfacetopography_matrix-3_afm.txt"};
  for (int k = 0; k < 2 && !text; k++) {
    snprintf(path, sizeof path, "%s", vl_test_source_path(rel[k]));
    text = vl_test_read_file(path);
  }
  if (!text) {
    fprintf(stderr, "skipped: no %s\n", vl_test_source_path(rel[0]));
    return;
  }
  size_t n = 0, cap = 256 * 256;
  double *h = malloc(cap * sizeof *h);
  assert_non_null(h);
  char *save = NULL;
  for (char *l = strtok_r(text, "\n", &save); l; l = strtok_r(NULL, "\n", &save)) {
    if (l[0] == '#') continue;
    for (char *p = l, *end;; p = end) {
      double v = strtod(p, &end);
      if (end == p) break;
      assert_true(n < cap);
      h[n++] = v;
    }
  }
  free(text);
  assert_int_equal(n, 256 * 256);
  double rms = detrended_rms(h, 256, 256);
  free(h);
  assert_true(fabs(rms - 35.2e-9) < 0.1e-9); /* topography.h quotes 35.2 nm */
  char *out = run_ok("surface add matrix-3 --topography %s", path);
  assert_non_null(strstr(out, "height map, 256 x 256 px over 1e-05 x 1e-05 m"));
  fprintf(stderr, "%s", out);
  free(out);
  free(check_registered("matrix-3", rms));
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test_setup(test_flow_factors_persson_emt, vl_test_setup_db),
      cmocka_unit_test_setup(test_flow_factors_other_models, vl_test_setup_db),
      cmocka_unit_test_setup(test_flow_factors_plot, vl_test_setup_db),
      cmocka_unit_test_setup(test_flow_factors_refusals, vl_test_setup_db),
      cmocka_unit_test_setup(test_topography_add, vl_test_setup_db),
      cmocka_unit_test_setup(test_topography_refusals, vl_test_setup_db),
      cmocka_unit_test_setup(test_topography_real_afm, vl_test_setup_db),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
