/* viscolube: the command line, a thin layer over libviscolube. */
#include <errno.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "cli_options.h"
#include "viscolube/manifest.h" /* vl_manifest_interrupt */
#include "vl_version.h"         /* generated at configure time (src/CMakeLists.txt) */

static void usage(FILE *out) {
  fputs(
      "usage: viscolube [--db PATH] [--quiet] NOUN VERB ...\n"
      "       viscolube --version | --help\n"
      "\n"
      "Predicts the friction of wet rubber contacts (Scaraggi & Persson's mean-field\n"
      "theory of viscoelastic lubrication) from a material database.\n"
      "\n"
      "nouns:\n"
      "  compound   rubber compounds (Prony series): list, show, add, remove\n"
      "  surface    roughness power spectra: list, show, add, remove, flow-factors\n"
      "  fluid      lubricants: list, show, add, remove\n"
      "  run        run a scene file: viscolube run SCENE [--out DIR] [--json]\n"
      "  seal       both strokes of a seal scene: friction, film, leakage, tightness:\n"
      "             viscolube seal SCENE [--out DIR] [--json] [--plot]\n"
      "  study      many curves from a study file, serially, with --jobs N or under mpirun:\n"
      "             viscolube study STUDY --out DIR [--jobs N]\n"
      "  pair       a compound/surface/fluid's sigma_s law: list, show, add, remove, calibrate\n"
      "  friction   one operating point of a stored compound/surface/fluid triple\n"
      "  compare    Stribeck curves of several compounds side by side\n"
      "  flattening viscous flattening of the asperities, epsilon_f vs u/h_rms (seed Figs. 19-20)\n"
      "\n"
      "options:\n"
      "  --db PATH  database file (default: $VISCOLUBE_DB, else\n"
      "             $XDG_DATA_HOME/viscolube/materials.db, else\n"
      "             ~/.local/share/viscolube/materials.db; created on first use\n"
      "             from the materials shipped in the program)\n"
      "  --quiet    no model-validity warnings and no progress lines on stderr (run,\n"
      "             friction, compare; also an option of each). Errors and the list of\n"
      "             points that did not converge are still printed.\n"
      "  --version  the version and the source commit it was built from\n"
      "  --help     this text; `viscolube NOUN --help` for a noun\n"
      "\n"
      "exit status:\n"
      "  0   success\n"
      "  2   bad input: an option, a scene file, a table, a material name\n"
      "  3   a named compound, surface or fluid is not in the database\n"
      "  4   a name is already taken\n"
      "  5   database error (corrupt, read-only, locked, newer schema)\n"
      "  6   a file or folder could not be read or written (e.g. --out; a full disk:\n"
      "      the files that fit are kept, those that did not are named), or standard\n"
      "      output could not be written (e.g. its reader has gone: `| head`)\n"
      "  7   some points did not converge (results written, flagged converged = 0;\n"
      "      stderr lists each with its speed, iterations and residual)\n"
      "  8   every point converged, but some are above their error target or have no\n"
      "      error estimate (written with accuracy = above_target or no_estimate,\n"
      "      marked '!' in the table and in the figures; stderr lists them)\n"
      "  70  out of memory or internal error\n",
      out);
}

/* The global options before the noun; -1 to go on with the noun at
 * argv[*noun], else the exit status. */
static int global_options(vl_cli_globals *g, int argc, char **argv, int *noun) {
  vl_cli_option opts[] = {
      {.name = "--help", .alias = "-h", .kind = VL_CLI_HELP},
      {.name = "--version", .kind = VL_CLI_HELP},
      {.name = "--quiet", .alias = "-q", .kind = VL_CLI_FLAG, .dest = &g->quiet},
      {.name = "--db", .kind = VL_CLI_TEXT, .metavar = "PATH", .dest = &g->db_path},
  };
  vl_cli_parser p = {.opts = opts,
                     .n_opts = sizeof opts / sizeof opts[0],
                     .flags = VL_CLI_DASH_IS_OPTION | VL_CLI_STOP_AT_POSITIONAL,
                     .unknown = "unknown option '%s' (see viscolube --help)",
                     .missing = "option %s needs a %s"};
  int rc = vl_cli_parse(&p, argc, argv, 1);
  if (rc == VL_CLI_HELP_ASKED && opts[1].given) {
    printf("viscolube %s (source %s)\n", VL_VERSION, VL_SOURCE_COMMIT);
    return 0;
  }
  if (rc == VL_CLI_HELP_ASKED) {
    usage(stdout);
    return 0;
  }
  if (rc >= 0) return rc;
  if (p.next >= argc)
    return vl_cli_usage_error("", NULL, usage,
                              "missing NOUN (compound, surface, fluid, pair, run, study, "
                              "friction, compare or flattening)");
  *noun = p.next;
  return -1;
}

static int dispatch(int argc, char **argv) {
  vl_cli_globals g = {.db_path = getenv("VISCOLUBE_DB"), .argc = argc, .argv = argv};
  int i = 0, rc = global_options(&g, argc, argv, &i);
  if (rc >= 0) return rc;
  const char *noun = argv[i];
  if (!strcmp(noun, "compound") || !strcmp(noun, "surface") || !strcmp(noun, "fluid"))
    return vl_cli_materials(&g, argc - i, argv + i);
  if (!strcmp(noun, "run")) return vl_cli_run(&g, argc - i, argv + i);
  if (!strcmp(noun, "seal")) return vl_cli_seal(&g, argc - i, argv + i);
  if (!strcmp(noun, "study")) return vl_cli_study(&g, argc - i, argv + i);
  if (!strcmp(noun, "friction")) return vl_cli_friction(&g, argc - i, argv + i);
  if (!strcmp(noun, "compare")) return vl_cli_compare(&g, argc - i, argv + i);
  if (!strcmp(noun, "flattening")) return vl_cli_flattening(&g, argc - i, argv + i);
  if (!strcmp(noun, "pair")) return vl_cli_pair(&g, argc - i, argv + i);
  fprintf(stderr, "viscolube: unknown noun '%s' (see viscolube --help)\n", noun);
  return 2;
}

/* Standard output that could not be written (a closed pipe: `| head`, a
 * full disk): a message and the I/O exit status rather than silence. The
 * files a command writes do not depend on it: SIGPIPE is ignored, so a
 * reader that goes away cannot kill the program half-way through its
 * files; they are completed (or not written at all) as if it had stayed. */
static int check_stdout(int rc) {
  errno = 0;
  int flushed = fflush(stdout) == 0;
  int e = flushed ? 0 : errno;
  if (flushed && !ferror(stdout)) return rc;
  /* an earlier write failed, leaving no errno to trust: a pipe whose
   * reader has gone says so */
  struct pollfd p = {fileno(stdout), POLLOUT, 0};
  if (!e && poll(&p, 1, 0) == 1 && (p.revents & POLLERR)) e = EPIPE;
  fprintf(stderr, "viscolube: cannot write to standard output%s%s\n", e ? ": " : "",
          e ? strerror(e) : "");
  return rc == 0 || rc == 7 || rc == VL_CLI_EXIT_UNRELIABLE ? 6 : rc;
}

int main(int argc, char **argv) {
  signal(SIGPIPE, SIG_IGN);
  /* issue 32: Ctrl-C (or a kill) during a run puts the earlier complete
   * run back in its folder (manifest.h) */
  signal(SIGINT, vl_manifest_interrupt);
  signal(SIGTERM, vl_manifest_interrupt);
  return check_stdout(dispatch(argc, argv));
}
