/* Write to a temporary, then rename (atomic_file.h). */
#include "viscolube/atomic_file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Makes the temporary's name unique among the calls of this process (the
 * pid makes it unique among processes). */
static atomic_ulong counter;

/* Opens path itself for writing: the target is not a regular file (a
 * terminal, a pipe, /dev/null), which a rename would replace instead of
 * writing to. af->tmp stays empty. */
static vl_status open_direct(vl_atomic_file *af, vl_error *err) {
  af->f = fopen(af->path, "w");
  if (!af->f) {
    vl_error_set(err, "%s: cannot write: %s", af->path, strerror(errno));
    return VL_EIO;
  }
  errno = 0;
  return VL_OK;
}

vl_status vl_atomic_file_open(vl_atomic_file *af, const char *path, vl_error *err) {
  af->f = NULL;
  af->tmp[0] = '\0';
  int n = snprintf(af->path, sizeof af->path, "%s", path ? path : "");
  struct stat sb;
  if (n >= 0 && (size_t)n < sizeof af->path && stat(af->path, &sb) == 0) {
    if (!S_ISREG(sb.st_mode)) return open_direct(af, err);
    /* a symbolic link: replace the file it names, not the link */
    char *real = lstat(af->path, &sb) == 0 && S_ISLNK(sb.st_mode) ? realpath(af->path, NULL) : NULL;
    if (real) n = snprintf(af->path, sizeof af->path, "%s", real);
    free(real);
  }
  const char *slash = strrchr(af->path, '/');
  const char *name = slash ? slash + 1 : af->path;
  if (!name[0]) {
    vl_error_set(err, "%s: cannot write: not a file name", af->path);
    return VL_EIO;
  }
  int dir_len = (int)(name - af->path);
  int m = snprintf(af->tmp, sizeof af->tmp, "%.*s.%s.tmp.%ld.%lu", dir_len, af->path, name,
                   (long)getpid(), atomic_fetch_add(&counter, 1));
  if (n < 0 || (size_t)n >= sizeof af->path || m < 0 || (size_t)m >= sizeof af->tmp) {
    vl_error_set(err, "%.200s...: cannot write: %s", af->path, strerror(ENAMETOOLONG));
    af->tmp[0] = '\0';
    return VL_EIO;
  }
  int fd = open(af->tmp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd >= 0) af->f = fdopen(fd, "w");
  if (!af->f) {
    int e = errno;
    if (fd >= 0) {
      close(fd);
      unlink(af->tmp);
    }
    vl_error_set(err, "%s: cannot write: %s", af->path, strerror(e));
    af->tmp[0] = '\0';
    return VL_EIO;
  }
  errno = 0;
  return VL_OK;
}

vl_status vl_atomic_file_commit(vl_atomic_file *af, vl_error *err) {
  if (!af->f) {
    vl_error_set(err, "%s: cannot write: not open", af->path);
    return VL_EIO;
  }
  /* the first failing step names the cause. A write that failed earlier
     left the stream in error and, most likely, its errno (cleared at
     open, so a stale one is not blamed) */
  int e = 0, direct = !af->tmp[0];
  if (fflush(af->f) != 0 || ferror(af->f))
    e = errno ? errno : EIO;
  else if (!direct && fsync(fileno(af->f)) != 0)
    e = errno;
  if (fclose(af->f) != 0 && !e) e = errno ? errno : EIO;
  af->f = NULL;
  if (!e && !direct && rename(af->tmp, af->path) != 0) e = errno;
  if (e) {
    if (!direct) unlink(af->tmp);
    vl_error_set(err, "%s: cannot write: %s", af->path, strerror(e));
  }
  af->tmp[0] = '\0';
  return e ? VL_EIO : VL_OK;
}

void vl_atomic_file_abort(vl_atomic_file *af) {
  if (!af->f) return;
  fclose(af->f);
  af->f = NULL;
  if (af->tmp[0]) unlink(af->tmp);
  af->tmp[0] = '\0';
}
