/* The automatic layout of a smooth film's cells (numerics.h says which
 * lengths set it and why). */
#include "numerics_plan.h"
#include "profile.h"
#include "rheology_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "contact_internal.h"

/* Upstream extent of the domain in inlet lengths L_h (Martin's film 0.07 %
 * short there), the downstream one, and the growth of the cells away from
 * the zones they resolve. */
#define INLET_LH 60.0
#define OUTLET_LH 2.0
#define GROWTH 0.1

/* The planner's lengths, all in a0. */
typedef struct {
  double a;      /* contact half-width */
  double xl, xr; /* its edges: -a, a for the cylinder; a lip's or a table's contact may lie
                  * off the tip x = 0 */
  double lh;     /* hydrodynamic inlet length sqrt(2 R h) */
  double s;      /* edge-zone width of a soft film (INFINITY: not soft) */
  double core;   /* upstream end of the zone of background cells */
  double x_lo, x_hi;
  double fine, back, inlet; /* cell widths: edges, background, far inlet */
} lengths;

/* Width of the cell wanted at x. */
static double width_at(const lengths *L, double x) {
  double w = L->back + GROWTH * fmax(0.0, -L->core - x);
  w = fmin(w, L->inlet);
  if (isfinite(L->s)) {
    double d = fmin(fabs(x - L->xr), fabs(x - L->xl));
    w = fmin(w, L->fine + GROWTH * d);
  }
  return w;
}

/* A lip's or a table's lengths (in a0) in place of the cylinder's: the
 * edges of its dry contact (profile.h), the inlet length as the distance
 * upstream of the tip over which the profile rises by the film h (sqrt(2 R
 * h) on the cylinder, shorter on a steep flank), and the scale delta (m) of
 * the gap's opening outside the edges, a f'(a) = a^2/R on the cylinder: the
 * half-width times the steeper edge slope. False for the cylinder (or when
 * the profile's contact cannot be found: the cylinder's lengths then). */
static bool profile_lengths(const vl_contact_config *base, double h, double a0, lengths *L,
                            double *delta) {
  if (!base->profile_x_m && !(base->lip_tip_radius_m > 0.0)) return false;
  vl_profile p;
  if (vl_profile_init(&p, base, NULL) != VL_OK) return false;
  double er = vl_prony_e0(&base->rubber) * vl_prony_reduced_factor(&base->rubber), c, a, sl, sr;
  bool ok = vl_profile_dry_contact(&p, base->load_n_per_m, er, &c, &a, NULL) == VL_OK;
  if (ok) {
    vl_profile_height(&p, c - a, &sl);
    vl_profile_height(&p, c + a, &sr);
    L->a = a / a0, L->xl = (c - a) / a0, L->xr = (c + a) / a0;
    L->lh = vl_profile_rise_length(&p, h) / a0;
    *delta = a * fmax(fabs(sl), fabs(sr));
  }
  vl_profile_free(&p);
  return ok;
}

static void plan_lengths(const vl_contact_config *base, double v0, const vl_plan_input *in,
                         double a0, lengths *L) {
  double R = base->radius_m;
  double h = in && in->film_m > 0.0 ? in->film_m : vl_contact_film_estimate(base, v0);
  double r = in && in->resolution > 0.0 ? in->resolution : 1.0;
  double delta;
  if (!profile_lengths(base, h, a0, L, &delta)) {
    L->a = in && in->half_width_m > 0.0 ? in->half_width_m / a0 : 1.0;
    L->xl = -L->a, L->xr = L->a;
    L->lh = sqrt(2.0 * R * h) / a0;
    delta = L->a * L->a * a0 * a0 / R; /* m */
  }
  double s = L->a * pow(3.0 * h / (4.0 * M_SQRT2 * delta), 2.0 / 3.0);
  L->s = s < L->a / 3.0 ? s : INFINITY; /* edge zones only where the film is thin */
  L->core = fmax(-L->xl, 3.0 * L->lh);
  double in_scale = in && in->inlet_scale > 0.0 ? in->inlet_scale : 1.0;
  L->x_lo = -in_scale * fmax(-L->xl + 2.0, -L->xl + INLET_LH * L->lh);
  L->x_hi = fmax(fmax(L->xr + 0.6, VL_WET_DOMAIN_MAX_A0), OUTLET_LH * L->lh);
  /* the pressure spreads over the larger of the contact and the inlet length */
  L->back = r * fmax(L->a / 60.0, L->lh / 80.0);
  L->fine = isfinite(L->s) ? fmin(L->back, r * L->s / 32.0) : L->back;
  L->inlet = fmax(L->back, r * (-L->x_lo) / 20.0);
}

/* Odd spans of base cells of width dx from x_lo until x_hi is covered;
 * returns the count (spans has room for `room`), 0 when it is exceeded. */
static size_t lay_out(const lengths *L, double dx, size_t *spans, size_t room, size_t *nv) {
  size_t n = 0, total = 0;
  double x = L->x_lo;
  while (x < L->x_hi) {
    if (n == room) return 0;
    double w = width_at(L, x + 0.5 * width_at(L, x));
    size_t m = 2 * (size_t)fmax(0.0, round(0.5 * (w / dx - 1.0))) + 1; /* the nearest odd */
    spans[n++] = m;
    total += m;
    x += (double)m * dx;
  }
  *nv = total;
  return n;
}

vl_status vl_plan_wet(const vl_contact_config *base, double v0, const vl_plan_input *in,
                      vl_plan *out, vl_error *err) {
  memset(out, 0, sizeof *out);
  if (!(base->eta_pa_s > 0.0) || base->roughness) {
    vl_error_set(err, "automatic layout: a smooth lubricated contact only");
    return VL_EINPUT;
  }
  double er = vl_prony_e0(&base->rubber) * vl_prony_reduced_factor(&base->rubber);
  double a0 = sqrt(4.0 * base->load_n_per_m * base->radius_m / (M_PI * er));
  lengths L;
  plan_lengths(base, v0, in, a0, &L);
  out->spans = malloc(VL_AUTO_MAX_CELLS * sizeof *out->spans);
  if (!out->spans) {
    vl_error_set(err, "out of memory for a cell layout");
    return VL_ENOMEM;
  }
  size_t n = 0, nv = 0;
  for (int tries = 0; tries < 40 && n == 0; tries++) {
    double dx = fmax(L.fine, (L.x_hi - L.x_lo) / VL_CONTACT_MAX_GRID_LAYOUT);
    if (dx > L.fine) out->capped = 1;
    n = lay_out(&L, dx, out->spans, VL_AUTO_MAX_CELLS, &nv);
    if (n == 0 || nv > VL_CONTACT_MAX_GRID_LAYOUT) { /* too many cells: all widths wider */
      n = 0;
      L.fine *= 1.25, L.back *= 1.25, L.inlet *= 1.25;
      out->capped = 1;
    }
  }
  if (n < VL_CONTACT_MIN_GRID) {
    vl_plan_free(out);
    vl_error_set(err, "automatic layout: no layout within %d cells", VL_AUTO_MAX_CELLS);
    return VL_EINPUT;
  }
  double dx = fmax(L.fine, (L.x_hi - L.x_lo) / VL_CONTACT_MAX_GRID_LAYOUT);
  out->cfg = *base;
  out->cfg.grid = nv, out->cfg.grid_growth = 1.0;
  out->cfg.cell_spans = out->spans, out->cfg.n_cells = n;
  out->cfg.x_min_a0 = L.x_lo, out->cfg.x_max_a0 = L.x_lo + (double)nv * dx;
  out->fine_a0 = L.fine, out->background_a0 = L.back, out->inlet_a0 = L.inlet;
  out->edge_zone_a0 = L.s, out->inlet_length_a0 = L.lh;
  return VL_OK;
}

void vl_plan_free(vl_plan *p) {
  if (!p) return;
  free(p->spans);
  p->spans = NULL;
  p->cfg.cell_spans = NULL;
}
