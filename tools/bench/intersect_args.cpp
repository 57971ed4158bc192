// SPDX-License-Identifier: Apache-2.0
#include "intersect_args.h"

#include "bench_options.h"
#include "data_files.h"

#include <algorithm>

namespace bench {

namespace {

const char *const intersect_description = "Speed against accuracy of patch intersection: libppm, naive\n"
                                          "Newton, Embree and CGAL on tessellations, against a long-double\n"
                                          "reference";
const char *const intersect_footer =
    "Speed against accuracy of ray / Bezier patch intersection: libppm's exact intersector at\n"
    "several tolerances, naive Newton methods, and tessellations traced by Embree and CGAL, all\n"
    "judged ray by ray against an independent long-double reference intersector, on one thread\n"
    "and on all threads.\n"
    "Exit status: 0 ok, 1 usage error (also: no rays to trace), 2 runtime error.";

const char *const grid_list = "a list like 8,32 of grid sizes in [1, 4096], or none";
const char *const mesh_tolerance_list = "of mesh tolerances / diagonal in [1e-9, 0.1], or none";

CLI::Option *name_list(CLI::App &command, const std::string &name, std::vector<std::string> &out,
                       const std::vector<std::string> &known, const std::string &help) {
    return command.add_option(name, out, help)
        ->delimiter(',')
        ->check(CLI::IsMember(known).description(""))
        ->type_name("LIST")
        ->allow_extra_args(false); // one list per option: "--sets random camera" is an error
}

} // namespace

bool IntersectOptions::has_method(const std::string &name) const {
    return std::find(methods.begin(), methods.end(), name) != methods.end();
}

bool IntersectOptions::has_set(const std::string &name) const {
    return std::find(sets.begin(), sets.end(), name) != sets.end();
}

CLI::App *add_intersect_command(CLI::App &app, IntersectOptions &o) {
    CLI::App *command = app.add_subcommand("intersect", intersect_description);
    command->footer(intersect_footer);
    command->add_option("--bpt", o.bpt_path, "patches to load (default " + data_file("teapot.bpt") + ")")
        ->type_name("FILE");
    command
        ->add_option("--rays", o.rays,
                     "random rays (default 20000); grazing (per angle), seam\n"
                     "and leaving sets get N/4 rays each, poles N/10 (at least\n"
                     "1 each; 0 skips them)")
        ->check(CLI::Range(0, 100000000))
        ->type_name("N");
    command->add_option("--width", o.width, "camera rays across (default 256; 0 with --height 0 skips\nthe set)")
        ->check(CLI::Range(0, 16384))
        ->type_name("W");
    command->add_option("--height", o.height, "camera rays down (default 256)")
        ->check(CLI::Range(0, 16384))
        ->type_name("H");
    name_list(*command, "--sets", o.sets, {"random", "camera", "grazing", "seams", "poles", "leaving"},
              "any of random,camera,grazing,seams,poles,leaving\n(default all)");
    add_number_list(*command, "--angles", o.angles, 1e-12, 1.5, false,
                    "a list like 1e-3,1e-6 of angles in (0, 1.5] rad",
                    "grazing angles in radians (default 1e-2,1e-3,1e-4,1e-6)");
    name_list(*command, "--methods", o.methods, {"exact", "newton", "embree", "adaptive", "cgal"},
              "any of exact,newton,embree,adaptive,cgal (default all;\ncgal if built)");
    add_number_list(*command, "--tolerances", o.tolerances, 1e-14, 1e-2, false,
                    "a list like 1e-6,1e-9 of scene tolerances in [1e-14, 1e-2]",
                    "exact method scene tolerances (default\n1e-3,1e-6,1e-9,1e-12)");
    add_number_list(*command, "--presplits", o.presplits, 1, 32, true,
                    "a list like 1,4 of patch_presplit values in [1, 32], or none",
                    "exact method at tolerance 1e-9 with these scene\n"
                    "patch_presplit values, methods exact-presplit-N\n"
                    "(default 1,2,4,12; 'none' for none)");
    add_number_list(*command, "--grids", o.grids, 1, 4096, true, grid_list,
                    "uniform grids traced by Embree (default 8,16,32,64,128)");
    add_number_list(*command, "--cgal-grids", o.cgal_grids, 1, 4096, true, grid_list,
                    "uniform grids traced by CGAL (default 8,32,128)");
    add_number_list(*command, "--adaptive", o.adaptive, 1e-9, 1e-1, true,
                    std::string("a list like 1e-3,1e-4 ") + mesh_tolerance_list,
                    "adaptive meshes traced by Embree, tolerance / diagonal\n"
                    "(default 1e-3,1e-4,1e-5); 'none' for no mesh");
    add_number_list(*command, "--cgal-adaptive", o.cgal_adaptive, 1e-9, 1e-1, true,
                    std::string("a list like 1e-4 ") + mesh_tolerance_list,
                    "adaptive meshes traced by CGAL (default 1e-4)");
    command
        ->add_option("--threads", o.threads,
                     "threads of the all-thread runs (default 0: all hardware\n"
                     "threads; 1: single-thread runs only)")
        ->check(CLI::Range(0, 1024))
        ->type_name("N");
    command->add_option("--min-time", o.min_seconds, "trace each set again until S seconds have passed\n(default 0.1)")
        ->check(real_in(0, 60))
        ->type_name("S");
    command->add_option("--seed", o.seed, "seed of all random ray sets (default 1)")
        ->check(CLI::Range(uint64_t(0), uint64_t(INT64_MAX)).description(""))
        ->type_name("S");
    command->add_option("--list", o.max_listed, "disagreements with the reference listed per set\n(default 5)")
        ->check(CLI::Range(0, 1000000))
        ->type_name("K");
    command
        ->add_option("--explain", o.explain,
                     "whose disagreements to list, e.g. newton-r16 (default:\n"
                     "exact-1e-9, or the first exact method)")
        ->type_name("METHOD");
    command->add_option("--out", o.out_dir, "directory of the outputs (created; default: current\ndirectory)")
        ->type_name("DIR");
    command
        ->add_option("--csv", o.csv_path,
                     "results, one row per ray set and method (default\n"
                     "DIR/bench-results.csv)")
        ->type_name("FILE");
    command
        ->add_option("--stability-md", o.stability_path,
                     "markdown tables of miss and false-hit rates (default\n"
                     "DIR/stability.md with --out)")
        ->type_name("FILE");
    command->add_option("--summary-md", o.summary_path, "markdown summary table (default DIR/summary.md with\n--out)")
        ->type_name("FILE");
    command
        ->add_option("--chart", o.chart_dir,
                     "write DIR/intersect.png and .svg with plot_bench.py\n"
                     "(needs python3 with matplotlib)")
        ->type_name("DIR");
    return command;
}

void check_intersect_options(const IntersectOptions &o) {
    if ((o.width == 0) != (o.height == 0))
        throw ppm_tools::UsageError("intersect: --width and --height must both be 0 or both positive");
}

} // namespace bench
