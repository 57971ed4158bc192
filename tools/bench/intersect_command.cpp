// SPDX-License-Identifier: Apache-2.0
#include "intersect_command.h"

#include "bpt_patches.h"
#include "chart.h"
#include "data_files.h"
#include "driver.h"
#include "intersect_args.h"
#include "measure.h"
#include "method.h"
#include "parallel.h"
#include "ray_sets.h"
#include "report.h"
#include "rng.h"
#include "suspects.h"
#include "tessellate.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <sys/stat.h>

namespace bench {

namespace {

// The size of a set that scales with --rays: none for --rays 0, else at least one ray.
size_t fraction(size_t rays, size_t divisor) { return rays == 0 ? 0 : std::max<size_t>(1, rays / divisor); }

std::vector<RaySet> make_ray_sets(const IntersectOptions &o, const Bounds &box, const ref::Intersector &reference,
                                  int threads) {
    std::vector<RaySet> sets;
    auto add = [&](RaySet set) {
        if (set.size() > 0)
            sets.push_back(std::move(set));
        else
            std::fprintf(stderr, "ray set %s: no rays (%s)\n", set.name.c_str(), set.description.c_str());
    };
    if (o.has_set("random") && o.rays > 0) add(random_rays(box, o.rays, o.seed));
    if (o.has_set("camera") && o.width > 0) add(camera_rays(box, o.width, o.height));
    if (o.has_set("grazing") && o.rays > 0)
        for (double angle : o.angles) {
            // Seeded by the angle itself: a set does not change with the other angles listed.
            uint64_t bits = 0;
            std::memcpy(&bits, &angle, sizeof bits);
            add(grazing_rays(reference, angle, fraction(o.rays, 4), derive_seed(o.seed, bits)));
        }
    if (o.has_set("seams") && o.rays > 0) add(seam_rays(reference, fraction(o.rays, 4), derive_seed(o.seed, 200)));
    if (o.has_set("poles") && o.rays > 0) add(pole_rays(reference, fraction(o.rays, 10), derive_seed(o.seed, 201)));
    if (o.has_set("leaving") && o.rays > 0) {
        std::vector<double> spawn;
        if (o.has_method("exact")) spawn = o.tolerances;
        add(leaving_rays(reference, box, fraction(o.rays, 4), derive_seed(o.seed, 202), spawn, threads));
    }
    Stopwatch clock;
    size_t total = 0;
    for (RaySet &set : sets) {
        set.base.truth = compute_truth(reference, set.base.rays, threads);
        total += set.size();
        for (auto &variant : set.variants) {
            variant.second.truth = compute_truth(reference, variant.second.rays, threads);
            total += variant.second.rays.size();
        }
    }
    std::fprintf(stderr, "reference answers for %zu rays in %.1f s wall\n", total, clock.wall_seconds());
    return sets;
}

void make_directory(const std::string &dir) {
    if (dir.empty()) return;
    std::string partial;
    for (size_t i = 0; i <= dir.size(); ++i) {
        if (i == dir.size() || dir[i] == '/') {
            if (!partial.empty() && mkdir(partial.c_str(), 0777) != 0 && errno != EEXIST)
                throw std::runtime_error(partial + ": cannot create directory: " + std::strerror(errno));
        }
        if (i < dir.size()) partial += dir[i];
    }
}

std::string in_dir(const std::string &dir, const char *name) { return dir.empty() ? name : dir + "/" + name; }

// Runs every requested method in turn; meshes are made one at a time and dropped after their
// runs. Keeps the one-thread traces of the exact method at the default tolerance (or the
// first exact one) for the disagreement listing.
std::vector<MethodResult> run_methods(const IntersectOptions &o, const std::vector<double> &patches,
                                      const std::vector<RaySet> &sets, const DriverOptions &driver, double diagonal) {
    std::vector<MethodResult> results;
    // The method whose traces are kept for the disagreement listing.
    std::string explain = o.explain;
    if (explain.empty() && o.has_method("exact") && !o.tolerances.empty()) {
        const bool has_default =
            std::find(o.tolerances.begin(), o.tolerances.end(), default_tolerance) != o.tolerances.end();
        explain = "exact-" + format_number(has_default ? default_tolerance : o.tolerances.front());
    }
    auto run = [&](Method &method) {
        results.push_back(run_method(method, sets, driver, method.info().name == explain));
    };
    warm_up_library(patches);
    if (o.has_method("exact")) {
        for (double tolerance : o.tolerances) run(*make_exact_method(patches, tolerance));
        for (int presplit : o.presplits) run(*make_exact_method(patches, default_tolerance, presplit));
    }
    if (o.has_method("newton")) {
        run(*make_newton_method(patches, NewtonStarts::center, 1));
        run(*make_newton_method(patches, NewtonStarts::subpatch_centers, 4));
        run(*make_newton_method(patches, NewtonStarts::random, 4));
        run(*make_newton_method(patches, NewtonStarts::random, 16));
    }
    const bool embree = o.has_method("embree"), adaptive = o.has_method("adaptive"), cgal = o.has_method("cgal");
    struct MeshSpec {
        int grid;
        double tolerance;
        bool embree, cgal;
    };
    std::vector<MeshSpec> specs;
    auto add_spec = [&](int grid, double tolerance, bool with_embree, bool with_cgal) {
        for (MeshSpec &s : specs)
            if (s.grid == grid && s.tolerance == tolerance) {
                s.embree = s.embree || with_embree;
                s.cgal = s.cgal || with_cgal;
                return;
            }
        specs.push_back({grid, tolerance, with_embree, with_cgal});
    };
    if (embree)
        for (int n : o.grids) add_spec(n, 0, true, false);
    if (adaptive)
        for (double t : o.adaptive) add_spec(0, t, true, false);
    if (cgal) {
        for (int n : o.cgal_grids) add_spec(n, 0, false, true);
        for (double t : o.cgal_adaptive) add_spec(0, t, false, true);
    }
    // Embree runs first, then CGAL, so the table groups the families.
    std::vector<MethodResult> cgal_results;
    for (const MeshSpec &spec : specs) {
        auto mesh = std::make_shared<const Mesh>(tessellate(patches, spec.grid, spec.tolerance, diagonal));
        std::fprintf(stderr, "mesh %s: %zu triangles, %zu vertices, deviation %.3g diag, made in %.1f ms\n",
                     mesh->label.c_str(), mesh->triangle_count(), mesh->vertex_count(), mesh->deviation,
                     1e3 * mesh->seconds);
        if (spec.embree) run(*make_embree_method(mesh));
        if (spec.cgal) {
            auto method = make_cgal_method(mesh);
            cgal_results.push_back(run_method(*method, sets, driver, method->info().name == explain));
        }
    }
    for (MethodResult &r : cgal_results) results.push_back(std::move(r));
    return results;
}

} // namespace

int run_intersect_command(IntersectOptions options) {
    if (options.has_method("cgal") && !cgal_available()) {
        std::fprintf(stderr, "ppm-bench intersect: note: this build has no CGAL; the cgal method is skipped\n");
        options.methods.erase(std::find(options.methods.begin(), options.methods.end(), "cgal"));
    }
    try {
        options.bpt_path = input_or_data_file(options.bpt_path, "teapot.bpt", "--bpt");
        Stopwatch total;
        const double load_start = load_average();
        const int threads = options.threads > 0 ? options.threads : hardware_threads();
        const std::vector<double> patches = read_bpt_patches(options.bpt_path);
        std::vector<ref::Patch> reference_patches;
        std::string error;
        if (!ref::load_bpt(options.bpt_path, reference_patches, error))
            throw std::runtime_error(options.bpt_path + ": reference reader: " + error);
        const ref::Intersector reference(std::move(reference_patches));
        const Bounds box = control_point_bounds(patches);
        const double diagonal = box.diagonal();

        std::fprintf(stderr, "%s: %zu patches, bbox diagonal %.6g\n", options.bpt_path.c_str(), patches.size() / 48,
                     diagonal);
        const std::vector<RaySet> sets = make_ray_sets(options, box, reference, threads);
        if (sets.empty()) {
            std::fprintf(stderr, "ppm-bench intersect: no rays to trace\n");
            return 1;
        }
        DriverOptions driver;
        driver.threads = threads;
        driver.min_seconds = options.min_seconds;
        driver.diagonal = diagonal;
        const std::vector<MethodResult> runs = run_methods(options, patches, sets, driver, diagonal);
        const double load_end = load_average();

        std::printf("ppm-bench intersect on %s: %zu patches, bounding-box diagonal %.6g; libppm %s\n",
                    options.bpt_path.c_str(), patches.size() / 48, diagonal, ppm_version_string());
        std::printf("%s\n", reference_description(reference).c_str());
        std::printf("machine: %d hardware threads, all-thread runs on %d; load average %.2f at start, %.2f at end; "
                    "seed %llu\n",
                    hardware_threads(), threads, load_start, load_end, (unsigned long long)options.seed);
        std::printf("%s", statistics_definitions().c_str());
        std::printf("ray sets:\n");
        for (const RaySet &set : sets)
            std::printf("  %-14s %7zu rays: %s\n", set.name.c_str(), set.size(), set.description.c_str());
        print_set_tables(stdout, sets, runs);
        const std::string summary = summary_markdown(sets, runs), stability = stability_markdown(sets, runs);
        if (!summary.empty()) std::printf("\nSummary (random and camera rays):\n\n%s", summary.c_str());
        std::printf("\nStability:\n\n%s", stability.c_str());
        for (const MethodResult &run : runs)
            if (!run.traces.empty()) print_suspects(stdout, sets, run, diagonal, options.max_listed);

        make_directory(options.out_dir);
        const std::string csv =
            options.csv_path.empty() ? in_dir(options.out_dir, "bench-results.csv") : options.csv_path;
        write_csv(csv, sets, runs);
        std::fprintf(stderr, "wrote %s\n", csv.c_str());
        std::string stability_path = options.stability_path, summary_path = options.summary_path;
        if (!options.out_dir.empty()) {
            if (stability_path.empty()) stability_path = in_dir(options.out_dir, "stability.md");
            if (summary_path.empty()) summary_path = in_dir(options.out_dir, "summary.md");
        }
        if (!stability_path.empty()) {
            write_text(stability_path, stability);
            std::fprintf(stderr, "wrote %s\n", stability_path.c_str());
        }
        if (!summary_path.empty()) {
            write_text(summary_path, summary);
            std::fprintf(stderr, "wrote %s\n", summary_path.c_str());
        }
        if (!options.chart_dir.empty()) {
            make_directory(options.chart_dir);
            draw_chart(csv, options.chart_dir);
        }
        std::printf("\ndone in %.1f s wall\n", total.wall_seconds());
        std::fprintf(stderr, "done in %.1f s wall\n", total.wall_seconds());
    } catch (const std::exception &e) {
        std::fprintf(stderr, "ppm-bench intersect: %s\n", e.what());
        return 2;
    }
    return 0;
}

} // namespace bench
