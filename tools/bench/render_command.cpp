#include "render_command.h"

#include "bench_scenes.h"
#include "check_status.h"

#include <ppm/ppm.h>

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace bench {

namespace {

struct RenderOptions {
    std::vector<std::string> scenes{"smallppm", "teapot-glass"};
    std::vector<std::string> searches{"grid", "kdtree"};
    std::vector<long> photon_counts{100000, 1000000};
    int width = 1024, height = 768;
    int passes = 4;
    int threads = 0;
    std::string teapot = PPM_SOURCE_DIR "/tests/data/teapot.bpt";
    std::string image_dir;
};

void print_usage(std::FILE *out) {
    std::fprintf(out, "usage: ppm-bench render [options]\n"
                      "Times the renderer's passes: eye pass seconds, photon paths per second and peak\n"
                      "memory, per scene, hit-point search and photons per pass; build_s is the part of\n"
                      "eye_s spent building the hit-point search. Figures are medians over the passes.\n"
                      "  --scenes LIST      smallppm,teapot-glass (default both)\n"
                      "  --search LIST      grid,kdtree (default both)\n"
                      "  --photons LIST     photons per pass, in increasing order to see whether memory\n"
                      "                     grows with them (default 100000,1000000)\n"
                      "  --width N, --height N  image size (default 1024 x 768)\n"
                      "  --passes N         passes per configuration (default 4; figures are medians)\n"
                      "  --threads N        worker threads (default 0 = all)\n"
                      "  --teapot PATH      the .bpt of teapot-glass (default tests/data/teapot.bpt)\n"
                      "  --images DIR       write each final image as DIR/<scene>-<search>.pfm (linear)\n");
}

std::vector<std::string> split(const std::string &text) {
    std::vector<std::string> parts;
    std::stringstream in(text);
    for (std::string part; std::getline(in, part, ',');)
        if (!part.empty()) parts.push_back(part);
    return parts;
}

long parse_long(const char *text, const char *option, long lo, long hi) {
    char *end = nullptr;
    const long v = std::strtol(text, &end, 10);
    if (!*text || *end || v < lo || v > hi)
        throw std::runtime_error(std::string(option) + " expects a whole number in " + std::to_string(lo) + ".." +
                                 std::to_string(hi) + ", not '" + text + "'");
    return v;
}

RenderOptions parse(int argc, char **argv, int first) {
    RenderOptions o;
    for (int i = first; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "-h" || arg == "--help") {
            print_usage(stdout);
            std::exit(0);
        }
        if (i + 1 >= argc) throw std::runtime_error("unknown option or missing value: " + arg);
        const char *value = argv[++i];
        if (arg == "--scenes")
            o.scenes = split(value);
        else if (arg == "--search")
            o.searches = split(value);
        else if (arg == "--photons") {
            o.photon_counts.clear();
            for (const std::string &p : split(value))
                o.photon_counts.push_back(parse_long(p.c_str(), "--photons", 1, 1l << 31));
        } else if (arg == "--width")
            o.width = static_cast<int>(parse_long(value, "--width", 1, 16384));
        else if (arg == "--height")
            o.height = static_cast<int>(parse_long(value, "--height", 1, 16384));
        else if (arg == "--passes")
            o.passes = static_cast<int>(parse_long(value, "--passes", 1, 100000));
        else if (arg == "--threads")
            o.threads = static_cast<int>(parse_long(value, "--threads", 0, 1024));
        else if (arg == "--teapot")
            o.teapot = value;
        else if (arg == "--images")
            o.image_dir = value;
        else
            throw std::runtime_error("unknown option: " + arg);
    }
    return o;
}

double peak_rss_mib() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_maxrss / 1024.0; // kilobytes on Linux
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

void write_pfm(const std::string &path, ppm_renderer renderer, int w, int h) {
    std::vector<float> rgb(static_cast<size_t>(w) * h * 3);
    check(ppm_renderer_get_layer(renderer, "radiance", rgb.data(), rgb.size()), "ppm_renderer_get_layer");
    std::FILE *f = std::fopen(path.c_str(), "wb");
    if (!f) throw std::runtime_error("cannot write " + path);
    std::fprintf(f, "PF\n%d %d\n-1.0\n", w, h);
    for (int y = h - 1; y >= 0; --y) std::fwrite(&rgb[static_cast<size_t>(y) * w * 3], sizeof(float), w * 3u, f);
    std::fclose(f);
}

} // namespace

int run_render_command(int argc, char **argv, int first) {
    try {
        const RenderOptions o = parse(argc, argv, first);
        ppm_context context = nullptr;
        check(ppm_context_create(&context), "ppm_context_create");
        check(ppm_context_set_int(context, "threads", o.threads), "ppm_context_set_int");
        std::printf("render benchmark: %d x %d, %d passes per configuration, threads %d (0 = all)\n", o.width, o.height,
                    o.passes, o.threads);
        std::printf("%-13s %-7s %10s %10s %12s %14s %10s %10s\n", "scene", "search", "photons", "eye_s", "photon_s",
                    "Mpaths/s", "peak_MiB", "build_s");
        for (const std::string &name : o.scenes) {
            BenchScene bs = build_bench_scene(context, name, o.teapot, o.width, o.height);
            std::vector<double> rates;
            for (long photons : o.photon_counts)
                for (const std::string &search : o.searches) {
                    ppm_renderer r = nullptr;
                    check(ppm_renderer_create(bs.scene, &bs.camera, &r), "ppm_renderer_create");
                    check(ppm_renderer_set_string(r, "hit_point_search", search.c_str()), "hit_point_search");
                    check(ppm_renderer_set_int(r, "photons_per_pass", photons), "photons_per_pass");
                    std::vector<double> eye, photon, build;
                    for (int p = 0; p < o.passes; ++p) {
                        check(ppm_render_pass(r), "ppm_render_pass");
                        double e = 0, ph = 0, b = 0;
                        check(ppm_renderer_get_double(r, "last_eye_pass_seconds", &e), "get");
                        check(ppm_renderer_get_double(r, "last_search_build_seconds", &b), "get");
                        build.push_back(b);
                        check(ppm_renderer_get_double(r, "last_photon_pass_seconds", &ph), "get");
                        eye.push_back(e);
                        photon.push_back(ph);
                    }
                    const double rate = photons / median(photon) / 1e6;
                    std::printf("%-13s %-7s %10ld %10.3f %12.3f %14.3f %10.0f %10.3f\n", name.c_str(), search.c_str(),
                                photons, median(eye), median(photon), rate, peak_rss_mib(), median(build));
                    std::fflush(stdout);
                    if (photons == o.photon_counts.back()) rates.push_back(rate);
                    if (!o.image_dir.empty() && photons == o.photon_counts.back())
                        write_pfm(o.image_dir + "/" + name + "-" + search + ".pfm", r, o.width, o.height);
                    ppm_renderer_release(r);
                }
            if (rates.size() == 2)
                std::printf("%-13s photon paths/s, %s / %s: %.2f\n", name.c_str(), o.searches[0].c_str(),
                            o.searches[1].c_str(), rates[0] / rates[1]);
            ppm_scene_release(bs.scene);
        }
        ppm_context_release(context);
        return 0;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "ppm-bench render: %s\n", e.what());
        return 2;
    }
}

} // namespace bench
