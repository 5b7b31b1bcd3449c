/* viscolube._core: listing and adding compounds, surfaces and fluids. The
 * library checks every value (and refuses before touching the file); the
 * binding only says which arguments go together. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core.h"

/* Raises InputError with a message of the binding's own (which arguments
 * go together); returns NULL. */
static PyObject *refuse(const char *msg) {
  vl_error err;
  vl_error_set(&err, "%s", msg);
  return vlpy_raise(VL_EINPUT, &err);
}

/* ---- lists --------------------------------------------------------------- */

static PyObject *compound_dict(const vl_db_compound *c) {
  PyObject *d = PyDict_New();
  const vl_prony *p = &c->prony;
  if (!d || vlpy_set_text(d, "name", c->name) || vlpy_set_text(d, "class", c->class_name) ||
      vlpy_set_text(d, "description", c->description) ||
      vlpy_set_double(d, "e_inf_pa", p->e_inf_pa) || vlpy_set_double(d, "e0_pa", vl_prony_e0(p)) ||
      vlpy_set_double(d, "nu", p->nu) || vlpy_set(d, "tau_s", vlpy_array(p->tau_s, p->n_terms)) ||
      vlpy_set(d, "A", vlpy_array(p->A, p->n_terms)) || vlpy_set_double(d, "tref_c", c->tref_c) ||
      vlpy_set_double(d, "wlf_c1", c->wlf_c1) || vlpy_set_double(d, "wlf_c2_k", c->wlf_c2_k) ||
      vlpy_set_text(d, "method", c->method) || vlpy_set_text(d, "source_file", c->source_file) ||
      vlpy_set_double(d, "fit_rms_error", c->fit_rms_error) ||
      vlpy_set_text(d, "created_at", c->created_at))
    Py_CLEAR(d);
  return d;
}

static PyObject *surface_dict(const vl_db_surface *s) {
  PyObject *d = PyDict_New();
  int tab = s->kind == VL_PSD_TABULATED;
  if (!d || vlpy_set_text(d, "name", s->name) ||
      vlpy_set_text(d, "kind", tab ? "tabulated" : "self-affine") ||
      vlpy_set_text(d, "description", s->description) || vlpy_set_double(d, "hrms_m", s->hrms_m) ||
      vlpy_set_double(d, "rms_slope", s->rms_slope) ||
      vlpy_set_double(d, "c0_m4", tab ? NAN : s->c0_m4) ||
      vlpy_set_double(d, "q0_per_m", s->q0_per_m) || vlpy_set_double(d, "q1_per_m", s->q1_per_m) ||
      vlpy_set_double(d, "hurst", tab ? NAN : s->hurst) ||
      vlpy_set(d, "n_points", PyLong_FromSize_t(s->n_points)) ||
      vlpy_set_text(d, "source_file", s->source_file) ||
      vlpy_set_text(d, "created_at", s->created_at))
    Py_CLEAR(d);
  return d;
}

static PyObject *fluid_dict(const vl_db_fluid *f) {
  PyObject *d = PyDict_New();
  int law = f->law.kind != VL_VISCOSITY_LAW_NONE;
  if (!d || vlpy_set_text(d, "name", f->name) ||
      vlpy_set_double(d, "viscosity_pa_s", f->viscosity_pa_s) ||
      vlpy_set_double(d, "tref_c", f->tref_c) ||
      vlpy_set_text(d, "viscosity_law", law ? vl_viscosity_law_name(f->law.kind) : NULL) ||
      vlpy_set_double(d, "vogel_b_k", law ? f->law.vogel_b_k : NAN) ||
      vlpy_set_double(d, "vogel_c_k", law ? f->law.vogel_c_k : NAN) ||
      vlpy_set_double(d, "law_tmin_c", law ? f->law.tmin_c : NAN) ||
      vlpy_set_double(d, "law_tmax_c", law ? f->law.tmax_c : NAN) ||
      vlpy_set_text(d, "description", f->description) ||
      vlpy_set_text(d, "source_file", f->source_file) ||
      vlpy_set_text(d, "created_at", f->created_at))
    Py_CLEAR(d);
  return d;
}

/* The list of n items of size `size` at items, each made a dict by fn. */
static PyObject *list_of(const void *items, size_t n, size_t size, PyObject *(*fn)(const void *)) {
  PyObject *l = PyList_New((Py_ssize_t)n);
  for (size_t i = 0; l && i < n; i++) {
    PyObject *d = fn((const char *)items + i * size);
    if (!d)
      Py_CLEAR(l);
    else
      PyList_SET_ITEM(l, (Py_ssize_t)i, d);
  }
  return l;
}

static PyObject *compound_item(const void *p) { return compound_dict(p); }
static PyObject *surface_item(const void *p) { return surface_dict(p); }
static PyObject *fluid_item(const void *p) { return fluid_dict(p); }

PyObject *vlpy_compounds(DatabaseObject *self, PyObject *unused) {
  (void)unused;
  vl_db *db = vlpy_db(self);
  vl_db_compound *items = NULL;
  size_t n = 0;
  vl_error err = {{0}};
  if (!db) return NULL;
  vl_status st = vl_db_compound_list(db, &items, &n, &err);
  PyObject *l =
      st == VL_OK ? list_of(items, n, sizeof *items, compound_item) : vlpy_raise(st, &err);
  free(items);
  return l;
}

PyObject *vlpy_surfaces(DatabaseObject *self, PyObject *unused) {
  (void)unused;
  vl_db *db = vlpy_db(self);
  vl_db_surface *items = NULL;
  size_t n = 0;
  vl_error err = {{0}};
  if (!db) return NULL;
  vl_status st = vl_db_surface_list(db, &items, &n, &err);
  PyObject *l = st == VL_OK ? list_of(items, n, sizeof *items, surface_item) : vlpy_raise(st, &err);
  free(items);
  return l;
}

PyObject *vlpy_fluids(DatabaseObject *self, PyObject *unused) {
  (void)unused;
  vl_db *db = vlpy_db(self);
  vl_db_fluid *items = NULL;
  size_t n = 0;
  vl_error err = {{0}};
  if (!db) return NULL;
  vl_status st = vl_db_fluid_list(db, &items, &n, &err);
  PyObject *l = st == VL_OK ? list_of(items, n, sizeof *items, fluid_item) : vlpy_raise(st, &err);
  free(items);
  return l;
}

/* ---- compounds ----------------------------------------------------------- */

/* The terms tau_s and A (sequences of equal length) into p; -1 with an
 * exception when they are not numbers or too many. */
static int terms_from(PyObject *tau, PyObject *a, vl_prony *p) {
  PyObject *t = PySequence_Fast(tau, "tau_s must be a sequence of numbers");
  PyObject *s = t ? PySequence_Fast(a, "A must be a sequence of numbers") : NULL;
  int rc = -1;
  if (!s) goto done;
  Py_ssize_t n = PySequence_Fast_GET_SIZE(t);
  if (n != PySequence_Fast_GET_SIZE(s) || n > VL_PRONY_MAX_TERMS) {
    refuse("tau_s and A need the same length, at most 128 terms");
    goto done;
  }
  for (Py_ssize_t i = 0; i < n; i++) {
    p->tau_s[i] = PyFloat_AsDouble(PySequence_Fast_GET_ITEM(t, i));
    p->A[i] = PyFloat_AsDouble(PySequence_Fast_GET_ITEM(s, i));
    if (PyErr_Occurred()) goto done;
  }
  p->n_terms = (size_t)n;
  rc = 0;
done:
  Py_XDECREF(t);
  Py_XDECREF(s);
  return rc;
}

/* The fit options of a measured file; -1 with an exception. */
static int dma_options(const char *weights, vl_dma_options *o) {
  if (!weights) return 0;
  if (!strcmp(weights, vl_prony_weights_name(VL_PRONY_WEIGHTS_MODULUS)))
    o->weights = VL_PRONY_WEIGHTS_MODULUS;
  else if (strcmp(weights, vl_prony_weights_name(VL_PRONY_WEIGHTS_RELATIVE))) {
    refuse("fit_weights: not 'relative' or 'modulus'");
    return -1;
  }
  return 0;
}

/* Stores c, its series fitted to the measured file path (vl_dma_options
 * from o). */
static vl_status add_measured(vl_db *db, vl_db_compound *c, const char *path,
                              const vl_dma_options *o, char *notes, size_t cap, vl_error *err) {
  vl_measured m;
  vl_status st = vl_measured_read_file(path, o, &m, err);
  if (st == VL_OK) st = vl_db_compound_add_measured(db, c, &m, err);
  if (st == VL_OK) snprintf(notes, cap, "%s", m.notes);
  vl_measured_free(&m);
  return st;
}

/* Stores c with the Prony series of the CSV file path, or the terms
 * already in c when path is NULL. */
static vl_status add_prony(vl_db *db, vl_db_compound *c, const char *path, vl_error *err) {
  vl_status st = VL_OK;
  snprintf(c->method, sizeof c->method, "prony-csv");
  if (path) st = vl_csv_read_prony(path, &c->prony, err);
  if (st == VL_OK) st = vl_prony_validate(&c->prony, err);
  if (st == VL_OK) st = vl_db_compound_add(db, c, err);
  return st;
}

PyObject *vlpy_add_compound(DatabaseObject *self, PyObject *args, PyObject *kw) {
  static char *kwlist[] = {"name",        "prony",
                           "tau_s",       "A",
                           "e_inf_pa",    "nu",
                           "measured",    "class_name",
                           "description", "tref_c",
                           "wlf_c1",      "wlf_c2_k",
                           "freq_unit",   "modulus_unit",
                           "temp_unit",   "terms_per_decade",
                           "fit_weights", NULL};
  const char *name, *prony = NULL, *measured = NULL, *cls = "other", *desc = "";
  const char *fw = NULL;
  PyObject *tau = Py_None, *a = Py_None;
  double e_inf = NAN, nu = NAN, tref = NAN, c1 = NAN, c2 = NAN;
  vl_dma_options o = vl_dma_options_default();
  if (!PyArg_ParseTupleAndKeywords(args, kw, "s|zOOddzssdddzzzdz", kwlist, &name, &prony, &tau, &a,
                                   &e_inf, &nu, &measured, &cls, &desc, &tref, &c1, &c2,
                                   &o.freq_unit, &o.modulus_unit, &o.temp_unit, &o.terms_per_decade,
                                   &fw))
    return NULL;
  vl_db *db = vlpy_db(self);
  if (!db) return NULL;
  int arrays = tau != Py_None || a != Py_None;
  if ((prony != NULL) + (measured != NULL) + arrays != 1)
    return refuse("give one of prony=FILE, measured=FILE and tau_s=/A=");
  vl_db_compound *c = calloc(1, sizeof *c);
  if (!c) return PyErr_NoMemory();
  snprintf(c->name, sizeof c->name, "%s", name);
  snprintf(c->class_name, sizeof c->class_name, "%s", cls);
  snprintf(c->description, sizeof c->description, "%s", desc);
  snprintf(c->source_file, sizeof c->source_file, "%s", prony ? prony : measured ? measured : "");
  c->tref_c = isnan(tref) ? 20.0 : tref;
  c->wlf_c1 = c1, c->wlf_c2_k = c2, c->fit_rms_error = NAN;
  c->prony.e_inf_pa = e_inf, c->prony.nu = nu;
  vl_error err = {{0}};
  vl_status st = VL_OK;
  char notes[VL_DMA_NOTES_MAX] = "";
  if (measured) {
    o.tref_c = tref;
    if (!isnan(nu)) o.nu = nu;
    if (!isnan(c1) || !isnan(c2) || !isnan(e_inf))
      refuse("measured=: the fit determines e_inf_pa and the WLF constants");
    else if (dma_options(fw, &o) == 0)
      st = add_measured(db, c, measured, &o, notes, sizeof notes, &err);
  } else if (isnan(e_inf) || isnan(nu)) {
    refuse("a Prony series needs e_inf_pa and nu");
  } else if (!arrays || terms_from(tau, a, &c->prony) == 0) {
    st = add_prony(db, c, prony, &err);
  }
  free(c);
  if (PyErr_Occurred()) return NULL;
  if (st != VL_OK) return vlpy_raise(st, &err);
  if (measured) return PyUnicode_FromString(notes); /* the import's notes and warnings */
  Py_RETURN_NONE;
}

/* ---- surfaces and fluids ----------------------------------------------- */

PyObject *vlpy_add_surface(DatabaseObject *self, PyObject *args, PyObject *kw) {
  static char *kwlist[] = {"name",   "psd",         "hurst",      "q0_per_m", "q1_per_m",
                           "hrms_m", "description", "topography", NULL};
  const char *name, *path = NULL, *desc = NULL, *topo = NULL;
  double h = NAN, q0 = NAN, q1 = NAN, hrms = NAN;
  if (!PyArg_ParseTupleAndKeywords(args, kw, "s|zddddzz", kwlist, &name, &path, &h, &q0, &q1, &hrms,
                                   &desc, &topo))
    return NULL;
  vl_db *db = vlpy_db(self);
  if (!db) return NULL;
  int self_affine = !isnan(h) || !isnan(q0) || !isnan(q1) || !isnan(hrms);
  if ((path != NULL) + (topo != NULL) + self_affine != 1)
    return refuse("give psd=FILE, topography=FILE or hurst=, q0_per_m=, q1_per_m=, hrms_m= "
                  "(self-affine)");
  vl_psd psd;
  memset(&psd, 0, sizeof psd);
  vl_error err = {{0}};
  vl_status st = VL_OK;
  if (topo) { /* as `surface add --topography` (src/cli/cli_surface.c) */
    vl_topography t = {0};
    vl_topography_spectrum sp = {0};
    st = vl_topography_read_file(topo, &t, &err);
    if (st == VL_OK) st = vl_topography_psd(&t, NULL, &sp, &err);
    if (st == VL_OK) st = vl_psd_init_tabulated(&psd, sp.n, sp.q_per_m, sp.c_m4, &err);
    char d[VL_DB_TEXT_MAX]; /* the description, else the provenance (cut to fit) */
    snprintf(d, sizeof d, "%.*s", (int)sizeof d - 1, desc ? desc : sp.provenance);
    if (st == VL_OK) st = vl_db_surface_add(db, name, &psd, d, topo, &err);
    vl_topography_spectrum_free(&sp);
    vl_topography_free(&t);
  } else {
    st = path ? vl_csv_read_psd(path, &psd, &err)
              : vl_psd_init_self_affine(&psd, h, q0, q1, hrms, &err);
    if (st == VL_OK) st = vl_db_surface_add(db, name, &psd, desc, path, &err);
  }
  vl_psd_free(&psd);
  if (st != VL_OK) return vlpy_raise(st, &err);
  Py_RETURN_NONE;
}

PyObject *vlpy_add_fluid(DatabaseObject *self, PyObject *args, PyObject *kw) {
  static char *kwlist[] = {"name",       "viscosity_pa_s", "tref_c",      "vogel_b_k", "vogel_c_k",
                           "law_tmin_c", "law_tmax_c",     "description", NULL};
  const char *name, *desc = "";
  vl_db_fluid f;
  memset(&f, 0, sizeof f);
  f.tref_c = 20.0;
  double b = NAN, cc = NAN, lo = NAN, hi = NAN;
  if (!PyArg_ParseTupleAndKeywords(args, kw, "sd|dddddz", kwlist, &name, &f.viscosity_pa_s,
                                   &f.tref_c, &b, &cc, &lo, &hi, &desc))
    return NULL;
  vl_db *db = vlpy_db(self);
  if (!db) return NULL;
  int n_law = !isnan(b) + !isnan(cc) + !isnan(lo) + !isnan(hi);
  if (n_law != 0 && n_law != 4)
    return refuse("vogel_b_k, vogel_c_k, law_tmin_c and law_tmax_c go together");
  if (n_law) f.law = (vl_viscosity_law){VL_VISCOSITY_LAW_VOGEL, b, cc, lo, hi};
  snprintf(f.name, sizeof f.name, "%s", name);
  if (desc && strlen(desc) >= sizeof f.description) return refuse("description: too long");
  snprintf(f.description, sizeof f.description, "%s", desc ? desc : "");
  vl_error err = {{0}};
  vl_status st = vl_db_fluid_add(db, &f, &err);
  if (st != VL_OK) return vlpy_raise(st, &err);
  Py_RETURN_NONE;
}

PyObject *vlpy_remove(DatabaseObject *self, PyObject *args) {
  const char *kind, *name;
  if (!PyArg_ParseTuple(args, "ss", &kind, &name)) return NULL;
  vl_db *db = vlpy_db(self);
  if (!db) return NULL;
  vl_error err = {{0}};
  vl_status st;
  if (!strcmp(kind, "compound"))
    st = vl_db_compound_remove(db, name, &err);
  else if (!strcmp(kind, "surface"))
    st = vl_db_surface_remove(db, name, &err);
  else if (!strcmp(kind, "fluid"))
    st = vl_db_fluid_remove(db, name, &err);
  else
    return refuse("kind: not compound, surface or fluid");
  if (st != VL_OK) return vlpy_raise(st, &err);
  Py_RETURN_NONE;
}
