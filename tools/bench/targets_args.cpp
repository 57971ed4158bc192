// SPDX-License-Identifier: Apache-2.0
#include "targets_args.h"

#include "bench_options.h"
#include "data_files.h"

#include <algorithm>

namespace bench {

namespace {

const char *const targets_description = "The exact intersector's speed and memory targets against Embree\n"
                                        "and CGAL on a uniform mesh, from medians of interleaved timing\n"
                                        "rounds";
const char *const targets_footer =
    "Checks the speed and memory targets of libppm's exact intersector against the same model\n"
    "tessellated as a uniform mesh and traced by Embree and by CGAL's AABB tree: at least 0.5\n"
    "times Embree's speed and 5 times CGAL's on random rays, at least 1000 times less memory\n"
    "than either. Every method is built once on one thread; then, in each round, each method\n"
    "(in an order rotated from round to round) traces each ray set on one thread, and a speed\n"
    "ratio is taken within the round. Verdicts use the median of those per-round ratios, so a\n"
    "load burst on a shared machine moves one round, not the verdict.\n"
    "Exit status: 0 ok (whatever the verdicts), 1 usage error, 2 runtime error.";

} // namespace

CLI::App *add_targets_command(CLI::App &app, TargetsOptions &o) {
    CLI::App *command = app.add_subcommand("targets", targets_description);
    command->footer(targets_footer);
    command->add_option("--bpt", o.bpt_path, "patches to load (default " + data_file("teapot.bpt") + ")")
        ->type_name("FILE");
    add_number_list(*command, "--presplit", o.presplits, 1, 32, false,
                    "a list like 3,12 of patch_presplit values in [1, 32]",
                    "exact method at these scene patch_presplit values,\n"
                    "methods exact-presplit-N (default 3,12)");
    command->add_option("--grid", o.grid, "the meshes have N x N quads per patch (default 128)")
        ->check(CLI::Range(1, 4096))
        ->type_name("N");
    command->add_option("--rays", o.rays, "random rays (default 20000; 0 skips the set and the\nspeed targets)")
        ->check(CLI::Range(0, 100000000))
        ->type_name("N");
    command->add_option("--width", o.width, "camera rays across (default 256; 0 with --height 0 skips\nthe set)")
        ->check(CLI::Range(0, 16384))
        ->type_name("W");
    command->add_option("--height", o.height, "camera rays down (default 256)")
        ->check(CLI::Range(0, 16384))
        ->type_name("H");
    command->add_option("--rounds", o.rounds, "timing rounds (default 9)")->check(CLI::Range(1, 1000))->type_name("K");
    command
        ->add_option("--min-time", o.min_seconds,
                     "each timing traces its set again until S seconds have\n"
                     "passed (default 0.2; rays/s come from process CPU time)")
        ->check(real_in(0, 60))
        ->type_name("S");
    command->add_option("--seed", o.seed, "seed of the random rays (default 1)")
        ->check(CLI::Range(uint64_t(0), uint64_t(INT64_MAX)).description(""))
        ->type_name("S");
    command->add_option("--csv", o.csv_path, "every timing, one row per round, method and ray set")->type_name("FILE");
    return command;
}

void check_targets_options(TargetsOptions &o) {
    if ((o.width == 0) != (o.height == 0))
        throw ppm_tools::UsageError("targets: --width and --height must both be 0 or both positive");
    if (o.rays == 0 && o.width == 0) throw ppm_tools::UsageError("targets: no rays to trace (--rays 0 and --width 0)");
    std::vector<int> distinct;
    for (int n : o.presplits)
        if (std::find(distinct.begin(), distinct.end(), n) == distinct.end()) distinct.push_back(n);
    o.presplits = distinct;
}

} // namespace bench
