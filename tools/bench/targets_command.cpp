// SPDX-License-Identifier: Apache-2.0
#include "targets_command.h"

#include "bpt_patches.h"
#include "data_files.h"
#include "interleaved_rounds.h"
#include "measure.h"
#include "method.h"
#include "parallel.h"
#include "ray_sets.h"
#include "targets_args.h"
#include "targets_report.h"
#include "tessellate.h"

#include <ppm/ppm.h>

#include <cstdio>
#include <exception>

namespace bench {

namespace {

BuiltMethod build(std::unique_ptr<Method> method) {
    BuiltMethod built;
    Stopwatch clock;
    built.memory = method->build(1);
    built.build_seconds = clock.wall_seconds();
    built.method = std::move(method);
    std::fprintf(stderr, "%-20s %9zu primitives, %8.3f MiB, built in %8.2f ms\n", built.method->info().name.c_str(),
                 built.method->info().primitives, double(built.bytes()) / 1048576.0, 1e3 * built.build_seconds);
    return built;
}

// The exact methods first, before the mesh exists, so that their memory deltas are not blurred
// by the mesh's allocations; then the mesh methods. The first method is the one the others'
// hits are compared with.
std::vector<BuiltMethod> build_methods(const TargetsOptions &o, const std::vector<double> &patches, double diagonal) {
    warm_up_library(patches);
    std::vector<BuiltMethod> methods;
    for (int presplit : o.presplits) methods.push_back(build(make_exact_method(patches, default_tolerance, presplit)));
    auto mesh = std::make_shared<const Mesh>(tessellate(patches, o.grid, 0, diagonal));
    std::fprintf(stderr, "mesh %s: %zu triangles, %zu vertices, deviation %.3g diag, made in %.1f ms\n",
                 mesh->label.c_str(), mesh->triangle_count(), mesh->vertex_count(), mesh->deviation,
                 1e3 * mesh->seconds);
    methods.push_back(build(make_embree_method(mesh)));
    if (cgal_available()) methods.push_back(build(make_cgal_method(mesh)));
    return methods;
}

std::vector<RaySet> make_ray_sets(const TargetsOptions &o, const Bounds &box) {
    std::vector<RaySet> sets;
    if (o.rays > 0) sets.push_back(random_rays(box, o.rays, o.seed));
    if (o.width > 0) sets.push_back(camera_rays(box, o.width, o.height));
    return sets;
}

} // namespace

int run_targets_command(TargetsOptions options) {
    if (!cgal_available())
        std::fprintf(stderr, "ppm-bench targets: note: this build has no CGAL; the cgal method is skipped\n");
    try {
        options.bpt_path = input_or_data_file(options.bpt_path, "teapot.bpt", "--bpt");
        Stopwatch total;
        const double load_start = load_average();
        const std::vector<double> patches = read_bpt_patches(options.bpt_path);
        const Bounds box = control_point_bounds(patches);
        const double diagonal = box.diagonal();
        std::fprintf(stderr, "%s: %zu patches, bbox diagonal %.6g\n", options.bpt_path.c_str(), patches.size() / 48,
                     diagonal);
        const std::vector<RaySet> sets = make_ray_sets(options, box);
        const std::vector<BuiltMethod> methods = build_methods(options, patches, diagonal);
        const RoundsResult rounds = run_rounds(methods, sets, options.rounds, options.min_seconds);
        const double load_end = load_average();

        std::printf("ppm-bench targets on %s: %zu patches, bounding-box diagonal %.6g; libppm %s\n",
                    options.bpt_path.c_str(), patches.size() / 48, diagonal, ppm_version_string());
        std::printf("machine: %d hardware threads, every timing on 1 thread; load average %.2f at start, %.2f at "
                    "end; seed %llu\n",
                    hardware_threads(), load_start, load_end, (unsigned long long)options.seed);
        std::printf("%d rounds; in each, every method (order rotated each round) traces each set for at least "
                    "%g s; rays/s = rays / process CPU time; memory = input arrays + structure, built on 1 thread\n",
                    options.rounds, options.min_seconds);
        print_speed_tables(stdout, sets, methods, rounds);
        print_verdicts(stdout, sets, methods, rounds);
        if (!options.csv_path.empty()) {
            write_rounds_csv(options.csv_path, sets, methods, rounds);
            std::fprintf(stderr, "wrote %s\n", options.csv_path.c_str());
        }
        std::printf("\ndone in %.1f s wall\n", total.wall_seconds());
        std::fprintf(stderr, "done in %.1f s wall\n", total.wall_seconds());
    } catch (const std::exception &e) {
        std::fprintf(stderr, "ppm-bench targets: %s\n", e.what());
        return 2;
    }
    return 0;
}

} // namespace bench
