/* viscolube._core, the binding's private interface between its files:
 * core.c (module, errors, the Database type), materials.c (list and add),
 * solve.c (friction, scenes). Names are prefixed vlpy_ and hidden: the
 * module exports PyInit__core only. */
#ifndef VLPY_CORE_H
#define VLPY_CORE_H

#define PY_SSIZE_T_CLEAN
#include <Python.h>
/* One numpy C-API table for the files of the module: core.c imports it. */
#define NPY_NO_DEPRECATED_API NPY_1_7_API_VERSION
#define PY_ARRAY_UNIQUE_SYMBOL vlpy_numpy_api
#ifndef VLPY_IMPORT_NUMPY
#define NO_IMPORT_ARRAY
#endif
#include <numpy/arrayobject.h>

#include "viscolube.h"

#define VLPY_HIDDEN __attribute__((visibility("hidden")))

typedef struct {
  PyObject_HEAD vl_db *db;
} DatabaseObject;

/* Raises the viscolube._core exception of st (a subclass of Error) with
 * err's message (the status name when empty); returns NULL. */
VLPY_HIDDEN PyObject *vlpy_raise(vl_status st, const vl_error *err);
/* self's database, or NULL with an exception set when it was closed. */
VLPY_HIDDEN vl_db *vlpy_db(DatabaseObject *self);
/* A new 1-D float64 array holding v[0..n). */
VLPY_HIDDEN PyObject *vlpy_array(const double *v, size_t n);
/* d[key] = value (stolen; NULL fails); 0, or -1 with an exception. */
VLPY_HIDDEN int vlpy_set(PyObject *d, const char *key, PyObject *value);
VLPY_HIDDEN int vlpy_set_double(PyObject *d, const char *key, double v);
VLPY_HIDDEN int vlpy_set_text(PyObject *d, const char *key, const char *v); /* NULL: None */

/* materials.c */
VLPY_HIDDEN PyObject *vlpy_compounds(DatabaseObject *self, PyObject *unused);
VLPY_HIDDEN PyObject *vlpy_surfaces(DatabaseObject *self, PyObject *unused);
VLPY_HIDDEN PyObject *vlpy_fluids(DatabaseObject *self, PyObject *unused);
VLPY_HIDDEN PyObject *vlpy_add_compound(DatabaseObject *self, PyObject *args, PyObject *kw);
VLPY_HIDDEN PyObject *vlpy_add_surface(DatabaseObject *self, PyObject *args, PyObject *kw);
VLPY_HIDDEN PyObject *vlpy_add_fluid(DatabaseObject *self, PyObject *args, PyObject *kw);
VLPY_HIDDEN PyObject *vlpy_remove(DatabaseObject *self, PyObject *args);
#define VLPY_MATERIAL_METHODS                                                                      \
  {"compounds", (PyCFunction)vlpy_compounds, METH_NOARGS, "The compounds, as dicts."},             \
      {"surfaces", (PyCFunction)vlpy_surfaces, METH_NOARGS, "The surfaces, as dicts."},            \
      {"fluids", (PyCFunction)vlpy_fluids, METH_NOARGS, "The fluids, as dicts."},                  \
      {"add_compound", (PyCFunction)(void (*)(void))vlpy_add_compound,                             \
       METH_VARARGS | METH_KEYWORDS, "Add a compound (Prony series or measured file)."},           \
      {"add_surface", (PyCFunction)(void (*)(void))vlpy_add_surface, METH_VARARGS | METH_KEYWORDS, \
       "Add a surface (self-affine or PSD file)."},                                                \
      {"add_fluid", (PyCFunction)(void (*)(void))vlpy_add_fluid, METH_VARARGS | METH_KEYWORDS,     \
       "Add a Newtonian fluid."},                                                                  \
      {"remove", (PyCFunction)vlpy_remove, METH_VARARGS, "remove(kind, name)"},

/* solve.c */
VLPY_HIDDEN PyObject *vlpy_friction(DatabaseObject *self, PyObject *args, PyObject *kw);
VLPY_HIDDEN PyObject *vlpy_run_scene(DatabaseObject *self, PyObject *args, PyObject *kw);
VLPY_HIDDEN PyObject *vlpy_run_query(DatabaseObject *self, PyObject *args, PyObject *kw);
VLPY_HIDDEN PyObject *vlpy_check_query(DatabaseObject *self, PyObject *args, PyObject *kw);
/* pairs.c */
VLPY_HIDDEN PyObject *vlpy_calibrate(DatabaseObject *self, PyObject *args, PyObject *kw);

#define VLPY_SOLVE_METHODS                                                                         \
  {"calibrate", (PyCFunction)(void (*)(void))vlpy_calibrate, METH_VARARGS | METH_KEYWORDS,         \
   "Calibrate a pair's sigma_s law on a measured curve (calibrate.h)."},                           \
      {"friction", (PyCFunction)(void (*)(void))vlpy_friction, METH_VARARGS | METH_KEYWORDS,       \
       "One operating point (vl_query_friction)."},                                                \
      {"run_scene", (PyCFunction)(void (*)(void))vlpy_run_scene, METH_VARARGS | METH_KEYWORDS,     \
       "run_scene(text, path, seal=False): the curves (and fields) of a scene given as INI "       \
       "text; seal: both strokes of a seal, with its table."},                                     \
      {"run_query", (PyCFunction)(void (*)(void))vlpy_run_query, METH_VARARGS | METH_KEYWORDS,     \
       "The Stribeck sweep of a query (compare)."},                                                \
      {"check_query", (PyCFunction)(void (*)(void))vlpy_check_query, METH_VARARGS | METH_KEYWORDS, \
       "The checks of a query, before anything is computed."},

#endif
