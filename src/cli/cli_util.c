/* Small helpers shared by the command's nouns. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"

int vl_cli_make_dirs(const char *path) {
  char buf[4200];
  snprintf(buf, sizeof buf, "%s", path);
  for (char *p = buf + 1; *p; p++) {
    if (*p != '/') continue;
    *p = '\0';
    if (mkdir(buf, 0777) != 0 && errno != EEXIST) return -1;
    *p = '/';
  }
  return mkdir(buf, 0777) != 0 && errno != EEXIST ? -1 : 0;
}

/* ---- the points' warnings and failures, summed up on stderr ------------- */

/* One kind of warning: its text with every number cut out (the key), and
 * per number slot the range met over the points it applies to. */
#define SLOTS_MAX 8
#define KINDS_MAX 32

typedef struct {
  char key[VL_WARN_MAX];   /* the text with '#' for each number */
  char first[VL_WARN_MAX]; /* the text as the first point gave it */
  size_t n_slots;
  double lo[SLOTS_MAX], hi[SLOTS_MAX];
  char literal[SLOTS_MAX][32]; /* a number as written, shown when constant */
  size_t count, first_point;
  double v_lo, v_hi;     /* the speeds of the points, m/s */
  unsigned char *points; /* n flags */
} warn_kind;

/* A number starts a token unless it continues a word (lambda0, a0). */
static int number_at(const char *s, size_t i) {
  char c = s[i];
  int digit = isdigit((unsigned char)c) ||
              (c == '-' && isdigit((unsigned char)s[i + 1]) && (i == 0 || s[i - 1] == ' '));
  if (!digit) return 0;
  if (i == 0) return 1;
  unsigned char p = (unsigned char)s[i - 1];
  return !(isalnum(p) || p == '_');
}

/* Cuts one warning into its key and numbers (at most SLOTS_MAX; further
 * numbers stay in the key as written). */
static void warn_parse(const char *w, char *key, size_t cap, double *num, char (*lit)[32],
                       size_t *n_num) {
  size_t k = 0;
  *n_num = 0;
  for (size_t i = 0; w[i] && k + 1 < cap;) {
    char *end = NULL;
    if (*n_num < SLOTS_MAX && number_at(w, i)) {
      double d = strtod(w + i, &end);
      if (end && end > w + i) {
        snprintf(lit[*n_num], sizeof lit[0], "%.*s", (int)(end - (w + i)), w + i);
        num[(*n_num)++] = d;
        key[k++] = '#';
        i = (size_t)(end - w);
        continue;
      }
    }
    key[k++] = w[i++];
  }
  key[k] = '\0';
}

/* "1-3, 7, 9-45": the flagged points, 1-based, at most six runs. */
static void point_runs(const unsigned char *flags, size_t n, char *buf, size_t cap) {
  size_t len = 0, runs = 0;
  buf[0] = '\0';
  for (size_t i = 0; i < n && len < cap; i++) {
    if (!flags[i]) continue;
    size_t j = i;
    while (j + 1 < n && flags[j + 1])
      j++;
    if (runs == 6) {
      snprintf(buf + len, cap - len, ", ...");
      return;
    }
    int w = j > i ? snprintf(buf + len, cap - len, "%s%zu-%zu", runs ? ", " : "", i + 1, j + 1)
                  : snprintf(buf + len, cap - len, "%s%zu", runs ? ", " : "", i + 1);
    if (w < 0) return;
    len += (size_t)w;
    runs++;
    i = j;
  }
}

/* The warning with each number that varies over the points shown as its
 * range ("a_H = 0.21..1.7 lambda0 < 5 (...)"). */
static void warn_text(const warn_kind *k, char *buf, size_t cap) {
  size_t len = 0, slot = 0;
  for (const char *p = k->key; *p && len + 1 < cap; p++) {
    if (*p != '#' || slot >= k->n_slots) {
      buf[len++] = *p;
      continue;
    }
    int w = k->lo[slot] == k->hi[slot]
                ? snprintf(buf + len, cap - len, "%s", k->literal[slot])
                : snprintf(buf + len, cap - len, "%.2g..%.2g", k->lo[slot], k->hi[slot]);
    slot++;
    if (w < 0) break;
    len += (size_t)w;
    if (len >= cap) len = cap - 1;
  }
  buf[len] = '\0';
}

/* Adds one warning of point i to the kinds (a new kind when its key is new).
 * Returns 0 when the table is full. */
static int warn_add(warn_kind *kinds, size_t *n_kinds, size_t n, size_t i, const vl_point *p,
                    const char *w) {
  char key[VL_WARN_MAX], lit[SLOTS_MAX][32];
  double num[SLOTS_MAX];
  size_t n_num;
  warn_parse(w, key, sizeof key, num, lit, &n_num);
  warn_kind *k = NULL;
  for (size_t j = 0; j < *n_kinds && !k; j++)
    if (!strcmp(kinds[j].key, key)) k = &kinds[j];
  if (!k) {
    if (*n_kinds == KINDS_MAX) return 0;
    unsigned char *flags = calloc(n, 1);
    if (!flags) return 0;
    k = &kinds[(*n_kinds)++];
    *k = (warn_kind){
        .n_slots = n_num, .first_point = i, .points = flags, .v_lo = p->v0_m_s, .v_hi = p->v0_m_s};
    snprintf(k->key, sizeof k->key, "%s", key);
    snprintf(k->first, sizeof k->first, "%s", w);
    for (size_t s = 0; s < n_num; s++) {
      k->lo[s] = k->hi[s] = num[s];
      memcpy(k->literal[s], lit[s], sizeof lit[s]);
    }
  }
  for (size_t s = 0; s < n_num && s < k->n_slots; s++) {
    k->lo[s] = fmin(k->lo[s], num[s]);
    k->hi[s] = fmax(k->hi[s], num[s]);
  }
  if (!k->points[i]) k->count++;
  k->points[i] = 1;
  k->v_lo = fmin(k->v_lo, p->v0_m_s);
  k->v_hi = fmax(k->v_hi, p->v0_m_s);
  return 1;
}

size_t vl_cli_print_warnings(FILE *out, const char *label, size_t n, const vl_point *pts) {
  warn_kind kinds[KINDS_MAX];
  size_t n_kinds = 0, dropped = 0;
  for (size_t i = 0; i < n; i++) {
    char copy[VL_WARN_MAX], *save = NULL;
    snprintf(copy, sizeof copy, "%s", pts[i].warnings);
    for (char *t = strtok_r(copy, ";", &save); t; t = strtok_r(NULL, ";", &save)) {
      while (*t == ' ')
        t++;
      size_t len = strlen(t);
      while (len && t[len - 1] == ' ')
        t[--len] = '\0';
      if (len && !warn_add(kinds, &n_kinds, n, i, &pts[i], t)) dropped++;
    }
  }
  for (size_t j = 0; j < n_kinds; j++) {
    const warn_kind *k = &kinds[j];
    char text[2 * VL_WARN_MAX], runs[160];
    warn_text(k, text, sizeof text);
    fprintf(out, "warning: %s%s%s", label ? label : "", label ? ": " : "", text);
    if (n == 1) {
      fputc('\n', out);
      continue;
    }
    point_runs(k->points, n, runs, sizeof runs);
    fprintf(out, " \u2014 point%s %s of %zu", k->count > 1 ? "s" : "", runs, n);
    if (k->v_lo == k->v_hi)
      fprintf(out, " (v0 = %.3g m/s)\n", k->v_lo);
    else
      fprintf(out, " (v0 = %.3g..%.3g m/s)\n", k->v_lo, k->v_hi);
  }
  if (dropped)
    fprintf(out, "warning: %s%s%zu further warnings of other kinds (see the warnings column)\n",
            label ? label : "", label ? ": " : "", dropped);
  for (size_t j = 0; j < n_kinds; j++)
    free(kinds[j].points);
  return n_kinds;
}

size_t vl_cli_print_unreliable(FILE *out, const char *cmd, const char *label, size_t n,
                               const vl_point *pts) {
  size_t count = 0, shown = 0;
  for (size_t i = 0; i < n; i++)
    count += vl_point_unreliable(&pts[i]);
  if (!count) return 0;
  fprintf(out,
          "viscolube %s: %s%s%zu of %zu points are not known to their error target "
          "(marked '!'; exit status %d):\n",
          cmd, label ? label : "", label ? ": " : "", count, n, VL_CLI_EXIT_UNRELIABLE);
  for (size_t i = 0; i < n && shown < 10; i++) {
    if (!vl_point_unreliable(&pts[i])) continue;
    if (pts[i].accuracy == VL_ACCURACY_NO_ESTIMATE)
      fprintf(out, "  point %zu: v0 = %.4g m/s, no error estimate\n", i + 1, pts[i].v0_m_s);
    else
      fprintf(out, "  point %zu: v0 = %.4g m/s, error estimate %.2g %%\n", i + 1, pts[i].v0_m_s,
              100.0 * pts[i].error_estimate);
    shown++;
  }
  if (count > shown) fprintf(out, "  ... and %zu more\n", count - shown);
  return count;
}

int vl_cli_points_status(size_t failed, size_t unreliable) {
  return failed ? vl_status_exit_code(VL_ENOCONV) : unreliable ? VL_CLI_EXIT_UNRELIABLE : 0;
}

size_t vl_cli_print_failures(FILE *out, const char *cmd, const char *label, size_t n,
                             const vl_point *pts, const char *where) {
  size_t failed = 0, shown = 0;
  for (size_t i = 0; i < n; i++)
    failed += !pts[i].converged;
  if (!failed) return 0;
  fprintf(out, "viscolube %s: %s%s%zu of %zu points did not converge (exit status %d)%s%s\n", cmd,
          label ? label : "", label ? ": " : "", failed, n, vl_status_exit_code(VL_ENOCONV),
          where ? "; " : "", where ? where : "");
  for (size_t i = 0; i < n; i++) {
    if (pts[i].converged) continue;
    if (shown == 10) {
      fprintf(out, "  ... and %zu more\n", failed - shown);
      break;
    }
    fprintf(out, "  point %zu: v0 = %.4g m/s, %ld iterations, residual %.3g\n", i + 1,
            pts[i].v0_m_s, pts[i].iterations, pts[i].residual);
    shown++;
  }
  return failed;
}

vl_status vl_cli_check_out_dir(const char *option, const char *path, vl_error *err) {
  struct stat sb;
  if (vl_cli_make_dirs(path) != 0) {
    vl_error_set(err, "%s %s: cannot create the folder: %s", option, path, strerror(errno));
    return VL_EIO;
  }
  if (stat(path, &sb) != 0) {
    vl_error_set(err, "%s %s: %s", option, path, strerror(errno));
    return VL_EIO;
  }
  if (!S_ISDIR(sb.st_mode)) {
    vl_error_set(err, "%s %s: a file is in the way (it must be a folder)", option, path);
    return VL_EIO;
  }
  /* permission bits do not tell it all (root, read-only mounts): try */
  char probe[4300];
  snprintf(probe, sizeof probe, "%s/.viscolube-probe-XXXXXX", path);
  int fd = mkstemp(probe);
  if (fd < 0) {
    vl_error_set(err, "%s %s: cannot write in the folder: %s", option, path, strerror(errno));
    return VL_EIO;
  }
  close(fd);
  unlink(probe);
  return VL_OK;
}

double vl_cli_now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
