/* The manifest of an output folder (manifest.h). */
#include "viscolube/manifest.h"

#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "viscolube/atomic_file.h"
#include "viscolube/json.h"

#define PREVIOUS_NAME ".run.json.previous"
/* hard links to the earlier run's files while a run writes (restored when
 * it is interrupted: vl_manifest_interrupt) */
#define BACKUP_NAME ".run.previous.d"
#define PATH_MAX_VL 4352
/* how deep and how many files the search for unclaimed files looks: an
 * output folder is shallow (DIR/<fluid>/fields/NNN.csv) */
#define SCAN_DEPTH 4
#define SCAN_FILES 100000

/* A growing list of strings (or of groups of `width` strings). */
typedef struct {
  char **s;
  size_t n, cap;
} strings;

typedef struct {
  char *label;
  vl_contact_numerics_used nu;
  double a0_m, p0_pa;
} numerics;

struct vl_manifest {
  char dir[PATH_MAX_VL];
  int nomem;
  char started[32], finished[32];
  strings command, program; /* program: version, commit */
  strings texts, options;   /* key, value pairs */
  strings materials;        /* role, name, fingerprint triples */
  numerics *numerics;
  size_t n_numerics;
  strings files, unwritten; /* unwritten: path, reason pairs */
  strings removed, unclaimed, unwritten_names;
  size_t converged, failed;
  /* the earlier run's files, each as relative name, full path and the
   * full path of its hard link under BACKUP_NAME (triples) */
  strings backups;
  char cur_path[PATH_MAX_VL + 16], prev_path[PATH_MAX_VL + 32], backup_dir[PATH_MAX_VL + 32];
  pid_t pid; /* the process that began the run (a forked worker restores nothing) */
};

/* The run in progress, for vl_manifest_interrupt. */
static vl_manifest *volatile active;

static void now_utc(char *buf, size_t size) {
  time_t t = time(NULL);
  struct tm tm;
  if (!gmtime_r(&t, &tm) || !strftime(buf, size, "%Y-%m-%dT%H:%M:%SZ", &tm))
    snprintf(buf, size, "unknown");
}

static void push(vl_manifest *m, strings *l, const char *s) {
  if (l->n == l->cap) {
    size_t cap = l->cap ? 2 * l->cap : 16;
    char **p = realloc(l->s, cap * sizeof *p);
    if (!p) {
      m->nomem = 1;
      return;
    }
    l->s = p, l->cap = cap;
  }
  char *copy = strdup(s ? s : "");
  if (!copy) {
    m->nomem = 1;
    return;
  }
  l->s[l->n++] = copy;
}

static void strings_free(strings *l) {
  for (size_t i = 0; i < l->n; i++)
    free(l->s[i]);
  free(l->s);
  *l = (strings){0};
}

/* Index of s among the entries k, k + width, ... of l, or l->n. */
static size_t find(const strings *l, size_t width, const char *s) {
  for (size_t i = 0; i + width <= l->n; i += width)
    if (!strcmp(l->s[i], s)) return i;
  return l->n;
}

/* Sets key to value in a list of pairs. */
static void set_pair(vl_manifest *m, strings *l, const char *key, const char *value) {
  size_t i = find(l, 2, key);
  if (i < l->n) {
    char *copy = strdup(value ? value : "");
    if (!copy) {
      m->nomem = 1;
      return;
    }
    free(l->s[i + 1]);
    l->s[i + 1] = copy;
    return;
  }
  push(m, l, key);
  push(m, l, value);
}

#define SIGNATURE "{\n\"manifest\": \"viscolube run manifest"

/* True when the file at path begins as the manifests this module writes:
 * a run.json of another program is never moved, replaced or obeyed. */
static bool ours(const char *path) {
  char head[sizeof SIGNATURE] = {0};
  FILE *f = fopen(path, "rb");
  if (!f) return false;
  size_t n = fread(head, 1, sizeof head - 1, f);
  fclose(f);
  return n == sizeof head - 1 && !memcmp(head, SIGNATURE, n);
}

static bool files_of(vl_manifest *m, const char *path, strings *list);
static bool removable_name(const char *rel);

/* Removes the hard links under BACKUP_NAME and the folder. */
static void drop_backups(vl_manifest *m) {
  for (size_t i = 0; i + 2 < m->backups.n; i += 3)
    unlink(m->backups.s[i + 2]);
  if (m->backup_dir[0]) rmdir(m->backup_dir);
  strings_free(&m->backups);
}

/* Hard links to every regular file the earlier manifest at m->cur_path
 * lists, under DIR/BACKUP_NAME: while this run replaces them (each file
 * is written to a temporary and renamed over the old one), the earlier
 * contents survive there until finish, and vl_manifest_interrupt puts them
 * back. A file that cannot be linked is simply not restorable. */
static void backup_earlier(vl_manifest *m) {
  strings list = {0};
  if (!files_of(m, m->cur_path, &list)) {
    strings_free(&list);
    return;
  }
  char path[2 * PATH_MAX_VL], link_path[PATH_MAX_VL + 64];
  if (mkdir(m->backup_dir, 0777) != 0 && errno != EEXIST) {
    strings_free(&list);
    return;
  }
  for (size_t i = 0; i < list.n; i++) {
    struct stat sb;
    snprintf(path, sizeof path, "%s/%s", m->dir, list.s[i]);
    snprintf(link_path, sizeof link_path, "%s/%zu", m->backup_dir, i);
    unlink(link_path); /* left by a run that was killed outright */
    if (!removable_name(list.s[i]) || lstat(path, &sb) != 0 || !S_ISREG(sb.st_mode) ||
        link(path, link_path) != 0)
      continue;
    push(m, &m->backups, list.s[i]);
    push(m, &m->backups, path);
    push(m, &m->backups, link_path);
  }
  strings_free(&list);
}

/* Joins a, "/" and b into out[cap] without the stdio (signal handler). */
static void join_path(char *out, size_t cap, const char *a, const char *b) {
  size_t na = strlen(a), nb = strlen(b);
  if (na + nb + 2 > cap) {
    out[0] = '\0';
    return;
  }
  memcpy(out, a, na);
  out[na] = '/';
  memcpy(out + na + 1, b, nb + 1);
}

void vl_manifest_interrupt(int sig) {
  vl_manifest *m = active;
  if (m && m->pid == getpid()) {
    active = NULL;
    /* the files this run added that the earlier one did not have */
    size_t nf = m->files.n;
    for (size_t i = 0; i < nf; i++) {
      bool earlier = false;
      for (size_t k = 0; k + 2 < m->backups.n && !earlier; k += 3)
        earlier = !strcmp(m->backups.s[k], m->files.s[i]);
      char path[2 * PATH_MAX_VL];
      join_path(path, sizeof path, m->dir, m->files.s[i]);
      if (earlier || !path[0] || unlink(path) != 0) continue;
      /* and the folders that leaves empty, up to DIR */
      size_t top = strlen(m->dir);
      for (char *slash = strrchr(path, '/'); slash && (size_t)(slash - path) > top;
           slash = strrchr(path, '/')) {
        *slash = '\0';
        if (rmdir(path) != 0) break;
      }
    }
    /* the earlier contents back under their names, then its manifest */
    for (size_t k = 0; k + 2 < m->backups.n; k += 3) {
      rename(m->backups.s[k + 2], m->backups.s[k + 1]);
      unlink(m->backups.s[k + 2]); /* a rename between links to one file does nothing */
    }
    rmdir(m->backup_dir);
    rename(m->prev_path, m->cur_path);
  }
  signal(sig, SIG_DFL);
  raise(sig);
}

vl_status vl_manifest_begin(const char *dir, int argc, char *const *argv, vl_manifest **out,
                            vl_error *err) {
  *out = NULL;
  vl_manifest *m = calloc(1, sizeof *m);
  if (!m) {
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  snprintf(m->dir, sizeof m->dir, "%s", dir);
  now_utc(m->started, sizeof m->started);
  for (int i = 0; i < argc; i++)
    push(m, &m->command, argv[i]);
  if (m->nomem) {
    vl_manifest_free(m);
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  /* an earlier complete run: its manifest goes aside, so that this run,
   * if interrupted, leaves no manifest describing other files. An earlier
   * interrupted run left none: its predecessor's stays aside. */
  char *cur = m->cur_path, *prev = m->prev_path;
  snprintf(m->cur_path, sizeof m->cur_path, "%s/%s", dir, VL_MANIFEST_NAME);
  snprintf(m->prev_path, sizeof m->prev_path, "%s/%s", dir, PREVIOUS_NAME);
  snprintf(m->backup_dir, sizeof m->backup_dir, "%s/%s", dir, BACKUP_NAME);
  m->pid = getpid();
  struct stat sb;
  if (lstat(cur, &sb) == 0 && !(S_ISREG(sb.st_mode) && ours(cur))) {
    vl_error_set(err,
                 "%s exists and is not a viscolube manifest: remove it or choose another "
                 "output folder",
                 cur);
    vl_manifest_free(m);
    return VL_EIO;
  }
  if (lstat(cur, &sb) == 0) backup_earlier(m);
  if (m->nomem) {
    vl_manifest_free(m);
    vl_error_set(err, "out of memory");
    return VL_ENOMEM;
  }
  if (lstat(cur, &sb) == 0 && rename(cur, prev) != 0) {
    vl_error_set(err, "%s: cannot move the earlier manifest aside: %s", cur, strerror(errno));
    vl_manifest_free(m);
    return VL_EIO;
  }
  active = m;
  *out = m;
  return VL_OK;
}

void vl_manifest_set_program(vl_manifest *m, const char *version, const char *commit) {
  strings_free(&m->program);
  push(m, &m->program, version);
  push(m, &m->program, commit);
}

void vl_manifest_add_text(vl_manifest *m, const char *key, const char *value) {
  set_pair(m, &m->texts, key, value);
}

void vl_manifest_add_option(vl_manifest *m, const char *key, const char *value) {
  set_pair(m, &m->options, key, value);
}

void vl_manifest_add_material(vl_manifest *m, const char *role, const char *name,
                              const char *fingerprint) {
  for (size_t i = 0; i + 3 <= m->materials.n; i += 3)
    if (!strcmp(m->materials.s[i], role) && !strcmp(m->materials.s[i + 1], name)) return;
  push(m, &m->materials, role);
  push(m, &m->materials, name);
  push(m, &m->materials, fingerprint);
}

void vl_manifest_add_numerics(vl_manifest *m, const char *label, const vl_contact_numerics_used *nu,
                              double a0_m, double p0_pa) {
  numerics *p = realloc(m->numerics, (m->n_numerics + 1) * sizeof *p);
  char *copy = label ? strdup(label) : NULL;
  if (!p || (label && !copy)) {
    free(copy);
    if (p) m->numerics = p;
    m->nomem = 1;
    return;
  }
  m->numerics = p;
  p[m->n_numerics++] = (numerics){copy, *nu, a0_m, p0_pa};
}

/* path relative to the folder when it lies in it ("DIR/x" -> "x"). */
static const char *relative(const vl_manifest *m, const char *path) {
  size_t n = strlen(m->dir);
  if (n && !strncmp(path, m->dir, n) && path[n] == '/') {
    path += n;
    while (*path == '/')
      path++;
  }
  while (path[0] == '.' && path[1] == '/')
    path += 2;
  return path;
}

void vl_manifest_add_file(vl_manifest *m, const char *path) {
  const char *rel = relative(m, path);
  if (find(&m->files, 1, rel) == m->files.n) push(m, &m->files, rel);
}

void vl_manifest_add_unwritten(vl_manifest *m, const char *path, const char *reason) {
  const char *rel = relative(m, path);
  if (find(&m->unwritten_names, 1, rel) < m->unwritten_names.n) return;
  push(m, &m->unwritten_names, rel);
  push(m, &m->unwritten, rel);
  push(m, &m->unwritten, reason);
}

void vl_manifest_add_counts(vl_manifest *m, size_t converged, size_t failed) {
  m->converged += converged;
  m->failed += failed;
}

/* ---- the earlier manifest's file list ---------------------------------- */

/* A small reader for the one member needed, "files": an array of strings
 * in the top-level object. Anything it does not understand ends the read
 * with nothing found (the files are then left alone). */
typedef struct {
  const char *p, *end;
} reader;

static void skip_space(reader *r) {
  while (r->p < r->end && (*r->p == ' ' || *r->p == '\n' || *r->p == '\t' || *r->p == '\r'))
    r->p++;
}

/* Reads a string into buf (NULL: skips it). Only ASCII escapes are
 * decoded; a \u escape beyond ASCII fails the read. */
static bool read_string(reader *r, char *buf, size_t size) {
  if (r->p >= r->end || *r->p != '"') return false;
  size_t n = 0;
  for (r->p++; r->p < r->end && *r->p != '"'; r->p++) {
    char c = *r->p;
    if (c == '\\') {
      if (++r->p >= r->end) return false;
      static const char from[] = "\"\\/bfnrt", to[] = "\"\\/\b\f\n\r\t";
      const char *k = strchr(from, *r->p);
      if (*r->p == 'u') {
        unsigned v;
        if (r->end - r->p < 5 || sscanf(r->p + 1, "%4x", &v) != 1 || v == 0 || v > 0x7f)
          return false;
        c = (char)v, r->p += 4;
      } else if (k && *r->p) {
        c = to[k - from];
      } else {
        return false;
      }
    }
    if (buf && n + 1 >= size) return false;
    if (buf) buf[n++] = c;
  }
  if (r->p >= r->end) return false;
  r->p++;
  if (buf) buf[n] = '\0';
  return true;
}

/* Skips any value: strings, and nested arrays and objects by counting
 * brackets outside strings. */
static bool skip_value(reader *r) {
  skip_space(r);
  if (r->p < r->end && *r->p == '"') return read_string(r, NULL, 0);
  int depth = 0;
  while (r->p < r->end) {
    char c = *r->p;
    if (c == '"') {
      if (!read_string(r, NULL, 0)) return false;
      continue;
    }
    if (depth == 0 && (c == ',' || c == '}' || c == ']')) return true;
    if (c == '[' || c == '{') depth++;
    if (c == ']' || c == '}') depth--;
    r->p++;
    if (depth == 0 && (c == ']' || c == '}')) return true;
  }
  return false;
}

/* Reads the array of strings at r into list. */
static bool read_files(vl_manifest *m, reader *r, strings *list) {
  skip_space(r);
  if (r->p >= r->end || *r->p != '[') return false;
  r->p++;
  for (;;) {
    skip_space(r);
    if (r->p < r->end && *r->p == ']') return true;
    char name[PATH_MAX_VL];
    if (!read_string(r, name, sizeof name)) return false;
    push(m, list, name);
    skip_space(r);
    if (r->p < r->end && *r->p == ',') r->p++;
  }
}

/* The "files" of the manifest text, into list; false when it has none or
 * cannot be read. */
static bool manifest_files(vl_manifest *m, const char *text, size_t len, strings *list) {
  reader r = {text, text + len};
  skip_space(&r);
  if (r.p >= r.end || *r.p != '{') return false;
  r.p++;
  for (;;) {
    skip_space(&r);
    char key[64];
    if (!read_string(&r, key, sizeof key)) return false;
    skip_space(&r);
    if (r.p >= r.end || *r.p != ':') return false;
    r.p++;
    if (!strcmp(key, "files")) return read_files(m, &r, list);
    if (!skip_value(&r)) return false;
    skip_space(&r);
    if (r.p >= r.end || *r.p != ',') return false;
    r.p++;
  }
}

/* The file list of the manifest at path. */
static bool files_of(vl_manifest *m, const char *path, strings *list) {
  FILE *f = fopen(path, "rb");
  if (!f) return false;
  char *text = NULL;
  size_t len = 0, cap = 0;
  bool ok = true;
  for (;;) {
    if (len + 4096 > cap) {
      char *p = cap < (64u << 20) ? realloc(text, cap + 65536) : NULL;
      if (!p) {
        ok = false;
        break;
      }
      text = p, cap += 65536;
    }
    size_t got = fread(text + len, 1, cap - len, f);
    len += got;
    if (got == 0) break;
  }
  ok = ok && !ferror(f) && manifest_files(m, text, len, list);
  fclose(f);
  free(text);
  return ok;
}

/* The file list of the earlier manifest (moved aside by begin). */
static bool previous_files(vl_manifest *m, strings *list) {
  return files_of(m, m->prev_path, list);
}

/* ---- files of the earlier run ------------------------------------------ */

/* A name of the earlier list that may be removed: relative, inside the
 * folder (no ".." component), not the manifest itself. */
static bool removable_name(const char *rel) {
  if (!rel[0] || rel[0] == '/' || !strcmp(rel, VL_MANIFEST_NAME) || !strcmp(rel, PREVIOUS_NAME))
    return false;
  for (const char *p = rel; *p;) {
    size_t n = strcspn(p, "/");
    if (n == 2 && p[0] == '.' && p[1] == '.') return false;
    p += n;
    while (*p == '/')
      p++;
  }
  return true;
}

/* Removes the folders of rel that its removal left empty, up to DIR. */
static void remove_empty_parents(const vl_manifest *m, const char *rel) {
  char sub[PATH_MAX_VL];
  snprintf(sub, sizeof sub, "%s", rel);
  for (char *slash = strrchr(sub, '/'); slash; slash = strrchr(sub, '/')) {
    *slash = '\0';
    char path[2 * PATH_MAX_VL];
    snprintf(path, sizeof path, "%s/%s", m->dir, sub);
    if (rmdir(path) != 0) return; /* not empty (or not ours to remove) */
  }
}

/* The earlier run's files that this one did not write: removed. */
static void remove_superseded(vl_manifest *m, const strings *earlier) {
  for (size_t i = 0; i < earlier->n; i++) {
    const char *rel = earlier->s[i];
    if (!removable_name(rel) || find(&m->files, 1, rel) < m->files.n) continue;
    char path[2 * PATH_MAX_VL];
    snprintf(path, sizeof path, "%s/%s", m->dir, rel);
    struct stat sb;
    if (lstat(path, &sb) != 0 || !S_ISREG(sb.st_mode) || unlink(path) != 0) continue;
    push(m, &m->removed, rel);
    remove_empty_parents(m, rel);
  }
}

/* Every regular file under DIR/rel (hidden names aside) that this run did
 * not write, into m->unclaimed. */
static void scan_unclaimed(vl_manifest *m, const char *rel, int depth) {
  char path[2 * PATH_MAX_VL];
  snprintf(path, sizeof path, "%s%s%s", m->dir, rel[0] ? "/" : "", rel);
  DIR *d = opendir(path);
  if (!d) return;
  struct dirent *e;
  while ((e = readdir(d)) && m->unclaimed.n < SCAN_FILES) {
    if (e->d_name[0] == '.') continue; /* ., .., temporaries, .run.json.previous */
    char sub[PATH_MAX_VL], full[2 * PATH_MAX_VL + 256];
    int n = snprintf(sub, sizeof sub, "%s%s%s", rel, rel[0] ? "/" : "", e->d_name);
    if (n < 0 || (size_t)n >= sizeof sub) continue;
    snprintf(full, sizeof full, "%s/%s", m->dir, sub);
    struct stat sb;
    if (lstat(full, &sb) != 0) continue;
    if (S_ISDIR(sb.st_mode)) {
      if (depth < SCAN_DEPTH) scan_unclaimed(m, sub, depth + 1);
    } else if (strcmp(sub, VL_MANIFEST_NAME) && find(&m->files, 1, sub) == m->files.n) {
      push(m, &m->unclaimed, sub);
    }
  }
  closedir(d);
}

/* ---- run.json ------------------------------------------------------------ */

static void string_array(vl_json *w, const char *key, const strings *l) {
  vl_json_key(w, key);
  vl_json_array_begin(w, VL_JSON_STACKED);
  for (size_t i = 0; i < l->n; i++)
    vl_json_string(w, l->s[i]);
  vl_json_end(w);
}

static void pairs_object(vl_json *w, const strings *l) {
  vl_json_object_begin(w, VL_JSON_STACKED);
  for (size_t i = 0; i + 2 <= l->n; i += 2)
    vl_json_key_string(w, l->s[i], l->s[i + 1]);
  vl_json_end(w);
}

static void numerics_json(vl_json *w, const numerics *x) {
  vl_json_object_begin(w, VL_JSON_INLINE);
  if (x->label) vl_json_key_string(w, "curve", x->label);
  vl_json_key_integer(w, "grid", (long long)x->nu.grid);
  vl_json_key_integer(w, "cells", (long long)x->nu.cells);
  vl_json_key_number(w, "grid_growth", x->nu.grid_growth > 1.0 ? x->nu.grid_growth : 1.0);
  vl_json_key_number(w, "domain_min_a0", x->nu.x_min_a0);
  vl_json_key_number(w, "domain_max_a0", x->nu.x_max_a0);
  vl_json_key_number(w, "tolerance", x->nu.tolerance);
  vl_json_key_integer(w, "max_iterations", x->nu.max_iterations);
  vl_json_key_string(w, "linear_solver", x->nu.linear_solver);
  vl_json_key_number(w, "a0_m", x->a0_m);
  vl_json_key_number(w, "p0_pa", x->p0_pa);
  vl_json_end(w);
}

static void write_json(const vl_manifest *m, FILE *f) {
  vl_json w;
  vl_json_init(&w, f, 10);
  vl_json_object_begin(&w, VL_JSON_BLOCKS);
  /* first, as written: SIGNATURE recognises the file by it */
  vl_json_key_string(&w, "manifest", "viscolube run manifest, version 1");
  vl_json_key(&w, "program");
  vl_json_object_begin(&w, VL_JSON_INLINE);
  vl_json_key_string(&w, "name", "viscolube");
  vl_json_key_string(&w, "version", m->program.n > 0 ? m->program.s[0] : NULL);
  vl_json_key_string(&w, "commit", m->program.n > 1 ? m->program.s[1] : NULL);
  vl_json_end(&w);
  vl_json_key(&w, "command");
  vl_json_array_begin(&w, VL_JSON_INLINE);
  for (size_t i = 0; i < m->command.n; i++)
    vl_json_string(&w, m->command.s[i]);
  vl_json_end(&w);
  vl_json_key_string(&w, "started_utc", m->started);
  vl_json_key_string(&w, "finished_utc", m->finished);
  for (size_t i = 0; i + 2 <= m->texts.n; i += 2)
    vl_json_key_string(&w, m->texts.s[i], m->texts.s[i + 1]);
  if (m->options.n) {
    vl_json_key(&w, "options");
    pairs_object(&w, &m->options);
  }
  vl_json_key(&w, "materials");
  vl_json_array_begin(&w, VL_JSON_STACKED);
  for (size_t i = 0; i + 3 <= m->materials.n; i += 3) {
    vl_json_object_begin(&w, VL_JSON_INLINE);
    vl_json_key_string(&w, "role", m->materials.s[i]);
    vl_json_key_string(&w, "name", m->materials.s[i + 1]);
    vl_json_key_string(&w, "fingerprint", m->materials.s[i + 2]);
    vl_json_end(&w);
  }
  vl_json_end(&w);
  vl_json_key(&w, "numerics");
  vl_json_array_begin(&w, VL_JSON_STACKED);
  for (size_t i = 0; i < m->n_numerics; i++)
    numerics_json(&w, &m->numerics[i]);
  vl_json_end(&w);
  vl_json_key(&w, "points");
  vl_json_object_begin(&w, VL_JSON_INLINE);
  vl_json_key_integer(&w, "converged", (long long)m->converged);
  vl_json_key_integer(&w, "failed", (long long)m->failed);
  vl_json_end(&w);
  string_array(&w, "files", &m->files);
  vl_json_key(&w, "not_written");
  vl_json_array_begin(&w, VL_JSON_STACKED);
  for (size_t i = 0; i + 2 <= m->unwritten.n; i += 2) {
    vl_json_object_begin(&w, VL_JSON_INLINE);
    vl_json_key_string(&w, "file", m->unwritten.s[i]);
    vl_json_key_string(&w, "error", m->unwritten.s[i + 1]);
    vl_json_end(&w);
  }
  vl_json_end(&w);
  vl_json_end(&w);
  fputc('\n', f);
}

vl_status vl_manifest_finish(vl_manifest *m, vl_error *err) {
  if (m->nomem) {
    vl_error_set(err, "%s/%s: out of memory", m->dir, VL_MANIFEST_NAME);
    return VL_ENOMEM;
  }
  now_utc(m->finished, sizeof m->finished);
  strings earlier = {0};
  strings_free(&m->removed);
  strings_free(&m->unclaimed);
  if (previous_files(m, &earlier)) remove_superseded(m, &earlier);
  strings_free(&earlier);
  scan_unclaimed(m, "", 0);
  char path[PATH_MAX_VL + 16], prev[PATH_MAX_VL + 32];
  snprintf(path, sizeof path, "%s/%s", m->dir, VL_MANIFEST_NAME);
  vl_atomic_file af;
  if (vl_atomic_file_open(&af, path, err) != VL_OK) return VL_EIO;
  write_json(m, af.f);
  if (vl_atomic_file_commit(&af, err) != VL_OK) return VL_EIO;
  snprintf(prev, sizeof prev, "%s/%s", m->dir, PREVIOUS_NAME);
  unlink(prev);
  active = NULL; /* complete: nothing to restore any more */
  drop_backups(m);
  if (m->nomem) {
    vl_error_set(err, "%s: out of memory", path);
    return VL_ENOMEM;
  }
  return VL_OK;
}

const char *const *vl_manifest_removed(const vl_manifest *m, size_t *n) {
  *n = m->removed.n;
  return (const char *const *)m->removed.s;
}

const char *const *vl_manifest_unclaimed(const vl_manifest *m, size_t *n) {
  *n = m->unclaimed.n;
  return (const char *const *)m->unclaimed.s;
}

const char *const *vl_manifest_unwritten(const vl_manifest *m, size_t *n) {
  *n = m->unwritten_names.n;
  return (const char *const *)m->unwritten_names.s;
}

const char *vl_manifest_unwritten_reason(const vl_manifest *m, size_t i) {
  return 2 * i + 1 < m->unwritten.n ? m->unwritten.s[2 * i + 1] : "";
}

void vl_manifest_free(vl_manifest *m) {
  if (!m) return;
  if (active == m) active = NULL;
  drop_backups(m);
  strings *lists[] = {&m->command, &m->program,   &m->texts,   &m->options,   &m->materials,
                      &m->files,   &m->unwritten, &m->removed, &m->unclaimed, &m->unwritten_names};
  for (size_t i = 0; i < sizeof lists / sizeof lists[0]; i++)
    strings_free(lists[i]);
  for (size_t i = 0; i < m->n_numerics; i++)
    free(m->numerics[i].label);
  free(m->numerics);
  free(m);
}
