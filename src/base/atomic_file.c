/* Write to a temporary, then rename (atomic_file.h). */
#include "viscolube/atomic_file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

/* Makes the temporary's name unique among the calls of this process (the
 * pid makes it unique among the processes of one machine). */
static atomic_ulong counter;

/* 32 random bits for the temporary's name: two machines sharing a folder
 * (NFS) may run processes with the same pid. getrandom never fails for so
 * few bytes once the kernel's pool is ready; else the time and the counter
 * stand in (O_EXCL still refuses a collision, and the caller retries). */
static unsigned long random_tag(unsigned long n) {
  uint32_t r = 0;
  if (getrandom(&r, sizeof r, GRND_NONBLOCK) != (ssize_t)sizeof r) {
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    r = (uint32_t)((unsigned long)ts.tv_nsec * 2654435761u ^ n);
  }
  return r;
}

/* Tries a few names: a collision (EEXIST) draws another. */
#define TEMP_TRIES 8

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
  int dir_len = (int)(name - af->path), fd = -1;
  for (int t = 0; t < TEMP_TRIES && fd < 0; t++) {
    unsigned long k = atomic_fetch_add(&counter, 1);
    int m = snprintf(af->tmp, sizeof af->tmp, "%.*s.%s.tmp.%ld.%lu.%08lx", dir_len, af->path, name,
                     (long)getpid(), k, random_tag(k));
    if (n < 0 || (size_t)n >= sizeof af->path || m < 0 || (size_t)m >= sizeof af->tmp) {
      vl_error_set(err, "%.200s...: cannot write: %s", af->path, strerror(ENAMETOOLONG));
      af->tmp[0] = '\0';
      return VL_EIO;
    }
    fd = open(af->tmp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST) break;
  }
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
