/* viscolube: influence coefficients of the point contact (a ball on the
 * half-space): the surface displacement at the nodes of a uniform grid of
 * rectangular cells, each loaded with a uniform pressure, elastic and with
 * the steady-sliding Prony memory (docs/POINT_CONTACT.md section 3).
 *
 * Frame (docs/MODEL.md section 1): the rubber moves at +v0 along x, the
 * inlet is at x < 0. A point of the surface now at x was at x - s a time
 * s/v0 ago, so with the creep form of docs/MODEL.md section 2 the
 * displacement is
 *   w(x, y) = (Jr_inf/pi) \int dA' p(x', y') [ 1/r(x - x', y - y')
 *             + sum_k A_k \int_0^inf ds e^{-s/b_k}/b_k / r(x - s - x', y - y') ],
 * r(x, y) = sqrt(x^2 + y^2), b_k = v0 tau_k, Jr_inf = (1 - nu^2)/Einf.
 *
 * With p piecewise constant on cells hx x hy, the coefficient of a cell at
 * the offset (X, Y) = (d hx, e hy) from a node is
 *   T(d, e) = Kel(X, Y) + sum_k A_k F_k(X, Y),
 *   Kel(X, Y)  = \int\int_cell dA' / r(X - x', Y - y')          (Love: closed form)
 *   F_k(X, Y)  = \int_0^inf ds e^{-s/b_k}/b_k Kel(X - s, Y),
 * so that w(node) = (Jr_inf/pi) sum_cells T p. F_k is the displacement of
 * the cell's pressure filtered along x by the memory: inside the cell the
 * filtered load is 1 - e^{-u/b} (u from the cell's upstream edge), in the
 * m-th cell downstream (1 - r) r^{m-1} e^{-u/b} with r = e^{-hx/b}. So
 *   F(d) = Kel(d) - Kexp(d) + (1 - r) sum_{m>=1} r^{m-1} Kexp(d - m),
 * Kexp the displacement of a cell loaded with e^{-u/b}. The sum is a
 * recursive filter along d (S(d+1) = r S(d) + (1 - r) Kexp(d)) run from an
 * upstream extension of the grid, whose far end starts from the point-load
 * limit in closed form (exponential integrals). Kexp is its cell's first
 * two moments (the uniform and the linear load, both closed forms) and,
 * where the node is near the cell (|d|, e <= KERNEL2D_NEAR) and b is not
 * large against the cell, by quadrature: there the moments miss where the
 * boundary layer e^{-u/b} sits in the cell. Checked against adaptive
 * quadrature of the defining integral in tests/test_kernel2d.c. */
#ifndef VISCOLUBE_KERNEL2D_H
#define VISCOLUBE_KERNEL2D_H

#include <stddef.h>

#include "viscolube/status.h"

/* The most Prony terms a table takes (VL_PRONY_MAX_TERMS). */
#define VL_KERNEL2D_MAX_TERMS 128

/* Kel: \int\int dx' dy' / sqrt((x - x')^2 + (y - y')^2) over the rectangle
 * |x'| <= ax, |y'| <= ay (Love's closed form; a length). ax, ay > 0. */
double vl_kernel2d_rect(double x, double y, double ax, double ay);

/* The same with the linear load x'/(2 ax) (from -1/2 to 1/2 across the
 * cell): the displacement of a cell's first moment. */
double vl_kernel2d_rect_moment(double x, double y, double ax, double ay);

/* Kexp: the same with the load e^{-(x' + ax)/b} (1 at the upstream edge
 * x' = -ax, decaying downstream over b > 0), by Gauss-Legendre quadrature
 * across x' (the y' integral in closed form), accurate to about 1e-9 of
 * Kel(0, 0). */
double vl_kernel2d_rect_exp(double x, double y, double ax, double ay, double b);

/* The influence table of an nx x ny grid of cells hx x hy (a length unit of
 * the caller's; T is in the same unit): T(d, e) for the offsets
 * d = -(nx-1) .. nx-1 along x and e = 0 .. 2 ny - 1 across (a grid on
 * y >= 0 and its mirror image reach these). */
typedef struct {
  size_t nx, ny, ne; /* ne = 2 ny offsets across */
  double hx, hy;
  size_t ext;        /* cells of the upstream extension of the elastic tables */
  size_t nd;         /* offsets along x in the extended tables: ext + 2 nx - 1 */
  double *kel, *mom; /* Kel and the moment kernel over the extended offsets, [e][d] */
  double *coef;      /* T, [e][d] with d + nx - 1 (2 nx - 1 values per e) */
  double *work;      /* per term: the near-field corrections and the powers of r */
} vl_kernel2d;

/* Allocates k for the grid and fills its elastic tables (independent of
 * speed); coef is then Kel. VL_EINPUT for nx, ny < 1 or hx, hy not
 * positive and finite, VL_ENOMEM; on failure k holds nothing to free. */
vl_status vl_kernel2d_init(vl_kernel2d *k, size_t nx, size_t ny, double hx, double hy,
                           vl_error *err);

/* Fills k->coef for the Prony strengths A[0..n_terms-1] (finite, >= 0) and
 * memory lengths b[k] = v0 tau_k (>= 0, same unit as hx; 0: relaxed, the
 * term adds A_k Kel; +inf: glassy, the term adds nothing). n_terms <=
 * VL_KERNEL2D_MAX_TERMS. No allocation. */
void vl_kernel2d_fill(vl_kernel2d *k, const double *A, const double *b, size_t n_terms);

/* Releases k's arrays (k may be NULL; safe to call twice). */
void vl_kernel2d_free(vl_kernel2d *k);

/* T(d, e), |d| <= nx - 1, e < 2 ny. */
static inline double vl_kernel2d_at(const vl_kernel2d *k, long d, size_t e) {
  return k->coef[e * (2 * k->nx - 1) + (size_t)(d + (long)k->nx - 1)];
}

#endif
