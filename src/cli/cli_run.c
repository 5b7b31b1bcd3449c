/* `viscolube run SCENE [--out DIR] [--json]` */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"
#include "viscolube/database.h"
#include "viscolube/output.h"
#include "viscolube/scene.h"
#include "viscolube/simulation.h"

static void run_usage(FILE *out) {
  fputs("usage: viscolube run SCENE [--out DIR] [--json]\n"
        "\n"
        "Runs the sweep of a scene file (see cases/ and README.md) and writes\n"
        "  DIR/curve.csv         one row per speed (mu and its four components, separations,\n"
        "                        contact width, load shares, |Er(wH)|, a_H, Q, convergence)\n"
        "  DIR/fields/NNN.csv    x, pressures, separation, contact area at the speeds of\n"
        "                        [sweep] fields_at (NNN = row of curve.csv, from 000)\n"
        "A scene whose [materials] fluid lists several fluids runs one curve per fluid,\n"
        "written to DIR/<fluid>/ (with --json: an object keyed by fluid).\n"
        "DIR defaults to out/<scene name>. Prints a short table, or with --json the curve\n"
        "as a JSON array. Exit status 0 when every point converged, 7 when some did not\n"
        "(they are still written, flagged converged = 0).\n",
        out);
}

/* mkdir -p */
static int make_dirs(const char *path) {
  char buf[4096];
  snprintf(buf, sizeof buf, "%s", path);
  for (char *p = buf + 1; *p; p++) {
    if (*p != '/') continue;
    *p = '\0';
    if (mkdir(buf, 0777) != 0 && errno != EEXIST) return -1;
    *p = '/';
  }
  if (mkdir(buf, 0777) != 0 && errno != EEXIST) return -1;
  return 0;
}

typedef struct {
  vl_simulation *sim;
  const char *out_dir;
  vl_fields fields;
  int tty;
  int io_failed;
  vl_error err;
} run_ctx;

static void on_point(void *user, size_t i, size_t total, const vl_point *pt,
                     const vl_contact *contact) {
  run_ctx *ctx = user;
  if (ctx->tty) {
    fprintf(stderr, "\r  point %zu/%zu  v0 = %-10.3g m/s  %s", i + 1, total, pt->v0_m_s,
            pt->converged ? "ok       " : "FAILED   ");
    if (i + 1 == total) fputc('\n', stderr);
    fflush(stderr);
  }
  if (!vl_simulation_wants_fields(ctx->sim, i) || !pt->converged || ctx->io_failed) return;
  vl_contact_fields(contact, &ctx->fields);
  char path[4200];
  snprintf(path, sizeof path, "%s/fields/%03zu.csv", ctx->out_dir, i);
  if (vl_write_fields_csv(path, &ctx->fields, vl_contact_a0(contact), &ctx->err) != VL_OK)
    ctx->io_failed = 1;
}

/* Runs one curve of the scene (one fluid) into out_dir. *failed counts the
 * points that did not converge. json_sep: NULL for a single curve, else the
 * key this curve gets in the JSON object. */
static vl_status run_one(const char *scene_path, const vl_scene *scene, vl_db *db,
                         const char *out_dir, int json, const char *json_key, size_t *failed,
                         vl_error *err) {
  vl_simulation *sim = NULL;
  vl_point *pts = NULL;
  double *buf = NULL;
  run_ctx ctx = {0};
  vl_status st = vl_simulation_create(scene, db, &sim, err);
  if (st != VL_OK) goto done;
  size_t n = vl_simulation_points(sim), grid = vl_contact_grid(vl_simulation_contact(sim));
  char fields_dir[4200];
  snprintf(fields_dir, sizeof fields_dir, "%s/fields", out_dir);
  if (make_dirs(out_dir) != 0 || (scene->n_fields_at && make_dirs(fields_dir) != 0)) {
    vl_error_set(err, "%s: cannot create output directory: %s", out_dir, strerror(errno));
    st = VL_EIO;
    goto done;
  }
  pts = calloc(n, sizeof *pts);
  buf = calloc(6 * grid, sizeof *buf);
  if (!pts || !buf) {
    vl_error_set(err, "out of memory");
    st = VL_ENOMEM;
    goto done;
  }
  ctx.fields = (vl_fields){grid,           buf,           buf + grid, buf + 2 * grid,
                           buf + 3 * grid, buf + 4 * grid, buf + 5 * grid};
  ctx.sim = sim;
  ctx.out_dir = out_dir;
  ctx.tty = isatty(STDERR_FILENO);
  const vl_contact *contact = vl_simulation_contact(sim);
  if (!json)
    printf("scene %s%s%s%s%s: %zu points, grid %zu on [%g, %g] a0, a0 = %.4g m, p0 = %.4g Pa\n",
           scene_path, scene->title[0] ? " - " : "", scene->title,
           scene->effects.fluid ? ", fluid " : "", scene->effects.fluid ? scene->fluid : "", n,
           grid, scene->domain_min_a0, scene->domain_max_a0, vl_contact_a0(contact),
           vl_contact_p0(contact));
  vl_sweep_stats stats;
  st = vl_simulation_run(sim, pts, on_point, &ctx, &stats, err);
  if (st != VL_OK) goto done;
  if (ctx.io_failed) {
    *err = ctx.err;
    st = VL_EIO;
    goto done;
  }
  vl_curve_meta meta = {vl_simulation_eta(sim), vl_simulation_tau(sim), vl_contact_a0(contact)};
  char curve_path[4200];
  snprintf(curve_path, sizeof curve_path, "%s/curve.csv", out_dir);
  st = vl_write_curve_csv(curve_path, n, pts, &meta, err);
  if (st != VL_OK) goto done;
  *failed += stats.failed;
  if (json) {
    if (json_key) printf("\"%s\": ", json_key);
    vl_print_curve_json(stdout, n, pts, &meta);
  } else {
    printf("%11s %11s %10s %10s %10s %10s %10s %10s %12s %4s %4s\n", "v0_m_s",
           vl_sweep_quantity_name(scene->quantity), "mu", "mu_Rc", "mu_Rf", "mu_Sc", "mu_Sf",
           "u_min_m", "regime", "conv", "iter");
    for (size_t i = 0; i < n; i++) {
      const vl_point *p = &pts[i];
      double q = scene->quantity == VL_SWEEP_V0       ? p->v0_m_s
                 : scene->quantity == VL_SWEEP_V0_ETA ? p->v0_m_s * meta.eta_pa_s
                                                      : p->v0_m_s * meta.tau_s / meta.a0_m;
      if (p->converged)
        printf("%11.4g %11.4g %10.4g %10.3g %10.3g %10.3g %10.3g %10.4g %12s %4s %4ld\n",
               p->v0_m_s, q, p->mu, p->mu_Rc + 0.0, p->mu_Rf + 0.0, p->mu_Sc + 0.0,
               p->mu_Sf + 0.0, p->u_min_m, vl_regime_name(p->regime), "yes", p->iterations);
      else
        printf("%11.4g %11.4g %10s %10s %10s %10s %10s %10s %12s %4s %4ld\n", p->v0_m_s, q, "-",
               "-", "-", "-", "-", "-", "-", "NO", p->iterations);
    }
    printf("%zu converged, %zu failed, %ld Newton iterations, %.3f s (%.1f ms per point)\n",
           stats.converged, stats.failed, stats.newton_iterations, stats.seconds,
           1e3 * stats.seconds / (double)n);
    printf("wrote %s%s\n", curve_path, scene->n_fields_at ? " and fields/" : "");
  }
done:
  free(buf);
  free(pts);
  vl_simulation_free(sim);
  return st;
}

int vl_cli_run(const vl_cli_globals *g, int argc, char **argv) {
  const char *scene_path = NULL, *out_dir = NULL;
  int json = 0;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
      run_usage(stdout);
      return 0;
    } else if (!strcmp(argv[i], "--json")) {
      json = 1;
    } else if (!strcmp(argv[i], "--out")) {
      if (i + 1 >= argc) {
        fputs("viscolube run: option --out needs a DIR\n", stderr);
        return 2;
      }
      out_dir = argv[++i];
    } else if (argv[i][0] == '-') {
      fprintf(stderr, "viscolube run: unknown option '%s' (see viscolube run --help)\n", argv[i]);
      return 2;
    } else if (!scene_path) {
      scene_path = argv[i];
    } else {
      fprintf(stderr, "viscolube run: one scene at a time (got '%s' and '%s')\n", scene_path,
              argv[i]);
      return 2;
    }
  }
  if (!scene_path) {
    run_usage(stderr);
    return 2;
  }
  vl_error err = {{0}};
  vl_scene scene;
  vl_db *db = NULL;
  int rc = 0;
  size_t failed = 0;
  char default_dir[2048];
  vl_status st = vl_scene_load(scene_path, &scene, &err);
  if (st != VL_OK) goto fail;
  if (!out_dir) {
    const char *base = strrchr(scene_path, '/');
    base = base ? base + 1 : scene_path;
    /* drop the extension only: fig03-rough-0.1um.ini -> out/fig03-rough-0.1um */
    const char *dot = strrchr(base, '.');
    size_t stem = dot && dot != base ? (size_t)(dot - base) : strlen(base);
    snprintf(default_dir, sizeof default_dir, "out/%.*s", (int)stem, base);
    out_dir = default_dir;
  }
  st = vl_db_open(g->db_path, &db, &err);
  if (st != VL_OK) goto fail;
  if (scene.n_fluids <= 1) {
    st = run_one(scene_path, &scene, db, out_dir, json, NULL, &failed, &err);
    if (st != VL_OK) goto fail;
  } else {
    /* one curve per fluid, each in DIR/<fluid>/ */
    if (json) fputs("{\n", stdout);
    for (size_t k = 0; k < scene.n_fluids; k++) {
      vl_scene one = scene;
      snprintf(one.fluid, sizeof one.fluid, "%s", scene.fluids[k]);
      one.n_fluids = 1;
      char dir[4200];
      snprintf(dir, sizeof dir, "%s/%s", out_dir, one.fluid);
      if (json && k) fputs(",\n", stdout);
      st = run_one(scene_path, &one, db, dir, json, one.fluid, &failed, &err);
      if (st != VL_OK) goto fail;
    }
    if (json) fputs("}\n", stdout);
  }
  if (failed) rc = vl_status_exit_code(VL_ENOCONV);
  goto done;
fail:
  fprintf(stderr, "viscolube run: %s\n", err.msg[0] ? err.msg : vl_status_name(st));
  rc = vl_status_exit_code(st);
done:
  vl_db_close(db);
  return rc;
}
