#include "intersect_command.h"

#include "bpt_patches.h"
#include "intersect_args.h"
#include "measure.h"
#include "method.h"
#include "ray_sets.h"
#include "report.h"
#include "suspects.h"
#include "tessellate.h"

#include <cstdio>
#include <exception>

namespace bench {

namespace {

std::vector<RaySet> make_ray_sets(const IntersectOptions &options, const Bounds &box) {
    std::vector<RaySet> sets;
    if (options.random_rays > 0) sets.push_back(random_rays(box, options.random_rays, options.seed));
    if (options.width > 0) sets.push_back(camera_rays(box, options.width, options.height));
    return sets;
}

std::vector<MethodRun> run_methods(const IntersectOptions &options, const std::vector<double> &patches,
                                   const std::vector<RaySet> &sets) {
    std::vector<MethodRun> runs;
    if (options.has_method("exact")) runs.push_back(run_exact(options.bpt_path, sets));
    if (!options.has_method("embree") && !options.has_method("cgal")) return runs;
    for (int n : options.grids) {
        Stopwatch clock;
        const Mesh mesh = tessellate_patches(patches.data(), patches.size() / 48, n);
        std::fprintf(stderr, "tessellated N = %d: %zu vertices, %zu triangles in %.3f ms\n", n,
                     mesh.vertex_count(), mesh.triangle_count(), 1e3 * clock.cpu_seconds());
        if (options.has_method("embree")) runs.push_back(run_embree(mesh, sets));
        if (options.has_method("cgal")) runs.push_back(run_cgal(mesh, sets));
    }
    return runs;
}

} // namespace

int run_intersect_command(int argc, char **argv, int first) {
    IntersectOptions options;
    switch (parse_intersect_args(argc, argv, first, options)) {
    case ParseResult::help: print_intersect_usage(stdout); return 0;
    case ParseResult::error: std::fprintf(stderr, "run 'ppm-bench intersect -h' for usage\n"); return 1;
    case ParseResult::run: break;
    }
    if (options.has_method("cgal") && !cgal_available()) {
        std::fprintf(stderr, "ppm-bench intersect: this build has no CGAL; use --methods exact,embree\n");
        return 1;
    }
    try {
        Stopwatch total;
        const std::vector<double> patches = read_bpt_patches(options.bpt_path);
        const Bounds box = control_point_bounds(patches);
        const double diagonal = box.diagonal();
        const std::vector<RaySet> sets = make_ray_sets(options, box);
        std::fprintf(stderr, "%s: %zu patches, bbox diagonal %.6g; %zu ray sets\n",
                     options.bpt_path.c_str(), patches.size() / 48, diagonal, sets.size());
        const std::vector<MethodRun> runs = run_methods(options, patches, sets);

        const MethodRun *exact = nullptr;
        for (const MethodRun &run : runs)
            if (run.family == "exact") exact = &run;
        print_table(stdout, sets, runs, exact, diagonal);
        if (exact) print_suspects(stdout, sets, runs, *exact, diagonal, options.max_listed);
        if (!options.csv_path.empty()) write_csv(options.csv_path, sets, runs, exact, diagonal);
        std::fprintf(stderr, "done in %.1f s wall\n", total.wall_seconds());
    } catch (const std::exception &e) {
        std::fprintf(stderr, "ppm-bench intersect: %s\n", e.what());
        return 2;
    }
    return 0;
}

} // namespace bench
