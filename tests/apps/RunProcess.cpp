#include "RunProcess.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace strata::testing {
namespace {

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace

ProcessResult runProcess(const std::vector<std::string>& argv,
                         const std::vector<std::pair<std::string, std::string>>& env) {
    char outName[] = "/tmp/strata-test-out-XXXXXX";
    char errName[] = "/tmp/strata-test-err-XXXXXX";
    char resultName[] = "/tmp/strata-test-status-XXXXXX";
    const int outFd = mkstemp(outName);
    const int errFd = mkstemp(errName);
    const int resultFd = mkstemp(resultName);
    if (outFd < 0 || errFd < 0 || resultFd < 0) throw std::runtime_error("runProcess: cannot make temporary files");
    close(resultFd);

    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("runProcess: fork failed");
    if (pid == 0) {
        dup2(outFd, STDOUT_FILENO);
        dup2(errFd, STDERR_FILENO);
        const int null = open("/dev/null", O_RDONLY);
        if (null >= 0) dup2(null, STDIN_FILENO);
        for (const auto& [name, value] : env) setenv(name.c_str(), value.c_str(), 1);
        // The program runs under strata_peak_rss, which reports its status and peak memory.
        std::vector<char*> args{const_cast<char*>(STRATA_PEAK_RSS_EXE), resultName};
        for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
        args.push_back(nullptr);
        execv(args[0], args.data());
        std::perror("execv");
        _exit(127);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    close(outFd);
    close(errFd);

    ProcessResult result;
    result.out = slurp(outName);
    result.err = slurp(errName);
    std::istringstream reported(slurp(resultName));
    unlink(outName);
    unlink(errName);
    unlink(resultName);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !(reported >> result.exitCode >> result.peakKiB))
        throw std::runtime_error("runProcess: strata_peak_rss did not report on " + argv.at(0) + ": " + result.err);
    return result;
}

int lineCount(const std::string& text) {
    int lines = 0;
    for (char c : text) lines += c == '\n';
    if (!text.empty() && text.back() != '\n') ++lines;
    return lines;
}

}  // namespace strata::testing
