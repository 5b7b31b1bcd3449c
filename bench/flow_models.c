/* The main job's unfilled Stribeck curve (cases/fig15.ini: sbr-unfilled on
 * paper-0.5um in water) under the three flow-factor models, side by side:
 * prints mu, u_min/h_rms and the fluid's share of the load at every decade
 * of v0 eta and the convergence count per model, and draws
 * OUT-mu.{png,svg} and OUT-umin.{png,svg} (README, docs/img/flow-models-*).
 *
 *   flow_models [--case FILE] [--out STEM]
 *
 * Uses the default database (VISCOLUBE_DB or the user's). Not a test: it
 * documents what each model predicts. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "viscolube.h"

#define N_MODELS 3

static const vl_flow_factor_kind MODELS[N_MODELS] = {
    VL_FLOW_FACTORS_PERSSON_EMT, VL_FLOW_FACTORS_PATIR_CHENG, VL_FLOW_FACTORS_SMOOTH};

/* One curve of the scene under model k; NULL on failure (message printed). */
static vl_point *curve(const vl_scene *base, vl_db *db, vl_flow_factor_kind kind, size_t *n,
                       vl_curve_meta *meta, double *hrms) {
  vl_scene sc = *base;
  sc.effects.flow_factors = kind;
  vl_simulation *sim = NULL;
  vl_error err;
  vl_sweep_stats stats;
  vl_point *pts = NULL;
  if (vl_simulation_create(&sc, db, &sim, &err) != VL_OK) goto fail;
  *n = vl_simulation_points(sim);
  pts = calloc(*n, sizeof *pts);
  if (!pts) {
    vl_error_set(&err, "out of memory");
    goto fail;
  }
  vl_status st = vl_simulation_run(sim, pts, NULL, NULL, &stats, &err);
  if (st != VL_OK && st != VL_ENOCONV) goto fail;
  *meta = (vl_curve_meta){vl_simulation_eta(sim), 0.0, 0.0, NULL, 0.0, NULL};
  meta->flow_factors = vl_simulation_flow_factors(sim, &meta->film_cutoff_m);
  *hrms = vl_psd_hrms(vl_simulation_psd(sim));
  printf("%-12s %zu of %zu points converged, %.2f s\n", vl_flow_factors_name(kind), stats.converged,
         *n, stats.seconds);
  vl_simulation_free(sim);
  return pts;
fail:
  fprintf(stderr, "flow_models: %s: %s\n", vl_flow_factors_name(kind), err.msg);
  vl_simulation_free(sim);
  free(pts);
  return NULL;
}

int main(int argc, char **argv) {
  const char *case_path = VL_CASES_DIR "/fig15.ini", *stem = "flow-models";
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!strcmp(argv[i], "--case"))
      case_path = argv[i + 1];
    else if (!strcmp(argv[i], "--out"))
      stem = argv[i + 1];
  }
  vl_error err;
  vl_scene sc;
  vl_db *db = NULL;
  if (vl_scene_load(case_path, &sc, &err) != VL_OK || vl_db_open(NULL, &db, &err) != VL_OK) {
    fprintf(stderr, "flow_models: %s\n", err.msg);
    return 1;
  }
  vl_plot_curve curves[N_MODELS];
  vl_point *pts[N_MODELS] = {0};
  int rc = 0;
  for (int k = 0; k < N_MODELS; k++) {
    curves[k].label = vl_flow_factors_name(MODELS[k]);
    pts[k] = curve(&sc, db, MODELS[k], &curves[k].n, &curves[k].meta, &curves[k].h_rms_m);
    if (!pts[k]) rc = 1;
    curves[k].pts = pts[k];
  }
  if (rc == 0) {
    printf("%10s", "v0eta_Pa_m");
    for (int k = 0; k < N_MODELS; k++)
      printf(" | %-11.11s mu  u/h  fluid", curves[k].label);
    putchar('\n');
    for (size_t i = 0; i < curves[0].n; i += 4) {
      printf("%10.1e", pts[0][i].v0_m_s * curves[0].meta.eta_pa_s);
      for (int k = 0; k < N_MODELS; k++) {
        const vl_point *p = &pts[k][i];
        if (p->converged)
          printf(" | %8.4f %7.3f %5.2f      ", p->mu, p->u_min_m / curves[k].h_rms_m,
                 p->fluid_load_fraction);
        else
          printf(" | %8s %7s %5s      ", "failed", "-", "-");
      }
      putchar('\n');
    }
    vl_plot_options opt;
    vl_plot_options_defaults(&opt);
    opt.mark_half_load = true;
    char path[4096], title[512];
    snprintf(title, sizeof title, "%s: flow-factor models", sc.title[0] ? sc.title : case_path);
    opt.title = title;
    snprintf(path, sizeof path, "%s-mu", stem);
    if (vl_plot_compare(path, N_MODELS, curves, VL_SWEEP_V0_ETA, VL_PLOT_Y_MU, &opt, NULL, &err) !=
            VL_OK ||
        (snprintf(path, sizeof path, "%s-umin", stem),
         vl_plot_compare(path, N_MODELS, curves, VL_SWEEP_V0_ETA, VL_PLOT_Y_U_MIN, &opt, NULL,
                         &err)) != VL_OK) {
      fprintf(stderr, "flow_models: %s\n", err.msg);
      rc = 1;
    }
  }
  for (int k = 0; k < N_MODELS; k++)
    free(pts[k]);
  vl_db_close(db);
  return rc;
}
