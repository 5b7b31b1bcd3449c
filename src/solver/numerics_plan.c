/* The automatic layout of a smooth film's cells (numerics.h says which
 * lengths set it and why). */
#include "numerics_plan.h"
#include "persson_internal.h"
#include "profile.h"
#include "rheology_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "contact_internal.h"
#include "viscolube/persson.h"

/* Upstream extent of the domain in inlet lengths L_h (Martin's film 0.07 %
 * short there), the downstream one, and the growth of the cells away from
 * the zones they resolve. */
#define INLET_LH 60.0
#define OUTLET_LH 2.0
#define GROWTH 0.1

/* Rough films (docs/NUMERICS.md section 11). The film the edge zones are
 * planned for is at least ROUGH_FILM_FLOOR h_rms: the films of the wiper
 * on glass reach 0.16 h_rms at 1 mm/s on fine cells, while a collapsed
 * solution (u_min = 0) must not plan cells for a zero film. Edge cells of
 * s/ROUGH_EDGE_CELLS; background a/ROUGH_BACKGROUND (the validated a0/30 of
 * section 9); the inlet's cells grow by ROUGH_INLET_GROWTH a cell (the
 * graded inlet's 1.05) to at most a twentieth of the inlet. */
#define ROUGH_FILM_FLOOR 0.1
#define ROUGH_EDGE_CELLS 8.0
#define ROUGH_BACKGROUND 30.0
#define ROUGH_INLET_GROWTH 0.05
/* A rough film is planned only where its edge zone s is narrower than
 * 1/ROUGH_PLAN_EDGE of a standard cell (a0/30), and kept planned while it
 * is narrower than 1/ROUGH_KEEP_EDGE of one (a sweep that moves between
 * layouts can change branch: the O-ring at 1e-4 m/s gave mu 0.183 on the
 * standard cells continued from planned ones, 0.171 continued from its
 * own). The wiper's films (s a0/250 at 1 mm/s, a0/72 at 0.05 m/s) are
 * planned; the O-ring's (s a0/75 at 1e-5 m/s, on the standard cells
 * within 1.4 % of the reference) are not. Planned, the background is a/ROUGH_BACKGROUND_PLANNED:
 * on the wiper at 1 mm/s a background of a0/30 with edge cells of s/8 still
 * found the collapsed solution (mu 0.483, u_min 0), a0/120 the film (mu
 * 0.098, u_min 1.8 nm, 91 % of the load on the fluid). */
#define ROUGH_PLAN_EDGE 4.0
#define ROUGH_KEEP_EDGE 2.0
#define ROUGH_BACKGROUND_PLANNED 120.0

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
  double inlet_growth;      /* of the cells upstream of core, per cell */
  bool planned;             /* a rough film: edge zones below the standard cells */
} lengths;

/* Width of the cell wanted at x. */
static double width_at(const lengths *L, double x) {
  double w = L->back + L->inlet_growth * fmax(0.0, -L->core - x);
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
  bool rough = base->roughness != NULL;
  if (rough) h = fmax(h, vl_plan_rough_film_floor(base));
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
  double out_scale = in && in->outlet_scale > 0.0 ? in->outlet_scale : 1.0;
  L->x_lo = -in_scale * fmax(-L->xl + 2.0, -L->xl + INLET_LH * L->lh);
  L->x_hi = out_scale * fmax(fmax(L->xr + 0.6, VL_WET_DOMAIN_MAX_A0), OUTLET_LH * L->lh);
  /* the pressure spreads over the larger of the contact and the inlet length */
  L->back = r * fmax(L->a / 60.0, L->lh / 80.0);
  L->fine = isfinite(L->s) ? fmin(L->back, r * L->s / 32.0) : L->back;
  L->inlet_growth = GROWTH;
  L->planned = false;
  if (rough) { /* at least the validated rough inlet and its cells */
    L->x_lo = fmin(L->x_lo, in_scale * VL_WET_ROUGH_DOMAIN_MIN_A0);
    /* edge zones narrower than ROUGH_PLAN_EDGE standard cells: planned, with
     * the finer background (else the standard cells, L->planned false) */
    double edge = in && in->planned ? ROUGH_KEEP_EDGE : ROUGH_PLAN_EDGE;
    L->planned = L->s < L->a / (edge * ROUGH_BACKGROUND) && in &&
                 in->fluid_share >= VL_PLAN_ROUGH_FLUID_SHARE;
    double back = L->planned ? ROUGH_BACKGROUND_PLANNED : ROUGH_BACKGROUND;
    L->back = r * fmax(L->a / back, L->lh / 80.0);
    L->fine = isfinite(L->s) ? fmin(L->back, r * L->s / ROUGH_EDGE_CELLS) : L->back;
    L->inlet_growth = ROUGH_INLET_GROWTH;
  }
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
  if (!(base->eta_pa_s > 0.0)) {
    vl_error_set(err, "automatic layout: a lubricated contact only");
    return VL_EINPUT;
  }
  double er = vl_prony_e0(&base->rubber) * vl_prony_reduced_factor(&base->rubber);
  double a0 = sqrt(4.0 * base->load_n_per_m * base->radius_m / (M_PI * er));
  lengths L;
  plan_lengths(base, v0, in, a0, &L);
  size_t room = in && in->max_cells > 0 ? in->max_cells : VL_AUTO_MAX_CELLS;
  out->spans = malloc(room * sizeof *out->spans);
  if (!out->spans) {
    vl_error_set(err, "out of memory for a cell layout");
    return VL_ENOMEM;
  }
  size_t n = 0, nv = 0;
  for (int tries = 0; tries < 40 && n == 0; tries++) {
    double dx = fmax(L.fine, (L.x_hi - L.x_lo) / VL_CONTACT_MAX_GRID_LAYOUT);
    if (dx > L.fine) out->capped = 1;
    n = lay_out(&L, dx, out->spans, room, &nv);
    if (n == 0 || nv > VL_CONTACT_MAX_GRID_LAYOUT) { /* too many cells: all widths wider */
      n = 0;
      L.fine *= 1.25, L.back *= 1.25, L.inlet *= 1.25;
      out->capped = 1;
    }
  }
  if (n < VL_CONTACT_MIN_GRID) {
    vl_plan_free(out);
    vl_error_set(err, "automatic layout: no layout within %zu cells", room);
    return VL_EINPUT;
  }
  double dx = fmax(L.fine, (L.x_hi - L.x_lo) / VL_CONTACT_MAX_GRID_LAYOUT);
  out->cfg = *base;
  out->cfg.grid = nv, out->cfg.grid_growth = 1.0;
  out->cfg.cell_spans = out->spans, out->cfg.n_cells = n;
  out->cfg.x_min_a0 = L.x_lo, out->cfg.x_max_a0 = L.x_lo + (double)nv * dx;
  out->fine_a0 = L.fine, out->background_a0 = L.back, out->inlet_a0 = L.inlet;
  out->edge_zone_a0 = L.s, out->inlet_length_a0 = L.lh;
  /* a rough film whose edge zones the standard cells resolve keeps them */
  out->standard = base->roughness && !L.planned;
  return VL_OK;
}

double vl_plan_rough_film_floor(const vl_contact_config *base) {
  return base->roughness ? ROUGH_FILM_FLOOR * vl_persson_hrms(base->roughness) : 0.0;
}

void vl_plan_free(vl_plan *p) {
  if (!p) return;
  free(p->spans);
  p->spans = NULL;
  p->cfg.cell_spans = NULL;
}
