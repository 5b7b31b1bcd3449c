/* `viscolube run SCENE --out DIR [--json]` end to end, as a separate
 * program through vl_test_cli, on small scenes written to a temporary
 * directory: the files written (curve.csv with the documented columns, the
 * fields files), physics that must hold on every row (the friction
 * components add up; dry rolling friction is the pressure centroid's moment
 * arm; an elastic contact is Hertz's and has no rolling friction), the JSON
 * through an independent validator, and every kind of failure: non-zero
 * status, a message naming file and line, and no curve written. */
#define _POSIX_C_SOURCE 200809L

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include "vl_test_util.h"

#include <ctype.h>
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define PI 3.14159265358979323846

/* The model rubber of the shipped database (seed Fig. 5 caption): E0 =
 * 3.6 MPa, nu = 0.5, one retardation time tau = 0.1 s. */
#define E0_PA 3.6e6
#define NU 0.5
#define TAU_S 0.1
#define RADIUS_M 0.01
#define LOAD_N_PER_M 1000.0

/* Hertz half-width of a cylinder on an elastic half-space (Johnson, Contact
 * Mechanics, eq. 4.43): a = sqrt(4 w R / (pi E*)), E* = E / (1 - nu^2). */
static double hertz_a(double e_pa) {
  return sqrt(4.0 * LOAD_N_PER_M * RADIUS_M * (1.0 - NU * NU) / (PI * e_pa));
}

/* The columns README and output.h document, in order. */
static const char *const COLUMNS[] = {"v0_m_s",
                                      "v0_eta_pa_m",
                                      "deborah",
                                      "mu",
                                      "mu_Rc",
                                      "mu_Rf",
                                      "mu_Sc",
                                      "mu_Sf",
                                      "u_min_m",
                                      "u_central_m",
                                      "contact_width_m",
                                      "fluid_load_fraction",
                                      "u_min_over_h_rms",
                                      "regime",
                                      "E_wH_pa",
                                      "a_H_m",
                                      "Q",
                                      "x_centroid_m",
                                      "load_error",
                                      "converged",
                                      "iterations",
                                      "residual",
                                      "eps_f_min",
                                      "error_estimate",
                                      "accuracy",
                                      "warnings"};
#define NCOL (sizeof COLUMNS / sizeof COLUMNS[0])
static const char *const FIELD_COLUMNS =
    "x_m,x_over_a0,p_f_pa,p_c_pa,u_m,area_ratio,film_fraction,cell_width_m";

/* No value written as nan, inf or -0: every token between separators of
 * CSV or JSON is checked (words of a warning cannot match). */
static void no_bad_numbers(const char *what, const char *text) {
  const char *sep = ",\n :{}[]\"";
  for (const char *p = text; *p;) {
    size_t n = strcspn(p, sep);
    if (n) {
      const char *t = p + (*p == '-' || *p == '+');
      size_t m = n - (size_t)(t - p);
      if ((m == 3 && (!strncasecmp(t, "nan", 3) || !strncasecmp(t, "inf", 3))) ||
          (m == 8 && !strncasecmp(t, "infinity", 8)) || (n == 2 && !strncmp(p, "-0", 2)))
        fail_msg("%s holds the value '%.*s'", what, (int)n, p);
      p += n;
    } else {
      p++;
    }
  }
}

/* ---- a CSV reader (our files hold no quotes) ------------------------------ */

/* A file read and cut into cells in place (text is no longer one string). */
typedef struct {
  size_t rows, cols;
  char *header; /* the first line as written */
  char ***cell; /* cell[row][col], rows after the header */
  char *text;
} csv_table;

static csv_table csv_read(const char *path) {
  csv_table t = {0};
  t.text = vl_test_read_file(path);
  if (!t.text) fail_msg("%s was not written", path);
  no_bad_numbers(path, t.text); /* before the text is cut into cells */
  size_t nl = 0;
  for (const char *p = t.text; *p; p++)
    nl += *p == '\n';
  size_t len = strlen(t.text);
  if (len == 0 || t.text[len - 1] != '\n') fail_msg("%s does not end with a newline", path);
  t.cell = calloc(nl, sizeof *t.cell);
  char *line = t.text;
  for (size_t r = 0; r < nl; r++) {
    char *end = strchr(line, '\n');
    *end = '\0';
    if (r == 0) {
      t.header = line;
      t.cols = 1;
      for (const char *p = line; *p; p++)
        t.cols += *p == ',';
    } else {
      char **cells = calloc(t.cols, sizeof *cells);
      size_t c = 0;
      for (char *p = line;; c++) {
        char *comma = strchr(p, ',');
        if (c >= t.cols) fail_msg("%s row %zu has more than %zu cells", path, r, t.cols);
        cells[c] = p;
        if (!comma) break;
        *comma = '\0';
        p = comma + 1;
      }
      if (c + 1 != t.cols) fail_msg("%s row %zu has %zu cells, want %zu", path, r, c + 1, t.cols);
      t.cell[t.rows++] = cells;
    }
    line = end + 1;
  }
  return t;
}

static void csv_free(csv_table *t) {
  for (size_t r = 0; r < t->rows; r++)
    free(t->cell[r]);
  free(t->cell);
  free(t->text);
}

static size_t col_of(const char *name) {
  for (size_t c = 0; c < NCOL; c++)
    if (!strcmp(COLUMNS[c], name)) return c;
  fail_msg("no column %s", name);
  return 0;
}

/* The number in a curve cell (fails on an empty or non-numeric cell). */
static double num(const csv_table *t, size_t row, const char *name) {
  const char *s = t->cell[row][col_of(name)];
  char *end;
  double v = strtod(s, &end);
  if (!*s || *end) fail_msg("row %zu, %s: '%s' is not a number", row, name, s);
  if (!isfinite(v)) fail_msg("row %zu, %s: '%s' is not finite", row, name, s);
  return v;
}

/* ---- running the program -------------------------------------------------- */

static int exists(const char *path) { return access(path, F_OK) == 0; }

/* A scene from its parts (one or more lines each, without the last
 * newline). Line numbers: 1 comment, 2 [scene], 3 title, 4 [materials],
 * then the materials; with one materials line, 6 [contact], 7 and 8 the
 * contact lines. The scenes solve on coarse cells for speed, so their
 * target error is 0.5 (a point above it would be marked: exit status 8):
 * these tests are about the command, not the accuracy. Static storage, four
 * buffers in turn. */
static const char *scene_text(const char *materials, const char *contact, const char *sweep,
                              const char *effects, const char *numerics) {
  static char buf[4][2048];
  static int next;
  char *b = buf[next++ % 4];
  snprintf(b, sizeof buf[0],
           "; a test scene\n[scene]\ntitle = test\n[materials]\n%s\n[contact]\n%s\n[sweep]\n%s\n"
           "[effects]\n%s\n[numerics]\n%s\ntarget_error = 0.5\n",
           materials, contact, sweep, effects, numerics);
  return b;
}

#define RUBBER "compound = model-rubber"
#define CONTACT "radius_m = 0.01\nload_n_per_m = 1000"
/* A deborah sweep of 7 points from 1e-2 to 1e2 (one per 2/3 decade), fields
 * at 0.5 (between two points: added) and 1 (a sweep point: merged). */
#define SWEEP7 "quantity = deborah\nfrom = 1e-2\nto = 1e2\npoints = 7\nfields_at = 0.5, 1"
#define SMOOTH scene_text(RUBBER, CONTACT, SWEEP7, "viscoelastic = on", "grid = 128")
/* The same on paper-3um, with the wider domain of the shipped rough cases. */
#define ROUGH                                                                                      \
  scene_text(RUBBER "\nsurface = paper-3um", CONTACT, SWEEP7, "roughness = on",                    \
             "grid = 128\ndomain_a0 = -1.8, 1.8")

/* Runs a scene that must succeed; returns the curve (caller frees). */
static csv_table run_scene(const char *name, const char *text, const char *out_name) {
  const char *scene = vl_test_scratch(name, text);
  char out_dir[1300];
  snprintf(out_dir, sizeof out_dir, "%s/%s", vl_test_dir, out_name);
  char *out = NULL, *err = NULL;
  int rc = vl_test_run(&out, &err, "run %s --out %s", scene, out_dir);
  if (rc != 0) fail_msg("run %s exited %d: %s", name, rc, err);
  /* stderr is not a terminal here: no progress line, at most the
   * model-validity warnings (one "warning: " line per kind) */
  for (const char *l = err; *l; l = strchr(l, '\n') + 1)
    if (strncmp(l, "warning: ", 9) != 0 || !strchr(l, '\n')) fail_msg("stderr: %s", err);
  assert_non_null(strstr(out, "wrote"));
  free(out), free(err);
  char path[1400];
  snprintf(path, sizeof path, "%s/curve.csv", out_dir);
  assert_false(exists(vl_test_scratch("curve.csv.tmp", NULL)));
  return csv_read(path);
}

/* The curve's header is the documented list; every row converged, with a
 * full set of physics cells, and its friction adds up. */
static void check_curve(const csv_table *t, size_t rows) {
  char header[1024] = "";
  for (size_t c = 0; c < NCOL; c++) {
    if (c) strcat(header, ",");
    strcat(header, COLUMNS[c]);
  }
  assert_string_equal(t->header, header);
  assert_int_equal(t->rows, rows);
  for (size_t r = 0; r < t->rows; r++) {
    if (strcmp(t->cell[r][col_of("converged")], "1"))
      fail_msg("row %zu did not converge (warnings: %s)", r, t->cell[r][col_of("warnings")]);
    double mu = num(t, r, "mu"),
           sum = num(t, r, "mu_Rc") + num(t, r, "mu_Rf") + num(t, r, "mu_Sc") + num(t, r, "mu_Sf");
    /* each cell has 10 significant digits: the sum agrees to ~1e-10 of the
     * largest term */
    if (fabs(mu - sum) > 1e-9 * fmax(fabs(mu), 1e-12))
      fail_msg("row %zu: mu = %.10g but the components add to %.10g", r, mu, sum);
    assert_true(num(t, r, "load_error") < 1e-6);
    assert_true(num(t, r, "residual") <= 1e-9); /* the default Newton tolerance */
    assert_true(num(t, r, "iterations") >= 0);
    assert_true(num(t, r, "contact_width_m") > 0);
    assert_true(num(t, r, "E_wH_pa") > 0 && num(t, r, "a_H_m") > 0);
    assert_string_equal(t->cell[r][col_of("regime")], "dry");
    /* dry: no fluid at all */
    assert_true(num(t, r, "mu_Rf") == 0.0 && num(t, r, "mu_Sf") == 0.0);
    assert_true(num(t, r, "fluid_load_fraction") == 0.0);
    assert_true(num(t, r, "eps_f_min") == 1.0); /* no viscous flattening */
    /* every converged point carries its error estimate (relative, >= 0) */
    assert_true(num(t, r, "error_estimate") >= 0.0 && num(t, r, "error_estimate") < 1.0);
    /* and how it stands against the scene's target (0.5, scene_text) */
    assert_string_equal(t->cell[r][col_of("accuracy")],
                        num(t, r, "error_estimate") <= 0.5 ? "met" : "above_target");
    assert_string_equal(t->cell[r][col_of("v0_eta_pa_m")], ""); /* no fluid named */
    if (r) assert_true(num(t, r, "v0_m_s") > num(t, r - 1, "v0_m_s"));
  }
}

/* The sweep points: 7 log-spaced deborah numbers 10^(-2 + 2k/3) plus 0.5;
 * v0 = De a0 / tau with the Hertz a0 of the relaxed modulus. Returns the
 * rows where fields are expected (of 0.5 and 1). */
static void check_sweep_points(const csv_table *t, size_t *row_half, size_t *row_one) {
  double want[8];
  for (int k = 0; k < 7; k++)
    want[k] = pow(10.0, -2.0 + 2.0 * k / 3.0);
  want[7] = 0.5;
  for (int i = 0; i < 8; i++) /* sort */
    for (int j = i + 1; j < 8; j++)
      if (want[j] < want[i]) {
        double s = want[i];
        want[i] = want[j];
        want[j] = s;
      }
  double a0 = hertz_a(E0_PA);
  *row_half = *row_one = SIZE_MAX;
  for (size_t r = 0; r < 8; r++) {
    double de = num(t, r, "deborah");
    /* 10 significant digits in the file, log spacing by pow: 1e-9 */
    if (vl_test_rel(de, want[r]) > 1e-9)
      fail_msg("row %zu: deborah %.12g, want %.12g", r, de, want[r]);
    if (vl_test_rel(num(t, r, "v0_m_s"), want[r] * a0 / TAU_S) > 1e-9)
      fail_msg("row %zu: v0 %.12g, want De a0/tau = %.12g", r, num(t, r, "v0_m_s"),
               want[r] * a0 / TAU_S);
    if (want[r] == 0.5) *row_half = r;
    if (fabs(want[r] - 1.0) < 1e-12) *row_one = r;
  }
  assert_true(*row_half != SIZE_MAX && *row_one != SIZE_MAX);
}

/* Fields file of row r: header, one row per grid node, x symmetric on the
 * domain, and the contact pressure carries the load. */
static void check_fields(const char *out_dir, size_t row, size_t grid, double dom_a0, int rough) {
  char path[1500];
  snprintf(path, sizeof path, "%s/fields/%03zu.csv", out_dir, row);
  csv_table f = csv_read(path);
  assert_string_equal(f.header, FIELD_COLUMNS);
  assert_int_equal(f.cols, 8);
  assert_int_equal(f.rows, grid);
  double a0 = hertz_a(E0_PA), dx = 2.0 * dom_a0 * a0 / (double)grid, load = 0.0;
  double p0 = 2.0 * LOAD_N_PER_M / (PI * a0), u0 = a0 * a0 / RADIUS_M; /* Hertz scales */
  for (size_t i = 0; i < f.rows; i++) {
    double x = strtod(f.cell[i][0], NULL), xa = strtod(f.cell[i][1], NULL);
    double pc = strtod(f.cell[i][3], NULL), u = strtod(f.cell[i][4], NULL);
    /* cell centres of a uniform grid on [-dom, dom] a0 */
    double want = -dom_a0 + ((double)i + 0.5) * 2.0 * dom_a0 / (double)grid;
    if (fabs(xa - want) > 1e-9) fail_msg("%s row %zu: x/a0 = %.10g, want %.10g", path, i, xa, want);
    if (vl_test_rel(x, xa * a0) > 1e-8) fail_msg("%s row %zu: x_m %.10g vs x/a0 a0", path, i, x);
    /* complementarity p >= 0, u >= 0 holds to the Newton tolerance (1e-9
     * of the dimensionless residual) through the smoothed Fischer-Burmeister
     * function: allow 1e-8 of p0 and of a0^2/R (measured: -3e-10 p0) */
    if (!(pc >= -1e-8 * p0)) fail_msg("%s row %zu: p_c = %g Pa (p0 = %g Pa)", path, i, pc, p0);
    if (!(rough ? u > 0.0 : u >= -1e-8 * u0)) fail_msg("%s row %zu: u = %g m", path, i, u);
    assert_true(strtod(f.cell[i][2], NULL) == 0.0); /* dry: no fluid pressure */
    double ar = strtod(f.cell[i][5], NULL);
    assert_true(ar >= 0.0 && ar <= 1.0);
    double w = strtod(f.cell[i][7], NULL); /* a dry grid is uniform */
    if (vl_test_rel(w, dx) > 1e-9) fail_msg("%s row %zu: cell width %g m, want %g", path, i, w, dx);
    load += pc * w;
  }
  /* the load balance holds to the Newton tolerance, and the printed
   * pressures carry 10 digits: 1e-6 is loose (measured: 6e-9 smooth,
   * 1.1e-8 rough) but catches a wrong dx, a0 or unit */
  if (vl_test_rel(load, LOAD_N_PER_M) > 1e-6)
    fail_msg("%s: sum p_c dx = %.10g N/m, load %.10g N/m", path, load, LOAD_N_PER_M);
  csv_free(&f);
}

/* Only the expected fields files exist. */
static void check_fields_set(const char *out_dir, size_t a, size_t b) {
  char path[1400];
  snprintf(path, sizeof path, "%s/fields", out_dir);
  DIR *d = opendir(path);
  if (!d) fail_msg("no fields directory %s", path);
  size_t n = 0;
  for (struct dirent *e; (e = readdir(d));) {
    if (e->d_name[0] == '.') continue;
    char want_a[32], want_b[32];
    snprintf(want_a, sizeof want_a, "%03zu.csv", a);
    snprintf(want_b, sizeof want_b, "%03zu.csv", b);
    if (strcmp(e->d_name, want_a) && strcmp(e->d_name, want_b))
      fail_msg("unexpected file fields/%s (want %s and %s)", e->d_name, want_a, want_b);
    n++;
  }
  closedir(d);
  assert_int_equal(n, 2);
}

/* ---- the runs ---------------------------------------------------------- */

static void test_smooth_sweep(void **state) {
  (void)state;
  csv_table t = run_scene("smooth.ini", SMOOTH, "out");
  check_curve(&t, 8); /* 7 points + fields_at 0.5 (1 is a sweep point) */
  size_t half, one;
  check_sweep_points(&t, &half, &one);
  for (size_t r = 0; r < t.rows; r++) {
    double de = num(&t, r, "deborah"), mu_rc = num(&t, r, "mu_Rc");
    double xc = num(&t, r, "x_centroid_m");
    /* a smooth contact touches: the minimum separation is zero */
    assert_true(num(&t, r, "u_min_m") == 0.0);
    assert_true(num(&t, r, "mu_Sc") == 0.0); /* solid_shear off */
    /* Sign convention (README): rubber moving at +x, inlet at x < 0, the
     * dry viscoelastic pressure peak on the inlet side, friction positive. */
    if (de > 0.05 && de < 20) {
      if (!(mu_rc > 0 && xc < 0)) fail_msg("De %g: mu_Rc = %g, x_centroid = %g", de, mu_rc, xc);
    }
    /* A rigid parabolic cylinder, dry: the tangential force is
     * int p dh/dx dx = int p x / R dx = fN x_c / R, so mu_Rc = -x_c / R
     * (the force on the rubber resisting its motion). 10 printed digits. */
    if (fabs(mu_rc + xc / RADIUS_M) > 1e-9 * fmax(fabs(mu_rc), 1e-12))
      fail_msg("De %g: mu_Rc = %.10g, -x_c/R = %.10g", de, mu_rc, -xc / RADIUS_M);
  }
  /* hysteresis peaks inside the sweep: low at both ends (relaxed and glassy
   * limits), the largest value not at an end */
  size_t peak = 0;
  for (size_t r = 1; r < t.rows; r++)
    if (num(&t, r, "mu_Rc") > num(&t, peak, "mu_Rc")) peak = r;
  assert_true(peak > 0 && peak + 1 < t.rows);
  char out_dir[1300];
  snprintf(out_dir, sizeof out_dir, "%s/out", vl_test_dir);
  check_fields_set(out_dir, half, one);
  check_fields(out_dir, half, 128, 1.5, 0);
  check_fields(out_dir, one, 128, 1.5, 0);
  csv_free(&t);
}

static void test_rough_sweep(void **state) {
  (void)state;
  csv_table rough = run_scene("rough.ini", ROUGH, "rough");
  csv_table smooth = run_scene("smooth.ini", SMOOTH, "smooth");
  check_curve(&rough, 8);
  size_t half, one;
  check_sweep_points(&rough, &half, &one);
  double peak_rough = 0, peak_smooth = 0;
  for (size_t r = 0; r < rough.rows; r++) {
    double de = num(&rough, r, "deborah"), mu_rc = num(&rough, r, "mu_Rc");
    double xc = num(&rough, r, "x_centroid_m");
    /* Persson: the surfaces never touch everywhere */
    assert_true(num(&rough, r, "u_min_m") > 0.0);
    assert_true(num(&rough, r, "u_central_m") >= num(&rough, r, "u_min_m"));
    if (de > 0.05 && de < 20) {
      if (!(mu_rc > 0 && xc < 0))
        fail_msg("rough De %g: mu_Rc = %g, x_centroid = %g", de, mu_rc, xc);
    }
    /* the same moment-arm identity: the rigid cylinder is still a parabola */
    if (fabs(mu_rc + xc / RADIUS_M) > 1e-9 * fmax(fabs(mu_rc), 1e-12))
      fail_msg("rough De %g: mu_Rc = %.10g, -x_c/R = %.10g", de, mu_rc, -xc / RADIUS_M);
    /* seed Figs. 3-4: roughness widens the nominal contact ... */
    if (!(num(&rough, r, "contact_width_m") > num(&smooth, r, "contact_width_m")))
      fail_msg("De %g: rough width %g <= smooth width %g", de, num(&rough, r, "contact_width_m"),
               num(&smooth, r, "contact_width_m"));
    peak_rough = fmax(peak_rough, mu_rc);
    peak_smooth = fmax(peak_smooth, num(&smooth, r, "mu_Rc"));
  }
  /* ... and lowers the peak of mu_Rc */
  if (!(peak_rough < peak_smooth))
    fail_msg("rough peak %g >= smooth peak %g", peak_rough, peak_smooth);
  char out_dir[1300];
  snprintf(out_dir, sizeof out_dir, "%s/rough", vl_test_dir);
  check_fields_set(out_dir, half, one);
  check_fields(out_dir, half, 128, 1.8, 1);
  csv_free(&rough);
  csv_free(&smooth);
}

/* --json: one valid array, one object per curve row, the same numbers. */
static void test_json(void **state) {
  (void)state;
  csv_table t = run_scene("smooth.ini", SMOOTH, "out");
  char *out = NULL, *err = NULL;
  int rc = vl_test_run(&out, &err, "run %s --out %s/json --json",
                       vl_test_scratch("smooth.ini", NULL), vl_test_dir);
  if (rc != 0) fail_msg("run --json exited %d: %s", rc, err);
  assert_string_equal(err, "");
  size_t objects = 0;
  if (!vl_test_json_array_valid(out, &objects)) fail_msg("invalid JSON on stdout:\n%s", out);
  assert_int_equal(objects, t.rows);
  no_bad_numbers("JSON", out);
  for (size_t r = 0; r < t.rows; r++) {
    const char *keys[] = {"v0_m_s",       "deborah",         "mu",       "mu_Rc", "mu_Rf",
                          "x_centroid_m", "contact_width_m", "eps_f_min"};
    for (size_t k = 0; k < sizeof keys / sizeof *keys; k++)
      /* the JSON's 17 digits against the CSV's 10 */
      if (vl_test_rel(vl_test_json_number(out, keys[k], r), num(&t, r, keys[k])) > 1e-9)
        fail_msg("row %zu %s: JSON %.12g, CSV %.12g", r, keys[k],
                 vl_test_json_number(out, keys[k], r), num(&t, r, keys[k]));
    assert_true(isnan(vl_test_json_number(out, "v0_eta_pa_m", r))); /* null: no fluid */
  }
  assert_int_equal(strstr(out, "\"converged\": true") != NULL, 1);
  assert_null(strstr(out, "\"converged\": false"));
  free(out), free(err);
  /* the curve is written with --json too */
  char path[1400];
  snprintf(path, sizeof path, "%s/json/curve.csv", vl_test_dir);
  assert_true(exists(path));
  csv_free(&t);
}

/* viscoelastic = off: Hertz's contact with the relaxed modulus, and on the
 * symmetric default grid no rolling friction at all. */
static void test_elastic(void **state) {
  (void)state;
  const char *scene = "[materials]\ncompound = model-rubber\n"
                      "[contact]\nradius_m = 0.01\nload_n_per_m = 1000\n"
                      "[sweep]\nquantity = v0\nfrom = 1e-4\nto = 1\npoints = 3\n"
                      "[effects]\nviscoelastic = off\n";
  csv_table t = run_scene("elastic.ini", scene, "elastic");
  check_curve(&t, 3);
  double a0 = hertz_a(E0_PA), dx = 3.0 * a0 / 512.0;
  for (size_t r = 0; r < t.rows; r++) {
    /* symmetric pressure on a grid symmetric about x = 0: only round-off */
    if (!(fabs(num(&t, r, "mu_Rc")) < 1e-12 && fabs(num(&t, r, "mu")) < 1e-12))
      fail_msg("elastic row %zu: mu_Rc = %g", r, num(&t, r, "mu_Rc"));
    assert_true(fabs(num(&t, r, "x_centroid_m")) < 1e-12 * RADIUS_M); /* mu_Rc = -x_c / R */
    /* width where p >= 1 % of the peak: Hertz gives 2 a sqrt(1 - 1e-4) =
     * 2a (1 - 5e-5); on cell centres each edge is off by < 1 cell
     * (dx = 3 a0 / 512 = 0.6 % of 2 a0): within 1 % */
    double w = num(&t, r, "contact_width_m");
    if (vl_test_rel(w, 2.0 * a0) > 0.01) fail_msg("width %.6g, Hertz 2 a0 = %.6g", w, 2.0 * a0);
    assert_true(fabs(w - 2.0 * a0) <= 2.0 * dx);
  }
  csv_free(&t);
  /* elastic_modulus = glassy: Hertz with Einf = 10 E0, a = a0 / sqrt(10);
   * the same two-cell bound (2 dx = 1.9 % of 2 a here) */
  const char *glassy = "[materials]\ncompound = model-rubber\nelastic_modulus = glassy\n"
                       "[contact]\nradius_m = 0.01\nload_n_per_m = 1000\n"
                       "[sweep]\nquantity = v0\nfrom = 1e-2\nto = 1e-2\npoints = 1\n"
                       "[effects]\nviscoelastic = off\n";
  t = run_scene("glassy.ini", glassy, "glassy");
  check_curve(&t, 1);
  double ag = hertz_a(10.0 * E0_PA), w = num(&t, 0, "contact_width_m");
  if (fabs(w - 2.0 * ag) > 2.0 * dx) fail_msg("glassy width %.6g, Hertz %.6g", w, 2.0 * ag);
  assert_true(fabs(num(&t, 0, "mu_Rc")) < 1e-12);
  csv_free(&t);
}

/* Without --out: out/<scene file name without its extension>, relative to
 * the working directory; a dot inside the name stays. */
static void test_default_out_dir(void **state) {
  (void)state;
  const char *scene = vl_test_scratch("rough-0.1um.ini", SMOOTH);
  char env[2048], path[1400];
  snprintf(env, sizeof env, "cd %s && env -u VISCOLUBE_DB", vl_test_dir);
  char args[4096];
  snprintf(args, sizeof args, "--db %s run %s", vl_test_db, scene);
  assert_int_equal(vl_test_cli(env, args, NULL, NULL), 0);
  snprintf(path, sizeof path, "%s/out/rough-0.1um/curve.csv", vl_test_dir);
  if (!exists(path)) fail_msg("%s not written", path);
  snprintf(path, sizeof path, "%s/out/rough-0.1um/fields", vl_test_dir);
  assert_true(exists(path));
}

/* ---- failures: status, message, nothing written ------------------------ */

/* A failing run: status `code`, one line on stderr holding both needles,
 * and no curve in DIR. */
static void expect_fail(int code, const char *needle1, const char *needle2, const char *scene) {
  char out_dir[1300], curve[1400];
  snprintf(out_dir, sizeof out_dir, "%s/failed", vl_test_dir);
  snprintf(curve, sizeof curve, "%s/curve.csv", out_dir);
  char *out = NULL, *err = NULL;
  int rc = vl_test_run(&out, &err, "run %s --out %s", scene, out_dir);
  if (rc != code) fail_msg("run %s: exit %d, expected %d (stderr: %s)", scene, rc, code, err);
  size_t len = err ? strlen(err) : 0;
  if (len < 2 || err[len - 1] != '\n' || strchr(err, '\n') != err + len - 1)
    fail_msg("run %s: stderr is not exactly one line: '%s'", scene, err);
  if (needle1 && !strstr(err, needle1)) fail_msg("'%s' lacks '%s'", err, needle1);
  if (needle2 && !strstr(err, needle2)) fail_msg("'%s' lacks '%s'", err, needle2);
  assert_false(exists(curve));
  assert_string_equal(out, "");
  free(out), free(err);
}

static void test_errors(void **state) {
  (void)state;
  char where[1400];
  /* a typo in a key, on line 7 */
  const char *bad =
      vl_test_scratch("typo.ini", scene_text(RUBBER, "raduis_m = 0.01\nload_n_per_m = 1000", SWEEP7,
                                             "viscoelastic = on", "grid = 128"));
  snprintf(where, sizeof where, "%s:7:", bad);
  expect_fail(2, where, "raduis_m", bad);
  /* the output directory is not even created */
  snprintf(where, sizeof where, "%s/failed", vl_test_dir);
  assert_false(exists(where));
  /* a key in the wrong section (line 19: [numerics] is line 17) */
  bad = vl_test_scratch("wrongsection.ini", scene_text(RUBBER, CONTACT, SWEEP7, "viscoelastic = on",
                                                       "grid = 128\npoints = 9"));
  snprintf(where, sizeof where, "%s:19:", bad);
  expect_fail(2, where, "belongs in [sweep]", bad);
  /* an inconsistent effect: roughness without a surface (line 16) */
  bad = vl_test_scratch("nosurface.ini",
                        scene_text(RUBBER, CONTACT, SWEEP7, "roughness = on", "grid = 128"));
  snprintf(where, sizeof where, "%s:16: [effects] roughness", bad);
  expect_fail(2, where, "surface", bad);
  /* an unknown compound, surface and fluid: named, with the scene */
  bad = vl_test_scratch("nocompound.ini", scene_text("compound = model-ruber", CONTACT, SWEEP7,
                                                     "viscoelastic = on", "grid = 128"));
  expect_fail(3, "'model-ruber'", "[materials] compound", bad);
  bad = vl_test_scratch("nosurface2.ini", scene_text(RUBBER "\nsurface = paper-4um", CONTACT,
                                                     SWEEP7, "roughness = on", "grid = 128"));
  expect_fail(3, "'paper-4um'", "[materials] surface", bad);
  bad = vl_test_scratch("nofluid.ini", scene_text(RUBBER "\nfluid = watr", CONTACT, SWEEP7,
                                                  "viscoelastic = on", "grid = 128"));
  expect_fail(3, "'watr'", "[materials] fluid", bad);
  /* deborah needs a one-term compound */
  const char *terms = vl_test_scratch("terms.csv", "A,tau_s\n1,s\n4,0.01\n5,1\n");
  char *out = NULL, *err = NULL;
  int rc = vl_test_run(&out, &err, "compound add two-term --prony %s --e-inf 36e6 --nu 0.5", terms);
  if (rc != 0) fail_msg("compound add: %d %s", rc, err);
  free(out), free(err);
  bad = vl_test_scratch("twoterm.ini", scene_text("compound = two-term", CONTACT, SWEEP7,
                                                  "viscoelastic = on", "grid = 128"));
  expect_fail(2, "one-term", "two-term", bad);
  /* a missing scene file */
  snprintf(where, sizeof where, "%s/absent.ini", vl_test_dir);
  expect_fail(6, where, "cannot open", where);
}

static void test_usage(void **state) {
  (void)state;
  char *out = NULL, *err = NULL;
  assert_int_equal(vl_test_run(&out, &err, "run --help"), 0);
  assert_non_null(strstr(out, "usage: viscolube run SCENE"));
  assert_non_null(strstr(out, "curve.csv"));
  assert_string_equal(err, "");
  free(out), free(err);
  assert_false(exists(vl_test_db)); /* help opens no database */
  /* no scene, an unknown option, two scenes, --out without a directory */
  assert_int_equal(vl_test_run(&out, &err, "run"), 2);
  assert_non_null(strstr(err, "usage:"));
  assert_string_equal(out, "");
  free(out), free(err);
  const char *scene = vl_test_scratch("smooth.ini", SMOOTH);
  assert_int_equal(vl_test_run(&out, &err, "run %s --frobnicate", scene), 2);
  assert_non_null(strstr(err, "'--frobnicate'"));
  free(out), free(err);
  assert_int_equal(vl_test_run(&out, &err, "run %s %s", scene, scene), 2);
  assert_non_null(strstr(err, "one scene"));
  free(out), free(err);
  assert_int_equal(vl_test_run(&out, &err, "run %s --out", scene), 2);
  assert_non_null(strstr(err, "--out"));
  free(out), free(err);
  assert_false(exists(vl_test_db));
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test_setup(test_smooth_sweep, vl_test_setup_db),
      cmocka_unit_test_setup(test_rough_sweep, vl_test_setup_db),
      cmocka_unit_test_setup(test_json, vl_test_setup_db),
      cmocka_unit_test_setup(test_elastic, vl_test_setup_db),
      cmocka_unit_test_setup(test_default_out_dir, vl_test_setup_db),
      cmocka_unit_test_setup(test_errors, vl_test_setup_db),
      cmocka_unit_test_setup(test_usage, vl_test_setup_db),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
