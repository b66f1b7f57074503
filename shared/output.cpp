#include "output.h"

#include "display.h"
#include "files.h"
#include "interrupt.h"
#include "vk_check.h"

#include <stb_image_write.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace rg {

FloatImage readImage(const Gpu& gpu, const Image& image,
                     VkPipelineStageFlags lastWriter) {
    FloatImage out{image.extent.width, image.extent.height, {}};
    VkDeviceSize size = VkDeviceSize(out.width) * out.height * 4 * sizeof(float);
    DeletionQueue local;
    Buffer staging = createHostBuffer(gpu, local, size, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    submitOnce(gpu, [&](VkCommandBuffer cmd) {
        // GENERAL -> TRANSFER_SRC for the copy, and back: shaders keep writing GENERAL.
        imageBarrier(cmd, image.handle, VK_IMAGE_LAYOUT_GENERAL,
                     VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, lastWriter,
                     VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                     VK_ACCESS_TRANSFER_READ_BIT);
        VkBufferImageCopy region{
            .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
            .imageExtent = {out.width, out.height, 1},
        };
        vkCmdCopyImageToBuffer(cmd, image.handle, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                               staging.handle, 1, &region);
        imageBarrier(cmd, image.handle, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                     VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
                     lastWriter, VK_ACCESS_SHADER_WRITE_BIT);
        VkBufferMemoryBarrier toHost{
            .sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER,
            .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
            .dstAccessMask = VK_ACCESS_HOST_READ_BIT,
            .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
            .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
            .buffer = staging.handle,
            .size = VK_WHOLE_SIZE,
        };
        vkCmdPipelineBarrier(cmd,
                             VK_PIPELINE_STAGE_TRANSFER_BIT,  // after the copy
                             VK_PIPELINE_STAGE_HOST_BIT,      // before the CPU reads
                             0, 0, nullptr, 1, &toHost, 0, nullptr);
    });
    out.rgba.resize(size / sizeof(float));
    std::memcpy(out.rgba.data(), staging.mapped, size);
    return out;
}

void writePng(const std::string& path, const FloatImage& image) {
    std::vector<uint8_t> rgb(size_t(image.width) * image.height * 3);
    for (size_t i = 0; i < size_t(image.width) * image.height; ++i)
        for (int c = 0; c < 3; ++c) rgb[3 * i + c] = toDisplay8(image.rgba[4 * i + c]);
    std::string png;  // encoded in memory: stb's own file writer ignores write errors
    auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                                   size_t(size));
    };
    if (!stbi_write_png_to_func(append, &png, int(image.width), int(image.height), 3,
                                rgb.data(), int(image.width) * 3))
        throw std::runtime_error("cannot encode " + path);
    writeFileAtomically(path, png.data(), png.size());
}

void writePfm(const std::string& path, const FloatImage& image) {
    std::string pfm = "PF\n" + std::to_string(image.width) + " " +
                      std::to_string(image.height) +
                      "\n-1.0\n";  // negative: little endian
    for (uint32_t y = image.height; y-- > 0;)  // PFM stores the bottom row first
        for (uint32_t x = 0; x < image.width; ++x)
            pfm.append(reinterpret_cast<const char*>(
                           &image.rgba[4 * (size_t(y) * image.width + x)]),
                       12);
    writeFileAtomically(path, pfm.data(), pfm.size());
}

FloatImage readPfm(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    std::string magic;
    FloatImage image;
    double scale = 0;
    if (!(file >> magic >> image.width >> image.height >> scale) || magic != "PF" ||
        scale >= 0)
        throw std::runtime_error(path + ": not a little-endian RGB PFM file");
    file.get();
    image.rgba.assign(size_t(image.width) * image.height * 4, 1.0f);
    for (uint32_t y = image.height; y-- > 0;)
        for (uint32_t x = 0; x < image.width; ++x)
            if (!file.read(reinterpret_cast<char*>(
                               &image.rgba[4 * (size_t(y) * image.width + x)]),
                           12))
                throw std::runtime_error(path + ": truncated PFM file");
    return image;
}

double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

namespace {
nlohmann::json stats(const std::vector<double>& v) {
    if (v.empty()) return {{"median", nullptr}, {"min", nullptr}, {"max", nullptr}};
    return {{"median", median(v)},
            {"min", *std::min_element(v.begin(), v.end())},
            {"max", *std::max_element(v.begin(), v.end())}};
}
}  // namespace

nlohmann::json makeReport(const Options& opts, const Gpu& gpu, const FrameTimes& times) {
    nlohmann::json report = {
        {"chapter", opts.chapter},
        {"device", gpu.physical.properties.deviceName},
        {"driver", gpu.physical.driver},
        {"width", opts.width},
        {"height", opts.height},
        {"frames", times.gpuMs.size()},
        {"headless", opts.headless},
        {"gpu_ms", stats(times.gpuMs)},
        {"cpu_ms", stats(times.cpuMs)},
        {"validation", opts.validation},
        {"validation_messages", validationMessageCount().load()},
    };
    if (interrupted()) {  // Ctrl-C: the frames done so far (interrupt.h)
        std::string requested =
            opts.framesToRun() > 0 ? std::to_string(opts.framesToRun()) : "unlimited";
        report["interrupted"] = {{"signal", interruptSignalName()},
                                 {"frames_done", times.gpuMs.size()},
                                 {"frames_requested", requested}};
        setInterruptedRunSummary("after " + std::to_string(times.gpuMs.size()) + " of " +
                                 requested + " frames; the outputs hold the frames done");
    }
    return report;
}

void writeReport(const std::string& path, const nlohmann::json& report) {
    std::string text = report.dump(2) + "\n";
    writeFileAtomically(path, text.data(), text.size());
}

}  // namespace rg
