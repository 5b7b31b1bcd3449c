/* The grid and the influence coefficients (docs/MODEL.md section 3): the cells
 * (uniform, or merged into a graded inlet), and at each speed the dense
 * influence matrix of the surface displacement w(x) from the Toeplitz
 * coefficients of the uniform grid (kernel.h, Appendix A), with the
 * asperity state |Er(wH)|, aH of that speed (docs/MODEL.md section 4). */
#include "contact_internal.h"
#include "rheology_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Cells of the grid (vl_contact_config.grid_growth): nv uniform cells on
 * [x_min, x_max]; upstream of -start_a0 they are merged, from the
 * contact outwards, into runs of odd length growing by `growth` (never
 * shrinking), the last run taking the rest, between one and two of the
 * previous runs (one uniform cell more when the rest is even: the domain
 * then starts one uniform cell earlier). Writes span[] left to right (room
 * for nv + 1 cells) and the uniform cells covered in *nv_out. Returns the
 * number of cells. */
static size_t grid_layout(size_t nv, double x_min, double x_max, double growth, double start_a0,
                          size_t *span, size_t *nv_out) {
  double dx = (x_max - x_min) / (double)nv, start = -start_a0;
  size_t ig = 0;
  if (growth > 1.0 && x_min < start) ig = (size_t)fmin(floor((start - x_min) / dx), (double)nv);
  size_t cells = 0, rem = ig, prev = 1, covered = 0;
  double t = 1.0;
  /* the merged runs, from the contact outwards (reversed below) */
  while (rem > 0) {
    t *= growth;
    size_t m = 2 * (size_t)round((t - 1.0) / 2.0) + 1;
    if (m < prev) m = prev;
    if (rem < 2 * m) m = rem % 2 ? rem : rem + 1; /* the last run: m .. 2m */
    span[cells++] = m;
    covered += m;
    rem -= m < rem ? m : rem;
    prev = m;
  }
  for (size_t i = 0; i < cells / 2; i++) {
    size_t tmp = span[i];
    span[i] = span[cells - 1 - i], span[cells - 1 - i] = tmp;
  }
  for (size_t i = cells; i < cells + nv - ig; i++)
    span[i] = 1;
  *nv_out = covered + (nv - ig);
  return cells + nv - ig;
}

/* Node positions, cell widths and face distances of the n cells. */
static void place_cells(vl_contact *c) {
  const vl_contact_config *cfg = &c->cfg;
  size_t n = c->n;
  if (c->span) {
    /* the uniform grid extends the covered cells to the left of the domain's
     * end when the last run came out one cell longer (grid_layout) */
    double x0 = cfg->x_max_a0 - (double)c->nv * c->dxi;
    size_t pos = 0;
    for (size_t i = 0; i < n; i++) {
      c->first[i] = pos;
      c->wc[i] = (double)c->span[i] * c->dxi;
      c->xi[i] = x0 + ((double)(pos + c->span[i] / 2) + 0.5) * c->dxi;
      pos += c->span[i];
    }
  } else {
    for (size_t i = 0; i < n; i++) {
      c->xi[i] = cfg->x_min_a0 + ((double)i + 0.5) * c->dxi;
      c->wc[i] = c->dxi;
    }
  }
  c->hf[0] = 0.5 * c->wc[0], c->hf[n] = 0.5 * c->wc[n - 1];
  for (size_t f = 1; f < n; f++)
    c->hf[f] = c->xi[f] - c->xi[f - 1];
}

vl_status vl_contact_grid_init(vl_contact *c, vl_error *err) {
  const vl_contact_config *cfg = &c->cfg;
  size_t room = cfg->cell_spans ? cfg->n_cells : cfg->grid + 1;
  c->span = malloc(room * sizeof *c->span);
  if (!c->span) return vl_contact_nomem(c, err);
  if (cfg->cell_spans) { /* checked: odd spans summing to the grid */
    memcpy(c->span, cfg->cell_spans, cfg->n_cells * sizeof *c->span);
    c->n = cfg->n_cells, c->nv = cfg->grid;
  } else {
    double start = cfg->grade_start_a0 > 0.0 ? cfg->grade_start_a0 : VL_GRADE_START_A0;
    c->n = grid_layout(cfg->grid, cfg->x_min_a0, cfg->x_max_a0, cfg->grid_growth, start, c->span,
                       &c->nv);
  }
  if (c->n == cfg->grid && c->nv == cfg->grid) { /* nothing merged: the uniform grid */
    free(c->span);
    c->span = NULL;
  }
  if (c->n > VL_CONTACT_MAX_CELLS) {
    vl_error_set(err,
                 "grid %zu with growth %g gives %zu cells (at most %d: the matrices are dense)",
                 cfg->grid, cfg->grid_growth, c->n, VL_CONTACT_MAX_CELLS);
    return VL_EINPUT;
  }
  size_t n = c->n;
  c->dxi = (cfg->x_max_a0 - cfg->x_min_a0) / (double)cfg->grid;
  /* zeroed, though place_cells writes every entry: GCC cannot tell */
  c->xi = calloc(n, sizeof *c->xi);
  c->wc = calloc(n, sizeof *c->wc);
  c->hf = calloc(n + 1, sizeof *c->hf);
  if (!c->xi || !c->wc || !c->hf) return vl_contact_nomem(c, err);
  if (c->span) {
    c->first = malloc(n * sizeof *c->first);
    c->psum = malloc(2 * c->nv * sizeof *c->psum);
    if (!c->first || !c->psum) return vl_contact_nomem(c, err);
  }
  place_cells(c);
  return VL_OK;
}

vl_status vl_contact_kernel_init(vl_contact *c, vl_error *err) {
  return vl_toeplitz_build(&c->kern, c->nv, c->dxi, c->A, c->beta, c->nk, err);
}

/* The influence matrix M from the uniform grid's Toeplitz coefficients: on a
 * uniform grid they are M itself; a graded grid's cell is a run of uniform
 * cells whose node is a uniform node, so its coefficient is the sum of the
 * run's, taken from prefix sums (O(n^2) whatever the cell sizes; a direct
 * evaluation would cost n^2 exponential integrals per Prony term and speed).
 * Single cells take the coefficient itself, so the uniform part of a graded
 * grid has exactly the uniform grid's coefficients. */
static void graded_influence(vl_contact *c) {
  size_t n = c->n;
  if (!c->span) {
    for (size_t i = 0; i < n; i++)
      for (size_t j = 0; j < n; j++)
        c->M[i * n + j] = -c->kfac * vl_toeplitz_at(&c->kern, i, j);
    return;
  }
  size_t nv = c->nv;
  const double *coef = c->kern.coef;
  double *S = c->psum;
  S[0] = 0.0;
  for (size_t k = 0; k + 1 < 2 * nv; k++)
    S[k + 1] = S[k] + coef[k];
  for (size_t i = 0; i < n; i++) {
    size_t ci = c->first[i] + c->span[i] / 2;
    for (size_t j = 0; j < n; j++) {
      /* offsets ci - l of the run l = a .. a + m - 1 are coefficients
       * lo .. hi (offset d is coefficient d + nv - 1) */
      size_t a = c->first[j], m = c->span[j];
      size_t hi = ci + nv - 1 - a, lo = ci + nv - a - m;
      c->M[i * n + j] = -c->kfac * (m == 1 ? coef[hi] : S[hi + 1] - S[lo]);
    }
  }
}

const double *vl_contact_influence_matrix(vl_contact *c) {
  if (c->m_kernel != c->kernel_builds) {
    graded_influence(c);
    c->m_kernel = c->kernel_builds;
  }
  return c->M;
}

/* Rebuilds the influence matrix for speed v0 (viscoelastic kernels only):
 * M itself, or on a contact with mcoef its coefficients, M then waiting
 * for a reader (the Fischer-Burmeister fallback, the dry helper of a
 * smooth film, tests): the active-set Newton sums the gap from the
 * coefficients, and writing M (n^2 values) cost 0.12 ms of a dry point's
 * 2 ms at N 400. */
void vl_contact_set_speed(vl_contact *c, double v0) {
  if (c->v0 == v0) return;
  c->v0 = v0;
  vl_asperity_state(&c->cfg.rubber, c->cfg.load_n_per_m, c->cfg.radius_m, v0, &c->e_abs, &c->a_h,
                    &c->omega_h);
  c->sfac = c->e_abs / c->p0;
  /* v0 was validated (finite): set_speed cannot fail */
  if (c->flattening) vl_flattening_set_speed(c->flattening, v0, NULL);
  size_t nt = c->nk;
  if (nt == 0 && c->kernel_ready) return; /* elastic: one kernel for all speeds */
  double t0 = vl_contact_now_s();
  c->kernel_ready = true;
  for (size_t k = 0; k < nt; k++)
    c->beta[k] = v0 * c->cfg.rubber.tau_s[k] / c->a0;
  vl_toeplitz_refill(&c->kern, c->A, c->beta, nt);
  c->kernel_builds++;
  if (c->mcoef) {
    double mk = -c->kfac;
    for (size_t k = 0; k + 1 < 2 * c->n; k++)
      c->mcoef[k] = mk * c->kern.coef[k];
  } else {
    vl_contact_influence_matrix(c);
  }
  c->timing.t_kernel_s += vl_contact_now_s() - t0;
  c->timing.kernels++;
}
