// Work spread over the machine's cores (the CPU references): each worker
// thread gets a stack of its own size, since a reference follows a path by
// recursion (shared/reference/shading.cpp) and chapter 15's roulette lets
// a path run to ROULETTE_MAX_DEPTH bounces, deeper than the 8 MiB a
// std::thread gets.
#pragma once

#include <cstddef>
#include <functional>

namespace rg {

// The number of workers: the machine's hardware threads, at least 1.
unsigned workerCount();
// Runs work(i) for i = 0 .. count - 1, each on its own thread with a stack
// of stackBytes, and returns when all have; while they run, the calling
// thread calls waiting() every 10 ms (a progress line), if given.
void runWorkers(unsigned count, size_t stackBytes,
                const std::function<void(unsigned)>& work,
                const std::function<void()>& waiting = {});

}  // namespace rg
