/* viscolube._core: the Python binding of libviscolube, on the public API
 * only (viscolube.h). It converts arguments and results and nothing else:
 * every check, default and computation is the library's, so Python and the
 * command line answer alike. The pleasant API is python/viscolube/__init__.py.
 *
 * Results come back as plain Python objects (dicts, lists) and numpy float
 * arrays; a value that is not defined (a failed point's physics, v0_eta of
 * a dry scene) is NaN there, where the CSV has an empty cell. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define VLPY_IMPORT_NUMPY /* this file imports the numpy C API */
#include "core.h"

/* ---- errors ------------------------------------------------------------ */

/* viscolube._core.Error and one subclass per status, by vl_status. */
static PyObject *error_base;
static PyObject *error_by_status[VL_EINTERNAL + 1];

/* Raises the exception of st with the library's message; returns NULL. */
PyObject *vlpy_raise(vl_status st, const vl_error *err) {
  int k = (int)st;
  PyObject *cls = k > 0 && k <= VL_EINTERNAL ? error_by_status[k] : error_base;
  const char *msg = err && err->msg[0] ? err->msg : vl_status_name(st);
  /* a file name in the message need not be UTF-8 */
  PyObject *text = PyUnicode_DecodeUTF8(msg, (Py_ssize_t)strlen(msg), "replace");
  PyObject *exc = text ? PyObject_CallOneArg(cls, text) : NULL;
  PyObject *code = exc ? PyLong_FromLong(k) : NULL;
  if (code && PyObject_SetAttrString(exc, "status", code) == 0 &&
      PyObject_SetAttrString(exc, "message", text) == 0)
    PyErr_SetObject(cls, exc);
  Py_XDECREF(code);
  Py_XDECREF(exc);
  Py_XDECREF(text);
  return NULL;
}

static int make_errors(PyObject *m) {
  static const char *names[VL_EINTERNAL + 1] = {
      [VL_EINPUT] = "InputError",          [VL_ENOMEM] = "OutOfMemoryError",
      [VL_ENOTFOUND] = "NotFoundError",    [VL_EEXIST] = "ExistsError",
      [VL_EDB] = "DatabaseError",          [VL_EIO] = "FileError",
      [VL_ENOCONV] = "NoConvergenceError", [VL_EINTERNAL] = "InternalError"};
  error_base = PyErr_NewExceptionWithDoc(
      "viscolube.Error", "A failure of libviscolube: .status (its vl_status code), .message.", NULL,
      NULL);
  if (!error_base || PyModule_AddObjectRef(m, "Error", error_base) < 0) return -1;
  for (int k = 1; k <= VL_EINTERNAL; k++) {
    char full[64];
    snprintf(full, sizeof full, "viscolube.%s", names[k]);
    error_by_status[k] = PyErr_NewException(full, error_base, NULL);
    if (!error_by_status[k] || PyModule_AddObjectRef(m, names[k], error_by_status[k]) < 0)
      return -1;
  }
  return 0;
}

/* ---- small converters ---------------------------------------------------- */

/* A float array copied from v[0..n). */
PyObject *vlpy_array(const double *v, size_t n) {
  npy_intp dims[1] = {(npy_intp)n};
  PyObject *a = PyArray_SimpleNew(1, dims, NPY_DOUBLE);
  if (a && n) memcpy(PyArray_DATA((PyArrayObject *)a), v, n * sizeof *v);
  return a;
}

/* d[key] = value, stealing value; -1 on failure (value NULL included). */
int vlpy_set(PyObject *d, const char *key, PyObject *value) {
  if (!value) return -1;
  int rc = PyDict_SetItemString(d, key, value);
  Py_DECREF(value);
  return rc;
}

int vlpy_set_double(PyObject *d, const char *key, double v) {
  return vlpy_set(d, key, PyFloat_FromDouble(v));
}

int vlpy_set_text(PyObject *d, const char *key, const char *v) {
  if (!v) return PyDict_SetItemString(d, key, Py_None);
  return vlpy_set(d, key, PyUnicode_FromString(v));
}

/* ---- the Database type ---------------------------------------------------- */

static int db_init(DatabaseObject *self, PyObject *args, PyObject *kw) {
  static char *kwlist[] = {"path", NULL};
  const char *path = NULL;
  if (!PyArg_ParseTupleAndKeywords(args, kw, "|z", kwlist, &path)) return -1;
  vl_db_close(self->db);
  self->db = NULL;
  vl_error err = {{0}};
  vl_status st = vl_db_open(path, &self->db, &err);
  if (st != VL_OK) {
    vlpy_raise(st, &err);
    return -1;
  }
  return 0;
}

static void db_dealloc(DatabaseObject *self) {
  vl_db_close(self->db);
  Py_TYPE(self)->tp_free((PyObject *)self);
}

/* self's open database, or NULL with an exception set. */
vl_db *vlpy_db(DatabaseObject *self) {
  if (!self->db) {
    vl_error err;
    vl_error_set(&err, "the database is closed");
    vlpy_raise(VL_EDB, &err);
  }
  return self->db;
}

static PyObject *db_close(DatabaseObject *self, PyObject *unused) {
  (void)unused;
  vl_db_close(self->db);
  self->db = NULL;
  Py_RETURN_NONE;
}

static PyObject *db_path(DatabaseObject *self, PyObject *unused) {
  (void)unused;
  vl_db *db = vlpy_db(self);
  return db ? PyUnicode_FromString(vl_db_path(db)) : NULL;
}

static PyObject *db_readonly(DatabaseObject *self, PyObject *unused) {
  (void)unused;
  vl_db *db = vlpy_db(self);
  return db ? PyBool_FromLong(vl_db_readonly(db)) : NULL;
}

static PyMethodDef db_methods[] = {
    {"close", (PyCFunction)db_close, METH_NOARGS, "Close the database (idempotent)."},
    {"path", (PyCFunction)db_path, METH_NOARGS, "The file the database was opened from."},
    {"readonly", (PyCFunction)db_readonly, METH_NOARGS, "True if opened read-only."},
    VLPY_MATERIAL_METHODS VLPY_SOLVE_METHODS{NULL, NULL, 0, NULL}};

static PyTypeObject DatabaseType = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "viscolube._core.Database",
    .tp_basicsize = sizeof(DatabaseObject),
    .tp_flags = Py_TPFLAGS_DEFAULT | Py_TPFLAGS_BASETYPE,
    .tp_doc = "Database(path=None): the material database (None: the default one).",
    .tp_new = PyType_GenericNew,
    .tp_init = (initproc)db_init,
    .tp_dealloc = (destructor)db_dealloc,
    .tp_methods = db_methods,
};

/* ---- module -------------------------------------------------------------- */

static PyObject *curve_columns(PyObject *self, PyObject *unused) {
  (void)self, (void)unused;
  PyObject *l = PyList_New(0);
  for (size_t c = 0; l && vl_curve_columns[c]; c++) {
    PyObject *s = PyUnicode_FromString(vl_curve_columns[c]);
    if (!s || PyList_Append(l, s) < 0) Py_CLEAR(l);
    Py_XDECREF(s);
  }
  return l;
}

static PyObject *default_path(PyObject *self, PyObject *unused) {
  (void)self, (void)unused;
  char buf[4096];
  vl_error err = {{0}};
  vl_status st = vl_db_default_path(buf, sizeof buf, &err);
  return st == VL_OK ? PyUnicode_FromString(buf) : vlpy_raise(st, &err);
}

static PyMethodDef module_methods[] = {
    {"curve_columns", curve_columns, METH_NOARGS, "The columns of curve.csv, in order."},
    {"default_path", default_path, METH_NOARGS, "The default database path (nothing created)."},
    {NULL, NULL, 0, NULL}};

static struct PyModuleDef core_module = {PyModuleDef_HEAD_INIT,
                                         "viscolube._core",
                                         "libviscolube, bound (see the package viscolube).",
                                         -1,
                                         module_methods,
                                         NULL,
                                         NULL,
                                         NULL,
                                         NULL};

PyMODINIT_FUNC PyInit__core(void);
PyMODINIT_FUNC PyInit__core(void) {
  import_array();
  if (PyType_Ready(&DatabaseType) < 0) return NULL;
  PyObject *m = PyModule_Create(&core_module);
  if (!m) return NULL;
  if (make_errors(m) < 0 || PyModule_AddObjectRef(m, "Database", (PyObject *)&DatabaseType) < 0 ||
      PyModule_AddStringConstant(m, "PROJECT_VERSION", VL_PY_VERSION) < 0) {
    Py_DECREF(m);
    return NULL;
  }
  return m;
}
