/* The hard-case matrix (issue 8): shared helpers of tests/hard/test_*.c.
 *
 * A "corner" is one configuration (rubber, geometry, surface, fluid, grid,
 * domain) swept in speed by continuation (vl_sweep_run); each requested
 * speed is a "point". Every point is checked against the invariants below
 * (hard_check_point, hard_check_fields) and against the model's assumptions
 * (vl_assumptions_check, whose warnings are appended to the point's own).
 * Counts per family are printed at the end of each executable:
 *   converged  points that met the solver tolerance;
 *   flagged    converged points with a non-empty warning column;
 *   failed     points reported with converged = false (the sweep went on).
 *
 * Header-only (static functions): the CMake glob links one source per
 * test executable. */
#ifndef VL_HARD_UTIL_H
#define VL_HARD_UTIL_H

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "assumptions_internal.h"
#include "contact_private.h"
#include "persson_internal.h"
#include "rheology_internal.h"
#include "roughness_internal.h"
#include "sweep_internal.h"
#include "viscolube/assumptions.h"
#include "viscolube/contact.h"
#include "viscolube/persson.h"
#include "viscolube/rheology.h"
#include "viscolube/sweep.h"

/* The seed's model rubber and cylinder (docs/CASES.md fig05: E0 = 3.6 MPa,
 * Einf/E0 = 10, tau = 0.1 s, nu = 0.5, R = 1 cm, fN = 1 kN/m; paper
 * surface H = 0.8, q0 = 2e5 1/m, q1 = 7.8e9 1/m, h_rms = 3 um). */
#define HARD_E0 3.6e6
#define HARD_NU 0.5
#define HARD_TAU 0.1
#define HARD_RADIUS 0.01
#define HARD_LOAD 1000.0
#define HARD_Q0 2e5

/* ------------------------------------------------------------ randomness */

/* splitmix64: a fixed-seed generator that gives the same design on every
 * platform (rand() does not). */
static inline uint64_t hard_rng_next(uint64_t *s) {
  uint64_t z = (*s += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}
static inline double hard_rng_uniform(uint64_t *s) {
  return (double)(hard_rng_next(s) >> 11) * 0x1.0p-53;
}
static inline double hard_rng_normal(uint64_t *s) {
  double u1 = hard_rng_uniform(s), u2 = hard_rng_uniform(s);
  if (u1 < 1e-300) u1 = 1e-300;
  return sqrt(-2.0 * log(u1)) * cos(2.0 * M_PI * u2);
}

/* Latin hypercube: n samples in d dimensions, u[i*d + k] in (0, 1), each
 * dimension cut in n strata with exactly one sample per stratum. */
static inline void hard_lhs(size_t n, size_t d, uint64_t seed, double *u) {
  uint64_t s = seed;
  size_t *perm = malloc(n * sizeof *perm);
  for (size_t k = 0; k < d; k++) {
    for (size_t i = 0; i < n; i++)
      perm[i] = i;
    for (size_t i = n; i > 1; i--) {
      size_t j = (size_t)(hard_rng_next(&s) % i);
      size_t t = perm[i - 1];
      perm[i - 1] = perm[j];
      perm[j] = t;
    }
    for (size_t i = 0; i < n; i++)
      u[i * d + k] = ((double)perm[i] + hard_rng_uniform(&s)) / (double)n;
  }
  free(perm);
}

/* A value log-uniform in [lo, hi] at fraction u. */
static inline double hard_log_between(double lo, double hi, double u) {
  return lo * pow(hi / lo, u);
}

/* The solid and the geometry of a Latin-hypercube corner, decoded from its
 * first 7 coordinates in [0, 1) (the same for every family): Einf/E0 in
 * 1 ... 1e4 (below 1.05: elastic, no Prony terms), 1-60 terms over 0-20
 * decades around tau_c in 1e-6 ... 1e2 s, the load 1e-3 ... 1e2 times the
 * seed's, radius 0.1 mm ... 1 m, and one of five grids. */
typedef struct {
  double ratio, decades, tau_c, load, radius;
  size_t terms, grid;
} hard_solid;

static inline hard_solid hard_decode_solid(const double *p, const size_t grids[5]) {
  hard_solid s;
  s.ratio = hard_log_between(1.0, 1e4, p[0]);
  s.terms = s.ratio < 1.05 ? 0 : (size_t)lround(hard_log_between(1.0, 60.0, p[1]));
  s.decades = 20.0 * p[2];
  s.tau_c = hard_log_between(1e-6, 1e2, p[3]);
  s.load = HARD_LOAD * hard_log_between(1e-3, 1e2, p[4]);
  s.radius = hard_log_between(1e-4, 1.0, p[5]);
  s.grid = grids[(size_t)(p[6] * 5.0)];
  return s;
}

/* The rough surface of a Latin-hypercube corner, decoded from coordinates
 * 7-10 (the same for dry and wet families): h_rms 1 nm ... 50 um, H 0.3 ...
 * 1, q1/q0 10 ... 1e6, and half the surfaces tabulated with a log-normal
 * scatter 0 ... 1 (noise < 0: self-affine). */
typedef struct {
  double hrms, hurst, q1_over_q0, noise;
} hard_rough;

static inline hard_rough hard_decode_rough(const double *p) {
  hard_rough r;
  r.hrms = hard_log_between(1e-9, 5e-5, p[7]);
  r.hurst = 0.3 + 0.7 * p[8];
  r.q1_over_q0 = hard_log_between(10.0, 1e6, p[9]);
  r.noise = p[10] < 0.5 ? -1.0 : 2.0 * (p[10] - 0.5);
  return r;
}

/* ------------------------------------------------------------ materials */

/* A rubber with relaxed modulus HARD_E0 and Einf/E0 = ratio: n_terms = 0
 * (elastic) when n == 0; otherwise n terms with tau_i log-spaced over
 * `decades` decades centred on tau_c (one term: tau_c), strengths
 * A_i = (ratio - 1) w_i / sum w, w_i = 1 or, with random_weights,
 * log-uniform over two decades (a ragged spectrum). */
static inline vl_prony hard_rubber(double ratio, size_t n, double decades, double tau_c,
                                   int random_weights, uint64_t *rng) {
  vl_prony r;
  memset(&r, 0, sizeof r);
  r.e_inf_pa = n ? HARD_E0 * ratio : HARD_E0; /* elastic: E = E0 */
  r.nu = HARD_NU;
  r.n_terms = n;
  double w[VL_PRONY_MAX_TERMS], sw = 0.0;
  for (size_t i = 0; i < n; i++) {
    w[i] = random_weights ? pow(10.0, 2.0 * hard_rng_uniform(rng) - 1.0) : 1.0;
    sw += w[i];
  }
  for (size_t i = 0; i < n; i++) {
    double t = n > 1 ? (double)i / (double)(n - 1) - 0.5 : 0.0;
    r.tau_s[i] = tau_c * pow(10.0, decades * t);
    r.A[i] = (ratio - 1.0) * w[i] / sw;
  }
  return r;
}

/* "elastic" or "Einf/E0 .., n terms over .. decades at tau .. s"; returns
 * the characters written (snprintf). */
static inline int hard_rubber_label(char *s, size_t cap, double ratio, size_t nt, double dec,
                                    double tau_c) {
  if (nt == 0) return snprintf(s, cap, "elastic");
  if (nt == 1) return snprintf(s, cap, "Einf/E0 %.3g, 1 term at tau %.3g s", ratio, tau_c);
  return snprintf(s, cap, "Einf/E0 %.3g, %zu terms over %.3g decades centred on tau %.3g s", ratio,
                  nt, dec, tau_c);
}

/* A surface: self-affine (noise < 0), or tabulated on n_tab log-spaced
 * points of the same self-affine PSD times exp(noise * N(0,1)) (a measured
 * spectrum's scatter). Returns VL_OK or the builder's error. */
static inline vl_status hard_surface(vl_psd *psd, double hurst, double q0, double q1, double hrms,
                                     double noise, size_t n_tab, uint64_t *rng, vl_error *err) {
  vl_status st = vl_psd_init_self_affine(psd, hurst, q0, q1, hrms, err);
  if (st != VL_OK || noise < 0.0) return st;
  double *q = malloc(n_tab * sizeof *q), *C = malloc(n_tab * sizeof *C);
  for (size_t k = 0; k < n_tab; k++) {
    q[k] = q0 * pow(q1 / q0, (double)k / (double)(n_tab - 1));
    C[k] = vl_psd_value(psd, q[k]) * exp(noise * hard_rng_normal(rng));
  }
  q[n_tab - 1] = q1; /* exact end (pow rounding) */
  vl_psd_free(psd);
  st = vl_psd_init_tabulated(psd, n_tab, q, C, err);
  free(q);
  free(C);
  return st;
}

/* A corner's surface (q0 = HARD_Q0; tabulated with `noise` >= 0, on a table
 * of *n_tab points growing with the bandwidth) and its Persson table; a
 * failure fails the test. */
static inline vl_persson *hard_rough_surface(vl_psd *psd, double hurst, double q1_over_q0,
                                             double hrms, double noise, uint64_t *rng,
                                             size_t *n_tab) {
  vl_persson *tab = NULL;
  vl_error err;
  *n_tab = 8 + (size_t)(4.0 * log10(q1_over_q0)) * 4;
  if (hard_surface(psd, hurst, HARD_Q0, HARD_Q0 * q1_over_q0, hrms, noise, *n_tab, rng, &err) !=
      VL_OK)
    fail_msg("surface: %s", err.msg);
  if (vl_persson_build(psd, 0, &tab, &err) != VL_OK) fail_msg("Persson table: %s", err.msg);
  return tab;
}

/* ------------------------------------------------------------ statistics */

#define HARD_MAX_FAILS 64
#define HARD_NBITS 10

typedef struct {
  const char *name;
  double min_rate;       /* stated minimum share of converged points, continuum films */
  double min_rate_subnm; /* the same where the a priori film is below 1 nm */
  int max_subdivisions;  /* sweep step control (0: the library's default) */
  size_t corners, points, converged, flagged, failed;
  size_t corners_with_failures;
  size_t subnm_points, subnm_converged; /* a priori film scale below 1 nm */
  size_t real_points, real_converged;   /* realistic operating points (hard_realistic) */
  bool edge_numerics;           /* deliberately broken numerics (test_hard_inputs): realistic
                                 * points are counted, not required */
  size_t bit_count[HARD_NBITS]; /* points flagged per assumption */
  size_t solver_warned;         /* points with the solver's own warnings */
  double worst_load_error, worst_jump, worst_pf_neg, worst_rc_neg;
  size_t jumps_skipped; /* neighbour pairs with a regime change */
  double seconds;
  char fails[HARD_MAX_FAILS][512];
  size_t n_fails;
  size_t majority_failed;  /* corners where most points failed */
  char solver_msgs[4][96]; /* distinct solver warnings seen (first 4, cut at a digit) */
  size_t on_wall;          /* rough points with u = 0 somewhere (Persson wall) */
  size_t violations;       /* invariant violations (each printed, up to 40) */
} hard_family;

/* Bounds (each stated with its reason in hard_check_point). */
#define HARD_LOAD_TOL 1e-8
#define HARD_PNEG 1e-8
#define HARD_JUMP_SLOPE 2.0
#define HARD_JUMP_SLACK 0.30103 /* log10 2 */
#define HARD_MU_FLOOR 1e-4

typedef struct {
  char label[400];
  vl_contact_config cfg;
  const vl_psd *psd;
  hard_family *fam;
  double p0, a0, dx;
} hard_ctx;

/* Records a violated invariant: printed (the first 40 of a family) and
 * counted; hard_assert_rate fails the test if any occurred, after the
 * whole family has run, so that one run shows every violation. */
static inline void hard_violation(hard_family *f, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
static inline void hard_violation(hard_family *f, const char *fmt, ...) {
  if (f->violations++ < 40) {
    va_list ap;
    va_start(ap, fmt);
    printf("  VIOLATION (%s): ", f->name);
    vprintf(fmt, ap);
    printf("\n");
    va_end(ap);
  }
}

static inline void hard_assert_finite(double v, const char *what, const hard_ctx *x, double v0) {
  if (!isfinite(v))
    hard_violation(x->fam, "%s = %g not finite at v0 = %g m/s in %s", what, v, v0, x->label);
}

/* Fields of a converged point:
 * - finite everywhere, x increasing;
 * - pf >= -1e-8 p_ref and pc >= -1e-8 p_ref, p_ref = max(p0, peak): both
 *   come from Fischer-Burmeister rows FB(a, b) = a + b - sqrt(a^2 + b^2 +
 *   eps) (eps > 0 alone would keep a, b > 0) solved to the max-norm
 *   tolerance 1e-9, and |FB| <= tol implies a >= -tol; the unknowns are
 *   p/p0 (smooth contact) and pf/(kappa p0) with the fluid scale kappa <= 10
 *   p0 or the current peak (contact.c), hence 1e-8 p_ref. A rough contact's
 *   pc = |Er| s(u) is positive by construction;
 * - u >= 0: the solver reports max(u, 0), so no negative can show. On a
 *   rough surface Persson's pc(u) is finite only for u > 0, and u = 0 means
 *   the state sits on the linear wall below the table (roughness.h), which
 *   vl_assumptions_check flags (u_min < 1e-3 h_rms): counted as on_wall. A
 *   smooth wet film must stay open (u > 0, pc = 0);
 * - 0 <= A/A0 <= 1, 0 <= theta <= 1. */
static inline void hard_check_fields(hard_ctx *x, const vl_contact *c, const vl_point *pt) {
  size_t n = vl_contact_grid(c);
  double *b = malloc(6 * n * sizeof *b);
  vl_fields f = {n, b, b + n, b + 2 * n, b + 3 * n, b + 4 * n, b + 5 * n, NULL};
  vl_contact_fields(c, &f);
  double pref = fmax(x->p0, pt->peak_pressure_pa);
  double v0 = pt->v0_m_s;
  int on_wall = 0;
  for (size_t i = 0; i < n; i++) {
    hard_assert_finite(f.x_m[i], "x", x, v0);
    hard_assert_finite(f.p_f_pa[i], "pf", x, v0);
    hard_assert_finite(f.p_c_pa[i], "pc", x, v0);
    hard_assert_finite(f.u_m[i], "u", x, v0);
    hard_assert_finite(f.area_ratio[i], "A/A0", x, v0);
    hard_assert_finite(f.film_fraction[i], "theta", x, v0);
    if (i > 0 && !(f.x_m[i] > f.x_m[i - 1]))
      hard_violation(x->fam, "x not increasing in %s", x->label);
    double pfn = -f.p_f_pa[i] / pref, pcn = -f.p_c_pa[i] / pref;
    x->fam->worst_pf_neg = fmax(x->fam->worst_pf_neg, fmax(pfn, pcn));
    if (pfn > HARD_PNEG || pcn > HARD_PNEG)
      hard_violation(x->fam, "pf = %g / pc = %g Pa below -%g p_ref at x = %g m, v0 = %g m/s in %s",
                     f.p_f_pa[i], f.p_c_pa[i], HARD_PNEG, f.x_m[i], v0, x->label);
    if (f.u_m[i] < 0.0) hard_violation(x->fam, "u < 0 at v0 = %g in %s", v0, x->label);
    if (x->cfg.roughness && !(f.u_m[i] > 0.0)) on_wall = 1;
    if (x->cfg.eta_pa_s > 0.0 && !x->cfg.roughness && (f.p_c_pa[i] != 0.0 || !(f.u_m[i] > 0.0)))
      hard_violation(x->fam, "smooth wet film closed (pc %g, u %g) at v0 = %g in %s", f.p_c_pa[i],
                     f.u_m[i], v0, x->label);
    if (f.area_ratio[i] < 0.0 || f.area_ratio[i] > 1.0 || f.film_fraction[i] < 0.0 ||
        f.film_fraction[i] > 1.0)
      hard_violation(x->fam, "A/A0 = %g or theta = %g outside [0, 1] in %s", f.area_ratio[i],
                     f.film_fraction[i], x->label);
  }
  x->fam->on_wall += (size_t)on_wall;
  free(b);
}

static inline void hard_on_point(void *user, size_t i, size_t total, const vl_point *pt,
                                 const vl_contact *c) {
  (void)i, (void)total;
  if (pt->converged) hard_check_fields(user, c, pt);
}

/* The warning column: terminated, no comma or quote (CSV and JSON). */
static inline void hard_check_warnings(const hard_ctx *x, const char *w) {
  size_t len = strnlen(w, VL_WARN_MAX);
  if (len >= VL_WARN_MAX) hard_violation(x->fam, "warnings not terminated in %s", x->label);
  if (strpbrk(w, ",\"\n"))
    hard_violation(x->fam, "warning with a comma or quote: '%s' in %s", w, x->label);
}

/* One point. Returns its assumption mask. */
static inline unsigned hard_check_point(hard_ctx *x, vl_point *pt) {
  hard_family *fam = x->fam;
  double v0 = pt->v0_m_s;
  hard_check_warnings(x, pt->warnings);
  size_t solver_len = strlen(pt->warnings);
  unsigned mask = vl_assumptions_check(&x->cfg, x->psd, pt, pt->warnings, sizeof pt->warnings);
  hard_check_warnings(x, pt->warnings);
  const double vals[] = {pt->mu,
                         pt->mu_Rc,
                         pt->mu_Rf,
                         pt->mu_Sc,
                         pt->mu_Sf,
                         pt->u_min_m,
                         pt->u_central_m,
                         pt->x_centroid_m,
                         pt->contact_width_m,
                         pt->fluid_load_fraction,
                         pt->load_error,
                         pt->E_wH_pa,
                         pt->a_H_m,
                         pt->Q,
                         pt->peak_pressure_pa,
                         pt->x_peak_m,
                         pt->mu_Sf_couette,
                         pt->mu_Sf_poiseuille,
                         pt->x_min_film_m,
                         pt->residual,
                         pt->eps_f_min};
  const char *names[] = {"mu",
                         "mu_Rc",
                         "mu_Rf",
                         "mu_Sc",
                         "mu_Sf",
                         "u_min",
                         "u_central",
                         "x_centroid",
                         "contact_width",
                         "fluid_load_fraction",
                         "load_error",
                         "E_wH",
                         "a_H",
                         "Q",
                         "peak_pressure",
                         "x_peak",
                         "mu_Sf_couette",
                         "mu_Sf_poiseuille",
                         "x_min_film",
                         "residual",
                         "eps_f_min"};
  for (size_t k = 0; k < sizeof vals / sizeof vals[0]; k++)
    hard_assert_finite(vals[k], names[k], x, v0);
  if (!pt->converged) {
    /* an explicit flag: zeros, a finite residual, no warning from the solver
     * (vl_assumptions_check may add those the configuration decides) */
    if (!(pt->mu == 0.0 && pt->iterations >= 0 && pt->residual >= 0.0 && solver_len == 0))
      hard_violation(fam, "failed point not cleanly flagged at v0 = %g in %s", v0, x->label);
    return mask;
  }
  if (solver_len) {
    fam->solver_warned++;
    /* remember the distinct warnings (their text up to the first digit) */
    char key[96];
    size_t k = 0;
    while (k < sizeof key - 1 && k < solver_len &&
           !(pt->warnings[k] >= '0' && pt->warnings[k] <= '9'))
      key[k] = pt->warnings[k], k++;
    key[k] = '\0';
    for (int m = 0; m < 4; m++) {
      if (strcmp(fam->solver_msgs[m], key) == 0) break;
      if (!fam->solver_msgs[m][0]) {
        snprintf(fam->solver_msgs[m], sizeof fam->solver_msgs[m], "%s", key);
        break;
      }
    }
  }
  /* load balance: the load row (\int p dx/fN - 1) is one of the residual
   * rows solved to the max-norm tolerance 1e-9; 10x for the sum's rounding */
  fam->worst_load_error = fmax(fam->worst_load_error, pt->load_error);
  if (!(pt->load_error <= HARD_LOAD_TOL))
    hard_violation(x->fam, "load error %g at v0 = %g m/s in %s", pt->load_error, v0, x->label);
  double sum = pt->mu_Rc + pt->mu_Rf + pt->mu_Sc + pt->mu_Sf;
  if (!(fabs(pt->mu - sum) <= 1e-12 * (1.0 + fabs(pt->mu))) ||
      !(fabs(pt->mu_Sf - pt->mu_Sf_couette - pt->mu_Sf_poiseuille) <=
        1e-12 * (1.0 + fabs(pt->mu_Sf))))
    hard_violation(fam, "friction components do not add up at v0 = %g in %s", v0, x->label);
  /* signs: shear in the real contact area (sigma_s >= 0 times A/A0 >= 0)
   * and the Couette shear (theta (phi_f + phi_fs) eta v0/u) resist the
   * motion; the Poiseuille part has either sign. */
  if (pt->mu_Sc < 0.0 || pt->mu_Sf_couette < 0.0)
    hard_violation(x->fam, "mu_Sc = %g or mu_Sf_couette = %g negative at v0 = %g in %s", pt->mu_Sc,
                   pt->mu_Sf_couette, v0, x->label);
  /* Dry: mu_Rc = -x_centroid/R is the hysteresis of the rubber, >= 0 for a
   * viscoelastic (and = 0 for an elastic) solid; the discrete centroid can
   * sit up to about one cell off (the domain is not symmetric about the
   * axis), so mu_Rc >= -dx/R. Wet: the fluid can push the solid contact
   * behind the axis (docs/MODEL.md section 7): no sign. The total friction times
   * v0 is the dissipated power: mu >= -dx/R always. */
  double slack = x->dx / x->cfg.radius_m;
  /* where the pressure reaches an end of the domain the contact is cut
   * and the centroid sits where the domain puts it (a domain beside the
   * axis gives any sign): the point says so, and the signs are not checked */
  if (strstr(pt->warnings, "domain edge")) slack = INFINITY;
  if (x->cfg.eta_pa_s == 0.0) {
    if (isfinite(slack)) fam->worst_rc_neg = fmax(fam->worst_rc_neg, -pt->mu_Rc / slack);
    if (pt->mu_Rc < -slack)
      hard_violation(x->fam, "dry mu_Rc = %g < -dx/R = %g at v0 = %g in %s", pt->mu_Rc, -slack, v0,
                     x->label);
  }
  if (pt->mu < -slack)
    hard_violation(x->fam, "mu = %g < -dx/R at v0 = %g in %s", pt->mu, v0, x->label);
  if (pt->u_min_m < 0.0 || pt->contact_width_m < 0.0 || !(pt->E_wH_pa > 0.0) ||
      !(pt->a_H_m > 0.0) || pt->fluid_load_fraction < -1e-6 || pt->fluid_load_fraction > 1.0 + 1e-6)
    hard_violation(x->fam, "derived quantity out of range at v0 = %g in %s", v0, x->label);
  if (!(pt->eps_f_min > 0.0 && pt->eps_f_min <= 1.0))
    hard_violation(fam, "eps_f_min = %g outside (0, 1] at v0 = %g in %s", pt->eps_f_min, v0,
                   x->label);
  /* |Er(wH)| lies between the relaxed and the glassy reduced moduli */
  double red = vl_prony_reduced_factor(&x->cfg.rubber);
  double er0 = vl_prony_e0(&x->cfg.rubber) * red, erinf = x->cfg.rubber.e_inf_pa * red;
  if (!(pt->E_wH_pa >= er0 * (1.0 - 1e-9) && pt->E_wH_pa <= erinf * (1.0 + 1e-9)))
    hard_violation(fam, "|Er(wH)| = %g outside [%g, %g] at v0 = %g in %s", pt->E_wH_pa, er0, erinf,
                   v0, x->label);
  if (pt->regime < VL_REGIME_DRY || pt->regime > VL_REGIME_HYDRODYNAMIC ||
      (x->cfg.eta_pa_s == 0.0) != (pt->regime == VL_REGIME_DRY))
    hard_violation(x->fam, "regime %d at v0 = %g in %s", pt->regime, v0, x->label);
  if (x->cfg.roughness && pt->u_min_m == 0.0 && !(mask & VL_ASSUME_PERSSON_TABLE))
    hard_violation(fam, "u = 0 on a rough surface not flagged at v0 = %g in %s", v0, x->label);
  if (pt->warnings[0]) fam->flagged++;
  for (unsigned b = 0; b < HARD_NBITS; b++)
    if (mask & (1u << b)) fam->bit_count[b]++;
  return mask;
}

/* A priori scale (m) of the separation in a wet contact at v0, before
 * solving: the larger of h_rms and the smooth film estimate L^2/(2R), L =
 * vl_contact_inlet_length_m (Martin's rigid film or the soft EHL one).
 * Below 1 nm the continuum film the model assumes does not exist (the seed
 * says so), so the convergence rate there is stated apart. Dry: infinity. */
static inline double hard_film_scale(const vl_contact_config *cfg, double v0) {
  if (!(cfg->eta_pa_s > 0.0)) return INFINITY;
  double l = vl_contact_inlet_length_m(cfg, v0);
  double h = l * l / (2.0 * cfg->radius_m);
  return cfg->roughness ? fmax(h, vl_persson_hrms(cfg->roughness)) : h;
}

/* A realistic operating point (README, "Hard cases"): speed 1e-9 ... 10 m/s,
 * viscosity 2e-4 ... 10 Pa s (a wet contact), h_rms >= 10 nm (a rough one)
 * and a relaxed Hertz half-width a0 <= 0.2 R (the half-space of the model). */
static inline bool hard_realistic(const vl_contact_config *cfg, const vl_psd *psd, double a0,
                                  double v0) {
  if (v0 < 1e-9 || v0 > 10.0 || a0 > 0.2 * cfg->radius_m) return false;
  if (cfg->eta_pa_s > 0.0 && (cfg->eta_pa_s < 2e-4 || cfg->eta_pa_s > 10.0)) return false;
  return !(cfg->roughness && psd && psd->hrms_m < 1e-8);
}

/* Runs one corner: create, sweep over v[0..n-1], check every point and
 * neighbouring pairs. Stores the points in out (n) when out != NULL. The
 * label names every parameter (printed with any failure). */
static inline void hard_run_corner(hard_family *fam, const char *label,
                                   const vl_contact_config *cfg, const vl_psd *psd, size_t n,
                                   const double *v, vl_point *out) {
  hard_ctx *x = calloc(1, sizeof *x);
  snprintf(x->label, sizeof x->label, "%s", label);
  x->cfg = *cfg;
  x->psd = psd;
  x->fam = fam;
  vl_contact *c = NULL;
  vl_error err;
  vl_status st = vl_contact_create(cfg, &c, &err);
  if (st != VL_OK) fail_msg("create failed (%s) for %s", err.msg, label);
  x->p0 = vl_contact_p0(c);
  x->a0 = vl_contact_a0(c);
  x->dx = (cfg->x_max_a0 - cfg->x_min_a0) * x->a0 / (double)cfg->grid;
  vl_point *pt = calloc(n, sizeof *pt);
  vl_sweep_stats ss;
  struct timespec t0, t1;
  clock_gettime(CLOCK_MONOTONIC, &t0);
  vl_sweep_options opt;
  vl_sweep_options_defaults(&opt);
  if (fam->max_subdivisions > 0) opt.max_subdivisions = fam->max_subdivisions;
  st = vl_sweep_run(c, n, v, &opt, pt, hard_on_point, x, &ss, &err);
  clock_gettime(CLOCK_MONOTONIC, &t1);
  double secs = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
  fam->seconds += secs;
  if (getenv("VL_HARD_VERBOSE"))
    printf("  corner %3zu: %zu/%zu converged (%zu from above), %ld Newton iterations, %zu "
           "sub-steps, %.2f s | %s\n",
           fam->corners, ss.converged, n, ss.recovered_below, ss.newton_iterations, ss.substeps,
           secs, label);
  if (st != VL_OK) fail_msg("sweep returned %d (%s) for %s", st, err.msg, label);
  assert_int_equal(ss.converged + ss.failed, n);
  fam->corners++;
  size_t nfail = 0;
  for (size_t i = 0; i < n; i++) {
    assert_true(pt[i].v0_m_s == v[i]); /* every requested speed is reported */
    hard_check_point(x, &pt[i]);
    fam->points++;
    if (pt[i].converged)
      fam->converged++;
    else
      fam->failed++, nfail++;
    if (hard_realistic(cfg, psd, x->a0, v[i])) {
      fam->real_points++;
      if (pt[i].converged) fam->real_converged++;
    }
    if (hard_film_scale(cfg, v[i]) < 1e-9) {
      fam->subnm_points++;
      if (pt[i].converged) fam->subnm_converged++;
    }
  }
  if (2 * nfail > n) fam->majority_failed++;
  if (nfail) {
    fam->corners_with_failures++;
    if (fam->n_fails < HARD_MAX_FAILS) {
      char *s = fam->fails[fam->n_fails++];
      int k = snprintf(s, sizeof fam->fails[0], "%zu/%zu failed (%.1f s) at v0 =", nfail, n, secs);
      for (size_t i = 0; i < n && k > 0 && (size_t)k < sizeof fam->fails[0] - 12; i++)
        if (!pt[i].converged)
          k += snprintf(s + k, sizeof fam->fails[0] - (size_t)k, " %.0e%s", v[i],
                        hard_film_scale(cfg, v[i]) < 1e-9 ? "*" : "");
      if (k > 0 && (size_t)k < sizeof fam->fails[0])
        snprintf(s + k, sizeof fam->fails[0] - (size_t)k, " | %s", label);
    }
  }
  /* Neighbouring speeds: no component of the model grows or decays faster
   * than v0^2 (the steepest is |E(w)| of a strong Prony term, whose
   * compliance falls as w^-2 in the transition; Couette shear and
   * low-speed hysteresis grow at most as v0), so within one regime
   * |log10(mu_b/mu_a)| <= 2 |log10(v_b/v_a)| + log10 2 (discretisation), with
   * mu floored at 1e-4 (friction below it is noise of the grid). A change
   * of regime (boundary/mixed/hydrodynamic) may jump. */
  size_t last = n;
  for (size_t i = 0; i < n; i++) {
    if (!pt[i].converged) continue;
    if (last < n) {
      const vl_point *a = &pt[last], *b = &pt[i];
      if (a->regime != b->regime) {
        fam->jumps_skipped++;
      } else {
        double j = fabs(log10((fabs(b->mu) + HARD_MU_FLOOR) / (fabs(a->mu) + HARD_MU_FLOOR)));
        double bound = HARD_JUMP_SLOPE * fabs(log10(v[i] / v[last])) + HARD_JUMP_SLACK;
        fam->worst_jump = fmax(fam->worst_jump, j / bound);
        if (j > bound)
          hard_violation(
              fam, "mu jumps from %g to %g between v0 = %g and %g m/s (bound %.2f decades) in %s",
              a->mu, b->mu, v[last], v[i], bound, label);
      }
    }
    last = i;
  }
  if (out) memcpy(out, pt, n * sizeof *pt);
  free(pt);
  vl_contact_free(c);
  free(x);
}

/* Speeds log-spaced from lo to hi, `per_decade` a decade (n returned). */
static inline size_t hard_speeds(double lo, double hi, double per_decade, double *v, size_t cap) {
  size_t n = (size_t)lround(log10(hi / lo) * per_decade) + 1;
  if (n > cap) n = cap;
  for (size_t i = 0; i < n; i++)
    v[i] = n > 1 ? lo * pow(hi / lo, (double)i / (double)(n - 1)) : lo;
  return n;
}

/* Convergence rates of the points with a continuum (>= 1 nm) and a sub-nm
 * a priori film (1 when there are none). */
static inline double hard_rate(const hard_family *f) {
  size_t p = f->points - f->subnm_points, c = f->converged - f->subnm_converged;
  return p ? (double)c / (double)p : 1.0;
}
static inline double hard_rate_subnm(const hard_family *f) {
  return f->subnm_points ? (double)f->subnm_converged / (double)f->subnm_points : 1.0;
}

static inline void hard_print_family(const hard_family *f) {
  printf("  %-22s corners %3zu  points %4zu  converged %4zu  flagged %4zu  failed %3zu  (%.1f s)\n",
         f->name, f->corners, f->points, f->converged, f->flagged, f->failed, f->seconds);
  printf("  %-22s converged: %.1f %% of %zu points with an a priori film >= 1 nm (stated minimum "
         "%.0f %%), %.1f %% of %zu below 1 nm (minimum %.0f %%)\n",
         "", 100.0 * hard_rate(f), f->points - f->subnm_points, 100.0 * f->min_rate,
         100.0 * hard_rate_subnm(f), f->subnm_points, 100.0 * f->min_rate_subnm);
  printf("  %-22s realistic points (README): %zu of %zu converged\n", "", f->real_converged,
         f->real_points);
  printf("  %-22s worst load error %.1e, worst jump %.2f of its bound (%zu regime changes "
         "skipped), worst pf/pc < 0: %.1e p_ref, worst dry mu_Rc < 0: %.2f dx/R; solver "
         "warnings on %zu points; u = 0 (Persson wall) on %zu\n",
         "", f->worst_load_error, f->worst_jump, f->jumps_skipped, f->worst_pf_neg, f->worst_rc_neg,
         f->solver_warned, f->on_wall);
  for (int m = 0; m < 4 && f->solver_msgs[m][0]; m++)
    printf("  %-22s solver warning: %s...\n", "", f->solver_msgs[m]);
  if (f->majority_failed)
    printf("  %-22s CORNERS WITH MOST POINTS FAILED: %zu\n", "", f->majority_failed);
  printf("  %-22s assumption flags:", "");
  int any = 0;
  for (unsigned b = 0; b < HARD_NBITS; b++)
    if (f->bit_count[b]) printf(" %s %zu", vl_assumption_name(1u << b), f->bit_count[b]), any = 1;
  printf("%s\n", any ? "" : " none");
  for (size_t i = 0; i < f->n_fails; i++)
    printf("    FAILED %s\n", f->fails[i]);
  if (f->n_fails) printf("    (* : a priori film below 1 nm)\n");
}

/* Prints the summary of families fam[0..n-1] and the totals. */
static inline void hard_print_summary(const char *title, hard_family *const *fam, size_t n) {
  printf("\n== hard-case matrix: %s ==\n", title);
  hard_family t;
  memset(&t, 0, sizeof t);
  for (size_t i = 0; i < n; i++) {
    hard_print_family(fam[i]);
    t.corners += fam[i]->corners, t.points += fam[i]->points;
    t.converged += fam[i]->converged, t.flagged += fam[i]->flagged, t.failed += fam[i]->failed;
    t.corners_with_failures += fam[i]->corners_with_failures;
    t.real_points += fam[i]->real_points, t.real_converged += fam[i]->real_converged;
    t.seconds += fam[i]->seconds;
  }
  printf("  TOTAL: corners tried %zu (%zu with a failed point), points %zu, converged %zu, "
         "flagged %zu, failed %zu; %.1f s in sweeps\n",
         t.corners, t.corners_with_failures, t.points, t.converged, t.flagged, t.failed, t.seconds);
  printf("  TOTAL realistic points (README): %zu of %zu converged\n", t.real_converged,
         t.real_points);
}

/* No invariant violated, and the family's stated minimum convergence rate. */
static inline void hard_assert_rate(const hard_family *f) {
  if (f->violations)
    fail_msg("%s: %zu invariant violations (printed above)", f->name, f->violations);
  if (hard_rate(f) < f->min_rate)
    fail_msg("%s: %.1f %% of points (film >= 1 nm) converged, below the stated %.0f %%", f->name,
             100.0 * hard_rate(f), 100.0 * f->min_rate);
  if (!f->edge_numerics && f->real_converged < f->real_points) /* issue 19: every one */
    fail_msg("%s: %zu of %zu realistic points converged (all are required)", f->name,
             f->real_converged, f->real_points);
  if (hard_rate_subnm(f) < f->min_rate_subnm)
    fail_msg("%s: %.1f %% of points (film < 1 nm) converged, below the stated %.0f %%", f->name,
             100.0 * hard_rate_subnm(f), 100.0 * f->min_rate_subnm);
}

#endif
