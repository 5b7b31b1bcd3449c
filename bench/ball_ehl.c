/* The lubricated smooth ball (soft EHL, docs/POINT_CONTACT.md section 9):
 * its films against Hamrock and Dowson's fits, where its time goes, and
 * its error estimate against finer references.
 *
 *   ball_ehl hd [--fine]
 *     an elastic ball (E 2 MPa, nu 0.5, R 9.525 mm, W 3 N, 0.1 Pa s) at
 *     v0 = 0.1 .. 6.4 m/s: h_min and h_c on nested cells (rim cells 0.08
 *     and 0.04 Hertz radii; --fine adds 0.02), Richardson-extrapolated at
 *     order 2, against the fits; the central film's exponent in speed.
 *   ball_ehl cost
 *     the same ball at 0.4 m/s on cells 0.08 .. 0.028: cells, the influence
 *     matrix's assembly (Love's rectangles; with a 28-term memory), the
 *     Newton steps and their mean cost (the dense LU's n^3).
 *   ball_ehl estimate [--compound NAME] [--eta PA_S] [--target E] [--radius M] [--load N]
 *                     [--db PATH]
 *     the automatic sweep (vl_point_contact_sweep) of the compound
 *     (default model-rubber) in a fluid of viscosity eta (default 1.41, pure
 *     glycerol), a ball of radius R (default 9.525 mm) under W (default 3 N),
 *     at 0.01 .. 1 m/s to the target (default 0.05), then each
 *     point on cells 2 and 4 times as wide (the sweep's own cells are at
 *     the dense solver's bound: no finer reference fits); the reference is
 *     the Richardson extrapolation of the two finest at the order the three
 *     give (clipped to [1, 3]); the estimate one level coarser (as the
 *     sweep makes it) against the reference.
 *   ball_ehl rough [--hrms M] [--compound NAME|elastic] [--eta PA_S] [--radius M] [--load N]
 *     the rough ball (docs/POINT_CONTACT.md section 10) on a self-affine
 *     surface (H 0.8, q0 2e5, q1 7.8e9 1/m) of h_rms (default 1 um),
 *     Patir and Cheng's flow factors, sigma_s 1 MPa, at 1e-4 .. 1 m/s, each
 *     point on rim cells 0.08, 0.056, 0.04 and 0.028 a0 (each started from
 *     the coarser one); the estimate at 0.04 as the sweep makes it (the
 *     change from 0.08) against the reference, the Richardson
 *     extrapolation of 0.04 and 0.028 at the order the last three give
 *     (clipped to [1, 3]). "elastic": E 2 MPa, nu 0.5.
 * CPU seconds, one thread (OPENBLAS_NUM_THREADS=1). */
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "viscolube.h"

#include "persson_internal.h"
#include "point_contact_internal.h"
#include "point_ehl.h"

static double cpu_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void hd_ball(vl_point_ehl_config *c, double v0, double h_fine) {
  vl_point_ehl_config_defaults(c);
  c->radius_m = 0.009525, c->load_n = 3.0, c->rubber.e_inf_pa = 2e6, c->rubber.nu = 0.5;
  c->eta_pa_s = 0.1, c->v0_m_s = v0;
  c->h_fine = h_fine, c->h_coarse = 7.5 * h_fine, c->growth = 25.0 * h_fine;
}

static int run_hd(int fine) {
  const double v[] = {0.1, 0.2, 0.4, 0.8, 1.6, 3.2, 6.4};
  const double hs[] = {0.08, 0.04, 0.02};
  int levels = fine ? 3 : 2;
  double lv[7], lhc[7], lhm[7];
  printf("# soft EHL, elastic ball E 2 MPa, R 9.525 mm, W 3 N, eta 0.1 Pa s; films in um\n");
  printf("# v0_m_s  cells(finest)  h_min_R  HD_min  diff_%%  h_c_R  HD_c  diff_%%  "
         "at(x/a,y/a)  cpu_s\n");
  for (size_t k = 0; k < sizeof v / sizeof v[0]; k++) {
    double hm[3], hc[3], t0 = cpu_s(), hdm = 0, hdc = 0, xm = 0, ym = 0;
    size_t cells = 0;
    for (int g = 0; g < levels; g++) {
      vl_point_ehl_config c;
      hd_ball(&c, v[k], hs[g]);
      vl_point_ehl_result r;
      vl_error err;
      if (vl_point_ehl_solve(&c, NULL, &r, NULL, &err) != VL_OK) {
        printf("%g: %s\n", v[k], err.msg);
        return 1;
      }
      hm[g] = r.h_min_m, hc[g] = r.h_c_m, cells = r.nx * r.ny;
      xm = r.x_min_m / r.a_m, ym = r.y_min_m / r.a_m;
      vl_point_ehl_hamrock_dowson(&c, &hdm, &hdc);
    }
    int f = levels - 1;
    double rm = hm[f] + (hm[f] - hm[f - 1]) / 3.0, rc = hc[f] + (hc[f] - hc[f - 1]) / 3.0;
    printf("%8.3g %6zu %8.4g %8.4g %+6.1f %8.4g %8.4g %+6.1f  (%.2f,%.2f) %6.1f\n", v[k], cells,
           1e6 * rm, 1e6 * hdm, 100 * (rm / hdm - 1), 1e6 * rc, 1e6 * hdc, 100 * (rc / hdc - 1), xm,
           ym, cpu_s() - t0);
    lv[k] = log(v[k]), lhc[k] = log(rc), lhm[k] = log(rm);
  }
  /* least-squares slopes */
  double n = (double)(sizeof v / sizeof v[0]);
  double sx = 0, sy = 0, sz = 0, sxx = 0, sxy = 0, sxz = 0;
  for (size_t k = 0; k < sizeof v / sizeof v[0]; k++)
    sx += lv[k], sy += lhc[k], sz += lhm[k], sxx += lv[k] * lv[k], sxy += lv[k] * lhc[k],
        sxz += lv[k] * lhm[k];
  double d = n * sxx - sx * sx;
  printf("# exponents in v0: h_c %.3f (Hamrock-Dowson 0.64), h_min %.3f (0.65)\n",
         (n * sxy - sx * sy) / d, (n * sxz - sx * sz) / d);
  return 0;
}

static int run_cost(void) {
  const double hs[] = {0.08, 0.056, 0.04, 0.028};
  printf("# the elastic ball at 0.4 m/s; then the same with a 28-term memory (sbr-like)\n");
  printf("# h_fine  cells  assembly_s  newton_steps  per_step_s  per_step/cells^3_ns\n");
  for (int mem = 0; mem < 2; mem++)
    for (size_t k = 0; k < sizeof hs / sizeof hs[0]; k++) {
      vl_point_ehl_config c;
      hd_ball(&c, 0.4, hs[k]);
      if (mem) { /* 28 terms two per decade, E0 2 MPa, Einf 2 GPa */
        c.rubber.n_terms = 28;
        double sumA = 0;
        for (size_t m = 0; m < 28; m++)
          c.rubber.tau_s[m] = 1e-9 * pow(10.0, 0.5 * (double)m), c.rubber.A[m] = 999.0 / 28.0,
          sumA += c.rubber.A[m];
        c.rubber.e_inf_pa = 2e6 * (1.0 + sumA);
      }
      vl_point_ehl_result r;
      vl_error err;
      vl_point_ehl_solve(&c, NULL, &r, NULL, &err);
      size_t n = r.nx * r.ny;
      double step = r.t_solve_s / (double)(r.iterations ? r.iterations : 1);
      printf("%s%6.3f %6zu %9.3f %6ld %9.4f %9.3f\n", mem ? "m " : "e ", hs[k], n, r.t_influence_s,
             r.iterations, step, 1e9 * step / ((double)n * (double)n * (double)n));
    }
  return 0;
}

/* mu of the point v0 on cells_per_a0 = r with the sweep's planned domain. */
static double mu_on(const vl_point_contact_config *base, const vl_point *pt, double r) {
  vl_point_contact_config cfg = *base;
  cfg.cells_per_a0 = r;
  cfg.y_max_a0 = pt->ball.y_max_a0 / 1.8 * VL_BALL_DOMAIN_A0; /* the wet domain's unit */
  vl_point_contact *c = NULL;
  vl_point p;
  vl_error err;
  if (vl_point_contact_create(&cfg, &c, &err) != VL_OK) return NAN;
  vl_status st = vl_point_contact_solve(c, pt->v0_m_s, &p, &err);
  vl_point_contact_free(c);
  return st == VL_OK ? p.mu : NAN;
}

/* The rubber named `compound`: "elastic" (E 2 MPa, nu 0.5), else the
 * compound of the database at db_path (NULL: a new one in a temporary
 * folder, from the shipped materials). False (said on stderr) when absent. */
static bool load_rubber(const char *compound, const char *db_path, vl_prony *rubber) {
  if (!strcmp(compound, "elastic")) {
    memset(rubber, 0, sizeof *rubber);
    rubber->e_inf_pa = 2e6, rubber->nu = 0.5;
    return true;
  }
  char tmp[] = "/tmp/ball_ehl_XXXXXX", p[64];
  if (!db_path) {
    if (!mkdtemp(tmp)) return false;
    snprintf(p, sizeof p, "%s/m.db", tmp);
    db_path = p;
  }
  vl_db *db = NULL;
  vl_error err;
  bool ok = vl_db_open(db_path, &db, &err) == VL_OK &&
            vl_db_compound_get(db, compound, rubber, &err) == VL_OK;
  if (!ok) fprintf(stderr, "%s\n", err.msg);
  vl_db_close(db);
  return ok;
}

static int run_estimate(const char *compound, double eta, double target, double radius, double load,
                        const char *db_path) {
  vl_error err;
  vl_point_contact_config base;
  vl_point_contact_config_defaults(&base);
  if (!load_rubber(compound, db_path, &base.rubber)) return 1;
  base.radius_x_m = base.radius_y_m = radius, base.load_n = load, base.eta_pa_s = eta;
  const double v[] = {0.01, 0.03, 0.1, 0.3, 1.0};
  size_t n = sizeof v / sizeof v[0];
  vl_point pts[5];
  vl_auto_options o = {target, -1, false};
  vl_sweep_stats st;
  double t0 = cpu_s();
  if (vl_point_contact_sweep(&base, &o, n, v, pts, NULL, NULL, &st, &err) != VL_OK) {
    fprintf(stderr, "%s\n", err.msg);
    return 1;
  }
  printf("# %s in a fluid of %g Pa s, R %g m, W %g N, target %g: the sweep in %.1f s\n", compound,
         eta, radius, load, target, cpu_s() - t0);
  printf("# the point on its cells r and on r/2 and r/4; the reference: Richardson from r/2 and\n"
         "# r at the order the three give (clipped to [1, 3]); 'r/2' is the point one level\n"
         "# coarser, its estimate as the sweep makes it (|mu(r/2) - mu(r/4)|/mu(r/2))\n");
  printf("# v0_m_s  r  cells  mu  est_%%  true_%%(vs ref)  |  r/2: est_%%  true_%%  order  "
         "ref_cpu_s\n");
  for (size_t i = 0; i < n; i++) {
    const vl_point *p = &pts[i];
    if (!p->converged) {
      printf("%8.3g not converged\n", v[i]);
      continue;
    }
    double t1 = cpu_s(), r = p->ball.cells_per_a0;
    double m4 = mu_on(&base, p, r / 4), m2 = mu_on(&base, p, r / 2), m1 = p->mu;
    double q = fabs(m4 - m2) / fabs(m2 - m1), order = log2(q);
    double po = order >= 1.0 ? (order > 3.0 ? 3.0 : order) : 1.0;
    double ref = m1 + (m1 - m2) / (pow(2.0, po) - 1.0);
    vl_point_contact_config at = base;
    at.cells_per_a0 = r, at.y_max_a0 = p->ball.y_max_a0 / 1.8 * VL_BALL_DOMAIN_A0;
    printf("%8.3g %6.1f %5zu %.5g %6.2f %6.2f  | %6.2f %6.2f %5.2f %6.1f\n", v[i], r,
           vl_point_contact_wet_cells(&at), m1, 100 * p->error_estimate, 100 * fabs(m1 / ref - 1),
           100 * fabs(m2 - m4) / fabs(m2), 100 * fabs(m2 / ref - 1), order, cpu_s() - t1);
  }
  return 0;
}

/* The rough ball's points on four nested cells, their estimates against
 * references (see the header). */
static int run_rough(double hrms, const char *compound, double eta, double radius, double load,
                     const char *db_path) {
  vl_point_contact_config base;
  vl_point_contact_config_defaults(&base);
  vl_error err;
  if (!load_rubber(compound, db_path, &base.rubber)) return 1;
  vl_psd psd;
  vl_persson *tab = NULL;
  if (vl_psd_init_self_affine(&psd, 0.8, 2e5, 7.8e9, hrms, &err) != VL_OK ||
      vl_persson_build(&psd, 0, &tab, &err) != VL_OK) {
    fprintf(stderr, "%s\n", err.msg);
    return 1;
  }
  base.radius_x_m = base.radius_y_m = radius, base.load_n = load, base.eta_pa_s = eta;
  base.roughness = tab, base.flow_factors = VL_FLOW_FACTORS_PATIR_CHENG, base.sigma_s_pa = 1e6;
  printf("# rough ball: %s, h_rms %g m, eta %g Pa s, R %g m, W %g N\n", compound, hrms, eta, radius,
         load);
  printf("# v0_m_s  mu(0.08 0.056 0.04 0.028)  est(0.04)_%%  true(0.04)_%%  order  fluid  "
         "cpu_s\n");
  const double v[] = {1e-4, 1e-3, 1e-2, 1e-1, 1.0}, h[4] = {0.08, 0.056, 0.04, 0.028};
  for (size_t i = 0; i < 5; i++) {
    double t0 = cpu_s(), mu[4] = {NAN, NAN, NAN, NAN}, share = NAN;
    vl_point_contact *prev = NULL;
    for (int g = 0; g < 4; g++) {
      vl_point_contact_config cfg = base;
      cfg.cells_per_a0 = 1.0 / h[g];
      vl_point_contact *c = NULL;
      vl_point p;
      if (vl_point_contact_create(&cfg, &c, &err) != VL_OK) break;
      vl_point_contact_wet_start_from(c, prev);
      if (vl_point_contact_solve(c, v[i], &p, &err) == VL_OK)
        mu[g] = p.mu, share = p.fluid_load_fraction;
      vl_point_contact_free(prev);
      prev = c;
    }
    vl_point_contact_free(prev);
    double order = log2(fabs(mu[1] - mu[2]) / fabs(mu[2] - mu[3])) * 2.0; /* steps of sqrt 2 */
    double po = order >= 1.0 ? (order > 3.0 ? 3.0 : order) : 1.0;
    double ref = mu[3] + (mu[3] - mu[2]) / (pow(M_SQRT2, po) - 1.0);
    printf("%8.3g  %.5g %.5g %.5g %.5g  %6.2f %6.2f  %5.2f  %.3f  %6.1f\n", v[i], mu[0], mu[1],
           mu[2], mu[3], 100 * fabs(mu[2] - mu[0]) / fabs(mu[2]), 100 * fabs(mu[2] / ref - 1),
           order, share, cpu_s() - t0);
    fflush(stdout);
  }
  vl_persson_free(tab);
  return 0;
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: ball_ehl hd [--fine] | cost | estimate [--compound NAME] [--eta "
                    "PA_S] [--target E] [--radius M] [--load N] [--db PATH] | rough [--hrms M]\n");
    return 2;
  }
  const char *compound = "model-rubber", *db = NULL;
  double eta = 1.41, target = 0.05, radius = 0.009525, load = 3.0, hrms = 1e-6;
  int fine = 0;
  for (int i = 2; i < argc; i++) {
    const char *v = i + 1 < argc ? argv[i + 1] : "";
    if (!strcmp(argv[i], "--fine"))
      fine = 1;
    else if (!strcmp(argv[i], "--compound"))
      compound = v, i++;
    else if (!strcmp(argv[i], "--eta"))
      eta = atof(v), i++;
    else if (!strcmp(argv[i], "--target"))
      target = atof(v), i++;
    else if (!strcmp(argv[i], "--radius"))
      radius = atof(v), i++;
    else if (!strcmp(argv[i], "--load"))
      load = atof(v), i++;
    else if (!strcmp(argv[i], "--db"))
      db = v, i++;
    else if (!strcmp(argv[i], "--hrms"))
      hrms = atof(v), i++;
  }
  if (!strcmp(argv[1], "hd")) return run_hd(fine);
  if (!strcmp(argv[1], "cost")) return run_cost();
  if (!strcmp(argv[1], "estimate")) return run_estimate(compound, eta, target, radius, load, db);
  if (!strcmp(argv[1], "rough")) return run_rough(hrms, compound, eta, radius, load, db);
  fprintf(stderr, "ball_ehl: unknown mode %s\n", argv[1]);
  return 2;
}
