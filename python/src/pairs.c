/* Pairs from Python (issue 34): Database.calibrate, the library's
 * calibration of a pair's sigma_s law (calibrate.h) on a measured curve
 * given as a file or as arrays, optionally stored as the pair. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core.h"

/* A sequence of numbers into a malloc'd array (*n its length). -1 with a
 * Python error set. */
static int doubles_of(PyObject *seq, const char *what, double **out, size_t *n) {
  PyObject *fast = PySequence_Fast(seq, what);
  if (!fast) return -1;
  Py_ssize_t len = PySequence_Fast_GET_SIZE(fast);
  *out = malloc((size_t)(len > 0 ? len : 1) * sizeof **out);
  *n = (size_t)len;
  if (!*out) {
    Py_DECREF(fast);
    PyErr_NoMemory();
    return -1;
  }
  for (Py_ssize_t i = 0; i < len; i++) {
    (*out)[i] = PyFloat_AsDouble(PySequence_Fast_GET_ITEM(fast, i));
    if (PyErr_Occurred()) {
      Py_DECREF(fast);
      free(*out);
      *out = NULL;
      return -1;
    }
  }
  Py_DECREF(fast);
  return 0;
}

static PyObject *speeds_where(const vl_calibration_sweep *s, const bool *flag, bool want) {
  PyObject *l = PyList_New(0);
  for (size_t i = 0; l && i < s->n; i++)
    if (flag[i] == want) {
      PyObject *x = PyFloat_FromDouble(s->v_m_s[i]);
      if (!x || PyList_Append(l, x) < 0) Py_CLEAR(l);
      Py_XDECREF(x);
    }
  return l;
}

static PyObject *params_dict(const vl_shear_law *law, const double *v) {
  PyObject *d = PyDict_New();
  for (size_t k = 0; d && k < vl_shear_law_n_params(law->kind); k++)
    if (vlpy_set_double(d, vl_shear_law_param_name(law->kind, k), v[k])) Py_CLEAR(d);
  return d;
}

static PyObject *fit_dict(const vl_calibration_sweep *s, const vl_calibration_fit *f) {
  PyObject *d = PyDict_New();
  if (d && (vlpy_set_text(d, "law", vl_shear_law_name(f->law.kind)) ||
            vlpy_set(d, "parameters", params_dict(&f->law, f->law.p)) ||
            vlpy_set(d, "ci95", params_dict(&f->law, f->ci95)) ||
            vlpy_set_double(d, "rms_log10_mu", f->rms_log10_mu) ||
            vlpy_set(d, "fits", PyBool_FromLong(f->fits)) ||
            vlpy_set_text(d, "why", f->fits ? NULL : f->why) ||
            vlpy_set(d, "n_points", PyLong_FromSize_t(s->n)) ||
            vlpy_set(d, "n_used", PyLong_FromSize_t(f->n_used)) ||
            vlpy_set(d, "unreached_v_m_s", speeds_where(s, s->converged, false)) ||
            vlpy_set(d, "uninformative_v_m_s", speeds_where(s, f->uninformative, true)) ||
            vlpy_set_double(d, "sweep_seconds", s->seconds) ||
            vlpy_set_double(d, "fit_seconds", f->seconds)))
    Py_CLEAR(d);
  return d;
}

/* The measured curve: from the file, or from the two sequences. */
static int measured_of(const char *path, PyObject *v_seq, PyObject *mu_seq, double **v, double **mu,
                       size_t *n, char fingerprint[VL_DB_FINGERPRINT_MAX]) {
  vl_error err;
  if (path) {
    vl_status st = vl_friction_curve_read_file(path, v, mu, n, &err);
    if (st != VL_OK) return vlpy_raise(st, &err), -1;
    FILE *f = fopen(path, "rb");
    char *buf = NULL;
    long len = -1;
    if (f && fseek(f, 0, SEEK_END) == 0 && (len = ftell(f)) >= 0 && fseek(f, 0, SEEK_SET) == 0 &&
        (buf = malloc((size_t)len + 1)) && fread(buf, 1, (size_t)len, f) == (size_t)len)
      vl_db_fingerprint_bytes(buf, (size_t)len, fingerprint);
    free(buf);
    if (f) fclose(f);
    return 0;
  }
  size_t nm = 0;
  if (!v_seq || !mu_seq) {
    vl_error_set(&err, "calibrate: give measured (a file) or v_m_s and mu (sequences)");
    return vlpy_raise(VL_EINPUT, &err), -1;
  }
  if (doubles_of(v_seq, "v_m_s: a sequence of speeds", v, n) < 0) return -1;
  if (doubles_of(mu_seq, "mu: a sequence of friction coefficients", mu, &nm) < 0) {
    free(*v);
    return -1;
  }
  if (nm != *n) {
    free(*v), free(*mu);
    vl_error_set(&err, "calibrate: v_m_s has %zu values, mu %zu", *n, nm);
    return vlpy_raise(VL_EINPUT, &err), -1;
  }
  /* the arrays' bytes stand for the file */
  double *both = malloc(2 * *n * sizeof *both + 1);
  if (both) {
    memcpy(both, *v, *n * sizeof *both);
    memcpy(both + *n, *mu, *n * sizeof *both);
    vl_db_fingerprint_bytes(both, 2 * *n * sizeof *both, fingerprint);
  }
  free(both);
  return 0;
}

static vl_status save(vl_db *db, const vl_query *q, const vl_calibration_sweep *s,
                      const vl_calibration_fit *f, const char *file, const char *fingerprint,
                      const char *description, vl_error *err) {
  if (!f->fits) {
    vl_error_set(err, "calibrate: not stored: %.900s", f->why);
    return VL_EINPUT;
  }
  vl_db_pair p;
  memset(&p, 0, sizeof p);
  snprintf(p.compound, sizeof p.compound, "%s", q->compound);
  snprintf(p.surface, sizeof p.surface, "%s", q->surface);
  snprintf(p.fluid, sizeof p.fluid, "%s", q->fluid);
  snprintf(p.source, sizeof p.source, "%s", VL_DB_SOURCE_CALIBRATED);
  if (description) snprintf(p.description, sizeof p.description, "%s", description);
  p.law = f->law;
  memcpy(p.ci95, f->ci95, sizeof p.ci95);
  snprintf(p.measured_file, sizeof p.measured_file, "%s", file);
  snprintf(p.measured_fingerprint, sizeof p.measured_fingerprint, "%s", fingerprint);
  p.n_points = f->n_used;
  p.load_n_per_m = q->load_n_per_m, p.radius_m = q->radius_m;
  p.temperature_c = s->temperature_c;
  p.rms_log10_mu = f->rms_log10_mu;
  return vl_db_pair_add(db, &p, err);
}

PyObject *vlpy_calibrate(DatabaseObject *self, PyObject *args, PyObject *kw) {
  static char *kwlist[] = {
      "compound",     "surface",  "fluid",         "measured", "v_m_s",       "mu", "law",
      "load_n_per_m", "radius_m", "temperature_c", "save",     "description", NULL};
  vl_query q;
  vl_query_defaults(&q);
  const char *path = NULL, *law = "constant", *description = NULL;
  PyObject *v_seq = NULL, *mu_seq = NULL;
  int do_save = 0;
  if (!PyArg_ParseTupleAndKeywords(args, kw, "sss|zOOsdddpz", kwlist, &q.compound, &q.surface,
                                   &q.fluid, &path, &v_seq, &mu_seq, &law, &q.load_n_per_m,
                                   &q.radius_m, &q.temperature_c, &do_save, &description))
    return NULL;
  if (v_seq == Py_None) v_seq = NULL;
  if (mu_seq == Py_None) mu_seq = NULL;
  q.at_temperature = !isnan(q.temperature_c);
  vl_db *db = vlpy_db(self);
  if (!db) return NULL;
  vl_error err = {{0}};
  vl_shear_law_kind kind;
  vl_status st = vl_shear_law_parse(law, &kind, &err);
  if (st != VL_OK) return vlpy_raise(st, &err);
  double *v = NULL, *mu = NULL;
  size_t n = 0;
  char fingerprint[VL_DB_FINGERPRINT_MAX] = "";
  if (measured_of(path, v_seq, mu_seq, &v, &mu, &n, fingerprint) < 0) return NULL;
  vl_calibration_sweep s = {0};
  vl_calibration_fit f = {0};
  PyObject *result = NULL;
  st = vl_calibration_sweep_run(db, &q, n, v, mu, &s, &err);
  if (st == VL_OK) st = vl_calibration_fit_law(&s, kind, &f, &err);
  if (st == VL_OK && do_save)
    st = save(db, &q, &s, &f, path ? path : "<python arrays>", fingerprint, description, &err);
  if (st == VL_OK) {
    result = fit_dict(&s, &f);
    if (result && vlpy_set(result, "saved", PyBool_FromLong(do_save))) Py_CLEAR(result);
  } else {
    vlpy_raise(st, &err);
  }
  vl_calibration_fit_free(&f);
  vl_calibration_sweep_free(&s);
  free(v);
  free(mu);
  return result;
}
