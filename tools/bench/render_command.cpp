// SPDX-License-Identifier: Apache-2.0
#include "render_command.h"

#include "bench_scenes.h"
#include "common/handle.h"
#include "common/status.h"
#include "data_files.h"

#include <ppm/ppm.h>

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace bench {

using ppm_tools::check_with_status;

namespace {

const char *const render_description = "Renderer speed: eye pass time, photon paths/s, memory";
const char *const render_footer = "Times the renderer's passes: eye pass seconds, photon paths per second and peak\n"
                                  "memory, per scene, hit-point search and photons per pass; build_s is the part of\n"
                                  "eye_s spent building the hit-point search. Figures are medians over the passes.\n"
                                  "In the bidirectional modes (vcm, bpt, vm) a pass is one estimate: eye_s is the\n"
                                  "whole pass, photon_s 0, and Mpaths/s counts light subpaths per second of the pass.\n"
                                  "Exit status: 0 ok, 1 usage error, 2 runtime error.";

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
    check_with_status(ppm_renderer_get_layer(renderer, "radiance", rgb.data(), rgb.size()), "ppm_renderer_get_layer");
    std::FILE *f = std::fopen(path.c_str(), "wb");
    if (!f) throw std::runtime_error("cannot write " + path);
    std::fprintf(f, "PF\n%d %d\n-1.0\n", w, h);
    for (int y = h - 1; y >= 0; --y) std::fwrite(&rgb[static_cast<size_t>(y) * w * 3], sizeof(float), w * 3u, f);
    std::fclose(f);
}

} // namespace

CLI::App *add_render_command(CLI::App &app, RenderOptions &o) {
    CLI::App *command = app.add_subcommand("render", render_description);
    command->footer(render_footer);
    auto list = [&](const std::string &name, std::vector<std::string> &out, const std::vector<std::string> &known,
                    const std::string &help) {
        command->add_option(name, out, help)
            ->delimiter(',')
            ->check(CLI::IsMember(known).description(""))
            ->type_name("LIST")
            ->allow_extra_args(false);
    };
    list("--scenes", o.scenes, {"smallppm", "teapot-glass"}, "smallppm,teapot-glass (default both)");
    list("--search", o.searches, {"grid", "kdtree"}, "grid,kdtree (default both)");
    command->add_option("--mode", o.mode, "sppm, ppm, pppm, vcm, bpt or vm (default sppm)")
        ->check(CLI::IsMember({"sppm", "ppm", "pppm", "vcm", "bpt", "vm"}).description(""))
        ->type_name("MODE");
    command
        ->add_option("--photons", o.photon_counts,
                     "photons per pass, in increasing order to see whether\n"
                     "memory grows with them (default 100000,1000000)")
        ->delimiter(',')
        ->check(CLI::Range(1L, 1L << 31))
        ->type_name("LIST")
        ->allow_extra_args(false);
    command->add_option("--width", o.width, "image width (default 1024)")->check(CLI::Range(1, 16384))->type_name("N");
    command->add_option("--height", o.height, "image height (default 768)")
        ->check(CLI::Range(1, 16384))
        ->type_name("N");
    command->add_option("--passes", o.passes, "passes per configuration (default 4; figures are\nmedians)")
        ->check(CLI::Range(1, 100000))
        ->type_name("N");
    command->add_option("--threads", o.threads, "worker threads (default 0 = all)")
        ->check(CLI::Range(0, 1024))
        ->type_name("N");
    command->add_option("--teapot", o.teapot, "the .bpt of teapot-glass (default " + data_file("teapot.bpt") + ")")
        ->type_name("PATH");
    command->add_option("--images", o.image_dir, "write each final image as DIR/<scene>-<search>.pfm\n(linear)")
        ->type_name("DIR");
    return command;
}

int run_render_command(const RenderOptions &options) {
    try {
        RenderOptions o = options;
        if (std::find(o.scenes.begin(), o.scenes.end(), "teapot-glass") != o.scenes.end())
            o.teapot = input_or_data_file(o.teapot, "teapot.bpt", "--teapot");
        ppm_tools::Context context;
        check_with_status(ppm_context_create(context.out()), "ppm_context_create");
        check_with_status(ppm_context_set_int(context, "threads", o.threads), "ppm_context_set_int");
        std::printf("render benchmark: %s, %d x %d, %d passes per configuration, threads %d (0 = all)\n",
                    o.mode.c_str(), o.width, o.height, o.passes, o.threads);
        std::printf("%-13s %-7s %10s %10s %12s %14s %10s %10s\n", "scene", "search", "photons", "eye_s", "photon_s",
                    "Mpaths/s", "peak_MiB", "build_s");
        for (const std::string &name : o.scenes) {
            BenchScene bs = build_bench_scene(context, name, o.teapot, o.width, o.height);
            std::vector<double> rates;
            for (long photons : o.photon_counts)
                for (const std::string &search : o.searches) {
                    ppm_tools::Renderer r;
                    check_with_status(ppm_renderer_create(bs.scene, &bs.camera, r.out()), "ppm_renderer_create");
                    check_with_status(ppm_renderer_set_string(r, "mode", o.mode.c_str()), "mode");
                    check_with_status(ppm_renderer_set_string(r, "hit_point_search", search.c_str()),
                                      "hit_point_search");
                    check_with_status(ppm_renderer_set_int(r, "photons_per_pass", photons), "photons_per_pass");
                    std::vector<double> eye, photon, build;
                    for (int p = 0; p < o.passes; ++p) {
                        check_with_status(ppm_renderer_render_pass(r), "ppm_renderer_render_pass");
                        double e = 0, ph = 0, b = 0;
                        check_with_status(ppm_renderer_get_double(r, "last_eye_pass_seconds", &e), "get");
                        check_with_status(ppm_renderer_get_double(r, "last_search_build_seconds", &b), "get");
                        build.push_back(b);
                        check_with_status(ppm_renderer_get_double(r, "last_photon_pass_seconds", &ph), "get");
                        eye.push_back(e);
                        photon.push_back(ph);
                    }
                    const double path_seconds = median(photon) > 0 ? median(photon) : median(eye);
                    const double rate = photons / path_seconds / 1e6;
                    std::printf("%-13s %-7s %10ld %10.3f %12.3f %14.3f %10.0f %10.3f\n", name.c_str(), search.c_str(),
                                photons, median(eye), median(photon), rate, peak_rss_mib(), median(build));
                    std::fflush(stdout);
                    if (photons == o.photon_counts.back()) rates.push_back(rate);
                    if (!o.image_dir.empty() && photons == o.photon_counts.back())
                        write_pfm(o.image_dir + "/" + name + "-" + search + ".pfm", r, o.width, o.height);
                }
            if (rates.size() == 2)
                std::printf("%-13s photon paths/s, %s / %s: %.2f\n", name.c_str(), o.searches[0].c_str(),
                            o.searches[1].c_str(), rates[0] / rates[1]);
        }
        return 0;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "ppm-bench render: %s\n", e.what());
        return 2;
    }
}

} // namespace bench
