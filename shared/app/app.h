// Start-up and shut-down shared by every chapter from 02 on: the window (or
// none), the Vulkan objects of chapter 01, and main()'s error handling.
#pragma once
#include "core/cli.h"
#include "core/files.h"
#include "vulkan/context.h"
#include "vulkan/deletion_queue.h"
#include "vulkan/window.h"

#include <functional>
#include <memory>
#include <stdexcept>

namespace rg {

struct App {
    std::unique_ptr<Window> window;  // declared first: outlives the queue below
    DeletionQueue deletion;          // flushed first: device objects, then the instance
    Gpu gpu;
    App() = default;
    App(const App&) = delete;
    ~App();  // waits until the device is idle, then the members go
};

// Window (unless headless), instance, surface, physical device, device,
// queue and a command pool for one-time submissions, as chapter 01 builds them.
void initApp(App& app, const Options& opts, const std::string& title);

// Runs a chapter's body: prints any error as one line and returns the exit
// code (1 for a failure, 2 for bad input, 130 after a signal, interrupt.h);
// with --validation, any validation message makes a clean run return 1 too.
int runChapter(const Options& opts, const std::function<void()>& body);

}  // namespace rg
