#include "core/workers.h"

#include <pthread.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace rg {

unsigned workerCount() { return std::max(1u, std::thread::hardware_concurrency()); }

namespace {
struct Worker {
    const std::function<void(unsigned)>* work;
    unsigned index;
    std::atomic<unsigned>* finished;  // how many workers have returned
};
void* runWorker(void* argument) {
    Worker* w = static_cast<Worker*>(argument);
    (*w->work)(w->index);
    ++*w->finished;
    return nullptr;
}
}  // namespace

void runWorkers(unsigned count, size_t stackBytes,
                const std::function<void(unsigned)>& work,
                const std::function<void()>& waiting) {
    std::vector<pthread_t> threads(count);
    std::atomic<unsigned> finished{0};
    std::vector<Worker> workers(count);
    pthread_attr_t attributes;
    pthread_attr_init(&attributes);
    pthread_attr_setstacksize(&attributes, stackBytes);
    unsigned started = 0;
    int error = 0;
    for (; started < count; ++started) {
        workers[started] = {&work, started, &finished};
        error = pthread_create(&threads[started], &attributes, runWorker,
                               &workers[started]);
        if (error != 0) break;
    }
    pthread_attr_destroy(&attributes);
    while (waiting && finished.load() < started) {
        waiting();
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    for (unsigned i = 0; i < started; ++i) pthread_join(threads[i], nullptr);
    if (error != 0)
        throw std::runtime_error("could not start a worker thread: " +
                                 std::string(std::strerror(error)));
}

}  // namespace rg
