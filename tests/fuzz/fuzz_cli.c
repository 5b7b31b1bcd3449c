/* Fuzz target: the command line's argument handling (`viscolube compound|
 * surface|fluid|run ...`), through the same entry points main() calls
 * (vl_cli_materials, vl_cli_run, vl_cli_friction, vl_cli_compare in
 * src/cli). The input is the argument vector, one argument per line (or
 * NUL-separated), starting at the noun.
 *
 * Confinement, so that no input can touch anything outside a private
 * directory: every '/' in an argument becomes '_' and the command runs with
 * that directory as its working directory, so file arguments (--prony,
 * --psd, scenes) can only name the seed files placed there (prony.csv,
 * psd.csv, scene.ini, bad.csv) or nothing. The material commands get a
 * database there whose permission bits are 0444 (opened read-only); `run`,
 * `friction` and `compare` get a database path in a missing directory, so
 * they stop before solving or writing anything (a solve takes seconds).
 *
 * Properties: the exit status is one of the documented codes; a command
 * that would write (add, remove) never reports success on the read-only
 * database, the database file is never modified, and no command creates a
 * file or directory (each fails before writing its output).
 * Under libFuzzer run with -close_fd_mask=3 (the commands print). */
#ifndef _GNU_SOURCE
#define _GNU_SOURCE
#endif

#include "vl_fuzz.h"

#include <dirent.h>
#include <ftw.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"
#include "viscolube/database.h"

#define MAX_ARGS 48

static char dir[PATH_MAX], db_ro[PATH_MAX + 32], db_missing[PATH_MAX + 64];
static struct stat db_stat;

static void put(const char *name, const char *text) {
  char path[PATH_MAX + 64];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  FILE *f = fopen(path, "wb");
  if (!f || fputs(text, f) < 0 || fclose(f) != 0)
    vl_fuzz_fail(__FILE__, __LINE__, "cannot write %s", path);
}

static int remove_entry(const char *path, const struct stat *sb, int flag, struct FTW *ftw) {
  (void)sb;
  (void)flag;
  (void)ftw;
  return remove(path);
}

static void cleanup(void) { nftw(dir, remove_entry, 16, FTW_DEPTH | FTW_PHYS); }

/* Entries in the private directory (the seed files: 5). */
static int entries(void) {
  DIR *d = opendir(dir);
  if (!d) return -1;
  int n = 0;
  struct dirent *e;
  while ((e = readdir(d)) != NULL)
    n += strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
  closedir(d);
  return n;
}

static void setup(void) {
  const char *tmp = getenv("TMPDIR");
  snprintf(dir, sizeof dir, "%s/vl-fuzz-cli.XXXXXX", tmp && *tmp ? tmp : "/tmp");
  if (!mkdtemp(dir)) vl_fuzz_fail(__FILE__, __LINE__, "mkdtemp failed");
  atexit(cleanup);
  put("prony.csv", "A,tau_s\n1,s\n9,1e-3\n0.5,1e-1\n");
  put("psd.csv", "q_per_m,C_m4\n1e3,1e-20\n1e5,1e-28\n1e7,1e-36\n");
  put("bad.csv", "A,tau_s\n1,-1\n");
  put("scene.ini", "[materials]\ncompound = model-rubber\n[contact]\nradius_m = 0.01\n"
                   "load_n_per_m = 100\n[sweep]\nquantity = v0\nfrom = 1e-3\nto = 1\n"
                   "points = 3\n");
  snprintf(db_ro, sizeof db_ro, "%s/materials.db", dir);
  snprintf(db_missing, sizeof db_missing, "%s/no-such-directory/materials.db", dir);
  vl_db *db = NULL;
  vl_error err;
  if (vl_db_open(db_ro, &db, &err) != VL_OK) vl_fuzz_fail(__FILE__, __LINE__, "%s", err.msg);
  vl_db_close(db);
  if (chmod(db_ro, 0444) != 0 || stat(db_ro, &db_stat) != 0)
    vl_fuzz_fail(__FILE__, __LINE__, "cannot make %s read-only", db_ro);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (!dir[0]) setup();
  char *buf = vl_fuzz_strdup(data, size);
  char *argv[MAX_ARGS + 1];
  int argc = 0;
  /* split at '\n' and NUL; '/' cannot leave the private directory */
  for (size_t i = 0, start = 0; i <= size && argc < MAX_ARGS; i++) {
    if (i == size || buf[i] == '\n' || buf[i] == '\0') {
      buf[i] = '\0';
      argv[argc++] = buf + start;
      start = i + 1;
    } else if (buf[i] == '/') {
      buf[i] = '_';
    }
  }
  argv[argc] = NULL;
  const char *noun = argv[0];
  int material = !strcmp(noun, "compound") || !strcmp(noun, "surface") || !strcmp(noun, "fluid");
  int (*entry)(const vl_cli_globals *, int, char **) = material               ? vl_cli_materials
                                                       : !strcmp(noun, "run") ? vl_cli_run
                                                       : !strcmp(noun, "friction") ? vl_cli_friction
                                                       : !strcmp(noun, "compare")  ? vl_cli_compare
                                                                                   : NULL;
  if (!entry) {
    free(buf);
    return 0;
  }
  int writes = material && argc >= 2 && (!strcmp(argv[1], "add") || !strcmp(argv[1], "remove"));
  int help = 0;
  for (int i = 1; i < argc; i++)
    help |= !strcmp(argv[i], "--help") || !strcmp(argv[i], "-h") || !strcmp(argv[i], "help");

  char cwd[PATH_MAX];
  if (!getcwd(cwd, sizeof cwd) || chdir(dir) != 0)
    vl_fuzz_fail(__FILE__, __LINE__, "cannot enter %s", dir);
  vl_cli_globals g = {.db_path = material ? db_ro : db_missing};
  int rc = entry(&g, argc, argv);
  fflush(stdout);
  fflush(stderr);
  if (chdir(cwd) != 0) vl_fuzz_fail(__FILE__, __LINE__, "cannot return to %s", cwd);

  FUZZ_CHECK(rc == 0 || rc == 2 || rc == 3 || rc == 4 || rc == 5 || rc == 6 || rc == 70,
             "undocumented exit status %d", rc);
  FUZZ_CHECK(!(writes && rc == 0 && !help), "a write reported success on a read-only database");
  /* every command here fails before its output (no database, or a
   * read-only one): none may have created a file or directory */
  FUZZ_CHECK(entries() == 5, "the command created files (%d entries in %s)", entries(), dir);
  struct stat now;
  FUZZ_CHECK(stat(db_ro, &now) == 0 && now.st_size == db_stat.st_size &&
                 now.st_mtim.tv_sec == db_stat.st_mtim.tv_sec &&
                 now.st_mtim.tv_nsec == db_stat.st_mtim.tv_nsec && now.st_mode == db_stat.st_mode,
             "the read-only database was modified");
  free(buf);
  return 0;
}
