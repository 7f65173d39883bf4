// strata_peak_rss RESULT PROGRAM [ARG...]
//
// Runs PROGRAM with its arguments, waits for it, and writes
// "<status> <peak resident KiB>\n" to the file RESULT: the status is the exit
// code, or 128 + the signal number when PROGRAM was killed.
//
// Why a process of its own: Linux counts into a child's ru_maxrss the resident
// size of the memory it was forked with, before exec replaced it. A test
// process that has grown (a whole test binary in one process, under ASan:
// 800 MB) would then see that size as its child's peak. Forked from this
// small program instead, PROGRAM's peak is its own.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: strata_peak_rss RESULT PROGRAM [ARG...]\n");
        return 2;
    }
    const pid_t pid = fork();
    if (pid < 0) {
        std::perror("strata_peak_rss: fork");
        return 2;
    }
    if (pid == 0) {
        execv(argv[2], argv + 2);
        std::perror("execv");
        _exit(127);
    }
    int status = 0;
    rusage usage{};
    if (wait4(pid, &status, 0, &usage) != pid) {
        std::perror("strata_peak_rss: wait4");
        return 2;
    }
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    std::FILE* result = std::fopen(argv[1], "w");
    if (!result) {
        std::perror("strata_peak_rss: result file");
        return 2;
    }
    const bool written = std::fprintf(result, "%d %ld\n", code, usage.ru_maxrss) > 0;
    return std::fclose(result) == 0 && written ? 0 : 2;
}
