#include "core/interrupt.h"

#include <atomic>
#include <csignal>
#include <cstring>
#include <unistd.h>

namespace rg {

namespace {
std::atomic<int> signalSeen{0};
// A signal handler may only call async-signal-safe functions (write,
// unlink, _exit) and read lock-free atomics: the path is a fixed buffer.
char fileInProgress[4096];
std::atomic<bool> haveFileInProgress{false};

void onSignal(int number) {
    int expected = 0;
    // the first: the run stops soon
    if (signalSeen.compare_exchange_strong(expected, number)) return;
    if (haveFileInProgress.load()) unlink(fileInProgress);
    const char line[] = "interrupted again: quitting now, nothing written\n";
    ssize_t ignored = write(STDERR_FILENO, line, sizeof line - 1);
    (void)ignored;
    _exit(130);
}
}  // namespace

void installInterruptHandlers() {
    struct sigaction action {};
    action.sa_handler = onSignal;
    action.sa_flags = SA_RESTART;  // reads and writes in progress go on
    sigemptyset(&action.sa_mask);
    for (int number : {SIGINT, SIGTERM, SIGHUP}) sigaction(number, &action, nullptr);
}

bool interrupted() { return signalSeen.load() != 0; }

std::string interruptSignalName() {
    switch (signalSeen.load()) {
        case SIGINT: return "SIGINT";
        case SIGTERM: return "SIGTERM";
        case SIGHUP: return "SIGHUP";
        default: return "";
    }
}

namespace {
std::string summary = "stopped before the first frame; nothing written";
}
void setInterruptedRunSummary(const std::string& text) { summary = text; }
std::string interruptedRunSummary() { return summary; }

void setFileInProgress(const char* path) {
    haveFileInProgress.store(false);
    if (!path) return;
    std::strncpy(fileInProgress, path, sizeof fileInProgress - 1);
    fileInProgress[sizeof fileInProgress - 1] = '\0';
    haveFileInProgress.store(true);
}

}  // namespace rg
