/* The point contact (viscolube/point_contact.h, docs/POINT_CONTACT.md):
 * creation (scales, cells, allocation), the influence blocks at a speed,
 * and the discretised equations, their residual and dense Jacobian.
 * point_contact_solve.c holds the Newton (KINSOL) and the results.
 *
 * Unknowns y = (P_0 .. P_{n-1}, H0), the cells on y >= 0, cell
 * k = ix ny + iy. The rows:
 *   gap    U_k = H0 + f_k + sum_j M_kj P_j,
 *          M_kj = kfac [T(ix - jx, |iy - jy|) + T(ix - jx, iy + jy + 1)]
 *          (the cell j and its mirror image across y = 0; T of kernel2d.h);
 *   contact min(P_k, U_k) = 0 (the active-set Newton), or
 *          Fischer-Burmeister FB(P_k, U_k) (the fallback with line search);
 *   load   load_unit sum_k P_k - 1 = 0 (both halves carry W).
 * M is block Toeplitz along x: the ny x ny blocks B(dx), dx = ix - jx,
 * are all the solver stores; the gap is a sum of block products over the
 * columns that carry pressure (BLAS dgemm), and the Jacobian's columns are
 * columns of the blocks. */
#include "point_contact_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lapack_abi.h"
#include "rheology_internal.h"
#include "viscolube/contact.h"

/* Smoothing of the Fischer-Burmeister fallback (as the line contact's:
 * P U = 5e-19 at the edge, far below any tolerance). */
#define BALL_FB_EPS 1e-18

void vl_point_contact_config_defaults(vl_point_contact_config *cfg) {
  memset(cfg, 0, sizeof *cfg);
  cfg->cells_per_a0 = VL_BALL_CELLS_PER_A0;
  cfg->x_half_a0 = VL_BALL_DOMAIN_A0;
  cfg->y_max_a0 = VL_BALL_DOMAIN_A0;
  cfg->tolerance = VL_BALL_TOLERANCE;
  cfg->max_iterations = VL_NEWTON_MAX_ITERATIONS;
}

static bool positive(double v) { return v > 0.0 && isfinite(v); }

/* Cells along x (odd: a column on the axis) and across for cfg. */
static void cell_counts(const vl_point_contact_config *cfg, size_t *nx, size_t *ny) {
  double r = cfg->cells_per_a0;
  *nx = 2 * (size_t)ceil(cfg->x_half_a0 * r - 0.5) + 1;
  *ny = (size_t)ceil(cfg->y_max_a0 * r - 1e-9);
  if (*ny < 1) *ny = 1;
}

/* A lubricated or rough ball: a ball (its solver's symmetry of
 * revolution about z is assumed by the Hertz scales and the zones), its
 * cells within the bound. */
static vl_status check_wet(const vl_point_contact_config *cfg, vl_error *err) {
  if (cfg->radius_x_m != cfg->radius_y_m) {
    vl_error_set(err,
                 "point contact: a %s ellipsoid is not available yet (radius_x_m "
                 "%g differs from radius_y_m %g; a ball only)",
                 cfg->roughness ? "rough" : "lubricated", cfg->radius_x_m, cfg->radius_y_m);
    return VL_EINPUT;
  }
  if (cfg->roughness && cfg->eta_pa_s > 0.0 && cfg->flow_factors == VL_FLOW_FACTORS_PERSSON_EMT &&
      !cfg->flow_table) {
    vl_error_set(err, "point contact: flow_factors persson-emt needs the surface's flow_table");
    return VL_EINPUT;
  }
  size_t n = vl_point_contact_wet_cells(cfg);
  if (n > VL_BALL_MAX_CELLS) {
    vl_error_set(err,
                 "point contact: %zu cells on the lubricated ball's grid, more than %d "
                 "(fewer cells per a0)",
                 n, VL_BALL_MAX_CELLS);
    return VL_EINPUT;
  }
  return VL_OK;
}

/* VL_OK when cfg describes a contact the solver can build; else VL_EINPUT
 * naming the field. */
static vl_status check_config(const vl_point_contact_config *cfg, vl_error *err) {
  vl_status st = vl_prony_validate(&cfg->rubber, err);
  if (st != VL_OK) return st;
  const char *bad = !positive(cfg->radius_x_m)   ? "radius_x_m"
                    : !positive(cfg->radius_y_m) ? "radius_y_m"
                    : !positive(cfg->load_n)     ? "load_n"
                    : !positive(cfg->x_half_a0)  ? "x_half_a0"
                    : !positive(cfg->y_max_a0)   ? "y_max_a0"
                    : !positive(cfg->tolerance)  ? "tolerance"
                                                 : NULL;
  if (bad) {
    vl_error_set(err, "point contact: %s must be positive and finite", bad);
    return VL_EINPUT;
  }
  if (!(cfg->sigma_s_pa >= 0.0 && isfinite(cfg->sigma_s_pa))) {
    vl_error_set(err, "point contact: sigma_s_pa must be finite and >= 0 (got %g)",
                 cfg->sigma_s_pa);
    return VL_EINPUT;
  }
  if (!(cfg->cells_per_a0 >= VL_BALL_MIN_CELLS_PER_A0 && isfinite(cfg->cells_per_a0))) {
    vl_error_set(err, "point contact: cells_per_a0 must be at least %d (got %g)",
                 VL_BALL_MIN_CELLS_PER_A0, cfg->cells_per_a0);
    return VL_EINPUT;
  }
  if (cfg->max_iterations < 0) {
    vl_error_set(err, "point contact: max_iterations must not be negative");
    return VL_EINPUT;
  }
  if (!(cfg->eta_pa_s >= 0.0 && isfinite(cfg->eta_pa_s))) {
    vl_error_set(err, "point contact: eta_pa_s must be finite and >= 0 (got %g)", cfg->eta_pa_s);
    return VL_EINPUT;
  }
  if (vl_point_contact_is_graded(cfg)) return check_wet(cfg, err);
  size_t nx, ny;
  if (cfg->x_half_a0 * cfg->cells_per_a0 > 1e5 || cfg->y_max_a0 * cfg->cells_per_a0 > 1e5) {
    vl_error_set(err, "point contact: domain too large for its cells");
    return VL_EINPUT;
  }
  cell_counts(cfg, &nx, &ny);
  if (nx * ny > VL_BALL_MAX_CELLS) {
    vl_error_set(err,
                 "point contact: %zu x %zu = %zu cells, more than %d (fewer cells per a0 or a "
                 "smaller domain)",
                 nx, ny, nx * ny, VL_BALL_MAX_CELLS);
    return VL_EINPUT;
  }
  return VL_OK;
}

/* Hertz scales, cells and their geometry (point_contact.h). */
static void set_scales(vl_point_contact *c) {
  const vl_point_contact_config *cfg = &c->cfg;
  double red = vl_prony_reduced_factor(&cfg->rubber);
  c->er_inf = cfg->rubber.e_inf_pa * red;
  c->er0 = vl_prony_e0(&cfg->rubber) * red;
  c->re = sqrt(cfg->radius_x_m * cfg->radius_y_m);
  c->a0 = cbrt(3.0 * cfg->load_n * c->re / (4.0 * c->er0));
  c->p0 = 3.0 * cfg->load_n / (2.0 * M_PI * c->a0 * c->a0);
  c->uscale = c->a0 * c->a0 / c->re;
  c->gx = c->re / cfg->radius_x_m, c->gy = c->re / cfg->radius_y_m;
  c->geometry = cfg->radius_x_m == cfg->radius_y_m ? VL_GEOMETRY_BALL : VL_GEOMETRY_ELLIPSOID;
  c->kfac = 2.0 / (M_PI * M_PI) * c->er0 / c->er_inf;
  cell_counts(cfg, &c->nx, &c->ny);
  c->n = c->nx * c->ny, c->nunk = c->n + 1, c->i0 = (c->nx - 1) / 2;
  c->h = 1.0 / cfg->cells_per_a0;
  c->load_unit = 3.0 * c->h * c->h / M_PI; /* 2 h^2 sum P p0 a0^2 / W */
}

static vl_status allocate(vl_point_contact *c, vl_error *err) {
  size_t n = c->n, nb = (2 * c->nx - 1) * c->ny * c->ny, nk = c->cfg.rubber.n_terms;
  c->X = malloc(7 * n * sizeof *c->X);
  c->B = malloc(nb * sizeof *c->B);
  c->A = malloc((2 * nk + 1) * sizeof *c->A);
  if (!c->X || !c->B || !c->A) {
    vl_error_set(err, "out of memory for a %zu-cell point contact", n);
    return VL_ENOMEM;
  }
  c->Y = c->X + n, c->f = c->X + 2 * n, c->P = c->X + 3 * n, c->U = c->X + 4 * n;
  c->dp = c->X + 5 * n, c->du = c->X + 6 * n;
  c->b = c->A + nk;
  c->nk = nk;
  for (size_t k = 0; k < nk; k++)
    c->A[k] = c->cfg.rubber.A[k];
  return vl_kernel2d_init(&c->kern, c->nx, c->ny, c->h, c->h, err);
}

static void place_cells(vl_point_contact *c) {
  for (size_t ix = 0; ix < c->nx; ix++)
    for (size_t iy = 0; iy < c->ny; iy++) {
      size_t k = ix * c->ny + iy;
      c->X[k] = ((double)ix - (double)c->i0) * c->h;
      c->Y[k] = ((double)iy + 0.5) * c->h;
      c->f[k] = 0.5 * (c->gx * c->X[k] * c->X[k] + c->gy * c->Y[k] * c->Y[k]);
    }
}

vl_status vl_point_contact_build(const vl_point_contact_config *cfg, vl_point_contact **out,
                                 vl_error *err) {
  *out = NULL;
  vl_status st = check_config(cfg, err);
  if (st != VL_OK) return st;
  vl_point_contact *c = calloc(1, sizeof *c);
  if (!c) {
    vl_error_set(err, "out of memory for a point contact");
    return VL_ENOMEM;
  }
  c->cfg = *cfg;
  if (c->cfg.max_iterations == 0) c->cfg.max_iterations = VL_NEWTON_MAX_ITERATIONS;
  c->v0 = NAN, c->v_state = NAN;
  set_scales(c);
  c->graded = vl_point_contact_is_graded(cfg);
  if (c->graded) { /* its own solver and cells: point_contact_wet.c */
    *out = c;
    return VL_OK;
  }
  st = allocate(c, err);
  if (st != VL_OK) {
    vl_point_contact_release(c);
    return st;
  }
  place_cells(c);
  *out = c;
  return VL_OK;
}

void vl_point_contact_release(vl_point_contact *c) {
  if (!c) return;
  vl_kernel2d_free(&c->kern);
  free(c->X), free(c->B), free(c->A);
  vl_point_ehl_map_free(&c->map);
  free(c);
}

/* The blocks B(dx) from the kernel's table (the cell and its mirror). */
static void build_blocks(vl_point_contact *c) {
  size_t ny = c->ny, ny2 = ny * ny;
  long n1 = (long)c->nx - 1;
  for (long dx = -n1; dx <= n1; dx++) {
    double *blk = c->B + (size_t)(dx + n1) * ny2;
    for (size_t jy = 0; jy < ny; jy++)
      for (size_t iy = 0; iy < ny; iy++) {
        size_t direct = iy > jy ? iy - jy : jy - iy, mirror = iy + jy + 1;
        blk[jy * ny + iy] =
            c->kfac * (vl_kernel2d_at(&c->kern, dx, direct) + vl_kernel2d_at(&c->kern, dx, mirror));
      }
  }
}

void vl_point_contact_set_speed(vl_point_contact *c, double v0) {
  if (v0 == c->v0 || (c->nk == 0 && c->kernel_builds > 0)) {
    c->v0 = v0;
    return;
  }
  double t0 = vl_point_contact_now_s();
  for (size_t k = 0; k < c->nk; k++)
    c->b[k] = v0 * c->cfg.rubber.tau_s[k] / c->a0;
  vl_kernel2d_fill(&c->kern, c->A, c->b, c->nk);
  build_blocks(c);
  c->v0 = v0;
  c->kernel_builds++;
  c->timing.kernels++;
  c->timing.t_kernel_s += vl_point_contact_now_s() - t0;
}

double vl_point_contact_influence(const vl_point_contact *c, size_t i, size_t j) {
  size_t ny = c->ny, ix = i / ny, iy = i % ny, jx = j / ny, jy = j % ny;
  long dx = (long)ix - (long)jx + (long)c->nx - 1;
  return c->B[(size_t)dx * ny * ny + jy * ny + iy];
}

void vl_point_contact_reset(vl_point_contact *c) {
  if (c->graded) return; /* each lubricated solve starts afresh */
  double *y = N_VGetArrayPointer(c->y), sum = 0.0;
  for (size_t k = 0; k < c->n; k++) {
    double rho2 = 2.0 * c->f[k]; /* (gx X^2 + gy Y^2): 1 at the Hertz edge of a ball */
    y[k] = rho2 < 1.0 ? sqrt(1.0 - rho2) : 0.0;
    sum += y[k];
  }
  for (size_t k = 0; k < c->n && sum > 0.0; k++) /* the load row satisfied */
    y[k] /= c->load_unit * sum;
  y[c->n] = -1.0; /* Hertz's approach a0^2/Re, relaxed */
  c->v_state = NAN;
}

/* ---- the equations ---------------------------------------------------- */

/* P and U of y: U = H0 + f + M P, the block products over the columns that
 * carry pressure. */
void vl_point_contact_eval(vl_point_contact *c, const double *y) {
  size_t n = c->n, ny = c->ny, nx = c->nx, ny2 = ny * ny;
  memcpy(c->P, y, n * sizeof *c->P);
  long jlo = (long)nx, jhi = -1;
  for (size_t k = 0; k < n; k++)
    if (c->P[k] != 0.0) {
      long jx = (long)(k / ny);
      jlo = jx < jlo ? jx : jlo, jhi = jx;
    }
  for (size_t k = 0; k < n; k++)
    c->U[k] = y[n] + c->f[k];
  c->jlo = (size_t)jlo, c->jhi = (size_t)jhi;
  int m = (int)ny;
  double one = 1.0;
  for (long dx = -(long)nx + 1; jhi >= 0 && dx <= (long)nx - 1; dx++) {
    long ilo = jlo + dx > 0 ? jlo + dx : 0, ihi = jhi + dx < (long)nx ? jhi + dx : (long)nx - 1;
    if (ihi < ilo) continue;
    int cols = (int)(ihi - ilo + 1);
    const double *blk = c->B + (size_t)(dx + (long)nx - 1) * ny2;
    dgemm_("N", "N", &m, &cols, &m, &one, blk, &m, c->P + (size_t)(ilo - dx) * ny, &m, &one,
           c->U + (size_t)ilo * ny, &m, 1, 1);
  }
}

/* Row k of the hard contact and its derivatives (min, FB, or the warm set). */
static double contact_row(const vl_point_contact *c, size_t k, double *dp, double *du) {
  double p = c->P[k], u = c->U[k];
  if (c->warm_set) {
    bool in = p > 0.0;
    *dp = in ? 0.0 : 1.0, *du = in ? 1.0 : 0.0;
    return in ? u : p;
  }
  if (c->min_rows) {
    bool gap = u < p;
    *dp = gap ? 0.0 : 1.0, *du = gap ? 1.0 : 0.0;
    return gap ? u : p;
  }
  double r = sqrt(p * p + u * u + BALL_FB_EPS);
  *dp = 1.0 - p / r, *du = 1.0 - u / r;
  return p + u - r;
}

int vl_point_contact_residual(vl_point_contact *c, const double *y, double *f) {
  vl_point_contact_eval(c, y);
  double sum = 0.0;
  for (size_t k = 0; k < c->n; k++) {
    f[k] = contact_row(c, k, &c->dp[k], &c->du[k]);
    sum += c->P[k];
  }
  f[c->n] = c->load_unit * sum - 1.0;
  for (size_t k = 0; k <= c->n; k++)
    if (!isfinite(f[k])) return 1; /* recoverable: KINSOL shortens the step */
  return 0;
}

/* The dense Jacobian at the state of the last residual (the rows' dp, du),
 * column-major nunk x nunk. With gap_rows_only, the rows outside the span
 * of the gap rows get their diagonal only: the reduced solver reads no
 * more of them (linsol_reduced.h). */
void vl_point_contact_jacobian(vl_point_contact *c, const double *y, double *Jd) {
  size_t n = c->n, ny = c->ny, ny2 = ny * ny, ld = c->nunk;
  vl_point_contact_eval(c, y);
  for (size_t k = 0; k < n; k++)
    contact_row(c, k, &c->dp[k], &c->du[k]);
  c->warm_set = false; /* only the first step of a solve takes the state's set */
  size_t lo = 0, hi = n;
  if (c->gap_rows_only) {
    while (lo < n && c->du[lo] == 0.0)
      lo++;
    while (hi > lo && c->du[hi - 1] == 0.0)
      hi--;
  }
  size_t ixlo = lo / ny, ixhi = hi > 0 ? (hi - 1) / ny : 0;
  for (size_t j = 0; j < n; j++) {
    double *col = Jd + j * ld;
    size_t jx = j / ny, jy = j % ny;
    for (size_t ix = ixlo; ix <= ixhi && lo < hi; ix++) {
      const double *bc = c->B + (size_t)((long)ix - (long)jx + (long)c->nx - 1) * ny2 + jy * ny;
      double *cc = col + ix * ny;
      const double *du = c->du + ix * ny;
      for (size_t iy = 0; iy < ny; iy++) /* + 0.0: a zero du gives +0 */
        cc[iy] = du[iy] * bc[iy] + 0.0;
    }
    col[j] = (j >= ixlo * ny && j < (ixhi + 1) * ny && lo < hi ? col[j] : 0.0) + c->dp[j];
    col[n] = c->load_unit;
  }
  double *col = Jd + n * ld; /* d/dH0 */
  for (size_t k = 0; k < n; k++)
    col[k] = c->du[k];
  col[n] = 0.0;
}
