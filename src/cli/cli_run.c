/* `viscolube run SCENE [--out DIR] [--json] [--plot]`, and `viscolube seal
 * SCENE ...`: the same run of a seal's two strokes with its own outputs
 * (cli_seal.c). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"
#include "cli_options.h"

static void run_usage(FILE *out) {
  fputs("usage: viscolube run SCENE [--out DIR] [--json] [--plot] [--quiet]\n"
        "\n"
        "Runs the sweep of a scene file (see cases/ and README.md) and writes\n"
        "  DIR/curve.csv         one row per speed (mu and its four components, separations,\n"
        "                        contact width, load shares, |Er(wH)|, a_H, Q, convergence)\n"
        "  DIR/fields/NNN.csv    x, pressures, separation, contact area at the speeds of\n"
        "                        [sweep] fields_at (NNN = row of curve.csv, from 000)\n"
        "With --plot, figures next to them, each as PNG and SVG:\n"
        "  DIR/stribeck          mu and its four components against the sweep quantity,\n"
        "                        the fields_at speeds numbered 1, 2, ...\n"
        "  DIR/separation        minimum separation u_min/h_rms (u_min in um when smooth)\n"
        "  DIR/fields-pc, -pf, -u  p_c/p0, p_f/p0 (wet) and u/h_rms against x/a0, one curve\n"
        "                        per fields_at speed, labelled with its number\n"
        "A ball or an ellipsoid ([contact] geometry, a dry point contact) writes its 2-D\n"
        "fields (x_m, y_m, p_c, u of the half y >= 0) and, with --plot, DIR/map-pc-K and\n"
        "DIR/map-u-K (p_c/p0 and u over the contact plane, the Hertz ellipse dashed) for\n"
        "the K-th fields_at speed instead of separation and fields-*; its curve.csv adds\n"
        "the contact area, extents and the minimum film's position.\n"
        "Points that did not converge are drawn as hollow circles above the x axis,\n"
        "never joined to their neighbours.\n"
        "A scene whose [materials] fluid lists several fluids runs one curve per fluid,\n"
        "written to DIR/<fluid>/ (with --json: an object keyed by fluid); with --plot also\n"
        "DIR/stribeck-all (mu of every fluid on one axis) and, for one-term compounds,\n"
        "DIR/rolling-all (mu_Rc + mu_Rf against v0 tau/a0).\n"
        "Last, DIR/run.json records the run: the command, the scene's text, the materials\n"
        "with their database fingerprints, the numerics of each contact, the program's\n"
        "version and commit, start and end times (UTC), the points converged and failed,\n"
        "the files written and those that could not be (a full disk: the others are kept,\n"
        "and named on stderr). Files of an earlier run listed in its run.json and not\n"
        "rewritten are removed; other files in DIR are left alone, named in a warning. A\n"
        "run interrupted by Ctrl-C (SIGINT) or SIGTERM puts the earlier run back as it\n"
        "was (its files and run.json); killed outright, it leaves no run.json. Every file\n"
        "is written whole: a temporary renamed into place.\n"
        "DIR defaults to out/<scene name>; it is checked (created, writable, not a file)\n"
        "before anything is computed. Prints a short table, or with --json the curve as a\n"
        "JSON array. After the table, on stderr: one line per kind of model-validity\n"
        "warning with the points it applies to (the warnings column of curve.csv; with\n"
        "--json only in the JSON), and the points that did not converge with their speed,\n"
        "iterations and residual. --quiet leaves out the warnings and the progress line.\n"
        "Exit status: 0 when every point converged, 7 when some did not (they are still\n"
        "written, flagged converged = 0), 2 bad scene or option, 3 unknown material,\n"
        "5 database error, 6 file error (e.g. --out not writable, a file that did not fit,\n"
        "standard output lost).\n",
        out);
}

typedef struct {
  vl_simulation *sim;
  const char *out_dir;
  vl_manifest *man; /* the files written, and those that could not be */
  vl_fields fields;
  int tty;
  int quiet;
  double t_start; /* for the progress line */
  /* --plot: the fields of the fields_at speeds, kept for the figures */
  size_t n_kept;
  size_t *kept_index; /* point index of each kept slot */
  vl_fields *kept;    /* n = 0 while (or when) the point has not converged */
  double *kept_buf;
  /* a point contact ([contact] geometry = ball, ellipsoid): its 2-D fields,
   * the kept ones as maps (kept_map[k], cells kept_cells[k], 0 when the
   * point has not converged) */
  double *map_buf;
  vl_plot_map_data *kept_map;
  size_t *kept_cells;
  bool lubricated; /* a point contact with the fluid effect: p_f fields and maps */
  bool rough;      /* and with roughness: p_c maps too */
} run_ctx;

/* The progress line of point i (on a terminal, unless quiet). */
static void progress(const run_ctx *ctx, size_t i, size_t total, const vl_point *pt) {
  if (ctx->tty && !ctx->quiet) {
    /* elapsed, and the rest at the mean cost so far (points differ, so
     * "about") */
    double el = vl_cli_now_s() - ctx->t_start,
           rest = el / (double)(i + 1) * (double)(total - i - 1);
    fprintf(stderr, "\r  point %zu/%zu  v0 = %-10.3g m/s  %s  %.1f s, about %.0f s to go   ", i + 1,
            total, pt->v0_m_s, pt->converged ? "ok    " : "FAILED", el, rest);
    if (i + 1 == total) fputc('\n', stderr);
    fflush(stderr);
  }
}

static void on_point(void *user, size_t i, size_t total, const vl_point *pt,
                     const vl_contact *contact) {
  run_ctx *ctx = user;
  progress(ctx, i, total, pt);
  if (!vl_simulation_wants_fields(ctx->sim, i) || !pt->converged) return;
  vl_fields *f = &ctx->fields;
  for (size_t k = 0; k < ctx->n_kept; k++)
    if (ctx->kept_index[k] == i) f = &ctx->kept[k];
  /* automatic numerics lay out each run of points anew: as many values as
   * this point's contact has cells (the buffers hold the most a contact can) */
  f->n = vl_contact_grid(contact);
  vl_contact_fields(contact, f);
  char path[4200];
  snprintf(path, sizeof path, "%s/fields/%03zu.csv", ctx->out_dir, i);
  /* a file that does not fit (a full disk) is noted; the sweep goes on and
   * the files after it are still tried: smaller ones may fit */
  vl_error err = {{0}};
  vl_status st = vl_write_fields_csv(path, f, vl_contact_a0(contact), &err);
  vl_cli_manifest_file(ctx->man, path, st, &err);
}

/* The cells of a point contact's field along y (cell k = ix ny + iy: the
 * cells before x changes). */
static size_t cells_across(const double *x_m, size_t n) {
  size_t ny = 1;
  while (ny < n && x_m[ny] == x_m[0])
    ny++;
  return ny;
}

/* A point contact's point: the progress line, its 2-D fields at the
 * fields_at speeds (DIR/fields/NNN.csv) and, with --plot, kept for the
 * maps. */
static void on_ball_point(void *user, size_t i, size_t total, const vl_point *pt,
                          const vl_point_contact *c) {
  run_ctx *ctx = user;
  progress(ctx, i, total, pt);
  if (!vl_simulation_wants_fields(ctx->sim, i) || !pt->converged || !c) return;
  size_t n = vl_point_contact_cells(c), cap = VL_BALL_MAX_CELLS, slot = ctx->n_kept;
  for (size_t k = 0; k < ctx->n_kept; k++)
    if (ctx->kept_index[k] == i) slot = k;
  double *b = ctx->map_buf + 5 * cap * (slot < ctx->n_kept ? slot + 1 : 0);
  vl_fields2d f = {b, b + cap, b + 2 * cap, b + 3 * cap, b + 4 * cap};
  vl_point_contact_fields(c, &f);
  bool wet = ctx->lubricated;
  if (slot < ctx->n_kept) {
    ctx->kept_cells[slot] = n;
    ctx->kept_map[slot] = (vl_plot_map_data){n / cells_across(f.x_m, n),
                                             cells_across(f.x_m, n),
                                             f.x_m,
                                             f.y_m,
                                             f.p_c_pa,
                                             f.u_m,
                                             f.p_f_pa};
  }
  char path[4200];
  snprintf(path, sizeof path, "%s/fields/%03zu.csv", ctx->out_dir, i);
  vl_error err = {{0}};
  vl_status st = vl_write_fields2d_csv(path, n, f.x_m, f.y_m, f.p_c_pa, f.u_m,
                                       wet ? f.p_f_pa : NULL, vl_simulation_a0(ctx->sim), &err);
  vl_cli_manifest_file(ctx->man, path, st, &err);
}

/* A point contact's buffers: one set of fields, and one per kept speed
 * (--plot). */
static vl_status ball_buffers(run_ctx *ctx, size_t n, bool plot, vl_error *err) {
  size_t cap = VL_BALL_MAX_CELLS;
  for (size_t i = 0; plot && i < n; i++)
    ctx->n_kept += vl_simulation_wants_fields(ctx->sim, i);
  ctx->map_buf = calloc(5 * cap * (ctx->n_kept + 1), sizeof *ctx->map_buf);
  ctx->kept_index = calloc(ctx->n_kept + 1, sizeof *ctx->kept_index);
  ctx->kept_map = calloc(ctx->n_kept + 1, sizeof *ctx->kept_map);
  ctx->kept_cells = calloc(ctx->n_kept + 1, sizeof *ctx->kept_cells);
  if (!ctx->map_buf || !ctx->kept_index || !ctx->kept_map || !ctx->kept_cells) {
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  for (size_t i = 0, k = 0; i < n && k < ctx->n_kept; i++)
    if (vl_simulation_wants_fields(ctx->sim, i)) ctx->kept_index[k++] = i;
  return VL_OK;
}

/* Sets aside the fields of the fields_at speeds for the figures. */
static vl_status keep_fields(run_ctx *ctx, size_t n, size_t grid, vl_error *err) {
  for (size_t i = 0; i < n; i++)
    ctx->n_kept += vl_simulation_wants_fields(ctx->sim, i);
  if (!ctx->n_kept) return VL_OK;
  ctx->kept_index = calloc(ctx->n_kept, sizeof *ctx->kept_index);
  ctx->kept = calloc(ctx->n_kept, sizeof *ctx->kept);
  ctx->kept_buf = calloc(7 * grid * ctx->n_kept, sizeof *ctx->kept_buf);
  if (!ctx->kept_index || !ctx->kept || !ctx->kept_buf) {
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  for (size_t i = 0, k = 0; i < n; i++) {
    if (!vl_simulation_wants_fields(ctx->sim, i)) continue;
    double *b = ctx->kept_buf + 7 * grid * k;
    ctx->kept_index[k] = i;
    ctx->kept[k] = (vl_fields){
        0, b, b + grid, b + 2 * grid, b + 3 * grid, b + 4 * grid, b + 5 * grid, b + 6 * grid};
    k++;
  }
  return VL_OK;
}

/* The sweep quantity of a point, as in the table and the CSV. */
static double sweep_value(vl_sweep_quantity q, const vl_point *p, const vl_curve_meta *m) {
  return q == VL_SWEEP_V0       ? p->v0_m_s
         : q == VL_SWEEP_V0_ETA ? p->v0_m_s * m->eta_pa_s
                                : p->v0_m_s * m->tau_s / m->a0_m;
}

/* The figures' subtitle: the materials and the conditions (compound,
 * surface, fluid or fluids, load, radius, flow-factor model). */
static void scene_subtitle(const vl_scene *scene, vl_simulation *sim, const vl_curve_meta *meta,
                           char *buf, size_t size) {
  char load[48], radius[48], fluids[512] = "";
  vl_plot_format_value(load, sizeof load, scene->load_n_per_m);
  vl_plot_format_value(radius, sizeof radius, scene->radius_m * 1e3);
  if (scene->effects.fluid && scene->n_fluids > 1) /* the legend names them */
    snprintf(fluids, sizeof fluids, " in %zu fluids", scene->n_fluids);
  else if (scene->effects.fluid) {
    char eta[48] = "";
    if (sim) vl_plot_format_value(eta, sizeof eta, vl_simulation_eta(sim));
    snprintf(fluids, sizeof fluids, " in %s%s%s%s", scene->fluid, eta[0] ? " (η = " : "", eta,
             eta[0] ? " Pa s)" : "");
  }
  char body[256];
  if (scene->geometry == VL_GEOMETRY_BALL || scene->geometry == VL_GEOMETRY_ELLIPSOID) {
    /* a point contact: its total load, its radius or radii */
    char ry[48];
    vl_plot_format_value(load, sizeof load, scene->load_n);
    vl_plot_format_value(ry, sizeof ry, scene->radius_y_m * 1e3);
    if (scene->geometry == VL_GEOMETRY_BALL)
      snprintf(body, sizeof body, "ball, W = %s N · R = %s mm", load, radius);
    else
      snprintf(body, sizeof body, "ellipsoid, W = %s N · Rx = %s mm, Ry = %s mm", load, radius, ry);
  } else if (scene->lip) { /* the lip's own parameters: radius_m is not the scene's */
    char tip[48];
    vl_plot_format_value(tip, sizeof tip, scene->lip_tip_radius_m * 1e3);
    snprintf(body, sizeof body, "fN = %s N/m · lip r = %s mm, %g°/%g°", load, tip,
             scene->lip_oil_angle_deg, scene->lip_air_angle_deg);
  } else {
    snprintf(body, sizeof body, "fN = %s N/m · R = %s mm", load, radius);
  }
  int n = snprintf(buf, size, "%s on %s%s · %s", scene->compound,
                   scene->effects.roughness ? scene->surface : "a smooth surface", fluids, body);
  if (meta && meta->flow_factors && n >= 0 && (size_t)n < size)
    n += snprintf(buf + n, size - (size_t)n, " · flow factors %s", meta->flow_factors);
  if (scene->effects.temperature && n >= 0 && (size_t)n < size)
    snprintf(buf + n, size - (size_t)n, " · %g °C", scene->effects.temperature_c);
}

/* What a figure of the scene is about: its title, else its materials. */
static void scene_subject(const vl_scene *scene, char *buf, size_t size) {
  if (scene->title[0])
    snprintf(buf, size, "%s", scene->title);
  else if (scene->effects.fluid)
    snprintf(buf, size, "%s on %s in %s", scene->compound,
             scene->effects.roughness ? scene->surface : "a smooth surface",
             scene->n_fluids > 1 ? "several fluids" : scene->fluid);
  else
    snprintf(buf, size, "%s on %s, dry", scene->compound,
             scene->effects.roughness ? scene->surface : "a smooth surface");
}

/* A figure's title: what it shows, then what it is about. */
static void figure_title(char *buf, size_t size, const char *kind, const char *subject) {
  snprintf(buf, size, "%s — %s", kind, subject);
}

/* The kept fields' speeds, numbered from 1 as the figures mark them:
 * marks[k] (their points) and labels[k] ("1: v0 = 0.01 m/s"). */
static void plot_marks(const vl_scene *scene, const vl_point *pts, const vl_curve_meta *meta,
                       const run_ctx *ctx, size_t *marks, char (*labels)[96],
                       const char **label_ptrs) {
  static const char *const pre[] = {"v₀ = ", "v₀η = ", "v₀τ/a₀ = "};
  static const char *const post[] = {" m/s", " Pa m", ""};
  for (size_t k = 0; k < ctx->n_kept; k++) {
    marks[k] = ctx->kept_index[k];
    char v[48];
    vl_plot_format_value(v, sizeof v, sweep_value(scene->quantity, &pts[marks[k]], meta));
    snprintf(labels[k], sizeof labels[k], "%zu: %s%s%s", k + 1, pre[scene->quantity], v,
             post[scene->quantity]);
    label_ptrs[k] = labels[k];
  }
}

/* The fields figures (p_c, p_f when wet, u) of the kept speeds, each
 * recorded in the manifest and appended to list (length *len). */
static vl_status plot_field_figures(const char *out_dir, const vl_scene *scene, vl_simulation *sim,
                                    double h_rms, const run_ctx *ctx, const char **label_ptrs,
                                    const char *subject, const vl_plot_options *opt_in, char *list,
                                    size_t list_size, size_t *len, vl_error *err) {
  vl_plot_scales sc = {vl_simulation_a0(sim), vl_simulation_p0(sim), h_rms};
  static const struct {
    vl_plot_field field;
    const char *name, *kind;
  } figs[] = {{VL_PLOT_FIELD_PC, "fields-pc", "Contact pressure"},
              {VL_PLOT_FIELD_PF, "fields-pf", "Fluid pressure"},
              {VL_PLOT_FIELD_U, "fields-u", "Separation"}};
  char stem[4200], title[1600];
  vl_plot_options opt = *opt_in;
  opt.title = title;
  for (size_t k = 0; k < sizeof figs / sizeof figs[0]; k++) {
    if (figs[k].field == VL_PLOT_FIELD_PF && !scene->effects.fluid) continue;
    snprintf(stem, sizeof stem, "%s/%s", out_dir, figs[k].name);
    figure_title(title, sizeof title, figs[k].kind, subject);
    vl_status st = vl_plot_fields(stem, figs[k].field, ctx->n_kept, ctx->kept, label_ptrs, &sc,
                                  &opt, NULL, err);
    vl_cli_manifest_figure(ctx->man, stem, st, err);
    if (st != VL_OK && st != VL_EIO) return st;
    if (*len < list_size)
      *len += (size_t)snprintf(list + *len, list_size - *len, ", %s", figs[k].name);
  }
  return VL_OK;
}

/* A point contact's maps of p_c and u at the kept speeds (DIR/map-pc-K,
 * DIR/map-u-K, K as the marks on the Stribeck figure), the relaxed Hertz
 * ellipse over them; appended to list. */
static vl_status plot_maps(const char *out_dir, vl_simulation *sim, const run_ctx *ctx,
                           const char **label_ptrs, const vl_plot_options *opt_in,
                           const char *subject, char *list, size_t list_size, size_t *len,
                           vl_error *err) {
  vl_plot_scales sc = {vl_simulation_a0(sim), vl_simulation_p0(sim), 0.0};
  double ax = 0.0, by = 0.0;
  vl_simulation_hertz_ellipse(sim, &ax, &by);
  /* the contact pressure where the solids touch (dry or rough), the
   * fluid's where there is one (a lubricated smooth ball: only it), the
   * separation always */
  static const vl_plot_field all[3] = {VL_PLOT_FIELD_PC, VL_PLOT_FIELD_PF, VL_PLOT_FIELD_U};
  static const char *const all_names[3] = {"pc", "pf", "u"};
  static const char *const all_kinds[3] = {"Contact pressure", "Fluid pressure", "Separation"};
  const bool drawn[3] = {!ctx->lubricated || ctx->rough, ctx->lubricated, true};
  vl_plot_field fields[3];
  const char *names[3], *kinds[3];
  int nf = 0;
  for (int q = 0; q < 3; q++)
    if (drawn[q]) fields[nf] = all[q], names[nf] = all_names[q], kinds[nf++] = all_kinds[q];
  for (size_t k = 0; k < ctx->n_kept; k++) {
    if (!ctx->kept_cells[k]) continue; /* did not converge: no map */
    for (int u = 0; u < nf; u++) {
      char stem[4200], kind[160], title[1800];
      vl_plot_options opt = *opt_in;
      /* the speed first: a long subject is cut at the figure's edge */
      snprintf(kind, sizeof kind, "%s at %s", kinds[u], label_ptrs[k]);
      figure_title(title, sizeof title, kind, subject);
      opt.title = title;
      snprintf(stem, sizeof stem, "%s/map-%s-%zu", out_dir, names[u], k + 1);
      vl_status st = vl_plot_map(stem, fields[u], &ctx->kept_map[k], &sc, ax, by, &opt, NULL, err);
      vl_cli_manifest_figure(ctx->man, stem, st, err);
      if (st != VL_OK && st != VL_EIO) return st;
      if (*len < list_size)
        *len += (size_t)snprintf(list + *len, list_size - *len, ", map-%s-%zu", names[u], k + 1);
    }
  }
  return VL_OK;
}

/* Writes the figures of one curve (see run_usage); names them in *list. */
static vl_status write_plots(const char *out_dir, const vl_scene *scene, const char *fluid_key,
                             vl_simulation *sim, size_t n, const vl_point *pts,
                             const vl_curve_meta *meta, const run_ctx *ctx, char *list,
                             size_t list_size, vl_error *err) {
  char subject[1536], title[1600], subtitle[1024], stem[4200];
  scene_subject(scene, subject, sizeof subject);
  if (fluid_key && scene->title[0]) /* one of several fluids: which (the materials name it) */
    snprintf(subject + strlen(subject), sizeof subject - strlen(subject), " | fluid %s", fluid_key);
  scene_subtitle(scene, sim, meta, subtitle, sizeof subtitle);
  vl_plot_options opt;
  vl_plot_options_defaults(&opt);
  opt.title = title;
  opt.subtitle = subtitle;
  opt.mark_half_load = scene->effects.fluid;
  const vl_psd *psd = vl_simulation_psd(sim);
  double h_rms = psd ? vl_psd_hrms(psd) : 0;
  size_t *marks = NULL;
  char(*labels)[96] = NULL;
  const char **label_ptrs = NULL;
  vl_status st = VL_ENOMEM;
  if (ctx->n_kept) {
    marks = calloc(ctx->n_kept, sizeof *marks);
    labels = calloc(ctx->n_kept, sizeof *labels);
    label_ptrs = calloc(ctx->n_kept, sizeof *label_ptrs);
    if (!marks || !labels || !label_ptrs) {
      vl_error_set(err, "out of memory");
      goto done;
    }
  }
  plot_marks(scene, pts, meta, ctx, marks, labels, label_ptrs);
  /* a figure that does not fit is noted and the next still tried */
  snprintf(stem, sizeof stem, "%s/stribeck", out_dir);
  figure_title(title, sizeof title, "Stribeck curve", subject);
  st = vl_plot_stribeck(stem, n, pts, meta, scene->quantity, ctx->n_kept, marks, &opt, NULL, err);
  vl_cli_manifest_figure(ctx->man, stem, st, err);
  if (st != VL_OK && st != VL_EIO) goto done;
  if (scene->geometry != VL_GEOMETRY_CYLINDER && !scene->effects.fluid) { /* no film */
    size_t len = (size_t)snprintf(list, list_size, "stribeck");
    st = plot_maps(out_dir, sim, ctx, label_ptrs, &opt, subject, list, list_size, &len, err);
    goto done;
  }
  snprintf(stem, sizeof stem, "%s/separation", out_dir);
  figure_title(title, sizeof title, "Minimum separation", subject);
  st = vl_plot_separation(stem, n, pts, meta, scene->quantity, h_rms, ctx->n_kept, marks, &opt,
                          NULL, err);
  vl_cli_manifest_figure(ctx->man, stem, st, err);
  if (st != VL_OK && st != VL_EIO) goto done;
  size_t len = (size_t)snprintf(list, list_size, "stribeck, separation");
  if (scene->geometry != VL_GEOMETRY_CYLINDER) { /* a lubricated ball: its maps */
    st = plot_maps(out_dir, sim, ctx, label_ptrs, &opt, subject, list, list_size, &len, err);
    goto done;
  }
  st = VL_OK; /* the files that did not fit are in the manifest */
  if (ctx->n_kept)
    st = plot_field_figures(out_dir, scene, sim, h_rms, ctx, label_ptrs, subject, &opt, list,
                            list_size, &len, err);
done:
  free(label_ptrs);
  free(labels);
  free(marks);
  return st;
}

/* The console line that states the flow-factor model of a rough film. */
static void print_flow_model(const vl_curve_meta *m) {
  printf("flow factors: %s", m->flow_factors);
  if (m->film_cutoff_m > 0.0) printf(" (film cut-off %g m)", m->film_cutoff_m);
  putchar('\n');
}

/* One curve of a multi-fluid scene, kept for the figures with all fluids. */
typedef struct {
  vl_point *pts;
  size_t n;
  vl_curve_meta meta;
  double h_rms_m;
} kept_curve;

/* The table of a curve: one row per point, then the solver's statistics. */
static void print_table(const vl_scene *scene, size_t n, const vl_point *pts,
                        const vl_curve_meta *meta, const vl_sweep_stats *stats) {
  bool ball = scene->geometry != VL_GEOMETRY_CYLINDER;
  printf("%11s %11s %10s %10s %10s %10s %10s %10s %12s %4s %4s %8s%s\n", "v0_m_s",
         vl_sweep_quantity_name(scene->quantity), "mu", "mu_Rc", "mu_Rf", "mu_Sc", "mu_Sf",
         "u_min_m", "regime", "conv", "iter", "err_est", ball ? "    area_m2" : "");
  for (size_t i = 0; i < n; i++) {
    const vl_point *p = &pts[i];
    double q = sweep_value(scene->quantity, p, meta);
    char est[16] = "-"; /* no estimate: the coarse solve failed */
    if (p->converged && isfinite(p->error_estimate))
      snprintf(est, sizeof est, "%.2g%%", 100.0 * p->error_estimate);
    if (vl_point_unreliable(p)) /* not known to its target: marked as such */
      snprintf(est + strlen(est), sizeof est - strlen(est), "!");
    /* the rolling terms of a moving counter-surface: not applicable, not 0 */
    char rc[16] = "n/a", rf[16] = "n/a";
    if (!p->rolling_na) {
      snprintf(rc, sizeof rc, "%.3g", p->mu_Rc + 0.0);
      snprintf(rf, sizeof rf, "%.3g", p->mu_Rf + 0.0);
    }
    if (p->converged)
      printf("%11.4g %11.4g %10.4g %10s %10s %10.3g %10.3g %10.4g %12s %4s %4ld %8s", p->v0_m_s, q,
             p->mu, rc, rf, p->mu_Sc + 0.0, p->mu_Sf + 0.0, p->u_min_m, vl_regime_name(p->regime),
             "yes", p->iterations, est);
    else
      printf("%11.4g %11.4g %10s %10s %10s %10s %10s %10s %12s %4s %4ld %8s", p->v0_m_s, q, "-",
             "-", "-", "-", "-", "-", "-", "NO", p->iterations, "-");
    if (ball && p->converged)
      printf(" %11.4g", p->ball.contact_area_m2);
    else if (ball)
      printf(" %11s", "-");
    putchar('\n');
  }
  printf("%zu converged, %zu failed, %ld Newton iterations, %.3f s (%.1f ms per point)\n",
         stats->converged, stats->failed, stats->newton_iterations, stats->seconds,
         1e3 * stats->seconds / (double)n);
}

/* What the curves of a run share: where they go and how they are shown. */
typedef struct {
  const char *scene_path;
  vl_db *db;
  vl_json *json; /* NULL for the table, else the writer the curves go to */
  int plot, quiet;
  vl_manifest *man;
  size_t failed;     /* points that did not converge, over the curves */
  size_t unreliable; /* converged, but above their error target or without an estimate */
  int seal;          /* `seal`: both strokes of a seal, with the seal's outputs */
} run_job;

/* The output folders and buffers of a curve of n points into ctx, *pts
 * and *buf (the fields of one point). */
static vl_status curve_prepare(const run_job *job, const vl_scene *scene, vl_simulation *sim,
                               const char *out_dir, size_t n, run_ctx *ctx, vl_point **pts,
                               double **buf, vl_error *err) {
  size_t grid = VL_CONTACT_MAX_CELLS;
  char fields_dir[4200];
  snprintf(fields_dir, sizeof fields_dir, "%s/fields", out_dir);
  if (vl_cli_make_dirs(out_dir) != 0 || (scene->n_fields_at && vl_cli_make_dirs(fields_dir) != 0)) {
    vl_error_set(err, "%s: cannot create output directory: %s", out_dir, strerror(errno));
    return VL_EIO;
  }
  *pts = calloc(n, sizeof **pts);
  *buf = calloc(7 * grid, sizeof **buf);
  if (!*pts || !*buf) {
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  double *b = *buf;
  ctx->fields = (vl_fields){
      grid, b, b + grid, b + 2 * grid, b + 3 * grid, b + 4 * grid, b + 5 * grid, b + 6 * grid};
  ctx->sim = sim;
  ctx->out_dir = out_dir;
  ctx->man = job->man;
  ctx->tty = isatty(STDERR_FILENO);
  ctx->quiet = job->quiet;
  ctx->lubricated = scene->effects.fluid;
  ctx->rough = scene->effects.roughness;
  if (scene->geometry != VL_GEOMETRY_CYLINDER) return ball_buffers(ctx, n, job->plot, err);
  if (job->plot) return keep_fields(ctx, n, grid, err);
  return VL_OK;
}

/* The numerics of the curve's contact into the manifest and, for the
 * table, the line that introduces the curve. */
static void curve_announce(const run_job *job, const vl_scene *scene, vl_simulation *sim,
                           const char *fluid_key, size_t n) {
  if (scene->geometry != VL_GEOMETRY_CYLINDER) { /* a point contact's numerics, per point */
    char numerics[200];
    snprintf(numerics, sizeof numerics,
             "point contact: cells planned per point (%d across the contact's shorter "
             "semi-axis), target error %g, tolerance %g",
             VL_BALL_CELLS_PER_A0, scene->target_error, scene->tolerance);
    vl_manifest_add_option(job->man, "numerics", numerics);
    if (!job->json)
      printf("scene %s%s%s: %s, %zu points, automatic numerics (target error %g %%), a0 = %.4g "
             "m, p0 = %.4g Pa\n",
             job->scene_path, scene->title[0] ? " - " : "", scene->title,
             vl_geometry_name(scene->geometry), n, 100.0 * scene->target_error,
             vl_simulation_a0(sim), vl_simulation_p0(sim));
    return;
  }
  const vl_contact *contact = vl_simulation_contact(sim);
  vl_contact_numerics_used nu;
  vl_contact_numerics_of(contact, &nu);
  vl_manifest_add_numerics(job->man, fluid_key, &nu, vl_contact_a0(contact),
                           vl_contact_p0(contact));
  if (scene->auto_numerics) { /* the base the automatic numerics start from, and their target */
    char target[64];
    snprintf(target, sizeof target, "automatic, target error %g", scene->target_error);
    vl_manifest_add_option(job->man, "numerics", target);
  }
  if (job->json) return;
  char numerics[160];
  if (scene->auto_numerics)
    snprintf(numerics, sizeof numerics, "automatic numerics (target error %g %%)",
             100.0 * scene->target_error);
  else
    snprintf(numerics, sizeof numerics, "grid %zu on [%g, %g] a0", scene->grid,
             scene->domain_min_a0, scene->domain_max_a0);
  printf("scene %s%s%s%s%s: %zu point%s, %s, a0 = %.4g m, p0 = %.4g Pa\n", job->scene_path,
         scene->title[0] ? " - " : "", scene->title, scene->effects.fluid ? ", fluid " : "",
         scene->effects.fluid ? scene->fluid : "", n, vl_cli_plural(n), numerics,
         vl_contact_a0(contact), vl_contact_p0(contact));
}

/* The curve's description for the writers, and its lines before the table. */
static vl_curve_meta curve_meta(const run_job *job, const vl_scene *scene, vl_simulation *sim) {
  vl_curve_meta meta = {
      vl_simulation_eta(sim),           vl_simulation_tau(sim), vl_simulation_a0(sim), NULL, 0.0,
      vl_simulation_shear_law_text(sim)};
  meta.flow_factors = vl_simulation_flow_factors(sim, &meta.film_cutoff_m);
  if (!job->json && meta.flow_factors) print_flow_model(&meta);
  if (!job->json && scene->effects.temperature)
    printf("at %g C: compound times x a_T = %.4g, fluid viscosity %.4g Pa s\n",
           vl_simulation_temperature_c(sim), vl_simulation_shift_factor(sim),
           vl_simulation_eta(sim));
  return meta;
}

/* `seal`: DIR/seal.csv, DIR/seal.json, with --plot the figure DIR/seal, and
 * the table of both strokes (or the seal's JSON) on stdout. */
static vl_status seal_outputs(run_job *job, const vl_scene *scene, vl_simulation *sim,
                              const char *out_dir, const char *fluid_key, size_t n,
                              const vl_point *pts, const vl_sweep_stats *stats, vl_error *err) {
  char title[1536], subtitle[1024];
  snprintf(title, sizeof title, "%s%s%s", scene->title[0] ? scene->title : scene->path,
           fluid_key ? " | fluid " : "", fluid_key ? fluid_key : "");
  scene_subtitle(scene, sim, NULL, subtitle, sizeof subtitle);
  vl_plot_options opt;
  vl_plot_options_defaults(&opt);
  opt.title = title, opt.subtitle = subtitle;
  vl_status st = vl_cli_seal_files(job->man, out_dir, n, pts, job->plot ? &opt : NULL, err);
  if (st != VL_OK) return st;
  if (job->json) {
    if (fluid_key) vl_json_key(job->json, fluid_key);
    vl_seal_json(job->json, n, pts);
    return VL_OK;
  }
  const vl_sweep_stats *in = vl_simulation_instroke_stats(sim);
  vl_cli_print_seal_table(n, pts);
  printf("outstroke: %zu converged, %zu failed, %ld Newton iterations, %.3f s; instroke: %zu "
         "converged, %zu failed, %ld Newton iterations, %.3f s\n",
         stats->converged, stats->failed, stats->newton_iterations, stats->seconds, in->converged,
         in->failed, in->newton_iterations, in->seconds);
  char path[4200];
  snprintf(path, sizeof path, "%s/seal.csv", out_dir);
  printf("wrote %s and seal.json\n", path);
  return VL_OK;
}

/* The instroke's failures, warnings and points above their target on
 * stderr, counted into the exit status (`seal`, and `run` of a scene with
 * [seal] stroke = both: its rows are the outstroke's, the instroke's points
 * fail or miss their target just as much). */
static vl_status instroke_lists(run_job *job, const char *cmd, const char *fluid_key, size_t n,
                                const vl_point *pts) {
  vl_point *in = vl_cli_instroke_points(n, pts);
  if (!in) return VL_ENOMEM;
  char label[VL_NAME_MAX + 16];
  snprintf(label, sizeof label, "%s%sinstroke", fluid_key ? fluid_key : "", fluid_key ? ", " : "");
  if (!job->json && !job->quiet) vl_cli_print_warnings(stderr, label, n, in);
  job->failed += vl_cli_print_failures(stderr, cmd, label, n, in, "written with empty cells");
  job->unreliable += vl_cli_print_unreliable(stderr, cmd, label, n, in);
  free(in);
  return VL_OK;
}

/* After the sweep: DIR/curve.csv, the figures, the table or JSON, then the
 * warnings and failures on stderr. */
static vl_status curve_outputs(run_job *job, const vl_scene *scene, vl_simulation *sim,
                               const char *out_dir, const char *fluid_key, size_t n,
                               const vl_point *pts, const vl_curve_meta *meta,
                               const vl_sweep_stats *stats, const run_ctx *ctx, vl_error *err) {
  char curve_path[4200];
  snprintf(curve_path, sizeof curve_path, "%s/curve.csv", out_dir);
  vl_error werr = {{0}};
  vl_status cst = vl_write_curve_csv(curve_path, n, pts, meta, &werr);
  vl_cli_manifest_file(job->man, curve_path, cst, &werr);
  job->failed += stats->failed;
  char plots[256] = "";
  if (job->plot) {
    vl_status st =
        write_plots(out_dir, scene, fluid_key, sim, n, pts, meta, ctx, plots, sizeof plots, err);
    if (st != VL_OK) return st;
  }
  if (job->seal) {
    vl_status st = seal_outputs(job, scene, sim, out_dir, fluid_key, n, pts, stats, err);
    if (st != VL_OK) return st;
  } else if (job->json) {
    if (fluid_key) vl_json_key(job->json, fluid_key);
    vl_curve_json(job->json, n, pts, meta);
  } else {
    print_table(scene, n, pts, meta, stats);
  }
  if (!job->json) {
    if (cst == VL_OK) printf("wrote %s%s\n", curve_path, scene->n_fields_at ? " and fields/" : "");
    if (job->plot)
      printf("plots (png, svg) in %s: %s%s\n", out_dir, plots, job->seal ? ", seal" : "");
  }
  /* stdout first, so that the lines follow the table in a shared log */
  fflush(stdout);
  const char *cmd = job->seal ? "seal" : "run";
  if (!job->json && !job->quiet) vl_cli_print_warnings(stderr, fluid_key, n, pts);
  char where[4300];
  snprintf(where, sizeof where, "written with converged = 0 in %s", curve_path);
  vl_cli_print_failures(stderr, cmd, fluid_key, n, pts, where);
  job->unreliable += vl_cli_print_unreliable(stderr, cmd, fluid_key, n, pts);
  bool both = n && pts[0].seal.stroke == VL_STROKE_BOTH;
  return job->seal || both ? instroke_lists(job, cmd, fluid_key, n, pts) : VL_OK;
}

/* Runs one curve of the scene (one fluid) into out_dir. fluid_key: NULL
 * for a single curve, else the name of this curve's fluid (its key in the
 * JSON object, in the figures' title). keep (may be NULL) gets the points
 * for the figures with every fluid. */
static vl_status run_one(run_job *job, const vl_scene *scene, const char *out_dir,
                         const char *fluid_key, kept_curve *keep, vl_error *err) {
  vl_simulation *sim = NULL;
  vl_point *pts = NULL;
  double *buf = NULL;
  run_ctx ctx = {0};
  vl_status st = vl_simulation_create(scene, job->db, &sim, err);
  if (st != VL_OK) goto done;
  size_t n = vl_simulation_points(sim);
  st = curve_prepare(job, scene, sim, out_dir, n, &ctx, &pts, &buf, err);
  if (st != VL_OK) goto done;
  ctx.t_start = vl_cli_now_s();
  curve_announce(job, scene, sim, fluid_key, n);
  vl_curve_meta meta = curve_meta(job, scene, sim);
  if (meta.shear_law) { /* a stored pair's law gave sigma_s: say which */
    char key[128];
    snprintf(key, sizeof key, "sigma_s%s%s", fluid_key ? "_" : "", fluid_key ? fluid_key : "");
    vl_manifest_add_text(job->man, key, meta.shear_law);
    if (!job->json) printf("sigma_s: %s\n", meta.shear_law);
  }
  vl_sweep_stats stats;
  if (scene->geometry != VL_GEOMETRY_CYLINDER)
    st = vl_simulation_run_point_contact(sim, pts, on_ball_point, &ctx, &stats, err);
  else
    st = vl_simulation_run(sim, pts, on_point, &ctx, &stats, err);
  if (st != VL_OK) goto done;
  vl_manifest_add_counts(job->man, stats.converged, stats.failed);
  st = curve_outputs(job, scene, sim, out_dir, fluid_key, n, pts, &meta, &stats, &ctx, err);
  if (st == VL_OK && keep) {
    const vl_psd *psd = vl_simulation_psd(sim);
    *keep = (kept_curve){pts, n, meta, psd ? vl_psd_hrms(psd) : 0};
    pts = NULL;
  }
done:
  free(ctx.kept_buf);
  free(ctx.kept);
  free(ctx.kept_index);
  free(ctx.map_buf);
  free(ctx.kept_map);
  free(ctx.kept_cells);
  free(buf);
  free(pts);
  vl_simulation_free(sim);
  return st;
}

/* The figures with one curve per fluid: DIR/stribeck-all and, when the
 * Deborah number is defined (one-term compound), DIR/rolling-all. */
static vl_status plot_all_fluids(const vl_scene *scene, const char *out_dir,
                                 const kept_curve *curves, int json, vl_manifest *man,
                                 vl_error *err) {
  vl_plot_curve pc[VL_FLUIDS_MAX];
  char labels[VL_FLUIDS_MAX][VL_NAME_MAX + 64];
  bool deborah = true;
  for (size_t k = 0; k < scene->n_fluids; k++) {
    char eta[48];
    vl_plot_format_value(eta, sizeof eta, curves[k].meta.eta_pa_s);
    /* the viscosity first: a long fluid name is what gets cut in the legend */
    snprintf(labels[k], sizeof labels[k], "η = %s Pa s (%s)", eta, scene->fluids[k]);
    pc[k] =
        (vl_plot_curve){labels[k], curves[k].n, curves[k].pts, curves[k].meta, curves[k].h_rms_m};
    if (!(curves[k].meta.tau_s > 0 && curves[k].meta.a0_m > 0)) deborah = false;
  }
  char subject[1536], title[1600];
  scene_subject(scene, subject, sizeof subject);
  vl_plot_options opt;
  vl_plot_options_defaults(&opt);
  opt.title = title;
  opt.mark_half_load = scene->effects.fluid;
  char stem[4200];
  snprintf(stem, sizeof stem, "%s/stribeck-all", out_dir);
  figure_title(title, sizeof title, "Friction coefficient in each fluid", subject);
  char subtitle[1024];
  scene_subtitle(scene, NULL, &curves[0].meta, subtitle, sizeof subtitle);
  opt.subtitle = subtitle;
  vl_status st =
      vl_plot_compare(stem, scene->n_fluids, pc, scene->quantity, VL_PLOT_Y_MU, &opt, NULL, err);
  vl_cli_manifest_figure(man, stem, st, err);
  if (st != VL_OK && st != VL_EIO) return st;
  if (deborah) {
    snprintf(stem, sizeof stem, "%s/rolling-all", out_dir);
    figure_title(title, sizeof title, "Rolling friction in each fluid", subject);
    opt.mark_half_load = false;
    st = vl_plot_compare(stem, scene->n_fluids, pc, VL_SWEEP_DEBORAH, VL_PLOT_Y_MU_ROLLING, &opt,
                         NULL, err);
    vl_cli_manifest_figure(man, stem, st, err);
    if (st != VL_OK && st != VL_EIO) return st;
  }
  if (!json)
    printf("plots (png, svg) in %s: stribeck-all%s\n", out_dir, deborah ? ", rolling-all" : "");
  return VL_OK;
}

/* The scene's material names are valid names (a multi-fluid scene makes a
 * folder of each fluid's: "..", "a/b" would leave DIR). */
static vl_status check_names(const vl_scene *scene, vl_error *err) {
  struct {
    const char *key, *name;
  } names[2 + VL_FLUIDS_MAX] = {{"compound", scene->compound}, {"surface", scene->surface}};
  size_t n = 2;
  for (size_t k = 0; k < scene->n_fluids && k < VL_FLUIDS_MAX; k++)
    names[n].key = "fluid", names[n++].name = scene->fluids[k];
  if (scene->n_fluids == 0) names[n].key = "fluid", names[n++].name = scene->fluid;
  for (size_t k = 0; k < n; k++) {
    if (!names[k].name[0]) continue; /* not used by this scene */
    if (vl_db_check_name(names[k].name, err) != VL_OK) {
      vl_error_prefix(err, "%s: [materials] %s", scene->path, names[k].key);
      return VL_EINPUT;
    }
  }
  return VL_OK;
}

/* Every folder the run writes in, checked before anything is computed. */
static vl_status check_outputs(const vl_scene *scene, const char *out_dir, vl_error *err) {
  char dir[4200], fields[4300];
  vl_status st = vl_cli_check_out_dir("--out", out_dir, err);
  for (size_t k = 0; st == VL_OK && k < (scene->n_fluids > 1 ? scene->n_fluids : 1); k++) {
    if (scene->n_fluids > 1)
      snprintf(dir, sizeof dir, "%s/%s", out_dir, scene->fluids[k]);
    else
      snprintf(dir, sizeof dir, "%s", out_dir);
    if (scene->n_fluids > 1) st = vl_cli_check_out_dir("--out", dir, err);
    snprintf(fields, sizeof fields, "%s/fields", dir);
    if (st == VL_OK && scene->n_fields_at) st = vl_cli_check_out_dir("--out", fields, err);
  }
  return st;
}

/* The run's record: the scene (its path and text) and its materials. */
static void run_manifest(vl_manifest *m, vl_db *db, const vl_scene *scene, const char *text) {
  vl_manifest_add_text(m, "scene_path", scene->path);
  vl_manifest_add_text(m, "scene", text);
  vl_cli_manifest_material(m, db, "compound", scene->compound);
  if (scene->effects.roughness && scene->surface[0])
    vl_cli_manifest_material(m, db, "surface", scene->surface);
  for (size_t k = 0; scene->effects.fluid && k < scene->n_fluids; k++)
    vl_cli_manifest_material(m, db, "fluid", scene->fluids[k]);
  if (scene->effects.fluid && scene->n_fluids == 0 && scene->fluid[0])
    vl_cli_manifest_material(m, db, "fluid", scene->fluid);
}

#if defined(__SANITIZE_ADDRESS__)
/* Sanitizer builds only: fontconfig, under PLplot's cairo drivers, keeps
 * caches it never frees (not ours to fix); LeakSanitizer would fail every
 * run with --plot. Open MPI's libraries keep theirs after MPI_Finalize
 * (`study` under mpirun). The summary of suppressed leaks is not printed. */
const char *__lsan_default_suppressions(void);
const char *__lsan_default_suppressions(void) {
  return "leak:libfontconfig.so\nleak:libmpi.so\nleak:libopen-pal.so\nleak:libopen-rte.so\n"
         "leak:libpmix.so\nleak:libhwloc.so\nleak:libevent\n";
}
const char *__lsan_default_options(void);
const char *__lsan_default_options(void) { return "print_suppressions=0"; }
#endif

static void seal_usage(FILE *out) {
  fputs("usage: viscolube seal SCENE [--out DIR] [--json] [--plot] [--quiet]\n"
        "\n"
        "Solves both strokes of a seal over the scene's speeds: the outstroke (the rod\n"
        "leaving the oil side) and the instroke (the profile mirrored, the sealed pressure\n"
        "at the film's outlet), whatever [seal] stroke says. The scene is a seal's:\n"
        "[contact] moving = counterface and [effects] fluid = on (docs/MODEL.md\n"
        "sections 11-13, docs/CASES.md \"seals\"). Writes, besides what `run` writes\n"
        "(curve.csv with the seal columns, fields/, run.json):\n"
        "  DIR/seal.csv   a row per speed, both strokes: friction force per length,\n"
        "                 mu, minimum and central film, flux per unit circumference,\n"
        "                 the error estimates of the friction and of the flux, and with\n"
        "                 [seal] rod_diameter_m and stroke_length_m the volumes carried\n"
        "                 out and back per cycle and whether the seal is tight\n"
        "  DIR/seal.json  the same (null where the CSV is empty)\n"
        "With --plot also DIR/seal (png, svg): the friction force and the flux of\n"
        "both strokes against the speed, besides run's figures.\n"
        "Prints the table of both strokes, or with --json the seal's JSON. Exit\n"
        "status as `run`, counting the points of both strokes: 7 when some did not\n"
        "converge, 8 when some are above their error target, 2 a scene that is not a\n"
        "seal's.\n",
        out);
}

/* The options of `run` and `seal`: -1 to go on, else the exit status (0
 * after --help). */
static int run_options(int seal, int argc, char **argv, const char **scene_path,
                       const char **out_dir, int *json, int *plot, int *quiet) {
  vl_cli_option opts[] = {
      {.name = "--help", .alias = "-h", .kind = VL_CLI_HELP},
      {.name = "--json", .kind = VL_CLI_FLAG, .dest = json},
      {.name = "--plot", .kind = VL_CLI_FLAG, .dest = plot},
      {.name = "--quiet", .alias = "-q", .kind = VL_CLI_FLAG, .dest = quiet},
      {.name = "--out",
       .kind = VL_CLI_TEXT,
       .metavar = "DIR",
       .dest = out_dir,
       .missing = "option %s needs a %s"},
  };
  void (*usage)(FILE *) = seal ? seal_usage : run_usage;
  vl_cli_parser p =
      vl_cli_file_command(seal ? "seal" : "run", opts, sizeof opts / sizeof opts[0], scene_path,
                          "one scene at a time (got '%s' and '%s')", usage);
  int rc = vl_cli_parse(&p, argc, argv, 1);
  if (rc >= 0) return rc;
  if (!*scene_path) return vl_cli_usage_error(seal ? "seal" : "run", NULL, usage, "missing SCENE");
  return -1;
}

/* DIR of a run without --out: out/<scene file name without extension>. */
static void default_out_dir(const char *scene_path, char *buf, size_t size) {
  const char *base = strrchr(scene_path, '/');
  base = base ? base + 1 : scene_path;
  /* drop the extension only: fig03-rough-0.1um.ini -> out/fig03-rough-0.1um */
  const char *dot = strrchr(base, '.');
  size_t stem = dot && dot != base ? (size_t)(dot - base) : strlen(base);
  snprintf(buf, size, "out/%.*s", (int)stem, base);
}

/* Everything checked before anything is computed: the scene loaded, the
 * plotting library there (--plot), the names, the database opened (*db),
 * the output folders, and the scene's text read (*text, for the manifest). */
static vl_status run_prepare(const vl_cli_globals *g, const char *scene_path, int plot, int seal,
                             const char *out_dir, vl_scene *scene, vl_db **db, char **text,
                             vl_error *err) {
  vl_status st = vl_scene_load(scene_path, scene, err);
  if (st == VL_OK && seal) st = vl_scene_as_seal(scene, err);
  if (st != VL_OK) return st;
  /* before the sweep, not after minutes of solving */
  if (plot && !vl_plot_available(err)) return VL_EIO;
  if ((st = check_names(scene, err)) != VL_OK) return st;
  /* the database first: a command that cannot open it leaves no folder
   * behind; then --out, still before anything is computed */
  if ((st = vl_db_open(g->db_path, db, err)) != VL_OK) return st;
  if ((st = check_outputs(scene, out_dir, err)) != VL_OK) return st;
  if (!(*text = vl_cli_read_text(scene_path))) {
    vl_error_set(err, "%s: cannot read: %s", scene_path, strerror(errno));
    return VL_EIO;
  }
  return VL_OK;
}

/* The curves of the scene: one, or one per fluid, each in DIR/<fluid>/
 * (with --json an object keyed by fluid; with --plot the figures of every
 * fluid). curves keeps their points for those figures. */
static vl_status run_curves(run_job *job, const vl_scene *scene, const char *out_dir,
                            kept_curve *curves, vl_error *err) {
  if (scene->n_fluids <= 1) return run_one(job, scene, out_dir, NULL, NULL, err);
  if (job->json) vl_json_object_begin(job->json, VL_JSON_BLOCKS);
  for (size_t k = 0; k < scene->n_fluids; k++) {
    vl_scene one = *scene;
    snprintf(one.fluid, sizeof one.fluid, "%s", scene->fluids[k]);
    one.n_fluids = 1;
    char dir[4200];
    snprintf(dir, sizeof dir, "%s/%s", out_dir, one.fluid);
    vl_status st = run_one(job, &one, dir, one.fluid, job->plot ? &curves[k] : NULL, err);
    if (st != VL_OK) return st;
  }
  if (job->json) {
    vl_json_end(job->json);
    fputc('\n', stdout);
  }
  if (!job->plot) return VL_OK;
  return plot_all_fluids(scene, out_dir, curves, job->json != NULL, job->man, err);
}

/* `run`, or with seal `seal` (the same run of both strokes, with the seal's
 * outputs). */
static int run_command(const vl_cli_globals *g, int argc, char **argv, int seal) {
  const char *scene_path = NULL, *out_dir = NULL, *cmd = seal ? "seal" : "run";
  int json = 0, plot = 0, quiet = g->quiet;
  int rc = run_options(seal, argc, argv, &scene_path, &out_dir, &json, &plot, &quiet);
  if (rc >= 0) return rc;
  vl_error err = {{0}};
  vl_scene scene;
  vl_json w;
  run_job job = {.scene_path = scene_path,
                 .json = json ? &w : NULL,
                 .plot = plot,
                 .quiet = quiet,
                 .seal = seal};
  char *scene_text = NULL, default_dir[2048];
  kept_curve curves[VL_FLUIDS_MAX] = {{0}};
  if (!out_dir) {
    default_out_dir(scene_path, default_dir, sizeof default_dir);
    out_dir = default_dir;
  }
  rc = 0;
  vl_status st =
      run_prepare(g, scene_path, plot, seal, out_dir, &scene, &job.db, &scene_text, &err);
  if (st == VL_OK && !(job.man = vl_cli_manifest_begin(g, cmd, out_dir, &rc))) goto done;
  if (st == VL_OK) {
    run_manifest(job.man, job.db, &scene, scene_text);
    vl_json_init(&w, stdout, 10);
    st = run_curves(&job, &scene, out_dir, curves, &err);
  }
  if (st != VL_OK) {
    fprintf(stderr, "viscolube %s: %s\n", cmd, err.msg[0] ? err.msg : vl_status_name(st));
    rc = vl_status_exit_code(st);
    goto done;
  }
  /* last: the manifest, once every file is in place */
  rc =
      vl_cli_manifest_finish(job.man, cmd, quiet, vl_cli_points_status(job.failed, job.unreliable));
  job.man = NULL;
done:
  vl_manifest_free(job.man); /* a failed run leaves no manifest: the folder is incomplete */
  free(scene_text);
  for (size_t k = 0; k < VL_FLUIDS_MAX; k++)
    free(curves[k].pts);
  vl_db_close(job.db);
  return rc;
}

int vl_cli_run(const vl_cli_globals *g, int argc, char **argv) {
  return run_command(g, argc, argv, 0);
}

int vl_cli_seal(const vl_cli_globals *g, int argc, char **argv) {
  return run_command(g, argc, argv, 1);
}
