// swath_rusage_probe COMMAND: runs COMMAND through /bin/sh and prints "EXIT CPU_S PEAK_RSS_KB" of
// it and its children alone (output_dir_test.cpp's bounded-input test).
//
// Why a process of its own: Linux keeps a process's peak RSS across exec (the pre-exec image's
// high-water mark is carried over), so a command forked from the test process and exec'ed reports
// at least the test process's own RSS — under the sanitizers a long-running test process holds
// hundreds of MB, and which tests ran before in its shard decided whether a 10 MB command
// "used" more than the 200 MB bound. Forked from this small process, the command starts clean.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: swath_rusage_probe COMMAND\n");
    return 2;
  }
  const pid_t child = fork();
  if (child < 0) return 3;
  if (child == 0) {
    execl("/bin/sh", "sh", "-c", argv[1], static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  rusage usage{};
  if (wait4(child, &status, 0, &usage) != child) return 3;
  const double cpu_s = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                       1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  std::printf("%d %.6f %ld\n", WIFEXITED(status) ? WEXITSTATUS(status) : -1, cpu_s,
              usage.ru_maxrss);
  return 0;
}
