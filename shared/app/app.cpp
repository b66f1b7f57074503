#include "app/app.h"

#include "core/interrupt.h"
#include "vk_check.h"

#include <cstdio>

namespace rg {

void initApp(App& app, const Options& opts, const std::string& title) {
    std::vector<const char*> windowExtensions;
    if (!opts.headless) {
        app.window = std::make_unique<Window>(opts.width, opts.height, title);
        windowExtensions = app.window->instanceExtensions();
    }
    Gpu& gpu = app.gpu;
    gpu.instance =
        createInstance(opts.chapter, opts.validation, windowExtensions, app.deletion);
    VkSurfaceKHR surface = app.window
                               ? app.window->createSurface(gpu.instance, app.deletion)
                               : VK_NULL_HANDLE;
    gpu.physical = pickPhysicalDevice(gpu.instance, surface, opts.device);
    std::printf("Using [%u] %s (%s)\n", gpu.physical.index,
                gpu.physical.properties.deviceName, gpu.physical.driver.c_str());
    std::fflush(stdout);  // shown at once, also when the output goes to a file or a pipe
    gpu.device = createDevice(gpu.physical, surface != VK_NULL_HANDLE, app.deletion);
    vkGetDeviceQueue(gpu.device, gpu.physical.queueFamily, 0, &gpu.queue);
    VkCommandPoolCreateInfo pool{
        .sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
        .flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT,
        .queueFamilyIndex = gpu.physical.queueFamily,
    };
    VK_CHECK(vkCreateCommandPool(gpu.device, &pool, nullptr, &gpu.commandPool));
    VkDevice device = gpu.device;
    VkCommandPool commandPool = gpu.commandPool;
    app.deletion.push([device, commandPool] {
        vkDeviceWaitIdle(device);  // nothing may be in flight when destruction starts
        vkDestroyCommandPool(device, commandPool, nullptr);
    });
}

App::~App() {
    // An error or a lost window can unwind while frames are in flight:
    // nothing may be destroyed before the GPU is done with it.
    if (gpu.device) vkDeviceWaitIdle(gpu.device);
}

int runChapter(const Options& opts, const std::function<void()>& body) {
    installInterruptHandlers();
    int code = 0;
    try {
        body();
    } catch (const InputError& e) {
        std::fprintf(stderr, "%s: error: %s\n", opts.chapter.c_str(),
                     escapeControl(e.what()).c_str());
        code = 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: error: %s\n", opts.chapter.c_str(),
                     escapeControl(e.what()).c_str());
        code = 1;
    }
    if (code == 0 && interrupted()) {
        std::fprintf(stderr, "%s: interrupted by %s: %s\n", opts.chapter.c_str(),
                     interruptSignalName().c_str(), interruptedRunSummary().c_str());
        return 130;  // 128 + SIGINT, as shells report it
    }
    uint32_t messages = validationMessageCount().load();
    if (messages > 0) {
        std::fprintf(stderr, "%s: %u validation message(s); failing the run\n",
                     opts.chapter.c_str(), messages);
        if (code == 0) code = 1;
    }
    return code;
}

}  // namespace rg
