// A full disk for one folder, without root: preloaded (LD_PRELOAD) into a process, it lets the files under
// MC_FULL_DISK_DIR take MC_FULL_DISK_FREE more bytes of disk in all, then fails writes that need more with ENOSPC,
// as a file system does whose free blocks are used up. A write needs space for the part of it that falls where the
// file has no blocks yet (past its end, or in a hole left by extending it with ftruncate, found with SEEK_DATA and
// SEEK_HOLE), counted in 4 KiB blocks; overwriting allocated blocks goes through. Space comes back when a file in the
// folder shrinks or goes (ftruncate, unlink, remove, rename over it). Interposes the calls through which HDF5, stdio
// and the C++ streams write, reserve and free: write, writev, pwrite(64), fallocate(64), posix_fallocate(64),
// ftruncate(64), unlink, remove, rename.
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/uio.h>
#include <unistd.h>

static atomic_llong free_bytes = -1;  // -1: not read from the environment yet
static long long initial_free, least_free;
static char folder[PATH_MAX];

static long long remaining(void) {
  if (atomic_load(&free_bytes) < 0) {
    const char* dir = getenv("MC_FULL_DISK_DIR");
    const char* bytes = getenv("MC_FULL_DISK_FREE");
    if (dir && !realpath(dir, folder)) folder[0] = '\0';
    initial_free = least_free = bytes ? atoll(bytes) : LLONG_MAX / 2;
    atomic_store(&free_bytes, initial_free);
  }
  const long long left = atomic_load(&free_bytes);
  if (left < least_free) least_free = left;
  return left;
}

// True when fd is a regular file inside the full folder.
static int on_full_disk(int fd) {
  remaining();
  if (!folder[0]) return 0;
  char link[64], target[PATH_MAX];
  snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
  const ssize_t n = readlink(link, target, sizeof target - 1);
  if (n <= 0) return 0;
  target[n] = '\0';
  const size_t len = strlen(folder);
  return strncmp(target, folder, len) == 0 && target[len] == '/';
}

// Bytes of [offset, offset + count) where the file has no blocks (the file position is kept).
static long long unallocated(int fd, off_t offset, size_t count) {
  const int saved_errno = errno;
  const off_t position = lseek(fd, 0, SEEK_CUR), end = offset + (off_t)count;
  long long holes = 0;
  for (off_t at = offset; at < end;) {
    const off_t data = lseek(fd, at, SEEK_DATA);
    if (data < 0 || data >= end) {  // no data from `at` to the end of the write
      holes += end - at;
      break;
    }
    holes += data - at;
    at = lseek(fd, data, SEEK_HOLE);
    if (at < 0) break;
  }
  lseek(fd, position, SEEK_SET);
  errno = saved_errno;
  return holes;
}

// True when writing `count` bytes at `offset` (-1: the file position) fits in the free space, which it then takes;
// else errno = ENOSPC.
static int fits(int fd, off_t offset, size_t count) {
  if (count == 0 || !on_full_disk(fd)) return 1;
  if (offset < 0) {
    struct stat st;
    offset = (fcntl(fd, F_GETFL) & O_APPEND) && fstat(fd, &st) == 0 ? st.st_size : lseek(fd, 0, SEEK_CUR);
  }
  // Whole blocks, as the file system allocates them.
  const off_t block = 4096, first = offset / block * block, last = (offset + (off_t)count + block - 1) / block * block;
  const long long needed = unallocated(fd, first, (size_t)(last - first));
  if (needed > remaining()) {
    errno = ENOSPC;
    return 0;
  }
  atomic_fetch_sub(&free_bytes, needed);
  remaining();  // the low-water mark
  return 1;
}

__attribute__((destructor)) static void report_peak(void) {
  const char* path = getenv("MC_FULL_DISK_PEAK");
  if (!path || atomic_load(&free_bytes) < 0) return;
  FILE* out = fopen(path, "w");
  if (!out) return;
  fprintf(out, "%lld\n", initial_free - least_free);
  fclose(out);
}

// The C library's own `name`, looked up once.
#define REAL(name)                      \
  static __typeof__(&name) real_##name; \
  if (!real_##name) real_##name = (__typeof__(&name))dlsym(RTLD_NEXT, #name)

ssize_t write(int fd, const void* buf, size_t count) {
  REAL(write);
  return fits(fd, -1, count) ? real_write(fd, buf, count) : -1;
}

ssize_t pwrite(int fd, const void* buf, size_t count, off_t offset) {
  REAL(pwrite);
  return fits(fd, offset, count) ? real_pwrite(fd, buf, count, offset) : -1;
}

ssize_t pwrite64(int fd, const void* buf, size_t count, off_t offset) { return pwrite(fd, buf, count, offset); }

ssize_t writev(int fd, const struct iovec* iov, int iovcnt) {
  REAL(writev);
  size_t count = 0;
  for (int i = 0; i < iovcnt; ++i) count += iov[i].iov_len;
  return fits(fd, -1, count) ? real_writev(fd, iov, iovcnt) : -1;
}

int posix_fallocate(int fd, off_t offset, off_t len) {
  REAL(posix_fallocate);
  return fits(fd, offset, (size_t)len) ? real_posix_fallocate(fd, offset, len) : ENOSPC;
}

int posix_fallocate64(int fd, off_t offset, off_t len) { return posix_fallocate(fd, offset, len); }

int fallocate(int fd, int mode, off_t offset, off_t len) {
  REAL(fallocate);
  return fits(fd, offset, (size_t)len) ? real_fallocate(fd, mode, offset, len) : -1;
}

int fallocate64(int fd, int mode, off_t offset, off_t len) { return fallocate(fd, mode, offset, len); }

// The disk space of the file at `path` inside the full folder, or 0.
static long long size_on_full_disk(const char* path) {
  remaining();
  char full[PATH_MAX];
  struct stat st;
  if (!folder[0] || !realpath(path, full) || stat(full, &st) != 0 || !S_ISREG(st.st_mode)) return 0;
  const size_t len = strlen(folder);
  return strncmp(full, folder, len) == 0 && full[len] == '/' ? (long long)st.st_blocks * 512 : 0;
}

int ftruncate(int fd, off_t length) {
  REAL(ftruncate);
  struct stat st;
  if (!on_full_disk(fd) || fstat(fd, &st) != 0) return real_ftruncate(fd, length);
  const long long freed =
      length < st.st_size ? (st.st_size - length) - unallocated(fd, length, st.st_size - length) : 0;
  const int r = real_ftruncate(fd, length);
  if (r == 0) atomic_fetch_add(&free_bytes, freed);
  return r;
}

int ftruncate64(int fd, off_t length) { return ftruncate(fd, length); }

int unlink(const char* path) {
  REAL(unlink);
  const long long freed = size_on_full_disk(path);
  const int r = real_unlink(path);
  if (r == 0) atomic_fetch_add(&free_bytes, freed);
  return r;
}

int remove(const char* path) {
  REAL(remove);
  const long long freed = size_on_full_disk(path);
  const int r = real_remove(path);
  if (r == 0) atomic_fetch_add(&free_bytes, freed);
  return r;
}

int rename(const char* from, const char* to) {
  REAL(rename);
  const long long freed = size_on_full_disk(to);  // the file replaced
  const int r = real_rename(from, to);
  if (r == 0) atomic_fetch_add(&free_bytes, freed);
  return r;
}
