/* Prints the highest x86-64 micro-architecture level this machine runs: CMakeLists.txt builds for it. */
#include <stdio.h>

int main(void) {
  __builtin_cpu_init();
  if (__builtin_cpu_supports("x86-64-v4"))
    puts("x86-64-v4");
  else if (__builtin_cpu_supports("x86-64-v3"))
    puts("x86-64-v3");
  else
    puts("x86-64-v2");
  return 0;
}
