#include "DiffImages.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <glm/geometric.hpp>

#include "strata/core/Error.h"
#include "strata/io/ImageWriter.h"

namespace strata::accuracy {

namespace {

struct Rgb {
    double r, g, b;
};

// A distinct hue per leaf id (golden-ratio steps around the colour wheel).
Rgb leafHue(int leaf) {
    const double h = std::fmod(0.13 + 0.618033988749895 * leaf, 1.0) * 6.0;
    const double x = 1.0 - std::abs(std::fmod(h, 2.0) - 1.0);
    Rgb c{0, 0, 0};
    switch (static_cast<int>(h)) {
        case 0: c = {1, x, 0}; break;
        case 1: c = {x, 1, 0}; break;
        case 2: c = {0, 1, x}; break;
        case 3: c = {0, x, 1}; break;
        case 4: c = {x, 0, 1}; break;
        default: c = {1, 0, x}; break;
    }
    // Pastel, so the shading reads.
    return {0.35 + 0.65 * c.r, 0.35 + 0.65 * c.g, 0.35 + 0.65 * c.b};
}

std::uint8_t byte(double v) { return static_cast<std::uint8_t>(std::clamp(v, 0.0, 1.0) * 255.0 + 0.5); }

void put(RgbaImage& image, std::size_t k, Rgb c) {
    image.rgba[4 * k + 0] = byte(c.r);
    image.rgba[4 * k + 1] = byte(c.g);
    image.rgba[4 * k + 2] = byte(c.b);
    image.rgba[4 * k + 3] = 255;
}

Rgb shade(const camera::Camera& camera, const AovView& image, int i, int j) {
    const std::size_t k = static_cast<std::size_t>(j) * image.width + i;
    if (image.leaf[k] < 0) return {0.16, 0.16, 0.19};
    const glm::dvec3 n(image.normal[k]);
    const double len = glm::length(n);
    if (!(len > 0.0) || !std::isfinite(len)) return {1.0, 0.0, 1.0};  // a hit without a normal: magenta
    const double facing = -glm::dot(n / len, camera.ray(i, j).direction);
    const Rgb hue = leafHue(image.leaf[k]);
    // Back-facing normals (the eye inside the result sees its first exit) shade darker.
    const double light = facing >= 0.0 ? 0.3 + 0.7 * facing : 0.15 + 0.35 * -facing;
    return {hue.r * light, hue.g * light, hue.b * light};
}

RgbaImage blank(int w, int h) {
    RgbaImage image;
    image.width = w;
    image.height = h;
    image.rgba.assign(static_cast<std::size_t>(w) * h * 4, 255);
    return image;
}

}  // namespace

RgbaImage falseColour(const camera::Camera& camera, const AovView& image) {
    RgbaImage out = blank(image.width, image.height);
    for (int j = 0; j < image.height; ++j) {
        for (int i = 0; i < image.width; ++i) put(out, static_cast<std::size_t>(j) * image.width + i, shade(camera, image, i, j));
    }
    return out;
}

RgbaImage heatMap(const camera::Camera& camera, const AovView& gpu, const AovView& reference,
                  const CompareResult& result) {
    RgbaImage out = blank(result.width, result.height);
    for (int j = 0; j < result.height; ++j) {
        for (int i = 0; i < result.width; ++i) {
            const std::size_t k = static_cast<std::size_t>(j) * result.width + i;
            const bool edge = result.edgeMask[k] != 0;
            Rgb c{0, 0, 0};
            switch (result.verdict[k]) {
                case Verdict::Agree: {
                    const Rgb s = shade(camera, reference, i, j);
                    const double v = 0.3 * (s.r + s.g + s.b) / 3.0;
                    c = edge ? Rgb{v, v, v + 0.22} : Rgb{v, v, v};
                    break;
                }
                case Verdict::Coverage: c = {1.0, 0.12, 0.12}; break;
                case Verdict::Depth: {
                    const double dz = std::abs(double(gpu.depth[k]) - double(reference.depth[k]));
                    const double t = std::isfinite(dz)
                                         ? std::clamp(std::log10(dz / result.options.depthTolerance) / 3.0, 0.0, 1.0)
                                         : 1.0;
                    c = {1.0, 0.5 + 0.5 * t, 0.0};
                    break;
                }
                case Verdict::Normal: c = {0.0, 0.85, 1.0}; break;
                case Verdict::Leaf: c = {0.25, 1.0, 0.25}; break;
                case Verdict::Cut: c = {1.0, 0.3, 1.0}; break;
            }
            if (edge && result.verdict[k] != Verdict::Agree) c = {c.r * 0.55, c.g * 0.55, c.b * 0.55};
            put(out, k, c);
        }
    }
    return out;
}

RgbaImage sideBySide(std::span<const RgbaImage> images, int gap) {
    int w = 0, h = 0;
    for (const RgbaImage& im : images) {
        w += im.width;
        h = std::max(h, im.height);
    }
    w += gap * std::max<int>(0, static_cast<int>(images.size()) - 1);
    RgbaImage out = blank(w, h);
    int x0 = 0;
    for (const RgbaImage& im : images) {
        for (int j = 0; j < im.height; ++j) {
            std::copy_n(&im.rgba[static_cast<std::size_t>(j) * im.width * 4], static_cast<std::size_t>(im.width) * 4,
                        &out.rgba[(static_cast<std::size_t>(j) * w + x0) * 4]);
        }
        x0 += im.width + gap;
    }
    return out;
}

void writePng(const std::string& path, const RgbaImage& image) {
    io::writePng(path, image.width, image.height, image.rgba);
}

ComparisonImages writeComparisonImages(const std::string& prefix, const camera::Camera& camera, const AovView& gpu,
                                       const AovView& reference, const CompareResult& result) {
    const std::filesystem::path folder = std::filesystem::path(prefix).parent_path();
    if (!folder.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(folder, ec);
        if (ec) throw Error(folder.string() + ": cannot create folder (" + ec.message() + ")");
    }
    const RgbaImage images[3] = {falseColour(camera, gpu), falseColour(camera, reference),
                                 heatMap(camera, gpu, reference, result)};
    ComparisonImages paths{prefix + "-strata.png", prefix + "-reference.png", prefix + "-diff.png",
                           prefix + "-strip.png"};
    writePng(paths.gpu, images[0]);
    writePng(paths.reference, images[1]);
    writePng(paths.diff, images[2]);
    writePng(paths.strip, sideBySide(images));
    return paths;
}

}  // namespace strata::accuracy
