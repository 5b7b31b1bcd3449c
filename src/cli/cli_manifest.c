/* Output folders: their manifests (run.json) and the files written. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "vl_version.h" /* generated at configure time (src/CMakeLists.txt) */

vl_manifest *vl_cli_manifest_begin(const vl_cli_globals *g, const char *cmd, const char *dir,
                                   int *rc) {
  vl_error err = {{0}};
  vl_manifest *m = NULL;
  vl_status st = vl_manifest_begin(dir, g->argc, g->argv, &m, &err);
  if (st != VL_OK) {
    fprintf(stderr, "viscolube %s: %s\n", cmd, err.msg);
    *rc = vl_status_exit_code(st);
    return NULL;
  }
  vl_manifest_set_program(m, VL_VERSION, VL_SOURCE_COMMIT);
  return m;
}

void vl_cli_manifest_material(vl_manifest *m, vl_db *db, const char *role, const char *name) {
  char fp[VL_DB_FINGERPRINT_MAX], text[VL_ERROR_MAX + 16];
  vl_error err = {{0}};
  if (vl_db_fingerprint(db, role, name, fp, &err) == VL_OK)
    vl_manifest_add_material(m, role, name, fp);
  else {
    snprintf(text, sizeof text, "unknown: %s", err.msg);
    vl_manifest_add_material(m, role, name, text);
  }
}

void vl_cli_manifest_file(vl_manifest *m, const char *path, vl_status st, const vl_error *err) {
  if (st == VL_OK)
    vl_manifest_add_file(m, path);
  else
    vl_manifest_add_unwritten(m, path, err && err->msg[0] ? err->msg : vl_status_name(st));
}

void vl_cli_manifest_figure(vl_manifest *m, const char *stem, vl_status st, const vl_error *err) {
  char path[4400];
  static const char *const ext[] = {"png", "svg"};
  for (size_t k = 0; k < 2; k++) {
    snprintf(path, sizeof path, "%s.%s", stem, ext[k]);
    vl_cli_manifest_file(m, path, st, err);
  }
}

/* Up to ten names of list, comma-separated, then "and N more". */
static void print_names(FILE *out, const char *const *list, size_t n) {
  for (size_t i = 0; i < n && i < 10; i++)
    fprintf(out, "%s%s", i ? ", " : "", list[i]);
  if (n > 10) fprintf(out, " and %zu more", n - 10);
  fputc('\n', out);
}

int vl_cli_manifest_finish(vl_manifest *m, const char *cmd, int quiet, int rc) {
  if (!m) return rc;
  vl_error err = {{0}};
  vl_status st = vl_manifest_finish(m, &err);
  size_t n;
  const char *const *list = vl_manifest_removed(m, &n);
  if (n && !quiet) {
    fprintf(stderr, "viscolube %s: removed %zu file%s of the earlier run (listed in its %s): ", cmd,
            n, n == 1 ? "" : "s", VL_MANIFEST_NAME);
    print_names(stderr, list, n);
  }
  list = vl_manifest_unclaimed(m, &n);
  if (n && !quiet) {
    fprintf(stderr,
            "warning: %zu file%s in the output folder not written by this run (no earlier %s "
            "lists %s; left alone): ",
            n, n == 1 ? "" : "s", VL_MANIFEST_NAME, n == 1 ? "it" : "them");
    print_names(stderr, list, n);
  }
  list = vl_manifest_unwritten(m, &n);
  if (n) {
    fprintf(stderr,
            "viscolube %s: %zu file%s could not be written (the others are complete): ", cmd, n,
            n == 1 ? "" : "s");
    print_names(stderr, list, n);
    fprintf(stderr, "viscolube %s: the first: %s\n", cmd, vl_manifest_unwritten_reason(m, 0));
    rc = vl_status_exit_code(VL_EIO);
  }
  if (st != VL_OK) {
    fprintf(stderr, "viscolube %s: %s\n", cmd, err.msg);
    rc = vl_status_exit_code(st);
  }
  vl_manifest_free(m);
  return rc;
}

char *vl_cli_read_text(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  size_t len = 0, cap = 4096;
  char *text = malloc(cap);
  while (text) {
    len += fread(text + len, 1, cap - len - 1, f);
    if (len + 1 < cap || ferror(f)) break;
    char *p = cap < (16u << 20) ? realloc(text, cap *= 2) : NULL;
    if (!p) {
      free(text);
      text = NULL;
      errno = ENOMEM;
    }
    text = p;
  }
  if (text && ferror(f)) {
    free(text);
    text = NULL;
  }
  if (text) text[len] = '\0';
  fclose(f);
  return text;
}
