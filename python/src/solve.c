/* viscolube._core: friction at one operating point (vl_query_friction),
 * scenes and Stribeck sweeps (vl_simulation_run), results as numpy arrays
 * with the columns of curve.csv. */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "core.h"

/* ---- points and curves ------------------------------------------------- */

/* The columns of curve.csv that hold a number of the solved state: NaN in
 * numpy where the CSV cell is empty (the point did not converge). */
static const struct {
  const char *name;
  size_t offset;
} solved_columns[] = {
    {"mu", offsetof(vl_point, mu)},
    {"mu_Rc", offsetof(vl_point, mu_Rc)},
    {"mu_Rf", offsetof(vl_point, mu_Rf)},
    {"mu_Sc", offsetof(vl_point, mu_Sc)},
    {"mu_Sf", offsetof(vl_point, mu_Sf)},
    {"u_min_m", offsetof(vl_point, u_min_m)},
    {"u_central_m", offsetof(vl_point, u_central_m)},
    {"contact_width_m", offsetof(vl_point, contact_width_m)},
    {"fluid_load_fraction", offsetof(vl_point, fluid_load_fraction)},
    {"u_min_over_h_rms", offsetof(vl_point, u_min_over_h_rms)},
    {"E_wH_pa", offsetof(vl_point, E_wH_pa)},
    {"a_H_m", offsetof(vl_point, a_H_m)},
    {"Q", offsetof(vl_point, Q)},
    {"x_centroid_m", offsetof(vl_point, x_centroid_m)},
    {"load_error", offsetof(vl_point, load_error)},
    {"eps_f_min", offsetof(vl_point, eps_f_min)},
    {"error_estimate", offsetof(vl_point, error_estimate)},
};

/* The value of the numeric column `name` at point p, as the CSV cell (NaN
 * for an empty cell). 0 when name is not a float column. */
static int column_number(const char *name, const vl_point *p, const vl_curve_meta *m, double *v) {
  if (!strcmp(name, "v0_m_s") || !strcmp(name, "residual")) {
    *v = name[0] == 'v' ? p->v0_m_s : p->residual;
    return 1;
  }
  if (!strcmp(name, "v0_eta_pa_m")) {
    *v = m->eta_pa_s > 0 ? p->v0_m_s * m->eta_pa_s : NAN;
    return 1;
  }
  if (!strcmp(name, "deborah")) {
    *v = m->tau_s > 0 && m->a0_m > 0 ? p->v0_m_s * m->tau_s / m->a0_m : NAN;
    return 1;
  }
  for (size_t k = 0; k < sizeof solved_columns / sizeof *solved_columns; k++)
    if (!strcmp(name, solved_columns[k].name)) {
      *v = p->converged ? *(const double *)((const char *)p + solved_columns[k].offset) : NAN;
      /* rolling terms of a moving counter-surface: not applicable, as the
       * CSV's empty cell */
      if (p->rolling_na && !strncmp(name, "mu_R", 4)) *v = NAN;
      return 1;
    }
  return 0;
}

/* One column of the curve pts[0..n) as a numpy array or a list of texts;
 * InternalError for a column the binding does not know (a column added to
 * the library must be added here too: the tests compare with curve.csv). */
static PyObject *column(const char *name, size_t n, const vl_point *pts, const vl_curve_meta *m) {
  npy_intp dims[1] = {(npy_intp)n};
  double v;
  if (n && column_number(name, &pts[0], m, &v)) {
    PyObject *a = PyArray_SimpleNew(1, dims, NPY_DOUBLE);
    double *d = a ? PyArray_DATA((PyArrayObject *)a) : NULL;
    for (size_t i = 0; d && i < n; i++)
      column_number(name, &pts[i], m, &d[i]);
    return a;
  }
  int type = !strcmp(name, "converged") ? NPY_BOOL : !strcmp(name, "iterations") ? NPY_INT64 : -1;
  if (type >= 0) {
    PyObject *a = PyArray_SimpleNew(1, dims, type);
    for (size_t i = 0; a && i < n; i++) {
      if (type == NPY_BOOL)
        ((npy_bool *)PyArray_DATA((PyArrayObject *)a))[i] = pts[i].converged;
      else
        ((npy_int64 *)PyArray_DATA((PyArrayObject *)a))[i] = pts[i].iterations;
    }
    return a;
  }
  int regime = !strcmp(name, "regime"), accuracy = !strcmp(name, "accuracy");
  if (!regime && !accuracy && strcmp(name, "warnings")) {
    vl_error err;
    vl_error_set(&err, "curve column '%s' unknown to the Python binding", name);
    return vlpy_raise(VL_EINTERNAL, &err);
  }
  PyObject *l = PyList_New((Py_ssize_t)n);
  for (size_t i = 0; l && i < n; i++) {
    const char *s = regime     ? (pts[i].converged ? vl_regime_name(pts[i].regime) : "")
                    : accuracy ? (pts[i].converged ? vl_accuracy_name(pts[i].accuracy) : "")
                               : pts[i].warnings;
    PyObject *t = PyUnicode_FromString(s);
    if (!t)
      Py_CLEAR(l);
    else
      PyList_SET_ITEM(l, (Py_ssize_t)i, t);
  }
  return l;
}

/* {column: values} of the curve, in the order of curve.csv. */
static PyObject *curve_dict(size_t n, const vl_point *pts, const vl_curve_meta *m) {
  PyObject *d = PyDict_New();
  for (size_t c = 0; d && vl_curve_columns[c]; c++)
    if (vlpy_set(d, vl_curve_columns[c], column(vl_curve_columns[c], n, pts, m)) < 0) Py_CLEAR(d);
  /* a seal scene's columns: `stroke` a list of words, the others numbers
   * (NaN where the CSV cell is empty; converged_in and tight 1/0) */
  for (size_t c = 0; d && n && pts[0].seal.stroke != VL_STROKE_NONE && vl_seal_columns[c]; c++) {
    npy_intp dims[1] = {(npy_intp)n};
    PyObject *o = c == 0 ? PyList_New((Py_ssize_t)n) : PyArray_SimpleNew(1, dims, NPY_DOUBLE);
    static const char *const words[] = {"", "out", "in", "both"};
    for (size_t i = 0; o && i < n; i++) {
      if (c > 0) {
        ((double *)PyArray_DATA((PyArrayObject *)o))[i] = vl_seal_column_value(&pts[i], c);
        continue;
      }
      PyObject *t = PyUnicode_FromString(words[pts[i].seal.stroke & 3]);
      if (!t)
        Py_CLEAR(o);
      else
        PyList_SET_ITEM(o, (Py_ssize_t)i, t);
    }
    if (vlpy_set(d, vl_seal_columns[c], o) < 0) Py_CLEAR(d);
  }
  /* a scene swept both ways: the downward sweep's columns (NaN where empty) */
  for (size_t c = 0; d && n && pts[0].down.swept && vl_down_columns[c]; c++) {
    npy_intp dims[1] = {(npy_intp)n};
    PyObject *o = PyArray_SimpleNew(1, dims, NPY_DOUBLE);
    for (size_t i = 0; o && i < n; i++)
      ((double *)PyArray_DATA((PyArrayObject *)o))[i] = vl_down_column_value(&pts[i], c);
    if (vlpy_set(d, vl_down_columns[c], o) < 0) Py_CLEAR(d);
  }
  /* a point contact's columns: `geometry` a list of words, the others numbers */
  bool ball = n && pts[0].ball.geometry != VL_GEOMETRY_CYLINDER;
  for (size_t c = 0; d && ball && vl_ball_columns[c]; c++) {
    npy_intp dims[1] = {(npy_intp)n};
    PyObject *o = c == 0 ? PyList_New((Py_ssize_t)n) : PyArray_SimpleNew(1, dims, NPY_DOUBLE);
    for (size_t i = 0; o && i < n; i++) {
      if (c > 0) {
        ((double *)PyArray_DATA((PyArrayObject *)o))[i] = vl_ball_column_value(&pts[i], c);
        continue;
      }
      PyObject *t = PyUnicode_FromString(vl_geometry_name(pts[i].ball.geometry));
      if (!t)
        Py_CLEAR(o);
      else
        PyList_SET_ITEM(o, (Py_ssize_t)i, t);
    }
    if (vlpy_set(d, vl_ball_columns[c], o) < 0) Py_CLEAR(d);
  }
  return d;
}

/* A seal's table (seal.csv, viscolube/output.h): {column: numpy array of
 * float64 (NaN where the CSV is empty; converged_*, tight 1.0/0.0) or list
 * of str (accuracy_*, warnings_*)}. */
static PyObject *seal_dict(size_t n, const vl_point *pts) {
  PyObject *d = PyDict_New();
  npy_intp dims[1] = {(npy_intp)n};
  for (size_t c = 0; d && vl_seal_table_columns[c]; c++) {
    bool text = n && vl_seal_table_text(&pts[0], c);
    PyObject *o = text ? PyList_New((Py_ssize_t)n) : PyArray_SimpleNew(1, dims, NPY_DOUBLE);
    for (size_t i = 0; o && i < n; i++) {
      if (!text) {
        ((double *)PyArray_DATA((PyArrayObject *)o))[i] = vl_seal_table_value(&pts[i], c);
        continue;
      }
      PyObject *t = PyUnicode_FromString(vl_seal_table_text(&pts[i], c));
      if (!t)
        Py_CLEAR(o);
      else
        PyList_SET_ITEM(o, (Py_ssize_t)i, t);
    }
    if (vlpy_set(d, vl_seal_table_columns[c], o) < 0) Py_CLEAR(d);
  }
  return d;
}

/* ---- queries ------------------------------------------------------------- */

/* The arguments every query takes; the rest go to *extra (speed, or the
 * sweep from, to, points and whether they are speeds). -1 with an
 * exception. */
typedef struct {
  double speed_m_s, v_from, v_to;
  Py_ssize_t points;
  int in_speed; /* v_from, v_to in m/s (else v0 eta, Pa m) */
} query_extra;

/* The vl_geometry named by name (NULL: a cylinder) into *g; -1 with an
 * InputError naming the keyword. */
static int parse_geometry(const char *name, int *g) {
  *g = VL_GEOMETRY_CYLINDER;
  for (int k = VL_GEOMETRY_CYLINDER; name && k <= VL_GEOMETRY_ELLIPSOID; k++)
    if (!strcmp(name, vl_geometry_name(k))) *g = k;
  if (!name || *g != VL_GEOMETRY_CYLINDER || !strcmp(name, "cylinder")) return 0;
  vl_error err;
  vl_error_set(&err, "geometry: expected cylinder, ball or ellipsoid (got '%s')", name);
  vlpy_raise(VL_EINPUT, &err);
  return -1;
}

static int parse_query(PyObject *args, PyObject *kw, vl_query *q, query_extra *x) {
  static char *kwlist[] = {"compound",      "surface",    "fluid",         "load_n_per_m",
                           "radius_m",      "sigma_s_pa", "temperature_c", "flow_factors",
                           "film_cutoff_m", "grid",       "speed_m_s",     "v_from",
                           "v_to",          "points",     "geometry",      "load_n",
                           "radius_y_m",    "in_speed",   "target_error",  NULL};
  const char *ff = NULL, *geometry = NULL;
  Py_ssize_t grid = 0;
  vl_query_defaults(q);
  *x = (query_extra){NAN, VL_QUERY_FROM_PA_M, VL_QUERY_TO_PA_M, VL_QUERY_POINTS, 0};
  q->sigma_s_pa = NAN; /* not given: the stored pair's law, else the default */
  /* surface and fluid None: a point contact's smooth or dry body */
  if (!PyArg_ParseTupleAndKeywords(args, kw, "szz|ddddzdndddnzddpd", kwlist, &q->compound,
                                   &q->surface, &q->fluid, &q->load_n_per_m, &q->radius_m,
                                   &q->sigma_s_pa, &q->temperature_c, &ff, &q->film_cutoff_m, &grid,
                                   &x->speed_m_s, &x->v_from, &x->v_to, &x->points, &geometry,
                                   &q->load_n, &q->radius_y_m, &x->in_speed, &q->target_error))
    return -1;
  if (parse_geometry(geometry, &q->geometry) < 0) return -1;
  vl_error err = {{0}};
  if (ff && vl_flow_factors_parse(ff, &q->flow_factors, &err) != VL_OK) {
    vl_error_prefix(&err, "flow_factors");
    vlpy_raise(VL_EINPUT, &err);
    return -1;
  }
  /* 0 is the library's default; the CLI's range otherwise */
  bool bad_target = q->target_error != 0.0 && !(q->target_error >= 1e-6 && q->target_error <= 0.5);
  if (grid < 0 || x->points < 2 || x->points > 10000 || bad_target) {
    vl_error_set(&err, grid < 0     ? "grid: must not be negative"
                       : bad_target ? "target_error: needs a relative error in [1e-6, 0.5]"
                                    : "points: needs 2 to 10000");
    vlpy_raise(VL_EINPUT, &err);
    return -1;
  }
  q->grid = (size_t)grid;
  q->at_temperature = !isnan(q->temperature_c);
  q->sigma_s_given = !isnan(q->sigma_s_pa);
  if (!q->sigma_s_given) q->sigma_s_pa = VL_QUERY_SIGMA_S_PA;
  return 0;
}

/* The result of friction: the point's columns and how it was computed. */
static PyObject *friction_dict(const vl_query *q, const vl_query_result *r) {
  vl_curve_meta meta = {r->eta_pa_s,      0.0,
                        r->a0_m,          r->flow_factors,
                        r->film_cutoff_m, r->has_pair ? r->shear_law_text : NULL};
  PyObject *d = PyDict_New();
  for (size_t c = 0; d && vl_curve_columns[c]; c++) {
    const char *name = vl_curve_columns[c];
    double v;
    PyObject *o =
        column_number(name, &r->point, &meta, &v) ? PyFloat_FromDouble(v)
        : !strcmp(name, "converged")              ? PyBool_FromLong(r->point.converged)
        : !strcmp(name, "iterations")             ? PyLong_FromLong(r->point.iterations)
        : !strcmp(name, "regime")
            ? PyUnicode_FromString(r->point.converged ? vl_regime_name(r->point.regime) : "")
        : !strcmp(name, "accuracy")
            ? PyUnicode_FromString(r->point.converged ? vl_accuracy_name(r->point.accuracy) : "")
            : PyUnicode_FromString(r->point.warnings);
    if (vlpy_set(d, name, o) < 0) Py_CLEAR(d);
  }
  /* a point contact's keys (friction --json's, run's curve.csv columns):
   * `geometry` a word, the others numbers (NaN where the CSV is empty) */
  for (size_t c = 0; d && q->geometry != VL_GEOMETRY_CYLINDER && vl_ball_columns[c]; c++) {
    PyObject *o = c == 0 ? PyUnicode_FromString(vl_geometry_name(r->point.ball.geometry))
                         : PyFloat_FromDouble(vl_ball_column_value(&r->point, c));
    if (vlpy_set(d, vl_ball_columns[c], o) < 0) Py_CLEAR(d);
  }
  if (d &&
      (vlpy_set_double(d, "eta_pa_s", r->eta_pa_s) || vlpy_set_double(d, "a_T", r->shift_factor) ||
       vlpy_set_double(d, "a0_m", r->a0_m) || vlpy_set_double(d, "hrms_m", r->hrms_m) ||
       vlpy_set_text(d, "flow_factors", r->flow_factors) ||
       vlpy_set_double(d, "film_cutoff_m", r->film_cutoff_m) ||
       vlpy_set_double(d, "temperature_c", q->temperature_c) ||
       vlpy_set_double(d, "sigma_s_pa", r->sigma_s_pa) ||
       vlpy_set_text(d, "sigma_s_law", r->has_pair ? r->shear_law_text : NULL) ||
       vlpy_set(d, "points_solved", PyLong_FromSize_t(r->points_solved))))
    Py_CLEAR(d);
  return d;
}

PyObject *vlpy_friction(DatabaseObject *self, PyObject *args, PyObject *kw) {
  vl_query q;
  query_extra x;
  if (parse_query(args, kw, &q, &x) < 0) return NULL;
  vl_db *db = vlpy_db(self);
  if (!db) return NULL;
  vl_query_result r;
  vl_error err = {{0}};
  vl_status st = vl_query_friction(db, &q, x.speed_m_s, &r, &err);
  return st == VL_OK ? friction_dict(&q, &r) : vlpy_raise(st, &err);
}

PyObject *vlpy_check_query(DatabaseObject *self, PyObject *args, PyObject *kw) {
  vl_query q;
  query_extra x;
  if (parse_query(args, kw, &q, &x) < 0) return NULL;
  vl_db *db = vlpy_db(self);
  if (!db) return NULL;
  vl_error err = {{0}};
  vl_scene *sc = malloc(sizeof *sc);
  vl_db_surface surf;
  vl_prony probe;
  double eta;
  if (!sc) return PyErr_NoMemory();
  vl_status st = vl_query_scene(&q, "compare", sc, &err);
  free(sc);
  if (st == VL_OK) st = vl_db_compound_get(db, q.compound, &probe, &err);
  if (st == VL_OK && q.surface) st = vl_db_surface_info(db, q.surface, &surf, &err);
  if (st == VL_OK) st = vl_query_check_compound(db, &q, q.compound, &err);
  /* the messages name the material and the temperature already */
  if (st == VL_OK) st = vl_query_fluid_eta(db, &q, &eta, &err);
  if (st != VL_OK) return vlpy_raise(st, &err);
  Py_RETURN_NONE;
}

/* ---- scenes -------------------------------------------------------------- */

/* The fields of the points a scene asks them at, kept while it runs (the
 * callback cannot raise: a failed allocation is remembered). */
typedef struct {
  vl_simulation *sim;
  size_t n, cap;
  size_t *index;
  vl_fields *fields;
  double **maps; /* a point contact: x, y, p_c, u, p_f of maps_n[k] cells each, in one block */
  size_t *maps_n;
  int failed;
} fields_store;

/* A point contact's 2-D fields (the callback of vl_simulation_run_point_contact). */
static void keep_maps(void *user, size_t i, size_t total, const vl_point *pt,
                      const vl_point_contact *c) {
  fields_store *s = user;
  (void)total;
  if (!vl_simulation_wants_fields(s->sim, i) || !pt->converged || s->failed || !c) return;
  size_t g = vl_point_contact_cells(c);
  double *b = calloc(5 * g, sizeof *b);
  if (!b || s->n == s->cap) {
    free(b);
    s->failed = 1;
    return;
  }
  s->index[s->n] = i;
  s->maps[s->n] = b;
  s->maps_n[s->n++] = g;
  vl_fields2d f = {b, b + g, b + 2 * g, b + 3 * g, b + 4 * g};
  vl_point_contact_fields(c, &f);
}

static void keep_fields(void *user, size_t i, size_t total, const vl_point *pt,
                        const vl_contact *contact) {
  fields_store *s = user;
  (void)total;
  if (!vl_simulation_wants_fields(s->sim, i) || !pt->converged || s->failed) return;
  size_t g = vl_contact_grid(contact);
  double *b = calloc(7 * g, sizeof *b);
  if (!b || s->n == s->cap) {
    free(b);
    s->failed = 1;
    return;
  }
  s->index[s->n] = i;
  s->fields[s->n++] =
      (vl_fields){g, b, b + g, b + 2 * g, b + 3 * g, b + 4 * g, b + 5 * g, b + 6 * g};
  vl_contact_fields(contact, &s->fields[s->n - 1]);
}

/* A point contact's fields kept, as a list of dicts with the columns of its
 * fields/NNN.csv (docs/FORMATS.md). */
static PyObject *maps_list(const fields_store *s, const vl_point *pts, double a0_m) {
  PyObject *l = PyList_New(0);
  for (size_t k = 0; l && k < s->n; k++) {
    size_t g = s->maps_n[k];
    const double *x = s->maps[k], *y = x + g, *p = x + 2 * g, *u = x + 3 * g, *pf = x + 4 * g;
    /* a lubricated ball's fields carry p_f (as its fields/NNN.csv) */
    bool wet = pts[s->index[k]].fluid_load_fraction > 0.0;
    PyObject *d = PyDict_New(), *xa = vlpy_array(x, g), *ya = vlpy_array(y, g);
    for (size_t i = 0; xa && ya && i < g; i++) {
      ((double *)PyArray_DATA((PyArrayObject *)xa))[i] /= a0_m;
      ((double *)PyArray_DATA((PyArrayObject *)ya))[i] /= a0_m;
    }
    if (!d || vlpy_set(d, "index", PyLong_FromSize_t(s->index[k])) ||
        vlpy_set_double(d, "v0_m_s", pts[s->index[k]].v0_m_s) ||
        vlpy_set(d, "x_m", vlpy_array(x, g)) || vlpy_set(d, "y_m", vlpy_array(y, g)) ||
        vlpy_set(d, "x_over_a0", xa) || vlpy_set(d, "y_over_a0", ya) ||
        vlpy_set(d, "p_c_pa", vlpy_array(p, g)) || vlpy_set(d, "u_m", vlpy_array(u, g)) ||
        (wet && vlpy_set(d, "p_f_pa", vlpy_array(pf, g))) || PyList_Append(l, d) < 0)
      Py_CLEAR(l);
    Py_XDECREF(d);
  }
  return l;
}

/* The fields kept, as a list of dicts with the columns of fields/NNN.csv. */
static PyObject *fields_list(const fields_store *s, const vl_point *pts, double a0_m) {
  if (s->maps) return maps_list(s, pts, a0_m);
  PyObject *l = PyList_New(0);
  for (size_t k = 0; l && k < s->n; k++) {
    const vl_fields *f = &s->fields[k];
    PyObject *d = PyDict_New();
    PyObject *xa = vlpy_array(f->x_m, f->n);
    for (size_t i = 0; xa && i < f->n; i++)
      ((double *)PyArray_DATA((PyArrayObject *)xa))[i] /= a0_m;
    if (!d || vlpy_set(d, "index", PyLong_FromSize_t(s->index[k])) ||
        vlpy_set_double(d, "v0_m_s", pts[s->index[k]].v0_m_s) ||
        vlpy_set(d, "x_m", vlpy_array(f->x_m, f->n)) || vlpy_set(d, "x_over_a0", xa) ||
        vlpy_set(d, "p_f_pa", vlpy_array(f->p_f_pa, f->n)) ||
        vlpy_set(d, "p_c_pa", vlpy_array(f->p_c_pa, f->n)) ||
        vlpy_set(d, "u_m", vlpy_array(f->u_m, f->n)) ||
        vlpy_set(d, "area_ratio", vlpy_array(f->area_ratio, f->n)) ||
        vlpy_set(d, "film_fraction", vlpy_array(f->film_fraction, f->n)) ||
        vlpy_set(d, "cell_width_m", vlpy_array(f->width_m, f->n)) || PyList_Append(l, d) < 0)
      Py_CLEAR(l);
    Py_XDECREF(d);
  }
  return l;
}

/* What describes a curve besides its points. */
static PyObject *curve_info(const vl_scene *sc, vl_simulation *sim, const vl_curve_meta *m) {
  PyObject *d = PyDict_New();
  const vl_psd *psd = vl_simulation_psd(sim);
  if (d &&
      (vlpy_set_text(d, "compound", sc->compound) || vlpy_set_text(d, "surface", sc->surface) ||
       vlpy_set_text(d, "fluid", sc->effects.fluid ? sc->fluid : NULL) ||
       vlpy_set_text(d, "quantity", vl_sweep_quantity_name(sc->quantity)) ||
       vlpy_set_double(d, "eta_pa_s", m->eta_pa_s) || vlpy_set_double(d, "tau_s", m->tau_s) ||
       vlpy_set_double(d, "a0_m", m->a0_m) || vlpy_set_double(d, "p0_pa", vl_simulation_p0(sim)) ||
       vlpy_set_double(d, "hrms_m", psd ? psd->hrms_m : 0.0) ||
       vlpy_set_text(d, "flow_factors", m->flow_factors) ||
       vlpy_set_double(d, "film_cutoff_m", m->film_cutoff_m) ||
       vlpy_set_double(d, "temperature_c", vl_simulation_temperature_c(sim)) ||
       vlpy_set_double(d, "a_T", vl_simulation_shift_factor(sim)) ||
       vlpy_set_text(d, "sigma_s_law", vl_simulation_shear_law_text(sim))))
    Py_CLEAR(d);
  return d;
}

static void store_free(fields_store *s) {
  for (size_t k = 0; k < s->n; k++) {
    if (s->fields) free(s->fields[k].x_m);
    if (s->maps) free(s->maps[k]);
  }
  free(s->fields);
  free(s->maps);
  free(s->maps_n);
  free(s->index);
}

/* Runs scene sc (one fluid): {"info": ..., "curve": {column: array},
 * "fields": [...]}. */
static PyObject *run_one(vl_db *db, const vl_scene *sc) {
  vl_error err = {{0}};
  fields_store s = {0};
  vl_point *pts = NULL;
  PyObject *ret = NULL;
  vl_status st = vl_simulation_create(sc, db, &s.sim, &err);
  size_t n = st == VL_OK ? vl_simulation_points(s.sim) : 0;
  if (st == VL_OK) {
    pts = calloc(n, sizeof *pts);
    s.cap = n;
    s.index = calloc(n, sizeof *s.index);
    bool point = sc->geometry != VL_GEOMETRY_CYLINDER;
    if (point) {
      s.maps = calloc(n, sizeof *s.maps);
      s.maps_n = calloc(n, sizeof *s.maps_n);
    } else {
      s.fields = calloc(n, sizeof *s.fields);
    }
    if (!pts || !s.index || (point ? !s.maps || !s.maps_n : !s.fields))
      st = VL_ENOMEM, vl_error_set(&err, "out of memory");
  }
  vl_sweep_stats stats;
  if (st == VL_OK && sc->geometry != VL_GEOMETRY_CYLINDER)
    st = vl_simulation_run_point_contact(s.sim, pts, keep_maps, &s, &stats, &err);
  else if (st == VL_OK)
    st = vl_simulation_run(s.sim, pts, keep_fields, &s, &stats, &err);
  if (st == VL_OK && s.failed) st = VL_ENOMEM, vl_error_set(&err, "out of memory (fields)");
  if (st != VL_OK) {
    vlpy_raise(st, &err);
    goto done;
  }
  vl_curve_meta m = {vl_simulation_eta(s.sim),
                     vl_simulation_tau(s.sim),
                     vl_simulation_a0(s.sim),
                     NULL,
                     0,
                     vl_simulation_shear_law_text(s.sim)};
  m.flow_factors = vl_simulation_flow_factors(s.sim, &m.film_cutoff_m);
  ret = PyDict_New();
  if (ret && (vlpy_set(ret, "info", curve_info(sc, s.sim, &m)) ||
              vlpy_set(ret, "curve", curve_dict(n, pts, &m)) ||
              vlpy_set(ret, "fields", fields_list(&s, pts, m.a0_m))))
    Py_CLEAR(ret);
  /* a seal's both strokes: its table too */
  if (ret && n && pts[0].seal.stroke == VL_STROKE_BOTH && vlpy_set(ret, "seal", seal_dict(n, pts)))
    Py_CLEAR(ret);
done:
  store_free(&s);
  free(pts);
  vl_simulation_free(s.sim);
  return ret;
}

/* Every curve of sc: one per fluid of `fluid = a, b, ...`. */
static PyObject *run_all(vl_db *db, const vl_scene *sc) {
  size_t nf = sc->n_fluids > 1 ? sc->n_fluids : 1;
  PyObject *l = PyList_New(0);
  vl_scene *one = malloc(sizeof *one);
  if (!one) Py_CLEAR(l);
  for (size_t k = 0; l && k < nf; k++) {
    *one = *sc;
    if (sc->n_fluids > 1) {
      snprintf(one->fluid, sizeof one->fluid, "%s", sc->fluids[k]);
      one->n_fluids = 1;
    }
    PyObject *r = run_one(db, one);
    if (!r || PyList_Append(l, r) < 0) Py_CLEAR(l);
    Py_XDECREF(r);
  }
  free(one);
  return l;
}

PyObject *vlpy_run_scene(DatabaseObject *self, PyObject *args, PyObject *kw) {
  static char *kwlist[] = {"text", "path", "seal", NULL};
  const char *text = NULL, *path = NULL;
  int seal = 0;
  if (!PyArg_ParseTupleAndKeywords(args, kw, "zs|p", kwlist, &text, &path, &seal)) return NULL;
  vl_db *db = vlpy_db(self);
  if (!db) return NULL;
  vl_scene *sc = malloc(sizeof *sc);
  if (!sc) return PyErr_NoMemory();
  vl_error err = {{0}};
  vl_status st = text ? vl_scene_parse(text, path, sc, &err) : vl_scene_load(path, sc, &err);
  /* seal(): both strokes, as `viscolube seal` */
  if (st == VL_OK && seal) st = vl_scene_as_seal(sc, &err);
  PyObject *ret = st == VL_OK ? run_all(db, sc) : vlpy_raise(st, &err);
  free(sc);
  return ret;
}

PyObject *vlpy_run_query(DatabaseObject *self, PyObject *args, PyObject *kw) {
  vl_query q;
  query_extra x;
  if (parse_query(args, kw, &q, &x) < 0) return NULL;
  vl_db *db = vlpy_db(self);
  if (!db) return NULL;
  vl_scene *sc = malloc(sizeof *sc);
  if (!sc) return PyErr_NoMemory();
  vl_error err = {{0}};
  vl_status st = vl_query_scene(&q, "compare", sc, &err);
  if (st == VL_OK && !(x.v_to > x.v_from && x.v_from > 0)) {
    vl_error_set(&err, "v_from, v_to: need 0 < v_from < v_to");
    st = VL_EINPUT;
  }
  if (st == VL_OK && !q.fluid && !x.in_speed) { /* a range in Pa m has no meaning dry */
    vl_error_set(&err, "v_from, v_to: a dry contact (no fluid) has no v0 eta: give the range "
                       "in m/s (in_speed)");
    st = VL_EINPUT;
  }
  sc->from = x.v_from, sc->to = x.v_to, sc->points = (size_t)x.points;
  if (x.in_speed) sc->quantity = VL_SWEEP_V0; /* the range in m/s, as compare --from-speed */
  PyObject *ret = st == VL_OK ? run_one(db, sc) : vlpy_raise(st, &err);
  free(sc);
  return ret;
}
