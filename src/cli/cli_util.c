/* Small helpers shared by the command's nouns. */
#include <errno.h>
#include <stdio.h>
#include <sys/stat.h>

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
