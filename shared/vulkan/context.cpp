#include "vulkan/context.h"

#include "vk_check.h"
#include "vulkan/vk_ext.h"

#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace rg {

std::atomic<uint32_t>& validationMessageCount() {
    static std::atomic<uint32_t> count{0};
    return count;
}

namespace {

VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
    validationMessageCount()++;
    const char* level =
        severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "error" : "warning";
    // Layers since 1.4 leave the rule's name (VUID-..., SYNC-HAZARD-...)
    // out of the message text; it is the message's id name.
    const char* id = data->pMessageIdName ? data->pMessageIdName : "";
    if (*id && !std::strstr(data->pMessage, id))
        std::fprintf(stderr, "[validation %s] [ %s ] %s\n", level, id, data->pMessage);
    else
        std::fprintf(stderr, "[validation %s] %s\n", level, data->pMessage);
    return VK_FALSE;  // never abort the call: report it and go on
}

bool hasLayer(const char* name) {
    uint32_t count = 0;
    VK_CHECK(vkEnumerateInstanceLayerProperties(&count, nullptr));
    std::vector<VkLayerProperties> layers(count);
    VK_CHECK(vkEnumerateInstanceLayerProperties(&count, layers.data()));
    for (const auto& layer : layers)
        if (std::strcmp(layer.layerName, name) == 0) return true;
    return false;
}

[[maybe_unused]] bool layerHasExtension(const char* layer, const char* extension) {
    uint32_t count = 0;
    VK_CHECK(vkEnumerateInstanceExtensionProperties(layer, &count, nullptr));
    std::vector<VkExtensionProperties> extensions(count);
    VK_CHECK(vkEnumerateInstanceExtensionProperties(layer, &count, extensions.data()));
    for (const auto& e : extensions)
        if (std::strcmp(e.extensionName, extension) == 0) return true;
    return false;
}

}  // namespace

// [region create_instance]
VkInstance createInstance(const std::string& appName, bool validation,
                          const std::vector<const char*>& windowExtensions,
                          DeletionQueue& deletion) {
    const char* validationLayer = "VK_LAYER_KHRONOS_validation";
    if (validation && !hasLayer(validationLayer))
        throw std::runtime_error(
            "--validation: the layer VK_LAYER_KHRONOS_validation is not installed "
            "(Debian: apt-get install vulkan-validationlayers)");

    std::vector<const char*> extensions = windowExtensions;
    if (validation) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);

    // Synchronization validation finds missing barriers (chapter 02): the
    // core checks alone only see invalid API usage, not data races.
    VkValidationFeatureEnableEXT enables[] = {
        VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT features{
        .sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT,
        .enabledValidationFeatureCount = 1,
        .pEnabledValidationFeatures = enables,
    };
// Vulkan headers >= 1.3.268 (Debian 13; Debian 12 has 1.3.239)
#ifdef VK_EXT_layer_settings
    // Since layer 1.4.3xx, synchronization validation sees what shaders read
    // and write through descriptors only with this setting (its default is
    // off): without it chapter 02's missing barrier goes unreported. Older
    // layers (Debian 12's 1.3.239) always track those accesses and have no
    // VK_EXT_layer_settings.
    VkBool32 on = VK_TRUE;
    VkLayerSettingEXT shaderAccesses{
        .pLayerName = validationLayer,
        .pSettingName = "syncval_shader_accesses_heuristic",
        .type = VK_LAYER_SETTING_TYPE_BOOL32_EXT,
        .valueCount = 1,
        .pValues = &on,
    };
    VkLayerSettingsCreateInfoEXT settings{
        .sType = VK_STRUCTURE_TYPE_LAYER_SETTINGS_CREATE_INFO_EXT,
        .settingCount = 1,
        .pSettings = &shaderAccesses,
    };
    if (validation &&
        layerHasExtension(validationLayer, VK_EXT_LAYER_SETTINGS_EXTENSION_NAME)) {
        extensions.push_back(VK_EXT_LAYER_SETTINGS_EXTENSION_NAME);
        features.pNext = &settings;
    }
#endif
    VkDebugUtilsMessengerCreateInfoEXT messengerInfo{
        .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
        .pNext = &features,
        .messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                           VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
        .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
        .pfnUserCallback = onValidationMessage,
    };
    VkApplicationInfo app{
        .sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
        .pApplicationName = appName.c_str(),
        .applicationVersion = VK_MAKE_VERSION(0, 1, 0),
        .pEngineName = "RayGlass",
        .engineVersion = VK_MAKE_VERSION(0, 1, 0),
        .apiVersion = VK_API_VERSION_1_2,  // ray tracing needs SPIR-V 1.4, core in 1.2
    };
    VkInstanceCreateInfo info{
        .sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
        .pNext = validation ? &messengerInfo : nullptr,  // also reports on create/destroy
        .pApplicationInfo = &app,
        .enabledLayerCount = validation ? 1u : 0u,
        .ppEnabledLayerNames = &validationLayer,
        .enabledExtensionCount = static_cast<uint32_t>(extensions.size()),
        .ppEnabledExtensionNames = extensions.data(),
    };
    VkInstance instance = VK_NULL_HANDLE;
    VkResult created = vkCreateInstance(&info, nullptr, &instance);
    // The two failures a user meets (no driver, no validation layer) are not
    // bugs: say what to install instead of where in the code it failed.
    // A driver manifest the loader cannot parse (a truncated .json) makes
    // it fail with VK_ERROR_OUT_OF_HOST_MEMORY: the same advice applies.
    const char* install =
        "Install one: tools/setup.sh does (on Debian 12, Mesa's lavapipe, "
        "mesa-vulkan-drivers >= 24.1 from "
        "bookworm-backports), or your GPU's driver; if VK_ICD_FILENAMES or "
        "VK_DRIVER_FILES is set, it must name an "
        "existing, readable driver .json";
    if (created == VK_ERROR_INCOMPATIBLE_DRIVER)
        throw std::runtime_error(std::string("no Vulkan driver found. ") + install);
    if (created == VK_ERROR_OUT_OF_HOST_MEMORY)
        throw std::runtime_error(
            std::string("no usable Vulkan driver (the loader returned "
                        "VK_ERROR_OUT_OF_HOST_MEMORY, "
                        "as it does for a driver manifest it cannot read). ") +
            install);
    if (created == VK_ERROR_LAYER_NOT_PRESENT)
        throw std::runtime_error(
            "--validation needs the Khronos validation layer (Debian: "
            "vulkan-validationlayers)");
    VK_CHECK(created);
    deletion.push([instance] { vkDestroyInstance(instance, nullptr); });
    loadInstanceFunctions(instance);

    if (validation) {
        messengerInfo.pNext = nullptr;
        VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
        VK_CHECK(vkCreateDebugUtilsMessengerEXT(instance, &messengerInfo, nullptr,
                                                &messenger));
        deletion.push([instance, messenger] {
            vkDestroyDebugUtilsMessengerEXT(instance, messenger, nullptr);
        });
    }
    return instance;
}
// [end]

std::vector<const char*> requiredDeviceExtensions(bool present) {
    std::vector<const char*> extensions = {
        VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME,
        VK_KHR_RAY_TRACING_PIPELINE_EXTENSION_NAME,
        // required by acceleration_structure
        VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME,
    };
    if (present) extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    return extensions;
}

namespace {

// Everything `device` lacks for this tutorial, empty when it fits: names
// that live as long as the program (literals and the extension macros).
std::vector<const char*> missingRequirements(VkPhysicalDevice device,
                                             VkSurfaceKHR surface,
                                             uint32_t& queueFamily) {
    std::vector<const char*> missing;
    VkPhysicalDeviceProperties properties;
    vkGetPhysicalDeviceProperties(device, &properties);
    if (properties.apiVersion < VK_API_VERSION_1_2) missing.push_back("Vulkan 1.2");

    uint32_t count = 0;
    VK_CHECK(vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr));
    std::vector<VkExtensionProperties> available(count);
    VK_CHECK(
        vkEnumerateDeviceExtensionProperties(device, nullptr, &count, available.data()));
    for (const char* name : requiredDeviceExtensions(surface != VK_NULL_HANDLE)) {
        bool found = false;
        for (const auto& e : available)
            found = found || std::strcmp(e.extensionName, name) == 0;
        if (!found) missing.push_back(name);
    }
    if (!missing.empty()) return missing;  // feature queries need the extensions

    VkPhysicalDeviceRayTracingPipelineFeaturesKHR rt{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_FEATURES_KHR};
    VkPhysicalDeviceAccelerationStructureFeaturesKHR as{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR,
        .pNext = &rt};
    VkPhysicalDeviceVulkan12Features v12{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, .pNext = &as};
    VkPhysicalDeviceFeatures2 features{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &v12};
    vkGetPhysicalDeviceFeatures2(device, &features);
    if (!v12.bufferDeviceAddress) missing.push_back("bufferDeviceAddress");
    if (!v12.hostQueryReset) missing.push_back("hostQueryReset");
    // chapter 12's textures, one array of images indexed per hit (every
    // device with acceleration structures has them: they come with
    // VK_EXT_descriptor_indexing, which VK_KHR_acceleration_structure requires)
    if (!v12.runtimeDescriptorArray) missing.push_back("runtimeDescriptorArray");
    if (!v12.shaderSampledImageArrayNonUniformIndexing)
        missing.push_back("shaderSampledImageArrayNonUniformIndexing");
    if (!as.accelerationStructure) missing.push_back("accelerationStructure");
    if (!rt.rayTracingPipeline) missing.push_back("rayTracingPipeline");

    // One queue family for everything: graphics (blits), compute (tracing),
    // timestamps, and presentation to the window's surface.
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
    bool foundQueue = false;
    for (uint32_t i = 0; i < count && !foundQueue; ++i) {
        VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
        VkBool32 present = VK_TRUE;
        if (surface)
            VK_CHECK(vkGetPhysicalDeviceSurfaceSupportKHR(device, i, surface, &present));
        if ((families[i].queueFlags & need) == need &&
            families[i].timestampValidBits > 0 && present) {
            queueFamily = i;
            foundQueue = true;
        }
    }
    if (!foundQueue)
        missing.push_back(
            surface ? "a graphics+compute queue with timestamps that can present"
                    : "a graphics+compute queue with timestamps");
    return missing;
}

int typeRank(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
        default: return 4;
    }
}

}  // namespace

// [region pick_physical_device]
PhysicalDeviceChoice pickPhysicalDevice(VkInstance instance, VkSurfaceKHR surface,
                                        int requested) {
    uint32_t count = 0;
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
    if (requested >= static_cast<int>(count))
        throw std::runtime_error("--device " + std::to_string(requested) + ": only " +
                                 std::to_string(count) + " Vulkan device(s) found");

    int best = -1, bestRank = 99;
    uint32_t bestQueue = 0;
    std::string report;
    for (uint32_t i = 0; i < count; ++i) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(devices[i], &p);
        uint32_t queue = 0;
        std::vector<const char*> missing =
            missingRequirements(devices[i], surface, queue);
        std::string line = "  [" + std::to_string(i) + "] " + p.deviceName;
        if (missing.empty()) line += ": fits";
        else {
            line += ": lacks";
            for (const char* m : missing) line.append(" ").append(m);
        }
        report += line + "\n";
        bool eligible =
            missing.empty() && (requested < 0 || requested == static_cast<int>(i));
        if (eligible && typeRank(p.deviceType) < bestRank) {
            best = static_cast<int>(i);
            bestRank = typeRank(p.deviceType);
            bestQueue = queue;
        }
    }
    std::printf("Vulkan devices:\n%s", report.c_str());
    if (best < 0)
        throw std::runtime_error(
            (requested >= 0
                 ? "device " + std::to_string(requested) + " cannot run RayGlass"
                 : std::string("no Vulkan device can run RayGlass")) +
            " (needs VK_KHR_ray_tracing_pipeline, VK_KHR_acceleration_structure and "
            "buffer device addresses):\n" +
            report);

    PhysicalDeviceChoice choice{.handle = devices[best],
                                .index = static_cast<uint32_t>(best),
                                .queueFamily = bestQueue};
    choice.accelerationStructure.sType =
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR;
    choice.rayTracing.sType =
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_PROPERTIES_KHR;
    choice.rayTracing.pNext = &choice.accelerationStructure;
    VkPhysicalDeviceDriverProperties driver{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES,
        .pNext = &choice.rayTracing};
    VkPhysicalDeviceProperties2 properties{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &driver};
    vkGetPhysicalDeviceProperties2(choice.handle, &properties);
    choice.properties = properties.properties;
    choice.rayTracing.pNext = nullptr;  // do not keep pointers into this stack frame
    choice.driver = std::string(driver.driverName) + " / " + driver.driverInfo;
    // An optional feature, used where the device has it: a launch sized by
    // the GPU (chapter 10's second launch).
    VkPhysicalDeviceRayTracingPipelineFeaturesKHR rt{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_FEATURES_KHR};
    VkPhysicalDeviceFeatures2 features{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &rt};
    vkGetPhysicalDeviceFeatures2(choice.handle, &features);
    choice.traceRaysIndirect = rt.rayTracingPipelineTraceRaysIndirect;
    choice.shaderFloat64 = features.features.shaderFloat64;
    return choice;
}
// [end]

// [region create_device]
VkDevice createDevice(const PhysicalDeviceChoice& physical, bool present,
                      DeletionQueue& deletion) {
    float priority = 1.0f;
    VkDeviceQueueCreateInfo queue{
        .sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
        .queueFamilyIndex = physical.queueFamily,
        .queueCount = 1,
        .pQueuePriorities = &priority,
    };
    // Features are enabled by chaining their structs: the device gets only
    // what is asked for here.
    VkPhysicalDeviceRayTracingPipelineFeaturesKHR rayTracing{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_FEATURES_KHR,
        .rayTracingPipeline = VK_TRUE,
        // optional (chapter 10)
        .rayTracingPipelineTraceRaysIndirect = physical.traceRaysIndirect,
    };
    VkPhysicalDeviceAccelerationStructureFeaturesKHR accelerationStructure{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR,
        .pNext = &rayTracing,
        .accelerationStructure = VK_TRUE,
    };
    VkPhysicalDeviceVulkan12Features vulkan12{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
        .pNext = &accelerationStructure,
        // chapter 12: the textures' array, indexed by each hit's material
        .shaderSampledImageArrayNonUniformIndexing = VK_TRUE,
        .runtimeDescriptorArray = VK_TRUE,
        .hostQueryReset = VK_TRUE,       // reset timestamp queries from the CPU
        // acceleration structures and the SBT live at GPU addresses
        .bufferDeviceAddress = VK_TRUE,
    };
    VkPhysicalDeviceFeatures2 core{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2,
        .pNext = &vulkan12,
        // optional: exact edge tests in double (chapter 12's triangle.rint)
        .features = {.shaderFloat64 = physical.shaderFloat64},
    };
    std::vector<const char*> extensions = requiredDeviceExtensions(present);
    VkDeviceCreateInfo info{
        .sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
        .pNext = &core,
        .queueCreateInfoCount = 1,
        .pQueueCreateInfos = &queue,
        .enabledExtensionCount = static_cast<uint32_t>(extensions.size()),
        .ppEnabledExtensionNames = extensions.data(),
    };
    VkDevice device = VK_NULL_HANDLE;
    VK_CHECK(vkCreateDevice(physical.handle, &info, nullptr, &device));
    deletion.push([device] { vkDestroyDevice(device, nullptr); });
    loadDeviceFunctions(device);
    return device;
}
// [end]

}  // namespace rg
