/* One operating point of the contact (dry or wet): creation and release of
 * the solver (contact.h). Sets the scales of docs/MODEL.md section 9 (the relaxed
 * Hertz half-width a0 and peak pressure p0, a0^2/R for the separation), the
 * unknowns (contact, fluid, rigid approach), the rolling number of section
 * 8, and builds the parts the other contact_*.c files work on
 * (contact_internal.h lists them). */
#include "contact_internal.h"
#include "contact_private.h"
#include "flattening_internal.h"
#include "persson_internal.h"
#include "profile.h"
#include "rheology_internal.h"

#include <kinsol/kinsol.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Which unknowns the contact has, and where they sit in y. A smooth wet
 * contact keeps a positive film (Reynolds' equation carries any load at any
 * v0 > 0): no contact unknowns, pressure-only system. */
static void set_unknowns(vl_contact *c) {
  c->nf = c->wet ? c->n : 0;
  c->nc = c->wet && !c->rough ? 0 : c->n;
  c->of = c->nc;
  c->ih = c->nc + c->nf;
  c->nunk = c->nc + c->nf + 1;
}

/* The scales of the dimensionless unknowns (the configuration check made
 * sure they exist) and the rolling number. */
static void set_scales(vl_contact *c) {
  const vl_contact_config *cfg = &c->cfg;
  double red = vl_prony_reduced_factor(&cfg->rubber);
  c->er_ref = vl_prony_e0(&cfg->rubber) * red;
  /* a moving counter-surface: the rubber at rest deforms statically, with
   * the relaxed modulus and no memory (docs/MODEL.md section 11) */
  c->nk = cfg->moving == VL_MOVING_COUNTERFACE ? 0 : cfg->rubber.n_terms;
  c->er_inf = c->nk == cfg->rubber.n_terms ? cfg->rubber.e_inf_pa * red : c->er_ref;
  c->a0 = sqrt(4.0 * cfg->load_n_per_m * cfg->radius_m / (M_PI * c->er_ref));
  c->p0 = 2.0 * cfg->load_n_per_m / (M_PI * c->a0);
  c->uscale = c->a0 * c->a0 / cfg->radius_m;
  /* w/(a0^2/R) = -(Er_ref/(pi Er_inf)) sum_j P_j Khat_ij, Khat in units of a0. */
  c->kfac = c->er_ref / (M_PI * c->er_inf);
  c->v0 = NAN;
  c->u_ref = 1.0;
  c->kappa = 1.0;
  if (c->wet && c->rough && c->nk > 0) {
    /* Q = v_GT / v_ML: v_GT = (loss-peak frequency) x (relaxed Hertz width
     * 2 a0), v_ML = 10 h_rms^2 Er0 / (R eta) (docs/MODEL.md section 8) */
    double wpk = 0.0;
    if (vl_prony_loss_peak(&cfg->rubber, &wpk, NULL, NULL) == VL_OK) {
      double v_ml = 10.0 * c->hrms * c->hrms * c->er_ref / (cfg->radius_m * cfg->eta_pa_s);
      c->q_rolling = wpk * 2.0 * c->a0 / v_ml;
    }
  }
}

/* The arrays of the state on the n cells, and the Prony strengths. No
 * allocation happens inside the Newton loop afterwards. */
static vl_status alloc_state(vl_contact *c, vl_error *err) {
  size_t n = c->n, nt = c->nk;
  c->A = malloc((nt ? nt : 1) * sizeof *c->A);
  c->beta = calloc(nt ? nt : 1, sizeof *c->beta);
  c->M = calloc(n * n, sizeof *c->M);
  c->P = calloc(n, sizeof *c->P);
  c->q = calloc(n, sizeof *c->q);
  c->U = calloc(n, sizeof *c->U);
  c->dPdU = calloc(n, sizeof *c->dPdU);
  c->F = calloc(n, sizeof *c->F);
  c->D = calloc(n, sizeof *c->D);
  c->theta = calloc(n, sizeof *c->theta);
  c->g = calloc(4 * n, sizeof *c->g);
  c->Jf = calloc(n + 1, sizeof *c->Jf);
  c->rw = calloc(n, sizeof *c->rw);
  if (!c->A || !c->beta || !c->M || !c->P || !c->q || !c->U || !c->dPdU || !c->F || !c->D ||
      !c->theta || !c->g || !c->Jf || !c->rw)
    return vl_contact_nomem(c, err);
  if (!c->rough && !c->wet) {
    c->fb_work = malloc((2 * n + c->nunk) * sizeof *c->fb_work);
    if (!c->fb_work) return vl_contact_nomem(c, err);
    c->state_y = c->fb_work + 2 * n;
    c->state_kernel = (size_t)-1; /* no state yet */
    c->min_rows = true;
    if (!c->span && !(c->mcoef = malloc((2 * n - 1) * sizeof *c->mcoef)))
      return vl_contact_nomem(c, err);
  }
  c->m_kernel = (size_t)-1; /* not built yet */
  if (c->rough && c->wet) {
    c->film_work = malloc((2 * c->nunk + 3 * n) * sizeof *c->film_work);
    if (!c->film_work) return vl_contact_nomem(c, err);
  }
  if (c->flattening) {
    c->sf = malloc(2 * n * sizeof *c->sf);
    if (!c->sf) return vl_contact_nomem(c, err);
    c->dsf = c->sf + n;
    for (size_t i = 0; i < n; i++)
      c->sf[i] = 1.0, c->dsf[i] = 0.0;
  }
  if (c->cfg.p_inlet_pa > 0.0 || c->cfg.p_outlet_pa > 0.0) {
    c->pamb = malloc(n * sizeof *c->pamb);
    if (!c->pamb) return vl_contact_nomem(c, err);
    for (size_t i = 0; i < n; i++)
      c->pamb[i] = (c->xi[i] < 0.0 ? c->cfg.p_inlet_pa : c->cfg.p_outlet_pa) / c->p0;
  }
  c->dg = c->g + n;
  c->cf = c->g + 2 * n;
  c->dcf = c->g + 3 * n;
  for (size_t k = 0; k < nt; k++)
    c->A[k] = c->cfg.rubber.A[k];
  return VL_OK;
}

/* The profile of cfg at the nodes (contact.h; profile.h): c->fprof, c->sprof;
 * none for the cylinder's parabola. A table is copied (c->ptab): cfg points
 * to the copy, which the helper contacts made later read. */
static vl_status build_profile(vl_contact *c, vl_error *err) {
  const vl_contact_config *cfg = &c->cfg;
  if (!cfg->profile_x_m && !(cfg->lip_tip_radius_m > 0.0)) return VL_OK;
  size_t m = cfg->profile_points, n = c->n;
  c->fprof = malloc(2 * n * sizeof *c->fprof);
  if (!c->fprof) return vl_contact_nomem(c, err);
  c->sprof = c->fprof + n;
  if (cfg->profile_x_m) {
    c->ptab = malloc(2 * m * sizeof *c->ptab);
    if (!c->ptab) return vl_contact_nomem(c, err);
    memcpy(c->ptab, cfg->profile_x_m, m * sizeof *c->ptab);
    memcpy(c->ptab + m, cfg->profile_z_m, m * sizeof *c->ptab);
    c->cfg.profile_x_m = c->ptab, c->cfg.profile_z_m = c->ptab + m;
  }
  vl_profile p;
  vl_status st = vl_profile_init(&p, cfg, err);
  if (st != VL_OK) return st;
  for (size_t i = 0; i < n; i++)
    c->fprof[i] = vl_profile_height(&p, c->xi[i] * c->a0, &c->sprof[i]) / c->uscale;
  vl_profile_free(&p);
  return VL_OK;
}

/* An imposed static pressure p_s (contact.h; docs/MODEL.md section 14):
 * the profile on which the dry smooth contact carries p_s, from the
 * contact's own influence coefficients (so that on its grid P = p_s
 * solves the dry contact): f_i = -(M p_s)_i where p_s > 0, continued
 * straight beyond the outermost loaded nodes with the slope of their last
 * two; f' by differences. Needs the elastic kernel (vl_contact_set_speed
 * done). The table is copied (c->stab) for the helpers made later. */
static vl_status build_static_profile(vl_contact *c, vl_error *err) {
  const vl_contact_config *cfg = &c->cfg;
  if (!cfg->static_x_m) return VL_OK;
  size_t m = cfg->static_points, n = c->n;
  c->stab = malloc(2 * m * sizeof *c->stab);
  c->fprof = malloc(3 * n * sizeof *c->fprof);
  if (!c->stab || !c->fprof) return vl_contact_nomem(c, err);
  memcpy(c->stab, cfg->static_x_m, m * sizeof *c->stab);
  memcpy(c->stab + m, cfg->static_p_pa, m * sizeof *c->stab);
  c->cfg.static_x_m = c->stab, c->cfg.static_p_pa = c->stab + m;
  c->sprof = c->fprof + n;
  double *ps = c->fprof + 2 * n;
  vl_static_pressure t;
  vl_status st = vl_static_pressure_init(&t, cfg, err);
  if (st != VL_OK) return st;
  size_t lo = n, hi = 0;
  for (size_t i = 0; i < n; i++) {
    ps[i] = vl_static_pressure_at(&t, c->xi[i] * c->a0) / c->p0;
    if (ps[i] > 0.0) lo = i < lo ? i : lo, hi = i;
  }
  vl_static_pressure_free(&t);
  if (lo + 1 >= hi) {
    vl_error_set(err, "a static pressure spans fewer than 3 cells of the grid");
    return VL_EINPUT;
  }
  for (size_t i = lo; i <= hi; i++) {
    double w = 0.0;
    for (size_t j = 0; j < n; j++)
      w += c->M[i * n + j] * ps[j];
    c->fprof[i] = -w;
  }
  double sl = (c->fprof[lo + 1] - c->fprof[lo]) / (c->xi[lo + 1] - c->xi[lo]);
  double sr = (c->fprof[hi] - c->fprof[hi - 1]) / (c->xi[hi] - c->xi[hi - 1]);
  for (size_t i = 0; i < lo; i++)
    c->fprof[i] = c->fprof[lo] + sl * (c->xi[i] - c->xi[lo]);
  for (size_t i = hi + 1; i < n; i++)
    c->fprof[i] = c->fprof[hi] + sr * (c->xi[i] - c->xi[hi]);
  double fmin = INFINITY;
  for (size_t i = 0; i < n; i++)
    fmin = fmin < c->fprof[i] ? fmin : c->fprof[i];
  for (size_t i = 0; i < n; i++)
    c->fprof[i] -= fmin; /* the tip at 0: h0 takes any constant */
  /* the slope (m/m): f is in a0^2/R over x in a0 */
  for (size_t i = 0; i < n; i++) {
    size_t a = i > 0 ? i - 1 : 0, b = i + 1 < n ? i + 1 : n - 1;
    c->sprof[i] = (c->fprof[b] - c->fprof[a]) / (c->xi[b] - c->xi[a]) * c->uscale / c->a0;
  }
  return VL_OK;
}

size_t vl_contact_merge_cells(const size_t *span, size_t n, size_t *out) {
  size_t m = 0, k = 0;
  for (; k + 3 <= n; k += 3) /* odd + odd + odd: odd, its node a uniform node */
    out[m++] = span[k] + span[k + 1] + span[k + 2];
  for (; k < n; k++) /* one or two cells left, kept */
    out[m++] = span[k];
  return m;
}

/* The helper contacts of a smooth film's fresh starts: a half-size grid,
 * or on the coarsest level of a viscoelastic film the dry contact
 * (contact_start.c). */
static vl_status create_helpers(vl_contact *c, vl_error *err) {
  if (c->nc != 0) return VL_OK;
  if (c->n >= 2 * VL_COARSE_MIN) {
    vl_contact_config coarse = c->cfg;
    if (!c->span) { /* uniform (a layout of single cells included) */
      coarse.cell_spans = NULL;
      coarse.grid = c->n / 2;
      return vl_contact_create(&coarse, &c->coarse, err);
    }
    size_t *spans = malloc(c->n * sizeof *spans);
    if (!spans) return vl_contact_nomem(c, err);
    coarse.n_cells = vl_contact_merge_cells(c->span, c->n, spans);
    coarse.cell_spans = spans;
    vl_status st = vl_contact_create(&coarse, &c->coarse, err);
    free(spans);
    return st;
  }
  if (c->nk > 0) {
    vl_contact_config dry = c->cfg;
    dry.eta_pa_s = 0.0;
    vl_status st = vl_contact_create(&dry, &c->dry, err);
    if (st == VL_OK) c->dry->min_rows = false; /* the smooth film's starts stay as they were */
    return st;
  }
  return VL_OK;
}

/* The contact's own viscous-flattening evaluator, at the contact's viscosity
 * (the coarse-grid helper builds its own: no evaluator is shared). */
static vl_status create_flattening(vl_contact *c, vl_error *err) {
  if (!c->cfg.flattening) return VL_OK;
  vl_status st =
      vl_flattening_create(c->cfg.flattening, c->cfg.flattening_psd, &c->flattening, err);
  if (st != VL_OK) return st;
  return vl_flattening_set_viscosity(c->flattening, c->cfg.eta_pa_s, err);
}

vl_status vl_contact_create(const vl_contact_config *cfg, vl_contact **out, vl_error *err) {
  *out = NULL;
  vl_status st = vl_contact_config_check(cfg, err);
  if (st != VL_OK) return st;
  vl_contact *c = calloc(1, sizeof *c);
  if (!c) {
    vl_error_set(err, "out of memory for a %zu-node contact solver", cfg->grid);
    return VL_ENOMEM;
  }
  c->cfg = *cfg;
  if (c->cfg.max_iterations <= 0) c->cfg.max_iterations = VL_NEWTON_MAX_ITERATIONS;
  c->rough = cfg->roughness != NULL;
  c->wet = cfg->eta_pa_s > 0.0;
  /* flow factors only make sense for a rough surface */
  if (!c->rough) c->cfg.flow_factors = VL_FLOW_FACTORS_SMOOTH;
  c->hrms = c->rough ? vl_persson_hrms(cfg->roughness) : 0.0;
  if ((st = create_flattening(c, err)) != VL_OK) goto fail;
  if ((st = vl_contact_grid_init(c, err)) != VL_OK) goto fail;
  set_unknowns(c);
  set_scales(c);
  if ((st = alloc_state(c, err)) != VL_OK) goto fail;
  if ((st = build_profile(c, err)) != VL_OK) goto fail;
  if ((st = vl_contact_kernel_init(c, err)) != VL_OK) goto fail;
  if ((st = vl_contact_kinsol_init(c, err)) != VL_OK) goto fail;
  if ((st = create_helpers(c, err)) != VL_OK) goto fail;
  vl_contact_set_speed(c, 0.0);
  if ((st = build_static_profile(c, err)) != VL_OK) goto fail;
  vl_contact_reset(c);
  *out = c;
  return VL_OK;
fail: /* each step has said why in err */
  vl_contact_free(c);
  return st;
}

void vl_contact_free(vl_contact *c) {
  if (!c) return;
  vl_contact_free(c->coarse);
  vl_contact_free(c->estimator);
  vl_contact_free(c->dry);
  vl_flattening_free(c->flattening);
  if (c->kmem) KINFree(&c->kmem);
  if (c->LS) SUNLinSolFree(c->LS);
  if (c->J) SUNMatDestroy(c->J);
  if (c->ones) N_VDestroy(c->ones);
  if (c->fwork) N_VDestroy(c->fwork);
  if (c->y_saved) N_VDestroy(c->y_saved);
  if (c->y_outer) N_VDestroy(c->y_outer);
  if (c->y_min) N_VDestroy(c->y_min);
  if (c->y) N_VDestroy(c->y);
  if (c->ctx) SUNContext_Free(&c->ctx);
  vl_toeplitz_free(&c->kern);
  free(c->xi);
  free(c->wc);
  free(c->hf);
  free(c->first);
  free(c->span);
  free(c->psum);
  free(c->A);
  free(c->beta);
  free(c->M);
  free(c->mcoef);
  free(c->P);
  free(c->q);
  free(c->U);
  free(c->dPdU);
  free(c->F);
  free(c->D);
  free(c->theta);
  free(c->g);
  free(c->Jf);
  free(c->rw);
  free(c->sf);
  free(c->pamb);
  free(c->fprof);
  free(c->ptab);
  free(c->stab);
  free(c->film_work);
  free(c->fb_work);
  free(c);
}

size_t vl_contact_grid(const vl_contact *c) { return c->n; }
double vl_contact_a0(const vl_contact *c) { return c->a0; }
double vl_contact_p0(const vl_contact *c) { return c->p0; }

void vl_contact_numerics_of(const vl_contact *c, vl_contact_numerics_used *out) {
  const vl_contact_config *cfg = &c->cfg;
  static const char *const solvers[] = {"lapack", "sundials", "schur"};
  *out = (vl_contact_numerics_used){
      cfg->grid,
      c->n,
      cfg->grid_growth,
      cfg->x_min_a0,
      cfg->x_max_a0,
      cfg->tolerance,
      cfg->max_iterations > 0 ? cfg->max_iterations : VL_NEWTON_MAX_ITERATIONS,
      (unsigned)cfg->linear_solver < 3 ? solvers[cfg->linear_solver] : "unknown"};
}

/* The viscosity of the contact and of its smooth-film helper (the coarse
 * level or the film that starts a rough one), which solve at the same. */
vl_status vl_contact_set_viscosity(vl_contact *c, double eta_pa_s, vl_error *err) {
  if (!c->wet || !(eta_pa_s > 0.0 && isfinite(eta_pa_s))) {
    vl_error_set(err, "viscosity: a wet contact takes a finite eta > 0 (got %g Pa s%s)", eta_pa_s,
                 c->wet ? "" : ", contact created dry");
    return VL_EINPUT;
  }
  if (c->q_rolling > 0.0) c->q_rolling *= eta_pa_s / c->cfg.eta_pa_s; /* Q ~ eta */
  c->cfg.eta_pa_s = eta_pa_s;
  /* epsilon_f depends on eta v0: its table is rebuilt (eta validated above) */
  if (c->flattening) vl_flattening_set_viscosity(c->flattening, eta_pa_s, NULL);
  if (c->coarse) vl_contact_set_viscosity(c->coarse, eta_pa_s, NULL);
  return VL_OK;
}

double vl_contact_viscosity(const vl_contact *c) { return c->cfg.eta_pa_s; }
