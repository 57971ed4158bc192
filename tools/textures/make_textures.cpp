// SPDX-License-Identifier: Apache-2.0
// ppm-textures: writes the procedural textures the example scenes use (examples/scenes/):
// blue-and-white porcelain, a checkerboard, wood planks and wall tiles, as 8-bit sRGB PNGs
// through OpenImageIO. Every image is a pure function of its pixel coordinates, so the
// files are the same on every run and every machine, and each one tiles seamlessly.
#include <ppm/ppm.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace {

const char *const usage_text =
    "usage: ppm-textures OUTDIR\n"
    "Writes the example scenes' procedural textures into OUTDIR (created if missing):\n"
    "  porcelain.png  1024 x 512   blue-and-white porcelain bands, to wrap a sphere or teapot\n"
    "  checker.png     512 x 512   8 x 8 checks in two muted colours\n"
    "  wood.png       1024 x 1024  wood planks: growth rings with noise\n"
    "  tiles.png       512 x 512   4 x 4 glazed wall tiles with grout\n"
    "  sky.exr         512 x 256   a sky with a small sun, linear radiance (an envmap)\n"
    "All are 8-bit sRGB, deterministic and tile seamlessly.\n"
    "options:\n"
    "  -h, --help   this text\n"
    "  --version    print the libppm version\n"
    "Exit status: 0 ok, 1 usage error, 2 runtime error.\n";

constexpr double pi = 3.14159265358979323846;

struct Rgb {
    double r, g, b;
};

Rgb mix(const Rgb &a, const Rgb &b, double t) {
    return {a.r + (b.r - a.r) * t, a.g + (b.g - a.g) * t, a.b + (b.b - a.b) * t};
}

double clamp01(double x) { return std::min(1.0, std::max(0.0, x)); }

double smoothstep(double e0, double e1, double x) {
    const double t = clamp01((x - e0) / (e1 - e0));
    return t * t * (3 - 2 * t);
}

// Floor-based modulo: always in [0, m).
double wrap(double x, double m) { return x - m * std::floor(x / m); }

// Integer hash (a 32-bit finaliser) -> [0, 1): the noise lattice's random values.
double hash01(uint32_t x, uint32_t y, uint32_t seed) {
    uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u ^ seed * 0xcb1ab31fu;
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return h / 4294967296.0;
}

// Value noise in [0, 1] on an integer lattice that repeats every (period_x, period_y) cells,
// so that textures built from it tile.
double value_noise(double x, double y, int period_x, int period_y, uint32_t seed) {
    const double fx = std::floor(x), fy = std::floor(y);
    const double tx = x - fx, ty = y - fy;
    const auto lattice = [&](double i, double j) {
        const auto xi = static_cast<uint32_t>(wrap(i, period_x)), yj = static_cast<uint32_t>(wrap(j, period_y));
        return hash01(xi, yj, seed);
    };
    const double sx = tx * tx * (3 - 2 * tx), sy = ty * ty * (3 - 2 * ty);
    const double a = lattice(fx, fy), b = lattice(fx + 1, fy), c = lattice(fx, fy + 1), d = lattice(fx + 1, fy + 1);
    return (a + (b - a) * sx) * (1 - sy) + (c + (d - c) * sx) * sy;
}

// Fractal sum of `octaves` value-noise layers, each twice as fine and half as strong; in [0, 1].
double fbm(double x, double y, int period_x, int period_y, int octaves, uint32_t seed) {
    double sum = 0, weight = 0.5, total = 0;
    for (int k = 0; k < octaves; ++k) {
        sum += weight * value_noise(x, y, period_x, period_y, seed + k);
        total += weight;
        x *= 2;
        y *= 2;
        period_x *= 2;
        period_y *= 2;
        weight *= 0.5;
    }
    return sum / total;
}

// An image as sRGB values in [0, 1]; each pixel averages samples x samples points of `shade`,
// which takes pixel coordinates (x to the right, y down, pixel centres at k + 0.5).
struct Image {
    int width, height;
    std::vector<Rgb> pixels;
};

Image render(int width, int height, int samples, const std::function<Rgb(double, double)> &shade) {
    Image image{width, height, std::vector<Rgb>(static_cast<size_t>(width) * height)};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            Rgb sum{0, 0, 0};
            for (int j = 0; j < samples; ++j)
                for (int i = 0; i < samples; ++i) {
                    const Rgb c = shade(x + (i + 0.5) / samples, y + (j + 0.5) / samples);
                    sum = {sum.r + c.r, sum.g + c.g, sum.b + c.b};
                }
            const double n = samples * samples;
            image.pixels[static_cast<size_t>(y) * width + x] = {sum.r / n, sum.g / n, sum.b / n};
        }
    return image;
}

void write_png(const Image &image, const std::string &path) {
    std::vector<uint8_t> bytes(image.pixels.size() * 3);
    for (size_t k = 0; k < image.pixels.size(); ++k) {
        const Rgb &c = image.pixels[k];
        bytes[3 * k + 0] = static_cast<uint8_t>(std::lround(clamp01(c.r) * 255));
        bytes[3 * k + 1] = static_cast<uint8_t>(std::lround(clamp01(c.g) * 255));
        bytes[3 * k + 2] = static_cast<uint8_t>(std::lround(clamp01(c.b) * 255));
    }
    auto out = OIIO::ImageOutput::create(path);
    if (!out) throw std::runtime_error(path + ": cannot create an image writer: " + OIIO::geterror());
    OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, bytes.data()) || !out->close())
        throw std::runtime_error(path + ": cannot write: " + out->geterror());
}

// Linear radiance as a 32-bit float EXR (an environment map).
void write_exr(const Image &image, const std::string &path) {
    std::vector<float> values(image.pixels.size() * 3);
    for (size_t k = 0; k < image.pixels.size(); ++k) {
        values[3 * k + 0] = static_cast<float>(image.pixels[k].r);
        values[3 * k + 1] = static_cast<float>(image.pixels[k].g);
        values[3 * k + 2] = static_cast<float>(image.pixels[k].b);
    }
    auto out = OIIO::ImageOutput::create(path);
    if (!out) throw std::runtime_error(path + ": cannot create an image writer: " + OIIO::geterror());
    OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::FLOAT);
    if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, values.data()) || !out->close())
        throw std::runtime_error(path + ": cannot write: " + out->geterror());
}

// ---- sky -------------------------------------------------------------------------------------
//
// A latitude-longitude environment in Mitsuba's envmap layout (the top row looks along +y,
// u = 0 along -z): a blue sky brightening towards the horizon, a warm grey ground, and a small
// sun 35 degrees high whose 6-degree disc carries about half of the light, so that shadows are
// clear and rough metal shows a highlight.
Rgb sky(double x, double y, int width, int height) {
    const double pi = 3.14159265358979323846;
    const double phi = 2 * pi * x / width, theta = pi * y / height;
    const double dx = std::sin(phi) * std::sin(theta), dy = std::cos(theta), dz = -std::cos(phi) * std::sin(theta);
    const double sun_elevation = 35 * pi / 180, sun_azimuth = 0.7;
    const double sx = std::sin(sun_azimuth) * std::cos(sun_elevation), sy = std::sin(sun_elevation),
                 sz = -std::cos(sun_azimuth) * std::cos(sun_elevation);
    if (dx * sx + dy * sy + dz * sz > std::cos(6 * pi / 180)) return {60, 54, 45};
    if (dy < 0) return {0.25, 0.22, 0.19};
    const double horizon = std::pow(1 - dy, 4);
    return {0.25 + 0.6 * horizon, 0.45 + 0.5 * horizon, 0.95 + 0.2 * horizon};
}

// ---- porcelain -------------------------------------------------------------------------------
//
// Laid out for a surface of revolution: u (x) goes around, v (y) from the top (rim, or a
// sphere's pole) to the bottom (foot). From top to bottom: a cobalt rim band, a key-fret
// (meander) band, a main field with a scrolling vine carrying lotus flowers and leaves, a
// band of lotus-petal panels, and a foot ring. Motifs are drawn as ink density in [0, 1]
// (1: outlines, about 0.5: the lighter wash that fills them), as painted cobalt does.

constexpr int porcelain_w = 1024, porcelain_h = 512;

// Horizontal band [y0, y1) in pixels, with a soft edge half a pixel wide.
double band(double y, double y0, double y1) {
    return smoothstep(y0 - 0.5, y0 + 0.5, y) * (1 - smoothstep(y1 - 0.5, y1 + 0.5, y));
}

// Ink of a stroke of half-width w at distance d.
double stroke(double d, double w) { return 1 - smoothstep(w - 0.6, w + 0.6, d); }

// Greek key: each unit is 6 x 6 cells; a spiral hook, then a baseline into the next unit.
double key_fret(double x, double y, double y0, double y1) {
    static const char *const unit[6] = {
        "#####.", "#...#.", "#.#.#.", "#.###.", "#.....", "######",
    };
    if (y < y0 || y >= y1) return 0;
    constexpr int units = 24;
    const double cell_w = porcelain_w / (units * 6.0), cell_h = (y1 - y0) / 6;
    const int col = static_cast<int>(wrap(x / cell_w, units * 6)) % 6;
    const int row = std::min(5, static_cast<int>((y - y0) / cell_h));
    return unit[row][col] == '#' ? 1 : 0;
}

// Signed distance in pixels to a lotus petal's outline (positive inside): straight sides of
// half-width w from the base (y = 0, y grows upwards here) to `shoulder`, then a pointed
// (gothic) arch made of two arcs of radius 2.2 w, each centred on the far side.
double petal_distance(double x, double y, double w, double shoulder) {
    const double R = 2.2 * w;
    double side;
    if (y <= shoulder) {
        side = w - std::fabs(x);
    } else {
        side = R - std::hypot(std::fabs(x) - (w - R), y - shoulder);
    }
    return std::min(side, y);
}

// The band of petal panels between y0 (top) and y1 (bottom): 16 petals pointing up, each an
// outline around a washed inner petal with a dark flame in its middle.
double lotus_panels(double x, double y, double y0, double y1) {
    if (y < y0 - 1 || y > y1 + 1) return 0;
    constexpr int panels = 16;
    const double panel_w = static_cast<double>(porcelain_w) / panels, h = y1 - y0;
    const double lx = wrap(x, panel_w) - panel_w / 2, ly = y1 - y; // ly: up from the base
    const double w = panel_w * 0.44;
    const double shoulder = h - std::sqrt(2 * 2.2 * w * w - w * w) - 2; // tip just under y0
    double ink = stroke(std::fabs(petal_distance(lx, ly, w, shoulder)), 1.6);
    const double inner = petal_distance(lx, ly - 8, w * 0.62, shoulder - 14);
    if (inner > 0) ink = std::max(ink, 0.5);
    ink = std::max(ink, stroke(std::fabs(inner), 1.1));
    if (petal_distance(lx, ly - 22, w * 0.16, shoulder - 40) > 0) ink = std::max(ink, 0.95);
    return ink;
}

// A lotus rosette centred at (cx, cy): `n` elliptical petals around a seed pod.
double rosette(double x, double y, double cx, double cy, double radius, int n, double phase) {
    const double dx = x - cx, dy = y - cy, r = std::hypot(dx, dy);
    if (r > radius * 1.1) return 0;
    double ink = 0;
    if (r < radius * 0.28) ink = std::max(ink, r > radius * 0.22 ? 1.0 : 0.55);
    if (r < radius * 0.12) ink = 1;
    const double a = std::atan2(dy, dx) + phase;
    const double sector = 2 * pi / n;
    const double local = wrap(a + sector / 2, sector) - sector / 2; // angle from the petal's axis
    // Petal: an ellipse along the axis from 0.3 to 1.0 radius.
    const double along = r * std::cos(local) / radius, across = r * std::sin(local) / radius;
    const double e = std::pow((along - 0.65) / 0.36, 2) + std::pow(across / 0.19, 2);
    if (e < 1) ink = std::max(ink, e > 0.72 ? 1.0 : 0.45 + 0.2 * (1 - e));
    return ink;
}

// A pointed leaf from (x0, y0) in direction `angle`, `length` long.
double leaf(double x, double y, double x0, double y0, double angle, double length) {
    const double dx = x - x0, dy = y - y0;
    const double along = (dx * std::cos(angle) + dy * std::sin(angle)) / length;
    const double across = (-dx * std::sin(angle) + dy * std::cos(angle)) / length;
    if (along < 0 || along > 1) return 0;
    const double half = 0.28 * std::sin(pi * along) * (1 - 0.3 * along);
    const double d = half - std::fabs(across);
    if (d < -0.04) return 0;
    if (std::fabs(across) < 0.015 && along < 0.85) return 1; // the midrib
    return d > 0.05 ? 0.5 : 1.0;
}

// Main field between y0 and y1: a vine y = c + A sin(2 pi k x / W) with a lotus rosette in
// each bend and a pair of leaves where it crosses the middle.
double vine_field(double x, double y, double y0, double y1) {
    if (y < y0 || y > y1) return 0;
    constexpr int waves = 5;
    const double W = porcelain_w, c = (y0 + y1) / 2, A = (y1 - y0) * 0.3, k = 2 * pi * waves / W;
    const double f = c + A * std::sin(k * x), slope = A * k * std::cos(k * x);
    double ink = stroke(std::fabs(y - f) / std::sqrt(1 + slope * slope), 2.2);
    const double wave_w = W / waves, flower_r = (y1 - y0) * 0.19;
    const int nearest = static_cast<int>(std::floor(x / wave_w));
    for (int i = nearest - 1; i <= nearest + 1; ++i) {
        // y grows downwards: the sine's crest is nearer y1; the flowers sit inside the bends.
        const double crest = (i + 0.25) * wave_w, trough = (i + 0.75) * wave_w;
        ink = std::max(ink, rosette(x, y, crest, c + A - flower_r - 6, flower_r, 8, 0.3 * i));
        ink = std::max(ink, rosette(x, y, trough, c - A + flower_r + 6, flower_r, 8, 0.3 * i + 0.4));
        for (int s = 0; s < 2; ++s) {
            const double xs = (i + 0.5 * s) * wave_w, dir = s == 0 ? 1 : -1;
            const double ys = c + A * std::sin(k * xs);
            ink = std::max(ink, leaf(x, y, xs, ys, -pi / 2 + dir * 0.75, 34));
            ink = std::max(ink, leaf(x, y, xs, ys, pi / 2 + dir * 0.75, 34));
        }
    }
    return ink;
}

double porcelain_ink(double x, double y) {
    const double H = porcelain_h;
    double ink = 0;
    ink = std::max(ink, band(y, 0, 0.035 * H));         // rim
    ink = std::max(ink, band(y, 0.052 * H, 0.060 * H)); // thin line
    ink = std::max(ink, band(y, 0.075 * H, 0.080 * H)); // fret border
    ink = std::max(ink, key_fret(x, y, 0.088 * H, 0.158 * H));
    ink = std::max(ink, band(y, 0.166 * H, 0.171 * H)); // fret border
    ink = std::max(ink, vine_field(x, y, 0.19 * H, 0.63 * H));
    ink = std::max(ink, band(y, 0.645 * H, 0.655 * H)); // double line
    ink = std::max(ink, band(y, 0.662 * H, 0.666 * H));
    ink = std::max(ink, lotus_panels(x, y, 0.68 * H, 0.90 * H));
    ink = std::max(ink, band(y, 0.915 * H, 0.922 * H));
    ink = std::max(ink, band(y, 0.945 * H, 1.0 * H + 1)); // foot ring
    return ink;
}

Rgb porcelain(double x, double y) {
    const Rgb glaze{0.925, 0.940, 0.955}, cobalt{0.075, 0.165, 0.460};
    // Cobalt pools unevenly: modulate the density by low-frequency noise (periodic across u).
    const double pooling = 0.82 + 0.3 * fbm(x / 32, y / 32, porcelain_w / 32, porcelain_h / 32 + 1, 3, 11);
    const double ink = clamp01(porcelain_ink(x, y) * pooling);
    // The glaze itself varies faintly.
    const double glaze_var = 0.985 + 0.015 * value_noise(x / 8, y / 8, porcelain_w / 8, porcelain_h / 8 + 1, 5);
    const Rgb base{glaze.r * glaze_var, glaze.g * glaze_var, glaze.b * glaze_var};
    return mix(base, cobalt, ink);
}

// ---- checker, wood, tiles --------------------------------------------------------------------

Rgb checker(double x, double y) {
    const Rgb a{0.80, 0.76, 0.68}, b{0.36, 0.42, 0.48};
    const int i = static_cast<int>(x / 64), j = static_cast<int>(y / 64);
    return (i + j) % 2 ? b : a;
}

// Four planks running along y, each cut at its own distance from a log's axis (so its
// growth rings show as grain lines of varying spacing), with dark gaps and an end joint.
Rgb wood(double x, double y) {
    constexpr int size = 1024, planks = 4;
    const double plank_w = static_cast<double>(size) / planks;
    const int p = static_cast<int>(x / plank_w);
    const double lx = x - p * plank_w;
    const double centre = (hash01(p, 0, 21) - 0.5) * 600, depth = 60 + 220 * hash01(p, 1, 21);
    // Rings bend with low-frequency noise that repeats along y.
    const double warp = 40 * (fbm(x / 128, y / 128, size / 128, size / 128, 3, 31) - 0.5);
    const double r = std::hypot(lx - plank_w / 2 - centre + warp, depth) / 9.0;
    const double ring = wrap(r + 0.3 * fbm(x / 16, y / 64, size / 16, size / 64, 2, 41), 1.0);
    const double late = smoothstep(0.55, 0.8, ring) * (1 - smoothstep(0.85, 1.0, ring));
    const Rgb early{0.74, 0.55, 0.36}, latewood{0.52, 0.33, 0.19};
    Rgb c = mix(early, latewood, late);
    const double fibre = 0.92 + 0.16 * value_noise(x / 2, y / 48, size / 2, size / 48, 51);
    const double tint = 0.9 + 0.2 * hash01(p, 2, 21);
    c = {c.r * fibre * tint, c.g * fibre * tint, c.b * fibre * tint};
    const Rgb gap{0.20, 0.12, 0.07};
    const double joint_y = hash01(p, 3, 21) * size;
    const double dx = std::min(lx, plank_w - lx), dy = std::fabs(wrap(y - joint_y + size / 2.0, size) - size / 2.0);
    const double edge = std::min(smoothstep(1.0, 3.0, dx), smoothstep(1.0, 3.0, dy));
    return mix(gap, c, edge);
}

// Glazed wall tiles: 4 x 4 per image, each with its own faint tint, a darker rim towards the
// grout and a mottled glaze.
Rgb tiles(double x, double y) {
    constexpr int size = 512, n = 4;
    const double tile = static_cast<double>(size) / n;
    const int i = static_cast<int>(x / tile), j = static_cast<int>(y / tile);
    const double lx = x - i * tile, ly = y - j * tile;
    const double d = std::min({lx, tile - lx, ly, tile - ly}); // distance to the tile's edge
    const Rgb grout{0.55, 0.54, 0.51};
    if (d < 3) return grout;
    const double tint = hash01(i, j, 61);
    Rgb c = mix(Rgb{0.88, 0.86, 0.80}, Rgb{0.82, 0.84, 0.82}, tint);
    const double mottle = 0.96 + 0.06 * fbm(x / 24, y / 24, size / 24 + 1, size / 24 + 1, 3, 71);
    const double rim = 0.90 + 0.10 * smoothstep(3, 12, d);
    return {c.r * mottle * rim, c.g * mottle * rim, c.b * mottle * rim};
}

struct Texture {
    const char *name;
    int width, height;
    Rgb (*shade)(double, double);
};

const Texture textures[] = {
    {"porcelain.png", porcelain_w, porcelain_h, porcelain},
    {"checker.png", 512, 512, checker},
    {"wood.png", 1024, 1024, wood},
    {"tiles.png", 512, 512, tiles},
};

} // namespace

int main(int argc, char **argv) {
    std::string outdir;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "-h") || !std::strcmp(argv[i], "--help")) {
            std::fputs(usage_text, stdout);
            return 0;
        }
        if (!std::strcmp(argv[i], "--version")) {
            std::printf("ppm-textures (libppm %s)\n", ppm_version_string());
            return 0;
        }
        if (argv[i][0] == '-' || !outdir.empty()) {
            std::fprintf(stderr, "ppm-textures: unexpected argument '%s'\n%s", argv[i], usage_text);
            return 1;
        }
        outdir = argv[i];
    }
    if (outdir.empty()) {
        std::fprintf(stderr, "ppm-textures: no output folder given\n%s", usage_text);
        return 1;
    }
    try {
        std::error_code ec;
        std::filesystem::create_directories(outdir, ec);
        if (ec) throw std::runtime_error(outdir + ": cannot create the folder: " + ec.message());
        for (const Texture &t : textures) {
            const std::string path = (std::filesystem::path(outdir) / t.name).string();
            std::fprintf(stderr, "ppm-textures: rendering %s ...\n", t.name);
            write_png(render(t.width, t.height, 3, t.shade), path);
            std::printf("wrote %s (%d x %d, 8-bit sRGB)\n", path.c_str(), t.width, t.height);
        }
        const std::string sky_path = (std::filesystem::path(outdir) / "sky.exr").string();
        write_exr(render(512, 256, 3, [](double x, double y) { return sky(x, y, 512, 256); }), sky_path);
        std::printf("wrote %s (512 x 256, linear float)\n", sky_path.c_str());
    } catch (const std::exception &e) {
        std::fprintf(stderr, "ppm-textures: %s\n", e.what());
        return 2;
    }
    return 0;
}
