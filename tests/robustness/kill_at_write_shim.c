// kill -9 at a chosen write, without a debugger: preloaded (LD_PRELOAD) into a process, it numbers the calls to
// pwrite (through which HDF5 writes its files) from 1. With MC_WRITE_LOG set, each call appends "number offset size"
// to that file; with MC_KILL_AT_WRITE = n, call n kills the process with SIGKILL before it writes anything, so the
// file is left exactly as the first n - 1 writes made it. Each rename is logged too, as "writes-so-far -1 0": the
// first is the output appearing under its name.
#define _GNU_SOURCE
#include <dlfcn.h>
#include <fcntl.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static atomic_long calls;

static void note(long number, off_t offset, size_t count) {
  const char* log = getenv("MC_WRITE_LOG");
  if (log) {
    const int fd = open(log, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (fd >= 0) {
      char line[96];
      const int n = snprintf(line, sizeof line, "%ld %lld %zu\n", number, (long long)offset, count);
      if (n > 0 && write(fd, line, (size_t)n) < 0) {
      }
      close(fd);
    }
  }
  const char* at = getenv("MC_KILL_AT_WRITE");
  if (at && atol(at) == number) kill(getpid(), SIGKILL);
}

ssize_t pwrite(int fd, const void* buf, size_t count, off_t offset) {
  static __typeof__(&pwrite) real_pwrite;
  if (!real_pwrite) real_pwrite = (__typeof__(&pwrite))dlsym(RTLD_NEXT, "pwrite");
  note(atomic_fetch_add(&calls, 1) + 1, offset, count);
  return real_pwrite(fd, buf, count, offset);
}

ssize_t pwrite64(int fd, const void* buf, size_t count, off_t offset) { return pwrite(fd, buf, count, offset); }

int rename(const char* from, const char* to) {
  static __typeof__(&rename) real_rename;
  if (!real_rename) real_rename = (__typeof__(&rename))dlsym(RTLD_NEXT, "rename");
  const char* log = getenv("MC_WRITE_LOG");
  if (log) {
    const int fd = open(log, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (fd >= 0) {
      char line[64];
      const int n = snprintf(line, sizeof line, "%ld -1 0\n", (long)atomic_load(&calls));
      if (n > 0 && write(fd, line, (size_t)n) < 0) {
      }
      close(fd);
    }
  }
  return real_rename(from, to);
}
