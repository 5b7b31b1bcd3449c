/* Tests of the point contact's influence coefficients (src/mechanics/kernel2d.h).
 *
 * References are independent of the closed forms and of the filter:
 *  - Love's rectangle, its moment and the exponential cell against nested
 *    adaptive GSL quadrature (the inner integral across y' in closed form,
 *    asinh, the outer one by QAGS split at the singular point);
 *  - the memory coefficients F(X, Y) = \int_0^inf e^{-s/b}/b Kel(X - s, Y) ds
 *    against adaptive quadrature of that integral (Kel from the closed form,
 *    itself checked first), for memory lengths from 1e-3 to 1e4 cells;
 *  - the relaxed and glassy limits.
 * Errors are measured against Kel(0, 0), the largest coefficient (a
 * displacement is a sum of coefficients times pressures of order one). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
/* cmocka.h needs the four above first (own block: not re-sorted) */
#include <cmocka.h>

#include "vl_test_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include "kernel2d.h"

#define WS 4000

/* ---------- nested quadrature of a cell's load over 1/r ---------- */

typedef struct {
  double x, y, ax, ay, b; /* the node, the half cell, the load's decay (0: uniform) */
  int weight;             /* 0 uniform, 1 linear x'/(2 ax), 2 exponential e^{-(x'+ax)/b} */
} cell_par;

/* \int_{-ay}^{ay} dy' / sqrt(X^2 + (y - y')^2) = asinh((y+ay)/|X|) - asinh((y-ay)/|X|) */
static double across(double X, double y, double ay) {
  double a = fabs(X);
  return asinh((y + ay) / a) - asinh((y - ay) / a);
}

static double f_cell(double xp, void *p) {
  const cell_par *c = p;
  double X = c->x - xp;
  if (X == 0.0) return 0.0; /* a point of measure zero (log singular) */
  double w = c->weight == 0 ? 1.0 : c->weight == 1 ? xp / (2.0 * c->ax) : exp(-(xp + c->ax) / c->b);
  return w * across(X, c->y, c->ay);
}

static double cell_quad(double x, double y, double ax, double ay, int weight, double b) {
  gsl_set_error_handler_off();
  gsl_integration_workspace *ws = gsl_integration_workspace_alloc(WS);
  cell_par par = {x, y, ax, ay, b, weight};
  gsl_function f = {f_cell, &par};
  double r = 0.0, e, r2 = 0.0;
  int st;
  if (x > -ax && x < ax && fabs(y) < ay) { /* log singular at x' = x: split there */
    st = gsl_integration_qags(&f, -ax, x, 0.0, 1e-13, WS, ws, &r, &e);
    assert_true(st == GSL_SUCCESS || st == GSL_EROUND);
    st = gsl_integration_qags(&f, x, ax, 0.0, 1e-13, WS, ws, &r2, &e);
  } else if (weight == 2 && b < 0.05 * ax) { /* the boundary layer at the upstream edge */
    st = gsl_integration_qags(&f, -ax, -ax + 40.0 * b, 0.0, 1e-13, WS, ws, &r, &e);
    assert_true(st == GSL_SUCCESS || st == GSL_EROUND);
    st = gsl_integration_qags(&f, -ax + 40.0 * b, ax, 1e-300, 1e-13, WS, ws, &r2, &e);
  } else {
    st = gsl_integration_qags(&f, -ax, ax, 0.0, 1e-13, WS, ws, &r, &e);
  }
  assert_true(st == GSL_SUCCESS || st == GSL_EROUND);
  gsl_integration_workspace_free(ws);
  return r + r2;
}

/* Love's rectangle and its moment against the nested quadrature, inside,
 * on and far from the cell, on square and oblong cells. */
static void test_rect_closed_forms(void **state) {
  (void)state;
  const double pts[][2] = {{0, 0},      {0.2, 0.1}, {0.5, 0.0}, {1, 0},     {-1, 0.3},   {0, 1},
                           {2.5, -1.5}, {-7, 3},    {30, 2},    {-120, 45}, {0.49, 0.51}};
  const double cells[][2] = {{0.5, 0.5}, {0.5, 0.2}, {0.3, 0.7}};
  double worst = 0.0, worst_m = 0.0;
  for (size_t c = 0; c < 3; c++)
    for (size_t i = 0; i < sizeof pts / sizeof pts[0]; i++) {
      double ax = cells[c][0], ay = cells[c][1], x = pts[i][0], y = pts[i][1];
      double scale = vl_kernel2d_rect(0, 0, ax, ay);
      double k = vl_kernel2d_rect(x, y, ax, ay), q = cell_quad(x, y, ax, ay, 0, 0);
      double m = vl_kernel2d_rect_moment(x, y, ax, ay), qm = cell_quad(x, y, ax, ay, 1, 0);
      worst = fmax(worst, fabs(k - q) / scale);
      worst_m = fmax(worst_m, fabs(m - qm) / scale);
    }
  printf("Love rectangle: worst %.2e, moment: worst %.2e (of Kel(0,0))\n", worst, worst_m);
  assert_true(worst < 1e-12);
  /* the moment far away is the difference of corner terms of size R^2: its
   * rounding, eps (R/h)^2, is 1e-11 of Kel(0, 0) at 100 cells (and enters
   * the solver only times the filter's weights, far below its tolerance) */
  assert_true(worst_m < 1e-10);
  /* the centre of a square cell of side 1: 4 asinh(1) */
  assert_true(fabs(vl_kernel2d_rect(0, 0, 0.5, 0.5) - 4.0 * asinh(1.0)) < 1e-14);
}

/* The exponential cell (Gauss-Legendre in the decay variable) against
 * the nested adaptive quadrature, for boundary layers from 1e-3 to 1e3
 * cells, at the singular point and around it. */
static void test_rect_exp(void **state) {
  (void)state;
  const double pts[][2] = {{0, 0}, {0.3, 0}, {-0.4, 0}, {1, 0}, {-1, 0}, {0, 1}, {2, 1}, {-3, 2}};
  const double bs[] = {1e-3, 0.02, 0.3, 1.0, 3.0, 30.0, 1e3};
  double scale = vl_kernel2d_rect(0, 0, 0.5, 0.5), worst = 0.0;
  for (size_t j = 0; j < sizeof bs / sizeof bs[0]; j++)
    for (size_t i = 0; i < sizeof pts / sizeof pts[0]; i++) {
      double x = pts[i][0], y = pts[i][1];
      double k = vl_kernel2d_rect_exp(x, y, 0.5, 0.5, bs[j]),
             q = cell_quad(x, y, 0.5, 0.5, 2, bs[j]);
      worst = fmax(worst, fabs(k - q) / scale);
    }
  printf("exponential cell: worst %.2e of Kel(0,0)\n", worst);
  assert_true(worst < 1e-9);
  /* b -> inf: the uniform cell */
  assert_true(fabs(vl_kernel2d_rect_exp(0, 0, 0.5, 0.5, 1e12) - scale) < 1e-9 * scale);
}

/* ---------- the memory coefficients against the defining integral ---------- */

typedef struct {
  double X, Y, b, ax, ay;
} mem_par;

static double f_mem(double s, void *p) {
  const mem_par *m = p;
  return exp(-s / m->b) / m->b * vl_kernel2d_rect(m->X - s, m->Y, m->ax, m->ay);
}

/* \int_0^inf e^{-s/b}/b Kel(X - s, Y) ds by QAGP (break points where Kel's
 * derivative is log singular: s = X -+ ax) and QAGIU beyond. */
static double mem_quad(double X, double Y, double b, double ax, double ay) {
  gsl_integration_workspace *ws = gsl_integration_workspace_alloc(WS);
  mem_par par = {X, Y, b, ax, ay};
  gsl_function f = {f_mem, &par};
  double pts[6];
  size_t np = 0;
  pts[np++] = 0.0;
  double cut = fmax(X + 4.0 * ax, 0.0) + 60.0 * b;
  if (X - ax > 0.0) pts[np++] = X - ax;
  if (X + ax > 0.0) pts[np++] = X + ax;
  if (b < 0.1 * ax && 50.0 * b < pts[np - 1] && np == 1) pts[np++] = 50.0 * b;
  pts[np++] = cut;
  double r = 0.0, e, tail = 0.0;
  int st = gsl_integration_qagp(&f, pts, np, 1e-300, 1e-12, WS, ws, &r, &e);
  assert_true(st == GSL_SUCCESS || st == GSL_EROUND);
  st = gsl_integration_qagiu(&f, cut, 1e-300, 1e-10, WS, ws, &tail, &e);
  assert_true(st == GSL_SUCCESS || st == GSL_EROUND);
  gsl_integration_workspace_free(ws);
  return r + tail;
}

/* A 21 x 10 grid of square cells of 1/8: T = Kel + F for one term of
 * strength 1; F at offsets near and far, upstream and downstream, across,
 * for memory lengths 1e-3 ... 1e4 cells. The moments' error, corrected
 * near the cell, is at most 6e-6 of Kel(0, 0) (measured; bound 2e-5). */
static void test_memory_coefficients(void **state) {
  (void)state;
  size_t nx = 21, ny = 10;
  double h = 0.125, one = 1.0;
  vl_kernel2d k;
  vl_error err;
  assert_int_equal(vl_kernel2d_init(&k, nx, ny, h, h, &err), VL_OK);
  double scale = vl_kernel2d_at(&k, 0, 0);
  const long offs[][2] = {{0, 0},  {1, 0},   {-1, 0}, {0, 1},   {3, 2},   {-5, 1}, {7, 0},
                          {10, 0}, {-15, 3}, {2, 15}, {20, 19}, {-20, 0}, {8, 1},  {-2, 6}};
  const double betas[] = {1e-3, 0.05, 0.3, 1.0, 3.0, 10.0, 30.0, 100.0, 1e4};
  double worst_all = 0.0;
  for (size_t j = 0; j < sizeof betas / sizeof betas[0]; j++) {
    double b = betas[j] * h, worst = 0.0;
    vl_kernel2d_fill(&k, &one, &b, 1);
    for (size_t i = 0; i < sizeof offs / sizeof offs[0]; i++) {
      long d = offs[i][0];
      size_t e = (size_t)offs[i][1];
      double F =
          vl_kernel2d_at(&k, d, e) - vl_kernel2d_rect((double)d * h, (double)e * h, h / 2, h / 2);
      double q = mem_quad((double)d * h, (double)e * h, b, h / 2, h / 2);
      worst = fmax(worst, fabs(F - q) / scale);
    }
    printf("memory b = %-6g cells: worst %.2e of Kel(0,0)\n", betas[j], worst);
    worst_all = fmax(worst_all, worst);
  }
  assert_true(worst_all < 2e-5);
  vl_kernel2d_free(&k);
}

/* b -> 0: the term adds A Kel (relaxed); b = inf: nothing (glassy); a very
 * long memory adds a nearly constant field (absorbed by the rigid
 * approach): its variation over the grid is of order (L/b) log(b/L). */
static void test_memory_limits(void **state) {
  (void)state;
  size_t nx = 15, ny = 7;
  double h = 0.1, A = 4.0;
  vl_kernel2d k;
  vl_error err;
  assert_int_equal(vl_kernel2d_init(&k, nx, ny, h, h, &err), VL_OK);
  double scale = vl_kernel2d_at(&k, 0, 0), worst0 = 0.0, worst_inf = 0.0;
  double b = 0.0;
  vl_kernel2d_fill(&k, &A, &b, 1);
  for (long d = -(long)nx + 1; d < (long)nx; d++)
    for (size_t e = 0; e < 2 * ny; e++)
      worst0 = fmax(worst0,
                    fabs(vl_kernel2d_at(&k, d, e) -
                         (1 + A) * vl_kernel2d_rect((double)d * h, (double)e * h, h / 2, h / 2)));
  b = INFINITY;
  vl_kernel2d_fill(&k, &A, &b, 1);
  for (long d = -(long)nx + 1; d < (long)nx; d++)
    for (size_t e = 0; e < 2 * ny; e++)
      worst_inf =
          fmax(worst_inf, fabs(vl_kernel2d_at(&k, d, e) -
                               vl_kernel2d_rect((double)d * h, (double)e * h, h / 2, h / 2)));
  assert_true(worst0 < 1e-14 * scale);
  assert_true(worst_inf == 0.0);
  /* b = 1e6 grid lengths: F varies by ~ (L/b) log(b/L) = 1e-5 over the grid */
  b = 1e6 * (double)nx * h;
  vl_kernel2d_fill(&k, &A, &b, 1);
  double lo = INFINITY, hi = -INFINITY;
  for (long d = -(long)nx + 1; d < (long)nx; d++)
    for (size_t e = 0; e < 2 * ny; e++) {
      double F = (vl_kernel2d_at(&k, d, e) -
                  vl_kernel2d_rect((double)d * h, (double)e * h, h / 2, h / 2)) /
                 A;
      lo = fmin(lo, F), hi = fmax(hi, F);
    }
  printf("glassy limit: F spans %.2e of Kel(0,0) over the grid\n", (hi - lo) / scale);
  assert_true(hi - lo < 1e-4 * scale && lo >= 0.0);
  vl_kernel2d_free(&k);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_rect_closed_forms),
      cmocka_unit_test(test_rect_exp),
      cmocka_unit_test(test_memory_coefficients),
      cmocka_unit_test(test_memory_limits),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
